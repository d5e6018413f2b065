//! Ordering alone: the painter's algorithm where depth-sort's first step settles everything,
//! (Newell, Newell & Sancha 1972, step 1: sort by depth; paint far to near).
//!
//! When no two polygons that overlap on the screen overlap in depth, sorting by depth is the
//! whole of hidden-surface removal: painting far to near leaves the nearer of any two
//! overlapping polygons on top. None of depth-sort's five tests is needed, nor any split, nor
//! a depth buffer. Scenes of objects stacked in depth — layers, a board with pieces in front
//! of it, separate convex objects with back faces culled — are like this.
//!
//! **Exact** (every sample shows the polygon any exact method shows, ties included) when the
//! scene satisfies [`Ordered::exact_for`](crate::ordered::Ordered::exact_for): every two polygons that share a sample have
//! disjoint depth ranges over their samples, or touch only at one depth, the polygon first in
//! the scene being nearer. Depth ranges are taken over each polygon's own samples (both ends
//! of every row span; depth is linear along a row), so they are the ranges an exact method
//! compares. Polygons are painted in decreasing order of their least depth, and among equal
//! ones in reverse scene order, so a tie goes to the polygon first in the scene. On a scene
//! that does not satisfy it the picture is a painter's, not an error: check first, as
//! `zrow-sim`'s `auto` does.
//!
//! The rows carry each painted pixel's depth (the plane stepped along the span, never
//! compared). RAM ([`Ordered::RAM_BYTES`](crate::ordered::Ordered::RAM_BYTES)): the polygon table, the order and each polygon's
//! depth range (`P·(2 + 2·size_of::<N>())` bytes more), one row of colour and depth.

use crate::error::RenderError;
use crate::method::{FrameStats, Renderer};
use crate::number::Scalar;
use crate::polygons::{paint_in_order, PolygonTable};
use crate::raster::Config;
use crate::scene::Scene;
use crate::sink::RowSink;
use embedded_graphics_core::pixelcolor::Rgb565;
use heapless::Vec;

/// The ordering renderer: rows of `W` pixels, `P` polygons, `E` edges.
pub struct Ordered<N: Scalar, const W: usize, const P: usize, const E: usize> {
    table: PolygonTable<N, P, E>,
    /// Each polygon's least and greatest depth over its samples (`None`: no sample).
    range: Vec<Option<(N, N)>, P>,
    /// Paint order, farthest first.
    order: Vec<u16, P>,
    depth: [N; W],
    intensity: [Rgb565; W],
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize> Default for Ordered<N, W, P, E> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize> Ordered<N, W, P, E> {
    /// Bytes of RAM the renderer occupies.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer.
    pub const fn new() -> Self {
        Ordered {
            table: PolygonTable::new(),
            range: Vec::new(),
            order: Vec::new(),
            depth: [N::ZERO; W],
            intensity: [Rgb565::new(0, 0, 0); W],
        }
    }

    /// Builds the polygon table, each polygon's depth range and the paint order.
    fn prepare(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        exact: bool,
    ) -> Result<(), crate::Error> {
        cfg.validate(W)?;
        self.table.build(scene, cfg, false, exact)?;
        self.range.clear();
        self.order.clear();
        let t = &self.table;
        for i in 0..t.len() {
            let p = t.get(i);
            let mut r: Option<(N, N)> = None;
            t.walk(i, 0, cfg.height as i32 - 1, |y, xl, xr| {
                let (xl, xr) = (xl.max(0), xr.min(cfg.width as i32));
                if xl < xr {
                    for z in [p.plane.at(xl, y), p.plane.at(xr - 1, y)] {
                        r = Some(match r {
                            None => (z, z),
                            Some((lo, hi)) => {
                                (if z < lo { z } else { lo }, if z > hi { z } else { hi })
                            }
                        });
                    }
                }
                true
            });
            // Cannot fail: the table holds at most P polygons.
            let _ = self.range.push(r);
            let _ = self.order.push(i as u16);
        }
        // Farthest least depth first; among equal ones the later polygon first, so the
        // polygon first in the scene is painted last. `f64::total_cmp` is a total order, so
        // the sort cannot panic whatever the depths.
        let key = |i: u16| {
            self.range
                .get(i as usize)
                .copied()
                .flatten()
                .map(|r| r.0.to_f64())
        };
        self.order.sort_unstable_by(|&a, &b| {
            let (ka, kb) = (key(a).unwrap_or(f64::MAX), key(b).unwrap_or(f64::MAX));
            kb.total_cmp(&ka).then(b.cmp(&a))
        });
        Ok(())
    }

    /// Whether ordering alone draws `scene` exactly under `cfg`: every two polygons that share
    /// a sample have disjoint depth ranges over their samples, or meet at one depth with the
    /// polygon first in the scene the nearer (ties go to it, as in every method). `O(P²)`
    /// pairs, each settled by its ranges and sample boxes before any sample is looked at.
    pub fn exact_for(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
    ) -> Result<bool, crate::Error> {
        self.prepare(scene, cfg, false)?;
        let t = &self.table;
        for a in 0..t.len() {
            for b in a + 1..t.len() {
                let (Some(Some(ra)), Some(Some(rb))) = (self.range.get(a), self.range.get(b))
                else {
                    continue;
                };
                // a comes first in the scene: fine if a is wholly nearer (a tie at one depth
                // included) or b wholly nearer (strictly).
                if ra.1 <= rb.0 || rb.1 < ra.0 {
                    continue;
                }
                if shares_a_sample(t, a, b, cfg.width as i32) {
                    return Ok(false);
                }
            }
        }
        Ok(true)
    }

    /// Renders `scene` and sends its rows, top to bottom, to `sink`.
    pub fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        self.prepare(scene, cfg, K::WANTS_DEPTH)?;
        let cue = crate::shading::Cue::for_rows(scene, cfg)?;
        let stats = FrameStats {
            polygons: self.table.len() as u32,
            edges: self.table.edge_count() as u32,
            ..FrameStats::default()
        };
        paint_in_order(
            &self.table,
            self.order.iter().map(|&i| i as usize),
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

/// Whether polygons `a` and `b` cover a common sample on a screen `width` wide (their sample
/// boxes first).
fn shares_a_sample<N: Scalar, const P: usize, const E: usize>(
    t: &PolygonTable<N, P, E>,
    a: usize,
    b: usize,
    width: i32,
) -> bool {
    let (pa, pb) = (t.get(a), t.get(b));
    if pa.last_row < pb.first_row
        || pb.last_row < pa.first_row
        || pa.last_col < pb.first_col
        || pb.last_col < pa.first_col
    {
        return false;
    }
    let (y0, y1) = (
        pa.first_row.max(pb.first_row) as i32,
        pa.last_row.min(pb.last_row) as i32,
    );
    (y0..=y1).any(|y| {
        let ((al, ar), (bl, br)) = (t.span(a, y), t.span(b, y));
        al.max(bl).max(0) < ar.min(br).min(width)
    })
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize> Renderer<N>
    for Ordered<N, W, P, E>
{
    const NAME: &'static str = "ordered";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        Ordered::render(self, scene, cfg, sink)
    }
}
