//! # zrow — hidden surfaces removed one scan line at a time, in fixed point
//!
//! zrow draws solid 3D on microcontrollers that cannot hold a frame buffer, let alone a
//! z-buffer. For each row it keeps only `depth[x]` and `intensity[x]`, resolves visibility with
//! an edge table, an active list and incremental depth, and hands the finished row to a
//! [`RowSink`] (a display, a simulator, memory).
//!
//! ```
//! use zrow::{Config, Face, FrameBuffer, Mesh, Q16_16, Scanline, ScreenScene, Vec3};
//! use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
//!
//! // Two triangles that pierce each other (z = depth, smaller is nearer), moved half a pixel
//! // so that pixel (3, 1)'s centre is the point (3, 1) where s1 is in front.
//! let q = |x: f32, y: f32, z: f32| Vec3::<Q16_16>::from_f32([x + 0.5, y + 0.5, z]).unwrap();
//! let vertices = [
//!     q(0.0, 0.0, 6.0), q(6.0, 0.0, 0.0), q(0.0, 6.0, 0.0), // s1
//!     q(2.0, 0.0, 6.0), q(6.0, 0.0, 6.0), q(4.0, 4.0, 0.0), // s2
//! ];
//! let faces = [
//!     Face { indices: &[0u16, 1, 2], color: Rgb565::RED, alpha: 255 },
//!     Face { indices: &[3, 4, 5], color: Rgb565::GREEN, alpha: 255 },
//! ];
//! let scene = ScreenScene { mesh: Mesh::new(&vertices, &faces) };
//!
//! // Capacities: 8-pixel rows, 8 vertex slots, 2 polygons, 2 polygons active in a row
//! // (`zrow::requirements` measures what a scene needs).
//! let mut renderer = Scanline::<Q16_16, 8, 8, 2, 2>::new();
//! let mut pixels = [Rgb565::BLACK; 8 * 8];
//! let mut frame = FrameBuffer::new(&mut pixels, 8);
//! renderer.render(&scene, &Config::screen(8, 8), &mut frame).unwrap();
//! assert_eq!(frame.pixel(3, 1), Some(Rgb565::RED)); // s1 is in front at (3, 1)
//! ```
//!
//! The pipeline, in the order a frame goes through it (the modules below, in that order):
//!
//! 1. [`number`]: the number formats ([`Q16_16`], [`Q24_8`], `f32`) behind [`Scalar`], with
//!    exact rounding rules; [`math`]: vectors and affine transforms in any of them.
//! 2. [`scene`]: meshes, objects, camera and light ([`ModelScene`]), or polygons already in
//!    screen space ([`ScreenScene`]; [`SnappedScene`] if their vertices are snapped too, which
//!    the scan-line method then reads where they are, keeping no copy).
//! 3. [`geometry`]: every vertex transformed, projected and snapped once, back faces culled by
//!    their snapped winding ([`backface`]), the rest clipped to the view and the guard band
//!    and lit: flat, or smooth from normals at the vertices ([`shading`], also the depth
//!    cue).
//! 4. [`raster`]: the exact edge walk and its top-left fill rule, the polygons' outlines and
//!    depth planes.
//! 5. A hidden-surface method behind [`Renderer`]: the scan-line method ([`scanline`],
//!    Foley & van Dam §15.6; Sutherland, Sproull & Schumacker 1974) by default, or the
//!    z-buffer, its tiled 16-bit variant, depth sort (Newell, Newell & Sancha 1972), Warnock's
//!    subdivision (1969), the BSP tree (Fuchs, Kedem & Naylor 1980), the A-buffer (Carpenter
//!    1984), culling or ordering alone.
//! 6. [`sink`]: finished rows, top to bottom, to a [`RowSink`]: memory ([`FrameBuffer`]), any
//!    embedded-graphics display ([`DrawTargetSink`]), an SPI panel; or the whole frame as an
//!    embedded-graphics `Drawable` ([`Drawing`]).
//!    [`lines`] turns a frame of facets ([`shading::Shading::Facets`]) into a hidden-line
//!    drawing on its way to one.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

/// Back-face culling (the normal test), a stage any method can use.
pub mod backface;
/// Typed errors.
pub mod error;
/// Transform, cull, clip, project, snap.
pub mod geometry;
/// Hidden-line drawings from a frame of facets, row by row (the `lines` feature, default).
#[cfg(feature = "lines")]
pub mod lines;
/// Vectors and affine transforms in any format.
pub mod math;
/// The interface every hidden-surface method implements.
pub mod method;
/// Number formats: [`Q16_16`], [`Q24_8`] and `f32` behind one trait.
pub mod number;
/// The polygon table methods that revisit polygons keep, with exact sample queries.
pub mod polygons;
/// Named configurations trading speed for accuracy.
pub mod presets;
/// Snapped polygons, the exact edge walk, polygon setup.
pub mod raster;
/// Capacities a scene needs.
pub mod requirements;
/// Meshes, objects, camera, light; screen-space scenes.
pub mod scene;
/// Depth cueing: intensity by distance, affine or perspective-correct.
pub mod shading;
/// Where rows go.
pub mod sink;
/// What a mesh's structure allows (one closed convex solid?).
pub mod structure;

// The methods, one file each, all behind [`Renderer`].
/// Transparency in the A-buffer spirit: translucent faces blended per row.
pub mod abuffer;
/// The BSP tree: built with splitting, traversed in view order.
pub mod bsp;
/// A precomputed BSP order over whole convex objects: for static scenes, no split, no depth.
pub mod bsporder;
/// Back-face culling alone: exact for one closed convex solid.
pub mod cullonly;
/// Depth-sort (Newell's painter): sort, the five tests, split.
pub mod depthsort;
/// Ordering alone: exact where polygons overlapping on screen never overlap in depth.
pub mod ordered;
/// The scan-line method: one row at a time, an edge table and an active list.
pub mod scanline;
/// Polygons split by another's plane, exactly (depth-sort and BSP share it).
pub mod split;
/// The tiled 16-bit z-buffer: one band of rows at a time.
pub mod tiled;
/// Warnock's area subdivision.
pub mod warnock;
/// The z-buffer: a depth and a colour for every pixel of the frame.
pub mod zbuffer;

/// The colour types zrow names (from `embedded-graphics-core`), so that code using zrow, and
/// the Rust a converter emits (`zrow::Rgb565::new(…)`), need no other crate.
pub use embedded_graphics_core::pixelcolor;
pub use embedded_graphics_core::pixelcolor::Rgb565;
pub use error::{Error, RenderError, Table};
pub use math::{Affine, MathLib, Vec3};
pub use method::{FrameStats, Renderer};
pub use number::{Scalar, Q16_16, Q24_8};
pub use raster::{Config, Cull};
pub use requirements::{requirements, requirements_with, Requirements};
pub use scanline::Scanline;
pub use scene::{
    Camera, Face, Faces, FacesIter, IntensityPlane, Light, Mesh, MeshIndex, ModelScene, Object,
    Projection, Scene, ScreenScene, SnappedScene, Vectors, VectorsIter,
};
pub use sink::{DrawTargetSink, Drawing, FrameBuffer, Row, RowSink};
pub use zbuffer::ZBuffer;

/// The scan-line renderer sized by a [`Requirements`] constant, each capacity taken from its
/// own field — `Scanline<N, {width}, {vertices}, {polygons}, {active_polygons}>` — so that
/// none can be swapped with another. The constant comes from [`requirements()`] (with
/// [`Requirements::max`] over an animation's views and [`Requirements::with_margin`]) or from
/// the converter.
///
/// ```
/// use zrow::{scanline_for, Requirements, Q16_16};
/// const REQ: Requirements = Requirements {
///     polygons: 480, edges: 1344, vertices: 512, active_polygons: 72, width: 240,
/// };
/// type Renderer = scanline_for!(Q16_16, REQ);
/// assert_eq!(Renderer::RAM_BYTES, core::mem::size_of::<zrow::Scanline<Q16_16, 240, 512, 480, 72>>());
/// ```
///
/// `scanline_for!(N, REQ, uncued)` is the same without the affine depth cue's per-edge state
/// ([`scanline::Uncued`]: 20 bytes less per active slot in a 32-bit format), for a renderer
/// that draws flat-shaded or with the perspective-correct cue only.
///
/// `scanline_for!(N, REQ, display)` is `uncued` without a depth row either
/// ([`scanline::NoDepth`]: a row's width of depths and 64 bytes less in a 32-bit format), for a
/// renderer whose sink takes colours only, as a display's does, drawing flat-shaded: a sink
/// that reads depth, or the perspective-correct cue (whose factor comes from the depth row), is
/// then [`Error::Unsupported`], and rows of heavy overlap are swept like the others instead of
/// being resolved against a depth row. Its polygon records keep their corners in 12 bits
/// ([`scanline::Slot12`]: 2 bytes less a polygon), so its vertex capacity is at most 4,096
/// (a larger one does not build; name the type with `u16` slots instead).
/// [`scanline::ram_bytes_display`] is its size.
///
/// `scanline_for!(N, REQ, gouraud)` draws smooth shading
/// ([`Shading::Gouraud`](shading::Shading::Gouraud)): uncued, with an intensity plane per
/// polygon ([`scanline::ShadeStore`]; 24 bytes a polygon in a 32-bit format,
/// [`scanline::ram_bytes_gouraud`]). The others refuse a smooth-shaded frame with
/// [`Error::Unsupported`].
#[macro_export]
macro_rules! scanline_for {
    ($n:ty, $req:expr) => {
        $crate::scanline_for!(@ $n, $req,)
    };
    ($n:ty, $req:expr, uncued) => {
        $crate::scanline_for!(@ $n, $req, u16, $crate::scanline::Uncued)
    };
    ($n:ty, $req:expr, display) => {
        $crate::scanline::Display<
            $n,
            { $req.width as usize },
            { $req.vertices as usize },
            { $req.polygons as usize },
            { $req.active_polygons as usize },
        >
    };
    ($n:ty, $req:expr, gouraud) => {
        $crate::scanline_for!(
            @ $n,
            $req,
            u16,
            $crate::scanline::Uncued,
            [$crate::scene::IntensityPlane<$n>; $req.polygons as usize]
        )
    };
    // The capacities from `$req`, then the slot, cue and shade parameters given.
    (@ $n:ty, $req:expr, $($rest:ty),*) => {
        $crate::Scanline<
            $n,
            { $req.width as usize },
            { $req.vertices as usize },
            { $req.polygons as usize },
            { $req.active_polygons as usize },
            $($rest),*
        >
    };
}

/// Includes a mesh a build script generated, so a converted model becomes `static` data in
/// flash: `include_mesh!("name")` expands to
/// `include!(concat!(env!("OUT_DIR"), "/", "name", ".rs"))`.
///
/// The build script (a model converter run from `build.rs`) writes `$OUT_DIR/name.rs`: Rust
/// items such as a vertex array, a face array with `u8`, `u16` or `u32` indices ([`scene::MeshIndex`]),
/// optionally one normal per face, and a `static` [`Mesh`] built with the `const fn`s
/// [`Mesh::new`] or [`Mesh::with_normals`]. The generated code names everything by full path
/// (`zrow::Mesh`, `zrow::Q16_16::from_bits`, ...), since it lands wherever the macro is
/// invoked. Invoke it at module level (the file holds items); the items keep the names the
/// script gave them.
///
/// The example is not compiled as a doctest: `OUT_DIR` exists only for a package with a build
/// script, which a doctest is not.
///
/// ```ignore
/// // build.rs wrote $OUT_DIR/teapot.rs, holding e.g.
/// //   pub static TEAPOT_VERTICES: [zrow::Vec3<zrow::Q16_16>; 26] = [..];
/// //   pub static TEAPOT_FACES: [zrow::Face<'static, u8>; 48] = [..];
/// //   pub static TEAPOT: zrow::Mesh<'static, zrow::Q16_16, u8> =
/// //       zrow::Mesh::new(&TEAPOT_VERTICES, &TEAPOT_FACES);
/// zrow::include_mesh!("teapot");
///
/// let object = zrow::Object { mesh: &TEAPOT, transform: zrow::Affine::identity() };
/// ```
#[macro_export]
macro_rules! include_mesh {
    ($name:literal) => {
        include!(concat!(env!("OUT_DIR"), "/", $name, ".rs"));
    };
}
