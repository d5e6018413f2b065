//! The scan-line method (seed 000 §2.2.2), made exact and fast.
//!
//! The seeds' algorithm: for each scan line, set `depth[x]` to the maximum and `intensity[x]` to
//! the background; for each polygon crossing the line and each pixel inside it, compute the
//! polygon's depth z and keep it where `z < depth[x]`; hand the finished row on. Depth moves
//! incrementally: `z −= A/C` one pixel right, `z += (A/m + B)/C` one row down an edge.
//!
//! Here, as in the seeds and Foley §15.6:
//!
//! - a **polygon table** holds each polygon's depth plane and colour;
//! - an **edge table** holds every edge that crosses a sample row, sorted by its first row (a
//!   sorted array with a cursor is the bucket list without the pointers);
//! - an **active list** holds the polygons the current row crosses, each with its current left
//!   and right edge stepped exactly (`x += 1/m`, see [`crate::raster::Dda`]) and its depth at
//!   its left end, stepped down the edge by `dzdy + dzdx·Δx` — the seeds' `(A/m + B)/C` with the
//!   pixel steps the edge actually takes, so it equals the plane at every pixel centre;
//! - **span coherence** (seed 000, the three cases): where one polygon is in front at both
//!   ends of its overlap with another it is in front throughout (depths are linear in x, so
//!   their difference cannot change sign in between). The row is filled from a *front*
//!   polygon with no per-pixel depth test up to the first column where another open polygon
//!   overtakes it — their intersection (case 3), found exactly by bisection — or it closes, or
//!   a newcomer opens in front of it. Work follows the visible changes along the row, not the
//!   pixels and not the polygons hidden behind the front.
//!
//! Ties go to the polygon that comes first in the scene (GUIDE §1): the winner is the least
//! `(depth, scene order)`. In Q16.16 depths step by wrapping integer additions, which equal the
//! direct plane evaluation bit for bit, so every span decision equals the per-pixel test
//! exactly (the property tests check this against an exact reference).
//!
//! Every capacity is checked while the tables are built, before the first row is sent.

use crate::error::{Error, RenderError, Table};
use crate::geometry::shade;
use crate::method::{FrameStats, Renderer};
use crate::number::{DepthPlane, Scalar};
use crate::raster::{setup, Config, Dda, Edge, Side};
use crate::requirements::Requirements;
use crate::scene::Scene;
use crate::shading::{Cue, Interpolation};
use crate::sink::{Row, RowSink};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use heapless::binary_heap::{BinaryHeap, Min};
use heapless::Vec;

const NONE: u16 = u16::MAX;

/// One entry of the polygon table.
#[derive(Clone, Copy, Debug)]
struct PolygonEntry<N> {
    plane: DepthPlane<N>,
    color: Rgb565,
    first_row: i16,
    last_row: i16,
    /// Position in the active list, or `NONE`.
    slot: u16,
}

/// One entry of the active list: a polygon crossing the current row and its two edges.
#[derive(Clone, Copy, Debug)]
struct Active<N> {
    left: Dda,
    right: Dda,
    /// Depth at the centre of pixel `xl` of the current row.
    z_left: N,
    dzdx: N,
    dzdy: N,
    /// This row's span: `xl..xr` (unclamped; may be empty).
    xl: i32,
    xr: i32,
    left_last: i16,
    right_last: i16,
    last_row: i16,
    poly: u16,
    color: Rgb565,
    fresh: bool,
    /// Affine depth cue only: the factor where the left and right edges cross this row, and
    /// its change per row down each edge (Gouraud).
    cue_left: N,
    cue_left_dy: N,
    cue_right: N,
    cue_right_dy: N,
}

/// The scan-line renderer.
///
/// - `N`: number format ([`crate::Q16_16`] or `f32`);
/// - `W`: row capacity (the widest frame, in pixels);
/// - `P`: polygon-table capacity; `E`: edge-table capacity; `A`: active-list capacity
///   (polygons in one row).
///
/// Choose the capacities with [`crate::requirements()`]. All memory is in the struct:
/// [`Scanline::RAM_BYTES`] is the whole of it.
pub struct Scanline<N, const W: usize, const P: usize, const E: usize, const A: usize> {
    polygons: Vec<PolygonEntry<N>, P>,
    edges: Vec<Edge, E>,
    active: Vec<Active<N>, A>,
    /// Polygons covering the current piece of the row, by the column where their span ends.
    open: BinaryHeap<(i32, u16), Min, A>,
    /// Scratch for [`Self::max_active`]: last rows of the polygons counted so far.
    last_rows: Vec<i16, A>,
    depth: [N; W],
    intensity: [Rgb565; W],
    /// This frame's depth cue, if shading is not flat.
    cue: Option<Cue<N>>,
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const A: usize> Default
    for Scanline<N, W, P, E, A>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const A: usize>
    Scanline<N, W, P, E, A>
{
    /// Bytes of RAM the renderer occupies (all its tables and row buffers).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer.
    pub const fn new() -> Self {
        const {
            assert!(P < NONE as usize, "polygon capacity must be below 65535");
            assert!(A < NONE as usize, "active capacity must be below 65535");
        }
        Scanline {
            polygons: Vec::new(),
            edges: Vec::new(),
            active: Vec::new(),
            open: BinaryHeap::new(),
            last_rows: Vec::new(),
            // All zero, so a `static` renderer lands in .bss, not copied from flash; both rows
            // are rewritten in full before each is sent.
            depth: [N::ZERO; W],
            intensity: [Rgb565::BLACK; W],
            cue: None,
        }
    }

    /// Renders `scene` and sends its rows, top to bottom, to `sink`.
    ///
    /// Errors in the scene or the configuration — including any capacity the scene exceeds —
    /// are returned before the first row is sent.
    pub fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        let mut stats = self.prepare(scene, cfg)?;
        self.run_rows(cfg, sink, &mut stats)
            .map_err(RenderError::Sink)?;
        Ok(stats)
    }

    /// Builds the polygon and edge tables and checks the active-list capacity.
    fn prepare(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
    ) -> Result<FrameStats, Error> {
        cfg.validate(W)?;
        self.cue = Cue::for_frame(scene, cfg)?;
        self.polygons.clear();
        self.edges.clear();
        self.active.clear();
        let (mut polys, mut edges) = (0u32, 0u32);
        let table = &mut self.polygons;
        let edge_table = &mut self.edges;
        scene.polygons(cfg, &mut |poly| {
            let Some(sp) = setup(poly, cfg)? else {
                return Ok(());
            };
            polys += 1;
            edges += sp.edges.len() as u32;
            let index = table.len() as u16;
            let entry = PolygonEntry {
                plane: sp.plane,
                color: sp.color,
                first_row: sp.first_row,
                last_row: sp.last_row,
                slot: NONE,
            };
            // Past a capacity, keep counting so the error can say what the scene needs.
            if table.push(entry).is_ok() {
                for mut e in sp.edges {
                    e.poly = index;
                    if edge_table.push(e).is_err() {
                        break;
                    }
                }
            }
            Ok(())
        })?;
        let over = |table, needed, capacity: usize| Error::Capacity {
            table,
            needed,
            capacity: capacity as u32,
        };
        if polys as usize > P {
            return Err(over(Table::Polygons, polys, P));
        }
        if edges as usize > E {
            return Err(over(Table::Edges, edges, E));
        }
        self.edges
            .sort_unstable_by_key(|e| (e.first_row, e.poly, e.side as u8));
        let max_active = self.max_active()?;
        Ok(FrameStats {
            polygons: polys,
            edges,
            max_active,
            ..FrameStats::default()
        })
    }

    /// Most polygons active in one row, checked against `A`.
    fn max_active(&mut self) -> Result<u32, Error> {
        self.last_rows.clear();
        let mut max = 0;
        for e in &self.edges {
            let p = &mut self.polygons[e.poly as usize];
            if p.slot != NONE {
                continue;
            }
            p.slot = 0; // seen
            let (row, last) = (p.first_row, p.last_row);
            self.last_rows.retain(|&l| l >= row);
            if self.last_rows.push(last).is_err() {
                return Err(Error::Capacity {
                    table: Table::ActivePolygons,
                    needed: self.max_active_exact(),
                    capacity: A as u32,
                });
            }
            max = max.max(self.last_rows.len() as u32);
        }
        for p in self.polygons.iter_mut() {
            p.slot = NONE;
        }
        Ok(max)
    }

    /// The exact maximum by brute force, only when reporting an overflow.
    fn max_active_exact(&self) -> u32 {
        let ps = &self.polygons;
        ps.iter()
            .map(|p| {
                ps.iter()
                    .filter(|q| q.first_row <= p.first_row && p.first_row <= q.last_row)
                    .count() as u32
            })
            .max()
            .unwrap_or(0)
    }

    fn run_rows<K: RowSink<N>>(
        &mut self,
        cfg: &Config,
        sink: &mut K,
        stats: &mut FrameStats,
    ) -> Result<(), K::Error> {
        let s = cfg.subpixel_bits as u32;
        let width = cfg.width as usize;
        let mut cursor = 0;
        for y in 0..cfg.height as i32 {
            // New edges from the edge table.
            while let Some(e) = self
                .edges
                .get(cursor)
                .copied()
                .filter(|e| e.first_row as i32 == y)
            {
                cursor += 1;
                self.activate(&e, y, s);
            }
            // This row's spans, and the depth at each span's left end.
            for a in self.active.iter_mut() {
                let (xl, xr) = (a.left.x, a.right.x);
                if a.fresh {
                    a.z_left = self.polygons[a.poly as usize].plane.at(xl, y);
                    a.fresh = false;
                } else {
                    a.z_left = a.z_left.step(a.dzdx, xl - a.xl).step(a.dzdy, 1);
                }
                a.xl = xl;
                a.xr = xr;
            }
            self.sort_active();
            self.resolve_row(width, cfg.background, stats);
            Cue::shade_row_if_perspective(
                &self.cue,
                &self.depth[..width],
                &mut self.intensity[..width],
            );
            sink.write_row(&Row {
                y: y as u16,
                intensity: &self.intensity[..width],
                depth: &self.depth[..width],
            })?;
            self.advance(y);
        }
        Ok(())
    }

    fn activate(&mut self, e: &Edge, y: i32, s: u32) {
        let (poly, side, dda, last) = (e.poly, e.side, e.dda_at(y, s), e.last_row);
        // Affine cue: the exact factor where the edge crosses its first and last rows, and
        // the linear step between (the seeds' incremental intensity down an edge).
        let (mut cue, mut cue_dy) = (N::ZERO, N::ZERO);
        if let Some(c) = self
            .cue
            .filter(|c| c.interpolation == Interpolation::Affine)
        {
            let plane = &self.polygons[poly as usize].plane;
            // Depth at the crossing: the plane at column x, stepped back by the fraction.
            let on_edge = |d: &Dda, row: i32| {
                c.at_depth(plane.at(d.x, row).sub(plane.dzdx.mul(d.fraction())))
            };
            cue = on_edge(&dda, y);
            let rows = last as i32 - y;
            if rows > 0 {
                let end = on_edge(&e.dda_at(last as i32, s), last as i32);
                let n = N::from_f32(rows as f32).unwrap_or(N::ONE);
                cue_dy = end.sub(cue).div(n).unwrap_or(N::ZERO);
            }
        }
        let entry = &mut self.polygons[poly as usize];
        if entry.slot == NONE {
            let a = Active {
                left: Dda::default(),
                right: Dda::default(),
                z_left: N::ZERO,
                dzdx: entry.plane.dzdx,
                dzdy: entry.plane.dzdy,
                xl: 0,
                xr: 0,
                left_last: -1,
                right_last: -1,
                last_row: entry.last_row,
                poly,
                color: entry.color,
                fresh: true,
                cue_left: N::ZERO,
                cue_left_dy: N::ZERO,
                cue_right: N::ZERO,
                cue_right_dy: N::ZERO,
            };
            // Cannot fail: `max_active` checked the capacity for every row.
            if self.active.push(a).is_err() {
                return;
            }
            entry.slot = (self.active.len() - 1) as u16;
        }
        let a = &mut self.active[entry.slot as usize];
        match side {
            Side::Left => {
                (a.left, a.left_last) = (dda, last);
                (a.cue_left, a.cue_left_dy) = (cue, cue_dy);
            }
            Side::Right => {
                (a.right, a.right_last) = (dda, last);
                (a.cue_right, a.cue_right_dy) = (cue, cue_dy);
            }
        }
    }

    /// Insertion sort by left end (stable): the order barely changes from row to row, but a
    /// polygon entering the list arrives at its end, so each entry out of order is placed by
    /// a binary search of the sorted part and one rotation (a block move), not by swapping
    /// it down one place at a time — with 230 polygons active, that swapping was a third of
    /// the frame.
    fn sort_active(&mut self) {
        let a = &mut self.active;
        let mut moved = false;
        for i in 1..a.len() {
            if a[i - 1].xl > a[i].xl {
                let x = a[i].xl;
                // `a[..i]` is sorted; after the entries at or left of x, as the swaps would.
                let pos = a[..i].partition_point(|e| e.xl <= x);
                a[pos..=i].rotate_right(1);
                moved = true;
            }
        }
        if moved {
            for (i, act) in a.iter().enumerate() {
                self.polygons[act.poly as usize].slot = i as u16;
            }
        }
    }

    /// Retires what ends on row `y` and steps the rest to the next row.
    fn advance(&mut self, y: i32) {
        let mut i = 0;
        while i < self.active.len() {
            let a = &mut self.active[i];
            if a.last_row as i32 <= y {
                self.polygons[a.poly as usize].slot = NONE;
                self.active.swap_remove(i);
                if let Some(moved) = self.active.get(i) {
                    self.polygons[moved.poly as usize].slot = i as u16;
                }
                continue;
            }
            if a.left_last as i32 > y {
                a.left.step();
                a.cue_left = a.cue_left.add(a.cue_left_dy);
            }
            if a.right_last as i32 > y {
                a.right.step();
                a.cue_right = a.cue_right.add(a.cue_right_dy);
            }
            i += 1;
        }
    }

    /// Sweeps the row left to right, filling it from a **front** polygon at a time.
    ///
    /// The seeds' cases 1 and 2 — a polygon in front at both ends of an overlap is in front
    /// throughout, depths being linear in x — applied to whole overlaps: the front beats every
    /// other open polygon from the current column up to `until`, the first column where one of
    /// them wins (their crossing, case 3, found exactly by bisection: the sign of a linear
    /// difference changes once). Until then the row is filled with no depth test. A polygon
    /// that opens costs one check against the front (two depth evaluations, bisection only if
    /// they cross); one that closes behind it costs nothing. The front is sought again among
    /// the open polygons only when it closes, is overtaken at its crossing, or a newcomer is
    /// in front of it — that is, where the visible surface changes.
    ///
    /// The open polygons sit in a min-heap on their span's end (retiring costs O(log n)).
    fn resolve_row(&mut self, width: usize, background: Rgb565, stats: &mut FrameStats) {
        let w = width as i32;
        let affine = self
            .cue
            .is_some_and(|c| c.interpolation == Interpolation::Affine);
        let (active, open) = (&self.active, &mut self.open);
        open.clear();
        let (mut cur, mut k) = (0i32, 0usize);
        // The front polygon and the first column where it may no longer be in front.
        let mut front: Option<(usize, i32)> = None;
        loop {
            while k < active.len() && active[k].xl <= cur {
                if active[k].xr > cur {
                    // Cannot fail: `open` has the active list's capacity.
                    let _ = open.push((active[k].xr, k as u16));
                    if let Some((p, until)) = front {
                        front = challenge(active, p, k, cur).map(|u| (p, until.min(u)));
                    }
                }
                k += 1;
            }
            let next_start = active.get(k).map_or(w, |a| a.xl).min(w);
            if front.is_none() && !open.is_empty() {
                front = Some(match open.len() {
                    // Alone: in front until it closes (the common case on a mesh).
                    1 => (open.peek().map_or(0, |&(_, i)| i as usize), i32::MAX),
                    _ => establish(active, open.iter().map(|&(_, i)| i as usize), cur),
                });
                stats.front_changes += 1;
            }
            let next = match front {
                Some((p, until)) => {
                    let next = next_start.min(active[p].xr).min(until).min(w);
                    fill(&mut self.depth, &mut self.intensity, &active[p], cur, next);
                    if affine {
                        cue_span(&mut self.intensity, &active[p], cur, next);
                    }
                    next
                }
                None => {
                    let (x0, x1) = (cur as usize, next_start as usize);
                    self.intensity[x0..x1].fill(background);
                    self.depth[x0..x1].fill(N::MAX);
                    next_start
                }
            };
            cur = next;
            if cur >= w {
                break;
            }
            while let Some(&(_, i)) = open.peek().filter(|&&(xr, _)| xr <= cur) {
                open.pop();
                if front.is_some_and(|(p, _)| p == i as usize) {
                    front = None;
                }
            }
            if front.is_some_and(|(_, until)| until <= cur) {
                stats.crossings += 1;
                front = None;
            }
        }
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const A: usize> Renderer<N>
    for Scanline<N, W, P, E, A>
{
    const NAME: &'static str = "scanline";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        Scanline::render(self, scene, cfg, sink)
    }
}

#[inline]
fn depth_at<N: Scalar>(a: &Active<N>, x: i32) -> N {
    a.z_left.step(a.dzdx, x - a.xl)
}

/// Affine depth cue across `x0..x1` (already filled with the polygon's colour): the factor
/// interpolated linearly between the edges' crossings of the row (one division per span).
fn cue_span<N: Scalar>(intensity: &mut [Rgb565], a: &Active<N>, x0: i32, x1: i32) {
    let (cl, cr) = (a.left.crossing::<N>(), a.right.crossing::<N>());
    let slope = a
        .cue_right
        .sub(a.cue_left)
        .div(cr.sub(cl))
        .unwrap_or(N::ZERO);
    let at = |x: i32| N::from_f32(x as f32).unwrap_or(N::ZERO);
    let mut f = a.cue_left.add(at(x0).sub(cl).mul(slope));
    for c in &mut intensity[x0 as usize..x1 as usize] {
        *c = shade(*c, f);
        f = f.add(slope);
    }
}

/// Fills `x0..x1` with one polygon, stepping its depth one pixel at a time.
#[inline]
fn fill<N: Scalar>(depth: &mut [N], intensity: &mut [Rgb565], a: &Active<N>, x0: i32, x1: i32) {
    let mut z = depth_at(a, x0);
    let (x0, x1) = (x0 as usize, x1 as usize);
    for d in &mut depth[x0..x1] {
        *d = z;
        z = z.step(a.dzdx, 1);
    }
    intensity[x0..x1].fill(a.color);
}

/// Whether polygon `p` is visible over `q` at column `x`: nearer, or as near and first.
#[inline]
fn beats<N: Scalar>(active: &[Active<N>], p: usize, q: usize, x: i32) -> bool {
    let (zp, zq) = (depth_at(&active[p], x), depth_at(&active[q], x));
    zp < zq || (zp == zq && active[p].poly < active[q].poly)
}

/// How long front `p` holds against `q` from column `x` on: `None` if `q` is in front at `x`,
/// else the first column where `q` wins within the stretch both cover (`i32::MAX` if none).
/// Depths are linear in x, so `p − q` changes sign at most once: check the stretch's far end,
/// then bisect (in Q16.16 exactly: the steps are exact integer arithmetic).
fn challenge<N: Scalar>(active: &[Active<N>], p: usize, q: usize, x: i32) -> Option<i32> {
    if !beats(active, p, q, x) {
        return None;
    }
    let mut hi = active[p].xr.min(active[q].xr) - 1;
    if beats(active, p, q, hi) {
        return Some(i32::MAX);
    }
    let mut lo = x; // p wins at lo, q at hi
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if beats(active, p, q, mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(hi)
}

/// The polygon in front at `x` among `open` (not empty), and the first column where another
/// open polygon overtakes it.
fn establish<N: Scalar>(
    active: &[Active<N>],
    open: impl Iterator<Item = usize> + Clone,
    x: i32,
) -> (usize, i32) {
    let p = winner(active, open.clone(), x);
    let until = open
        .filter(|&q| q != p)
        .filter_map(|q| challenge(active, p, q, x))
        .min()
        .unwrap_or(i32::MAX);
    (p, until)
}

/// The visible polygon at column `x` among `open` (not empty): least depth, then first in the
/// scene.
fn winner<N: Scalar>(active: &[Active<N>], mut open: impl Iterator<Item = usize>, x: i32) -> usize {
    let first = open.next().unwrap_or(0);
    open.fold(first, |b, i| if beats(active, i, b, x) { i } else { b })
}

/// RAM the scan-line renderer needs for a scene with these requirements, in bytes: its tables
/// at exactly the sizes required plus its two rows.
pub fn ram_bytes<N: Scalar>(req: &Requirements) -> usize {
    use core::mem::size_of;
    req.polygons as usize * size_of::<PolygonEntry<N>>()
        + req.edges as usize * size_of::<Edge>()
        + req.active_polygons as usize
            * (size_of::<Active<N>>() + size_of::<(i32, u16)>() + size_of::<i16>())
        + req.width as usize * (size_of::<N>() + size_of::<Rgb565>())
}
