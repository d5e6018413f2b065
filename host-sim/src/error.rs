//! The simulator's error: everything that can stop a command, each printing as one line.
//!
//! `main` prints it as `error: {this}` on stderr and exits non-zero ([`SimError::exit_code`]).
//! Errors about a scene file start with `FILE:LINE:` (or `FILE:` when no line is to blame, as
//! for a capacity the whole scene exceeds).

use crate::model::ModelError;
use crate::off::OffError;
use core::fmt;
use std::io;

/// What stopped a command.
#[derive(Debug)]
#[non_exhaustive]
pub enum SimError {
    /// The command line is wrong (the message says how).
    Usage(String),
    /// The scene file does not parse.
    Off(OffError),
    /// A model file (OBJ, STL, OFF in model mode) is malformed or unusable.
    Model(ModelError),
    /// zrow rejected the scene: a face (blamed on its line when the error names one) or a
    /// capacity.
    Scene {
        /// Scene file name.
        file: String,
        /// Line of the face the error names, if it names one.
        line: Option<usize>,
        /// zrow's error.
        error: zrow::Error,
    },
    /// Reading or writing a file failed.
    Io {
        /// The file.
        path: String,
        /// What was being done (`read`, `write`).
        action: &'static str,
        /// Why it failed.
        source: io::Error,
    },
    /// The PNG encoder failed.
    Png {
        /// The output file.
        path: String,
        /// Why it failed.
        source: png::EncodingError,
    },
    /// The render thread could not be started.
    Thread(io::Error),
}

impl SimError {
    /// The process exit code: 2 for a wrong command line, 1 for everything else.
    pub fn exit_code(&self) -> u8 {
        match self {
            SimError::Usage(_) => 2,
            _ => 1,
        }
    }
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Usage(m) => write!(f, "{m} (see `zrow-sim --help`)"),
            SimError::Off(e) => e.fmt(f),
            SimError::Model(e) => e.fmt(f),
            SimError::Scene {
                file,
                line: Some(line),
                error,
            } => write!(f, "{file}:{line}: {error}"),
            SimError::Scene {
                file,
                line: None,
                error,
            } => write!(f, "{file}: {error}"),
            SimError::Io {
                path,
                action,
                source,
            } => write!(f, "{path}: cannot {action}: {source}"),
            SimError::Png { path, source } => write!(f, "{path}: cannot encode PNG: {source}"),
            SimError::Thread(e) => write!(f, "cannot start the render thread: {e}"),
        }
    }
}

impl std::error::Error for SimError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SimError::Off(e) => Some(e),
            SimError::Model(e) => Some(e),
            SimError::Io { source, .. } | SimError::Thread(source) => Some(source),
            SimError::Png { source, .. } => Some(source),
            _ => None,
        }
    }
}

impl From<OffError> for SimError {
    fn from(e: OffError) -> Self {
        SimError::Off(e)
    }
}

impl From<ModelError> for SimError {
    fn from(e: ModelError) -> Self {
        SimError::Model(e)
    }
}
