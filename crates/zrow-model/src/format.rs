//! The number formats a model is converted to and drawn in.

use zrow::{Scalar, Q16_16};

/// The number format the renderer computes in, by its `--format` name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Format {
    /// Q16.16 fixed point (the microcontroller's format; the default).
    #[default]
    Q16_16,
    /// IEEE single precision.
    F32,
}

impl Format {
    /// Every format with its name.
    pub const ALL: &'static [(&'static str, Format)] =
        &[("q16.16", Format::Q16_16), ("f32", Format::F32)];

    /// The format called `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().find(|(n, _)| *n == name).map(|&(_, f)| f)
    }

    /// Its `--format` name (also zrow's [`Scalar::NAME`]).
    pub fn name(self) -> &'static str {
        match self {
            Format::Q16_16 => Q16_16::NAME,
            Format::F32 => f32::NAME,
        }
    }

    /// The accepted names, comma-separated (for messages).
    pub fn names() -> String {
        let names: Vec<&str> = Self::ALL.iter().map(|(n, _)| *n).collect();
        names.join(", ")
    }
}
