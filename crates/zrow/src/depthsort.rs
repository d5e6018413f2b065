//! Depth-sort (Newell, Newell & Sancha's painter's algorithm, 1972; Foley, van Dam, Feiner &
//! Hughes §15.5.1).
//!
//! The algorithm, in three steps: sort the polygons by their farthest depth; resolve
//! the ambiguities where depth extents overlap, splitting polygons where needed; then paint
//! them far to near, so nearer ones overwrite farther ones. For the polygon `P` at the far
//! end of the list and every `Q` whose depth extent overlaps `P`'s, up to five tests, in order
//! of cost, try to show that `P` does not obscure `Q` (so `P` may be painted first):
//!
//! 1. the x extents do not overlap;
//! 2. the y extents do not overlap;
//! 3. `P` is entirely on the far side of `Q`'s plane;
//! 4. `Q` is entirely on the viewer's side of `P`'s plane;
//! 5. the projections do not overlap.
//!
//! If one succeeds for every such `Q`, `P` is painted. If all five fail for some `Q`, the
//! reverse order is tried with tests 3' (`Q` entirely behind `P`'s plane) and 4' (`P`
//! entirely in front of `Q`'s plane); if one succeeds, `Q` moves to the far end of the list
//! and becomes the new `P`. A `Q` that moved once is **marked**: if it comes up again it is
//! not moved (that would loop on a cyclic overlap) — instead `P` is split by `Q`'s plane (or
//! `Q` by `P`'s), the pieces go back into the list in depth order, and the work goes on.
//!
//! Made exact: every test is decided on samples, not on vertices. Extents are the columns,
//! rows and depths of the samples a piece covers; "entirely on one side of a plane" means
//! [`PolygonTable::beats`](crate::polygons::PolygonTable::beats) holds at every sample (checked at both ends of each row's span:
//! the difference of two planes is linear); "projections overlap" means a shared sample.
//! Splits are [`crate::split`] pieces — sample sets, no new vertices — so the pieces partition
//! their polygon exactly. The order found is then right for every pair of pieces that share a
//! sample, and painting it gives exactly the per-sample nearest surface, ties included.
//!
//! When `Q` is marked and neither `P` nor `Q` straddles the other's plane, no split by their
//! planes helps (three polygons in cyclic overlap can be like that pairwise); then a piece of
//! the moved chain (the cycle is among them) that straddles another's plane is split. Every
//! split makes pieces with fewer samples and every move marks a piece, so the loop ends; the
//! piece table's capacity `Q` bounds the work, and running out is a typed error, raised before
//! any row is sent.
//!
//! Rows then leave top to bottom: each row is painted from the ordered pieces into one row
//! buffer (the painter's algorithm needs no frame buffer when done a row at a time). RAM is
//! the polygon table, the piece table, the list and order (`Q` entries each) and one row.

use crate::error::{Error, RenderError, Table};
use crate::method::{FrameStats, Renderer};
use crate::number::Scalar;
use crate::polygons::PolygonTable;
use crate::raster::Config;
use crate::scene::Scene;
use crate::sink::RowSink;
use crate::split::{paint_rows, Pieces};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use heapless::Vec;

/// The depth-sort renderer: rows of `W` pixels, `P` polygons, `E` edges, `Q` pieces
/// (polygons plus the parts splitting makes).
pub struct DepthSort<N: Scalar, const W: usize, const P: usize, const E: usize, const Q: usize> {
    table: PolygonTable<N, P, E>,
    pieces: Pieces<N, Q>,
    /// The list, sorted by greatest depth with the farthest last, then the pieces that moved.
    list: Vec<u16, Q>,
    /// Paint order, farthest first.
    order: Vec<u16, Q>,
    marked: [bool; Q],
    depth: [N; W],
    intensity: [Rgb565; W],
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const Q: usize> Default
    for DepthSort<N, W, P, E, Q>
{
    fn default() -> Self {
        Self::new()
    }
}

/// What to do about the far-end piece `P`.
enum Step {
    /// Move the piece at this list position to the far end.
    Move(usize),
    /// Split this piece by that polygon's plane.
    Split(u16, u16),
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const Q: usize>
    DepthSort<N, W, P, E, Q>
{
    /// Bytes of RAM the renderer occupies.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer.
    pub const fn new() -> Self {
        const { assert!(Q < u16::MAX as usize, "piece capacity must be below 65535") };
        DepthSort {
            table: PolygonTable::new(),
            pieces: Pieces::new(),
            list: Vec::new(),
            order: Vec::new(),
            marked: [false; Q],
            depth: [N::ZERO; W],
            intensity: [Rgb565::BLACK; W],
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
        self.sort(cfg.width as i32)?;
        let cue = crate::shading::Cue::for_rows(scene, cfg)?;
        let stats = FrameStats {
            polygons: self.table.len() as u32,
            edges: self.table.edge_count() as u32,
            splits: self.pieces.splits,
            ..FrameStats::default()
        };
        paint_rows(
            &self.table,
            &self.pieces,
            &self.order,
            cfg,
            &cue,
            &mut self.depth,
            &mut self.intensity,
            sink,
        )
        .map_err(RenderError::Sink)?;
        Ok(stats)
    }

    /// Steps 1 and 2: the sort and the resolution of ambiguities, into `self.order`.
    fn sort(&mut self, w: i32) -> Result<(), Error> {
        let full = || Error::Capacity {
            table: Table::Pieces,
            needed: Q as u32 + 1,
            capacity: Q as u32,
        };
        self.pieces.clear();
        self.list.clear();
        self.order.clear();
        self.marked = [false; Q];
        for i in 0..self.table.len() {
            if let Some(k) = self.pieces.whole(&self.table, w, i as u16)? {
                self.list.push(k).map_err(|_| full())?;
            }
        }
        let pieces = &self.pieces;
        self.list
            .sort_unstable_by(|&a, &b| zmax_cmp(pieces.get(a).zmax, pieces.get(b).zmax));
        // list[..sorted] is in depth order; pieces that moved sit after it.
        let mut sorted = self.list.len();
        let mut forced = 0usize;
        while let Some(&p) = self.list.last() {
            match self.next_step(p, sorted, w) {
                None => {
                    self.list.pop();
                    sorted = sorted.min(self.list.len());
                    self.order.push(p).map_err(|_| full())?;
                }
                Some(Step::Move(j)) => {
                    let q = self.list.remove(j);
                    if j < sorted {
                        sorted -= 1;
                    }
                    if self.marked[q as usize] {
                        // A forced move (no split found): bounded, so it cannot loop.
                        forced += 1;
                        if forced > Q {
                            return Err(full());
                        }
                    }
                    self.marked[q as usize] = true;
                    // Cannot fail: one was just removed.
                    let _ = self.list.push(q);
                }
                Some(Step::Split(k, by)) => {
                    let (near, far) = self.pieces.split(&self.table, k, by, w)?;
                    let at = self.list.iter().position(|&x| x == k).unwrap_or(0);
                    self.list.remove(at);
                    if at < sorted {
                        sorted -= 1;
                    }
                    for part in [near, far].into_iter().flatten() {
                        let z = self.pieces.get(part).zmax;
                        let pieces = &self.pieces;
                        let pos = self.list[..sorted]
                            .partition_point(|&x| zmax_cmp(pieces.get(x).zmax, z).is_le());
                        self.list.insert(pos, part).map_err(|_| full())?;
                        sorted += 1;
                    }
                }
            }
        }
        Ok(())
    }

    /// Tests the far-end piece `p` against every piece whose depth extent overlaps it.
    fn next_step(&self, p: u16, sorted: usize, w: i32) -> Option<Step> {
        let n = self.list.len();
        let pp = *self.pieces.get(p);
        for j in (0..n - 1).rev() {
            let q = self.list[j];
            let pq = self.pieces.get(q);
            if pq.zmax < pp.zmin {
                if j < sorted {
                    break; // sorted: every earlier piece is nearer still
                }
                continue;
            }
            if self.precedes(p, q, w) {
                continue;
            }
            // Q obscures P: can Q be painted first instead (tests 3' and 4')?
            let q_first = self.side(q, p, w, false) || self.side(p, q, w, true);
            if !self.marked[q as usize] && q_first {
                return Some(Step::Move(j));
            }
            return Some(self.choose_split(p, q, j, sorted, w));
        }
        None
    }

    /// Tests 1–5: `P` (`p`) does not obscure `Q` (`q`), so `P` may be painted first.
    fn precedes(&self, p: u16, q: u16, w: i32) -> bool {
        let (a, b) = (self.pieces.get(p), self.pieces.get(q));
        a.last_col < b.first_col
            || b.last_col < a.first_col
            || a.last_row < b.first_row
            || b.last_row < a.first_row
            || self.side(p, q, w, false)
            || self.side(q, p, w, true)
            || !self.pieces.overlap(&self.table, p, q, w)
    }

    /// Whether every sample of piece `k` is on one side of piece `o`'s polygon's plane: the
    /// viewer's side (`k` beats `o` there) if `near`, else the far side.
    fn side(&self, k: u16, o: u16, w: i32, near: bool) -> bool {
        let (pk, po) = (
            self.pieces.get(k).poly as usize,
            self.pieces.get(o).poly as usize,
        );
        let t = &self.table;
        self.pieces
            .all(t, k, w, |x, y| t.beats(pk, po, x, y) == near)
    }

    /// Which piece to split, by which polygon's plane: `P` by `Q`'s if `P` straddles it, else
    /// `Q` by `P`'s; else a moved piece that straddles another's plane; else a forced move.
    fn choose_split(&self, p: u16, q: u16, j: usize, sorted: usize, w: i32) -> Step {
        let straddles = |k: u16, o: u16| !self.side(k, o, w, true) && !self.side(k, o, w, false);
        let poly = |k: u16| self.pieces.get(k).poly;
        if straddles(p, q) {
            return Step::Split(p, poly(q));
        }
        if straddles(q, p) {
            return Step::Split(q, poly(p));
        }
        let moved = &self.list[sorted..];
        for &a in moved {
            for &b in moved {
                if a != b
                    && poly(a) != poly(b)
                    && self.pieces.overlap(&self.table, a, b, w)
                    && straddles(a, b)
                {
                    return Step::Split(a, poly(b));
                }
            }
        }
        // Neither straddles, and tests 3 and 4 failed: so P is wholly in front of Q's plane
        // (4') — Q may go first. Moving a marked piece again is counted and bounded.
        Step::Move(j)
    }
}

fn zmax_cmp<N: Scalar>(a: N, b: N) -> core::cmp::Ordering {
    a.partial_cmp(&b).unwrap_or(core::cmp::Ordering::Equal)
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const Q: usize> Renderer<N>
    for DepthSort<N, W, P, E, Q>
{
    const NAME: &'static str = "depth-sort";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        DepthSort::render(self, scene, cfg, sink)
    }
}
