//! # zrow-byo — bring your own model
//!
//! The build-time path of "model only what a scene requires": `build.rs` runs the converter
//! of the `zrow-model` crate (`zrow_model::convert::write_for_build` — checks, quantisation,
//! capacities over every orientation) on a model file, and [`zrow::include_mesh!`] pulls the generated const
//! data in. Everything below lives in flash; the only RAM is the renderer, whose capacities
//! the converter measured:
//!
//! ```
//! use zrow_byo::torus;
//! use zrow::{FrameBuffer, Renderer};
//! // The scan-line renderer sized for this model: its RAM is what the converter reported.
//! assert!(torus::Renderer::RAM_BYTES < 16 * 1024);
//! assert_eq!(torus::MESH.faces.len(), torus::FACES.len());
//! ```
//!
//! The same in a firmware crate: add `zrow-model` as a build-dependency (a host crate with no
//! simulator and no SDL in its dependency tree), call
//! `write_for_build(model, &options, out_dir, "name")` from `build.rs`, and
//! `zrow::include_mesh!("name")` where the mesh is wanted. The generated code names only
//! `zrow` (colours as `zrow::Rgb565`), so the crate needs no other dependency for it.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

// The converter reports a mesh's own flash as 52 bytes on a 32-bit target
// (`zrow_model::convert::MESH_BYTES`): held to it wherever this is built for one.
#[cfg(target_pointer_width = "32")]
const _: () = assert!(core::mem::size_of::<zrow::Mesh<'static, zrow::Q16_16, u8>>() == 52);

/// `assets/models/torus.off`: 128 vertices (u8 indices), 128 quadrilaterals.
pub mod torus {
    zrow::include_mesh!("torus");
}

/// `assets/models/cube.obj`: one closed convex solid, so back-face culling alone draws it
/// exactly ([`zrow::cullonly`]).
pub mod cube {
    zrow::include_mesh!("cube");
}

/// `assets/models/icosphere.stl`: triangles alone, so emitted as a triangle list
/// (`TRIANGLES` and `COLORS`, [`zrow::Faces::Triangles`]) instead of a list of faces.
pub mod icosphere {
    zrow::include_mesh!("icosphere");
}

/// `assets/models/torus.off` converted with one normal per vertex (`--smooth 60`:
/// `VERTEX_NORMALS`, for smooth shading): its faces are 22.5° and 45° apart, so every edge is
/// smooth and every vertex keeps one normal, the same vertices and faces as [`torus`].
pub mod torus_smooth {
    zrow::include_mesh!("torus_smooth");
}

/// `assets/models/icosphere.stl` converted with compact positions (`--compact`: 16-bit
/// integers at 2^-14, [`zrow::Vectors::Compact`], 6 bytes a vertex instead of 12).
pub mod icosphere_compact {
    zrow::include_mesh!("icosphere_compact");
}
