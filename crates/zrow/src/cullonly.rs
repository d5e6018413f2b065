//! Back-face culling alone (Foley, van Dam, Feiner & Hughes §15.2.4): for a single closed convex
//! object it is the whole of hidden-surface removal.
//!
//! The argument: a face whose outward normal points away from the viewer is hidden by
//! the object itself; for a closed **convex** object every face that points towards the viewer
//! is visible, whole, and no two of them overlap on the screen. So once back faces are culled
//! ([`Config::cull`] = [`Cull::Back`](crate::Cull::Back)), painting the front faces in any
//! order draws the visible surface: no depth comparison, no depth buffer, no sort.
//!
//! **Exact** when no two polygons that survive culling share a sample: then each sample is
//! painted by at most one polygon, the one any exact method shows. Two adjacent front faces
//! share an edge, and the top-left rule gives each sample on it to exactly one of them (their
//! snapped vertices are the same), so a closed convex mesh qualifies under any view.
//! [`crate::structure::closed_convex`] tells whether a mesh is one. On any other scene the
//! picture is that of a painter in scene order (later polygons over earlier ones) — not an
//! error, but not exact either; choose it only where the structure allows
//! (`zrow-sim`'s `auto` does).
//!
//! The rows carry depth when the sink reads it ([`RowSink::WANTS_DEPTH`]): each painted pixel's
//! depth is its polygon's plane stepped along the span (one addition a pixel), never compared.
//! A sink that shows colours only gets an empty depth row, and no depth is computed.
//!
//! RAM ([`CullOnly::RAM_BYTES`](crate::cullonly::CullOnly::RAM_BYTES)): the polygon table (`P` polygons, `E` edges) and one row of
//! colour and depth. Rows leave top to bottom; every capacity error comes before the first.
//!
//! [`Row`]: crate::sink::Row
//! [`Config::cull`]: crate::raster::Config::cull

use crate::error::RenderError;
use crate::method::{FrameStats, Renderer};
use crate::number::Scalar;
use crate::polygons::{paint_in_order, PolygonTable};
use crate::raster::Config;
use crate::scene::Scene;
use crate::sink::RowSink;
use embedded_graphics_core::pixelcolor::Rgb565;

/// The cull-only renderer: rows of `W` pixels, `P` polygons, `E` edges.
pub struct CullOnly<N: Scalar, const W: usize, const P: usize, const E: usize> {
    table: PolygonTable<N, P, E>,
    depth: [N; W],
    intensity: [Rgb565; W],
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize> Default for CullOnly<N, W, P, E> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize> CullOnly<N, W, P, E> {
    /// Bytes of RAM the renderer occupies.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer.
    pub const fn new() -> Self {
        CullOnly {
            table: PolygonTable::new(),
            depth: [N::ZERO; W],
            intensity: [Rgb565::new(0, 0, 0); W],
        }
    }

    /// Renders `scene` and sends its rows, top to bottom, to `sink`.
    pub fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        cfg.validate(W)?;
        self.table.build(scene, cfg, false, K::WANTS_DEPTH)?;
        let cue = crate::shading::Cue::for_rows(scene, cfg)?;
        let stats = FrameStats {
            polygons: self.table.len() as u32,
            edges: self.table.edge_count() as u32,
            ..FrameStats::default()
        };
        paint_in_order(
            &self.table,
            0..self.table.len(),
            cfg,
            &cue,
            &mut self.depth,
            &mut self.intensity,
            sink,
        )
        .map_err(RenderError::Sink)?;
        Ok(stats)
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize> Renderer<N>
    for CullOnly<N, W, P, E>
{
    const NAME: &'static str = "cull-only";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        CullOnly::render(self, scene, cfg, sink)
    }
}
