//! Typed errors: the bus's own errors passed through, and the stream's mistakes, each saying
//! the fix.

use core::fmt;

/// A mistake in how rows reach the panel (not a bus failure). Nothing is sent when one is
/// returned; call [`St7789Rows::begin_frame`](crate::St7789Rows::begin_frame) to start the
/// frame again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum StreamError {
    /// A row arrived outside a frame (before the first `begin_frame`, or after the frame's
    /// last row): call `begin_frame` once at the start of every frame.
    NoFrame,
    /// Row `got` arrived when row `expected` was due: rows go top to bottom, `0..height`, each
    /// once (zrow's renderers do this; check that one sink gets one frame at a time).
    OutOfOrder {
        /// The row the panel's address counter is at.
        expected: u16,
        /// The row that came.
        got: u16,
    },
    /// The row has `got` pixels but the window is `expected` wide: render with
    /// `Config::screen(width, height)` (or `Config::model`) of the same size as the
    /// [`Window`](crate::Window).
    WrongLength {
        /// The window's width.
        expected: u16,
        /// The row's length.
        got: u32,
    },
    /// The line buffer holds `capacity` bytes but a row needs `needed` (2 per pixel): make
    /// the buffer parameter `B` at least [`line_bytes`](crate::line_bytes)`(width)`.
    BufferTooSmall {
        /// Bytes a row needs.
        needed: u32,
        /// Bytes the buffer has (`B`).
        capacity: u32,
    },
    /// The window is empty or does not fit the panel's 240 × 320 RAM with its offsets: shrink
    /// it or fix the offsets (see [`Window`](crate::Window)).
    BadWindow,
    /// [`CoherentRows`](crate::CoherentRows) keeps `capacity` row signatures but the window
    /// is `height` rows tall: make its parameter `H` at least the height.
    TooFewSignatures {
        /// The window's height.
        height: u16,
        /// Signatures kept (`H`).
        capacity: u32,
    },
}

/// What went wrong on the way to the panel: `SE` is the SPI device's error, `PE` the DC pin's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error<SE, PE> {
    /// The SPI device failed: the bus error is inside; the panel may hold a partial row, so
    /// start the frame again with `begin_frame` once the bus works.
    Spi(SE),
    /// Setting the DC pin failed: the pin error is inside; start the frame again with
    /// `begin_frame`.
    Dc(PE),
    /// The rows or the configuration were wrong; see [`StreamError`].
    Stream(StreamError),
}

impl<SE, PE> From<StreamError> for Error<SE, PE> {
    fn from(e: StreamError) -> Self {
        Error::Stream(e)
    }
}

impl fmt::Display for StreamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            StreamError::NoFrame => f.write_str("row outside a frame: call begin_frame first"),
            StreamError::OutOfOrder { expected, got } => {
                write!(f, "row {got} arrived, row {expected} was due")
            }
            StreamError::WrongLength { expected, got } => {
                write!(f, "row of {got} pixels for a window {expected} wide")
            }
            StreamError::BufferTooSmall { needed, capacity } => {
                write!(f, "line buffer of {capacity} bytes, a row needs {needed}")
            }
            StreamError::BadWindow => f.write_str("window empty or outside the 240x320 panel"),
            StreamError::TooFewSignatures { height, capacity } => {
                write!(
                    f,
                    "{capacity} row signatures for a window {height} rows tall"
                )
            }
        }
    }
}

impl<SE: fmt::Debug, PE: fmt::Debug> fmt::Display for Error<SE, PE> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Spi(e) => write!(f, "SPI error: {e:?}"),
            Error::Dc(e) => write!(f, "DC pin error: {e:?}"),
            Error::Stream(e) => fmt::Display::fmt(e, f),
        }
    }
}
