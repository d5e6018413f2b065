//! The one interface every hidden-surface method implements.
//!
//! A method takes a [`Scene`] in a number format `N`, a [`Config`] and a [`RowSink`], and sends
//! the finished rows top to bottom, each once, with `intensity[x]` and `depth[x]`. Methods
//! differ in what they keep between rows (see each one's `RAM_BYTES`) and in how they decide
//! visibility; they agree on every convention (README, Conventions) — coverage (exact top-left rule on
//! the snapped vertices), depth planes (the same [`crate::number::DepthPlane`] bits) and ties
//! (the polygon first in the scene wins) — so an exact method gives the same picture as any
//! other.
//!
//! ```
//! use zrow::{Config, Face, FrameBuffer, Mesh, Renderer, ScreenScene, Vec3, ZBuffer, Scanline};
//! use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
//!
//! fn draw<R: Renderer<f32>>(r: &mut R, scene: &ScreenScene<'_, f32>) -> [Rgb565; 64] {
//!     let mut pixels = [Rgb565::BLACK; 64];
//!     r.render(scene, &Config::screen(8, 8), &mut FrameBuffer::new(&mut pixels, 8)).unwrap();
//!     pixels
//! }
//! let v = [Vec3::new(0.0f32, 0.0, 1.0), Vec3::new(8.0, 0.0, 1.0), Vec3::new(0.0, 8.0, 1.0)];
//! let faces = [Face::new(&[0, 1, 2], Rgb565::RED)];
//! let scene = ScreenScene { mesh: Mesh::new(&v, &faces) };
//! let a = draw(&mut Scanline::<f32, 8, 4, 1, 1>::new(), &scene);
//! let b = draw(&mut ZBuffer::<f32, 8, 8>::new(), &scene);
//! assert_eq!(a, b);
//! ```

use crate::error::RenderError;
use crate::number::Scalar;
use crate::raster::Config;
use crate::scene::Scene;
use crate::sink::RowSink;

/// What a frame cost, for benchmarks and tests. Each method fills in what applies to it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Polygons in the polygon table (after culling, on screen).
    pub polygons: u32,
    /// Edges in the edge table.
    pub edges: u32,
    /// Most polygons active in one row (scan-line).
    pub max_active: u32,
    /// Times a row's front polygon was sought among the open ones where spans overlap
    /// (scan-line; a span that meets no other is painted without a search, and not counted).
    pub front_changes: u32,
    /// Of those, how many were at an intersection (scan-line).
    pub crossings: u32,
    /// Pieces created by splitting a polygon by another's plane (depth-sort, BSP).
    pub splits: u32,
    /// Areas examined (Warnock), tiles or bands filled (tiled z-buffer).
    pub areas: u32,
}

/// A hidden-surface method: renders a scene and sends its rows, top to bottom, to a sink.
///
/// Errors in the scene or the configuration — including any capacity the scene exceeds —
/// are returned before the first row is sent, so a failed frame never corrupts what the sink
/// already shows.
pub trait Renderer<N: Scalar> {
    /// The method's name, as `zrow-sim render --algo` spells it.
    const NAME: &'static str;
    /// Bytes of RAM the renderer occupies (all its tables and buffers).
    const RAM_BYTES: usize;
    /// Renders `scene` under `cfg` into `sink`.
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>>;
}
