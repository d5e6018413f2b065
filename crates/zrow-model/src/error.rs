//! The one error type of loading, converting and (in `zrow-sim`) drawing: everything that can
//! stop a conversion or a command, each printing as one line.
//!
//! A build script prints it as `error: {this}`; `zrow-sim` does the same on stderr and exits
//! non-zero ([`Error::exit_code`]). Errors about a file start with `FILE:LINE:` (or `FILE:`
//! when no line is to blame, as for a capacity the whole scene exceeds).

use crate::model::ModelError;
use crate::off::OffError;
use core::fmt;
use std::io;

/// What stopped a command.
#[derive(Debug)]
#[non_exhaustive]
pub enum Error {
    /// An option or a command-line argument is wrong (the message says how).
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
    /// A worker thread could not be started.
    Thread(io::Error),
}

impl Error {
    /// The process exit code: 2 for a wrong command line, 1 for everything else.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Usage(_) => 2,
            _ => 1,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Usage(m) => m.fmt(f),
            Error::Off(e) => e.fmt(f),
            Error::Model(e) => e.fmt(f),
            Error::Scene {
                file,
                line: Some(line),
                error,
            } => write!(f, "{file}:{line}: {error}"),
            Error::Scene {
                file,
                line: None,
                error,
            } => write!(f, "{file}: {error}"),
            Error::Io {
                path,
                action,
                source,
            } => write!(f, "{path}: cannot {action}: {source}"),
            Error::Thread(e) => write!(f, "cannot start a worker thread: {e}"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Off(e) => Some(e),
            Error::Model(e) => Some(e),
            Error::Io { source, .. } | Error::Thread(source) => Some(source),
            _ => None,
        }
    }
}

impl From<OffError> for Error {
    fn from(e: OffError) -> Self {
        Error::Off(e)
    }
}

impl From<ModelError> for Error {
    fn from(e: ModelError) -> Self {
        Error::Model(e)
    }
}
