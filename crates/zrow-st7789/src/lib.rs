//! # zrow-st7789 — zrow rows straight to an ST7789 panel
//!
//! zrow finishes a frame one row at a time; this crate sends each row to an ST7789 as soon as
//! it is done, through any embedded-hal 1.0 [`SpiDevice`](embedded_hal::spi::SpiDevice) and
//! DC [`OutputPin`](embedded_hal::digital::OutputPin). The address window is set once per
//! frame (`CASET`, `RASET`, `RAMWR`); after that each row is one SPI write of big-endian
//! RGB565 bytes, and the panel's address counter does the rest.
//!
//! ```
//! use embedded_hal::{delay::DelayNs, digital::OutputPin, spi::SpiDevice};
//! use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
//! use zrow::{Config, Face, Mesh, Q16_16, RenderError, Scanline, ScreenScene, Vec3};
//! use zrow_st7789::{line_bytes, Error, St7789Rows, Window};
//!
//! const WINDOW: Window = Window::new(240, 240); // a 240x240 module: no offsets
//! const B: usize = line_bytes(240); // 480-byte line buffer
//! const _: () = assert!(WINDOW.check(B).is_ok()); // checked at compile time
//!
//! fn show<SPI: SpiDevice, DC: OutputPin>(
//!     spi: SPI,
//!     dc: DC,
//!     delay: &mut impl DelayNs,
//! ) -> Result<(), RenderError<Error<SPI::Error, DC::Error>>> {
//!     let q = |x, y, z| Vec3::<Q16_16>::from_f32([x, y, z]).unwrap();
//!     let vertices = [q(20.0, 20.0, 1.0), q(220.0, 60.0, 1.0), q(60.0, 220.0, 1.0)];
//!     let faces = [Face { indices: &[0u16, 1, 2], color: Rgb565::GREEN, alpha: 255 }];
//!     let scene = ScreenScene { mesh: Mesh::new(&vertices, &faces) };
//!
//!     let mut panel = St7789Rows::<_, _, B>::new(spi, dc, WINDOW).unwrap();
//!     panel.init(delay).map_err(RenderError::Sink)?;
//!     let mut renderer = Scanline::<Q16_16, 240, 8, 4, 4>::new();
//!     panel.begin_frame().map_err(RenderError::Sink)?; // once per frame
//!     renderer.render(&scene, &Config::screen(240, 240), &mut panel)?;
//!     Ok(())
//! }
//! ```
//!
//! The parts:
//!
//! - [`command`]: command codes, the power-on sequence as data ([`init_sequence`]) and the
//!   functions that send commands ([`send_command`], [`init`]); a firmware may initialise
//!   with another driver (mipidsi) instead and use only the row sink.
//! - [`St7789Rows`]: the [`zrow::RowSink`] for blocking SPI, with its [`Window`] (size and
//!   offsets in panel RAM) and typed errors ([`Error`], [`StreamError`]).
//! - [`coherence`]: frame coherence on the wire: [`CoherentRows`] sends only the rows that
//!   changed since the last frame (a 32-bit signature per row), [`Coherence`] the same
//!   decision for DMA firmware.
//! - [`dma`]: the same coherent sending from two row buffers by DMA (encode row *k + 1* while
//!   row *k* is on the wire), over a board's DMA transfer ([`dma::DmaLink`]): the row sink of
//!   both board firmwares.
//! - [`encode_row`]: the row encoding alone, for firmware of its own.
//! - `model` and `mock` (feature `model`, needs `std`): an ST7789 model that decodes the
//!   command/data stream into a frame, and mock SPI/DC/delay that feed it, so the whole path
//!   is tested on the host.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

#[cfg(feature = "std")]
extern crate std;

pub mod coherence;
pub mod command;
pub mod dma;
pub mod error;
#[cfg(feature = "model")]
pub mod mock;
#[cfg(feature = "model")]
pub mod model;
pub mod rows;

pub use coherence::{Coherence, CoherentRows, RowAction};
pub use command::{init, init_sequence, send_command, InitStep, INIT_SEQUENCE};
pub use error::{Error, StreamError};
pub use rows::{
    encode_row, encode_row_signed, line_bytes, St7789Rows, Window, PANEL_HEIGHT, PANEL_WIDTH,
};
