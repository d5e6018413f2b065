//! # zrow-model — models for zrow, on the host
//!
//! Everything a model goes through before it reaches a microcontroller, without the
//! simulator: a firmware's `build.rs` depends on this crate alone (and zrow), never on a
//! window or SDL.
//!
//! 1. [`model`] loads an OBJ, STL or OFF file ([`model::load`], input limits in
//!    [`model::read_input`]) into a [`model::LoadedModel`] normalised into the unit sphere,
//!    every error naming the file and line;
//! 2. [`convert`] checks it (non-manifold edges, non-convex and non-planar faces), quantises it
//!    to a [`Format`], measures the capacities [`zrow::Scanline`] needs from every orientation
//!    seen by model mode's [`camera`], and emits const Rust ([`convert::write_for_build`] for a
//!    build script, included with `zrow::include_mesh!`); the emitted code names only `zrow`;
//! 3. [`structure`] tells whether a mesh is one closed convex solid (then back-face culling
//!    alone draws it exactly), in O(E log E);
//! 4. [`off`] is the OFF format, also the simulator's scene file;
//! 5. [`vertex_normals`] gives every vertex a normal for smooth shading (the file's, or
//!    averaged from the faces within a crease angle), the converter's `--smooth`.
//!
//! Every failure is an [`Error`] that prints on one line.
//!
//! ```
//! use zrow_model::convert::{convert_model, ConvertOptions};
//! use zrow_model::model::{parse, ModelFormat};
//! let off = b"OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
//! let model = parse("tet.off", ModelFormat::Off, off, ".".as_ref()).unwrap();
//! let quick = ConvertOptions { directions: 16, rolls: 2, refine_steps: 5, check_views: 10, ..Default::default() };
//! let converted = convert_model(&model, &quick).unwrap();
//! assert!(converted.rust.contains("pub static MESH"));
//! assert!(converted.report.capacities.polygons >= 3);
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod camera;
pub mod convert;
pub mod error;
pub mod format;
pub mod model;
pub mod off;
pub mod structure;
pub mod vertex_normals;

pub use error::Error;
pub use format::Format;
