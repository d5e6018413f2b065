//! # zrow-sim — the zrow simulator on the host
//!
//! Renders zrow scenes without the hardware, for tests, golden images and looking at the
//! result. The command (`docs/conventions.md`):
//!
//! ```text
//! cargo run --release -p zrow-sim -- render --screen SCENE.off --size 240x240 --algo scanline --out OUT.png
//! ```
//!
//! The pipeline, in the order a command goes through it:
//!
//! 1. [`cli`] parses the arguments;
//! 2. [`off`] ([`zrow_model::off`]) parses the scene file, every error naming its file and
//!    line;
//! 3. [`render`] builds a [`zrow::ScreenScene`], measures it with [`zrow::requirements()`] and
//!    renders it with the chosen method and number format into an [`render::Image`];
//! 4. [`png_io`] writes the PNG.
//!
//! Model mode (`zrow-sim render-model --model FILE …`) goes the same way with [`model`]
//! ([`zrow_model::model`]) loading
//! an OBJ, STL or OFF model into the unit sphere and [`model_render`] drawing it from an
//! orbiting camera under a fixed light ([`model_render::render_model_image`], which the
//! window shares).
//!
//! `zrow-sim convert --model FILE --out FILE.rs` ([`convert`], the converter of
//! [`zrow_model::convert`]) turns a model into const Rust
//! data for flash with the scan-line capacities it needs from any orientation, and reports
//! every change it made, the quantisation error and the RAM.
//!
//! Every failure is a [`SimError`] that prints on one line.
//!
//! ```
//! use zrow_sim::{off, render::{render_screen, Algo, Format}};
//! let scene = off::parse("tri.off", b"OFF\n3 1 0\n0 0 0\n8 0 0\n0 8 0\n3 0 1 2 255 0 0\n").unwrap();
//! let image = render_screen(&scene, 8, 8, Algo::Scanline, Format::Q16_16).unwrap();
//! assert_eq!(&image.to_rgb8()[..3], &[255, 0, 0]); // pixel (0, 0) is red
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod bands;
pub mod cli;
pub mod convert;
pub mod demo;
pub mod model_render;
pub mod output;
pub mod png_io;
pub mod render;
#[cfg(feature = "window")]
pub mod window;

/// Loading, the OFF format, structure analysis and the error type come from
/// [`zrow_model`], the host crate a firmware's build script uses too.
pub use zrow_model::{error, model, off, structure};

/// Everything that can stop a command ([`zrow_model::Error`]), printing as one line.
pub use zrow_model::Error as SimError;
