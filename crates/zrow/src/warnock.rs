//! Warnock's area subdivision (Warnock 1969; Foley, van Dam, Feiner & Hughes §15.7.1).
//!
//! The algorithm: a polygon is **surrounding**, **intersecting**, **contained** in or
//! **disjoint** from an area of the screen, as the min-max (bounding box), intersection and
//! containment tests find. An area's potentially-visible polygon list (PVPL) holds the
//! non-disjoint ones sorted by `zmin`, their least depth in the area; a polygon `P` with
//! `z_pmin > z_smax` (the greatest depth of a surrounding `S` in the area) is hidden by `S`, and
//! so is every polygon after it. Then: (a) an empty list is background;
//! (b) one intersecting or contained polygon: background, then its part scan-converted; (c) one
//! surrounding polygon fills the area; (d) at one pixel, the polygon nearest at its centre;
//! (the fourth case) a surrounding polygon in front of all others at the area's four
//! corners fills it; otherwise the area is cut in four and each quarter goes back to the list
//! step. Surrounding and disjoint polygons stay so in sub-areas; only the others are
//! classified again.
//!
//! **Streaming.** Rows must leave top to bottom, so the top levels of the quadtree are replaced
//! by a raster order: the screen is cut into bands of `B` rows, each band into `B`×`B` squares
//! left to right (the last clipped by the screen's edges), and each square is subdivided
//! quadtree fashion down to single pixels, in a band buffer whose rows are sent when the band
//! is done. A band keeps the list of polygons reaching its rows; each area pushes its PVPL on
//! its parent's in one stack ([`Table::VisibleList`]) and pops it on return.
//!
//! **Made exact** (every pixel is the per-sample nearest polygon, ties included). An area is a
//! rectangle of pixels; its samples are their centres. Coverage is the top-left rule as integer
//! edge functions ([`PolygonTable::covers`](crate::polygons::PolygonTable::covers)), each linear, plus a row range, so the covered
//! samples are a convex set and the area's four **corner samples** decide: all four covered ⇒
//! every sample covered (surrounding); one edge or the row range excluding all four ⇒ none
//! (disjoint); the sample box (`first_col..=last_col` × `first_row..=last_row`) outside the
//! area ⇒ disjoint (min-max), inside ⇒ contained; else intersecting — conservatively, as it may
//! still miss every sample: at one pixel the four corners are its centre and the test is exact.
//! Depth is linear too, so a plane's extremes over a rectangle are at its corners, and `S`
//! beats `Q` ([`PolygonTable::beats`](crate::polygons::PolygonTable::beats): nearer, or as near and first in the scene) at every
//! sample of a rectangle if it does at its corners (the difference of two planes is linear).
//! `Q` is compared on the area clipped to its sample box, which holds all it covers. The hidden
//! test keeps ties the same way: `P` goes when `(zmin_P, P) > (zmax_S, S)` in (depth, scene
//! order), the list's sort order.
//!
//! In Q16.16 a plane's depth wraps modulo 2^32 LSB out of range ([`Scalar::step`]), so far from
//! a steep polygon the stored bits are not linear. Each frame every polygon's depths at its
//! sample box's corners are checked to lie on one line (exactly, in `f64`; a wrap is 65536
//! off). Then its depth is exactly linear over the box, which holds every rectangle it is
//! compared on; a polygon that fails never takes part in a decision on depth before the pixel
//! level. f32 never wraps, but rounds: area decisions equal the per-pixel test except within
//! rounding of a tie.
//!
//! **Capacity.** The stack holds a band list and at most `log2(B) + 1` area lists, each a subset
//! of it: a band reached by `n` polygons needs at most `n·(log2(B) + 2)` entries. The worst band
//! is found before the first row is sent; more than `L` is [`Error::Capacity`]
//! ([`Table::VisibleList`]), and nothing can fail later. RAM ([`Warnock::RAM_BYTES`](crate::warnock::Warnock::RAM_BYTES)): the
//! polygon table, `B` rows of colour and depth (`B·W·(2 + size_of::<N>())` bytes), `L` list
//! entries of 8 bytes and a flag per polygon.
//!
//! ```
//! use zrow::warnock::Warnock;
//! use zrow::{Config, Face, FrameBuffer, Mesh, Q16_16, ScreenScene, Vec3, ZBuffer};
//! use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
//!
//! let q = |x: f32, y: f32, z: f32| Vec3::<Q16_16>::from_f32([x, y, z]).unwrap();
//! let vertices = [
//!     q(0.0, 0.0, 6.0), q(16.0, 0.0, 0.0), q(0.0, 16.0, 0.0),
//!     q(4.0, 0.0, 6.0), q(16.0, 0.0, 6.0), q(8.0, 12.0, 0.0),
//! ];
//! let faces = [Face::new(&[0, 1, 2], Rgb565::RED), Face::new(&[3, 4, 5], Rgb565::GREEN)];
//! let scene = ScreenScene { mesh: Mesh::new(&vertices, &faces) };
//! let cfg = Config::screen(16, 16);
//! let (mut a, mut b) = ([Rgb565::BLACK; 256], [Rgb565::BLACK; 256]);
//! // Rows of 16 pixels, bands of 4 rows, 2 polygons, 8 edges, 16 list entries.
//! let mut warnock = Warnock::<Q16_16, 16, 4, 2, 8, 16>::new();
//! warnock.render(&scene, &cfg, &mut FrameBuffer::new(&mut a, 16)).unwrap();
//! ZBuffer::<Q16_16, 16, 16>::new().render(&scene, &cfg, &mut FrameBuffer::new(&mut b, 16)).unwrap();
//! assert_eq!(a, b);
//! ```

use crate::error::{Error, RenderError, Table};
use crate::method::{FrameStats, Renderer};
use crate::number::{DepthPlane, Scalar};
use crate::polygons::{paint_span, PolygonTable, Stored};
use crate::raster::{Config, Side};
use crate::scene::Scene;
use crate::sink::{Row, RowSink};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use heapless::Vec;

/// How a polygon stands to an area: covers every sample, its sample box is inside, or
/// anything else not known to miss it (disjoint polygons are never listed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Relation {
    Surrounding,
    Intersecting,
    Contained,
}

/// One entry of a potentially-visible list.
#[derive(Clone, Copy, Debug)]
struct Entry<N> {
    poly: u16,
    rel: Relation,
    /// Least depth over the area's rectangle clipped to the polygon's sample box (only for
    /// polygons whose depth is linear there).
    zmin: N,
}

/// A rectangle of pixels `x0..x1` × `y0..y1` (its samples are their centres).
#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: i32,
    y0: i32,
    x1: i32,
    y1: i32,
}

impl Rect {
    /// The four corner samples, as pixels.
    fn corners(&self) -> [(i32, i32); 4] {
        let (xr, yb) = (self.x1 - 1, self.y1 - 1);
        [(self.x0, self.y0), (xr, self.y0), (self.x0, yb), (xr, yb)]
    }
}

/// Warnock's area-subdivision renderer.
///
/// - `N`: number format; `W`: row capacity (the widest frame);
/// - `B`: band height and square side, a power of two (`B` rows of colour and depth in RAM);
/// - `P`, `E`: polygon and edge table capacities;
/// - `L`: potentially-visible list entries, summed over the levels of subdivision (see the
///   module doc for the bound a scene needs).
pub struct Warnock<
    N: Scalar,
    const W: usize,
    const B: usize,
    const P: usize,
    const E: usize,
    const L: usize,
> {
    table: PolygonTable<N, P, E>,
    /// Per polygon: its depth is exactly linear over its sample box.
    linear: [bool; P],
    color: [[Rgb565; W]; B],
    depth: [[N; W]; B],
    list: Vec<Entry<N>, L>,
    /// This frame's depth cue (each painted piece takes it when the sink reads depth: see
    /// [`paint_span`]).
    cue: Option<crate::shading::Cue<N>>,
}

impl<N: Scalar, const W: usize, const B: usize, const P: usize, const E: usize, const L: usize>
    Default for Warnock<N, W, B, P, E, L>
{
    fn default() -> Self {
        Self::new()
    }
}

/// What one frame shares with every area.
struct Frame {
    w: i32,
    h: i32,
    s: u32,
    band_y0: i32,
    background: Rgb565,
    areas: u32,
}

/// Whether a polygon's rows meet rows `y0..y1`.
fn reaches<N: Scalar>(p: &Stored<N>, y0: i32, y1: i32) -> bool {
    (p.first_row as i32) < y1 && p.last_row as i32 >= y0
}

/// A polygon's sample box: every sample it covers lies in it.
fn sample_box<N: Scalar>(p: &Stored<N>) -> Rect {
    Rect {
        x0: p.first_col as i32,
        y0: p.first_row as i32,
        x1: p.last_col as i32 + 1,
        y1: p.last_row as i32 + 1,
    }
}

impl<N: Scalar, const W: usize, const B: usize, const P: usize, const E: usize, const L: usize>
    Warnock<N, W, B, P, E, L>
{
    /// Bytes of RAM the renderer occupies (tables, band buffer, lists).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer.
    pub const fn new() -> Self {
        const {
            assert!(
                B.is_power_of_two(),
                "the band height B must be a power of two"
            );
            assert!(B <= 2048, "B above the largest viewport side is wasted RAM");
            assert!(P <= u16::MAX as usize, "polygon capacity must fit u16");
        };
        Warnock {
            table: PolygonTable::new(),
            linear: [false; P],
            color: [[Rgb565::BLACK; W]; B],
            depth: [[N::ZERO; W]; B],
            list: Vec::new(),
            cue: None,
        }
    }

    /// List entries a scene needs under `cfg` (the worst band), once the polygon table is
    /// built: polygons reaching the band times `log2(B) + 2` levels.
    fn needed(&self, h: i32) -> u32 {
        let levels = B.trailing_zeros() + 2;
        let mut most = 0u32;
        for y0 in (0..h).step_by(B) {
            let y1 = (y0 + B as i32).min(h);
            let polygons = self.table.polygons().iter();
            most = most.max(polygons.filter(|p| reaches(p, y0, y1)).count() as u32);
        }
        most.saturating_mul(levels)
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
        self.cue = cue;
        let (w, h) = (cfg.width as i32, cfg.height as i32);
        let needed = self.needed(h);
        if needed as usize > L {
            return Err(Error::Capacity {
                table: Table::VisibleList,
                needed,
                capacity: L as u32,
            }
            .into());
        }
        for (lin, p) in self.linear.iter_mut().zip(self.table.polygons()) {
            *lin = linear_over(&p.plane, &sample_box(p));
        }
        let mut frame = Frame {
            w,
            h,
            s: cfg.subpixel_bits as u32,
            band_y0: 0,
            background: cfg.background,
            areas: 0,
        };
        for band_y0 in (0..h).step_by(B) {
            let band_y1 = (band_y0 + B as i32).min(h);
            frame.band_y0 = band_y0;
            self.list.clear();
            for (i, p) in self.table.polygons().iter().enumerate() {
                if reaches(p, band_y0, band_y1) {
                    // Cannot fail: `needed` counted these and checked L.
                    let _ = self.list.push(Entry {
                        poly: i as u16,
                        rel: Relation::Intersecting,
                        zmin: N::ZERO,
                    });
                }
            }
            let top = self.list.len();
            for x0 in (0..w).step_by(B) {
                self.area(&mut frame, x0, band_y0, B as i32, (0, top));
            }
            for y in band_y0..band_y1 {
                let r = (y - band_y0) as usize;
                if let (Some(c), Some(d)) = (self.color.get_mut(r), self.depth.get(r)) {
                    // In bounds: `cfg.validate(W)` checked width <= W.
                    if !(crate::sink::EXACT_DEPTH && K::WANTS_DEPTH) {
                        // (For a sink that reads depth each piece had it: see `paint_span`.)
                        crate::shading::Cue::shade_row_if_perspective(
                            &cue,
                            &d[..w as usize],
                            &mut c[..w as usize],
                        );
                    }
                    let row = Row {
                        y: y as u16,
                        color: &c[..w as usize],
                        depth: &d[..w as usize],
                    };
                    sink.write_row(&row).map_err(RenderError::Sink)?;
                }
            }
        }
        Ok(FrameStats {
            polygons: self.table.len() as u32,
            edges: self.table.edge_count() as u32,
            areas: frame.areas,
            ..FrameStats::default()
        })
    }

    /// Decides the area `size`×`size` at (`x0`, `y0`) (clipped to the screen), whose parent's
    /// list is `list[parent.0..parent.1]`. Recursion depth is at most `log2(B) + 1`.
    fn area(&mut self, f: &mut Frame, x0: i32, y0: i32, size: i32, parent: (usize, usize)) {
        let r = Rect {
            x0,
            y0,
            x1: (x0 + size).min(f.w),
            y1: (y0 + size).min(f.h),
        };
        if r.x0 >= r.x1 || r.y0 >= r.y1 {
            return;
        }
        f.areas = f.areas.saturating_add(1);
        let start = self.list.len();
        // Step 2: the PVPL — the parent's list without the disjoint polygons.
        for k in parent.0..parent.1 {
            let Some(&e) = self.list.get(k) else { break };
            let i = e.poly as usize;
            let rel = match e.rel {
                // A surrounding polygon surrounds every sub-area.
                Relation::Surrounding => Relation::Surrounding,
                _ => match classify(&self.table, i, &r, f.s) {
                    Some(rel) => rel,
                    None => continue,
                },
            };
            let zmin = if self.is_linear(i) {
                let p = self.table.get(i);
                extreme(&p.plane, &clip_to_box(&r, p), false)
            } else {
                N::ZERO
            };
            // Cannot fail: each list is a subset of its parent's, see `needed`.
            let _ = self.list.push(Entry {
                poly: e.poly,
                rel,
                zmin,
            });
        }
        self.sort_from(start);
        self.remove_hidden(start, &r);
        let n = self.list.len() - start;
        let first = self.list.get(start).copied();
        match (n, first) {
            (0, _) | (_, None) => self.fill(f, &r, None),
            (1, Some(e)) if e.rel == Relation::Surrounding => {
                self.fill(f, &r, Some(e.poly as usize))
            }
            (1, Some(e)) => {
                self.fill(f, &r, None);
                self.scan_convert(f, &r, e.poly as usize);
            }
            _ => {
                if r.x1 - r.x0 == 1 && r.y1 - r.y0 == 1 {
                    // (d) One pixel: every listed polygon covers its centre (the
                    // classification is exact there); the one that beats all others is
                    // visible.
                    let mut best: Option<usize> = None;
                    for e in self.list.get(start..).unwrap_or(&[]) {
                        let i = e.poly as usize;
                        if e.rel == Relation::Surrounding
                            && best.is_none_or(|b| self.table.beats(i, b, r.x0, r.y0))
                        {
                            best = Some(i);
                        }
                    }
                    self.fill(f, &r, best);
                } else if let Some(s) = self.front_surrounding(start, &r) {
                    self.fill(f, &r, Some(s));
                } else {
                    let (end, half) = (self.list.len(), size / 2);
                    for (dx, dy) in [(0, 0), (half, 0), (0, half), (half, half)] {
                        self.area(f, x0 + dx, y0 + dy, half, (start, end));
                    }
                }
            }
        }
        self.list.truncate(start);
    }

    fn is_linear(&self, i: usize) -> bool {
        self.linear.get(i).copied().unwrap_or(false)
    }

    /// Whether entry `a` comes before `b`: polygons whose depth is not linear first (they
    /// are never removed), then by `(zmin, scene order)`.
    fn before(&self, a: &Entry<N>, b: &Entry<N>) -> bool {
        let (la, lb) = (
            self.is_linear(a.poly as usize),
            self.is_linear(b.poly as usize),
        );
        if la != lb {
            return lb;
        }
        if la && a.zmin != b.zmin {
            return a.zmin < b.zmin;
        }
        a.poly < b.poly
    }

    /// Sorts `list[start..]`: insertion sort for short lists (a child's list is nearly in its
    /// parent's order), heapsort for long ones (a band's list near the top of the quadtree
    /// holds every polygon reaching the band, in scene order: insertion sort would be
    /// quadratic there). Neither panics, whatever the comparisons say.
    fn sort_from(&mut self, start: usize) {
        let n = self.list.len().saturating_sub(start);
        if n <= 32 {
            for k in start + 1..self.list.len() {
                let mut j = k;
                while j > start && self.less(j, j - 1) {
                    self.list.swap(j - 1, j);
                    j -= 1;
                }
            }
            return;
        }
        for root in (0..n / 2).rev() {
            self.sift_down(start, root, n);
        }
        for end in (1..n).rev() {
            self.list.swap(start, start + end);
            self.sift_down(start, 0, end);
        }
    }

    /// Whether `list[a]` sorts before `list[b]` (`false` out of range).
    fn less(&self, a: usize, b: usize) -> bool {
        match (self.list.get(a), self.list.get(b)) {
            (Some(a), Some(b)) => self.before(a, b),
            _ => false,
        }
    }

    /// Heapsort's sift-down over `list[start..start + n]` (a max-heap in `before` order; every
    /// index swapped is below `start + n`, the list's length).
    fn sift_down(&mut self, start: usize, mut root: usize, n: usize) {
        loop {
            let mut child = 2 * root + 1;
            if child >= n {
                return;
            }
            if child + 1 < n && self.less(start + child, start + child + 1) {
                child += 1;
            }
            if !self.less(start + root, start + child) {
                return;
            }
            self.list.swap(start + root, start + child);
            root = child;
        }
    }

    /// Removes from the sorted `list[start..]` the polygons hidden by a surrounding polygon
    /// `S`: those after the first `P` with `(zmin_P, P) > (zmax_S, S)`, for the `S` with the
    /// least `(zmax_S, S)`.
    fn remove_hidden(&mut self, start: usize, r: &Rect) {
        let mut best: Option<(N, u16)> = None;
        for e in self.list.get(start..).unwrap_or(&[]) {
            if e.rel == Relation::Surrounding && self.is_linear(e.poly as usize) {
                let zmax = extreme(&self.table.get(e.poly as usize).plane, r, true);
                if best.is_none_or(|(z, s)| zmax < z || (zmax == z && e.poly < s)) {
                    best = Some((zmax, e.poly));
                }
            }
        }
        let Some((zmax, s)) = best else { return };
        let cut = self.list.get(start..).unwrap_or(&[]).iter().position(|e| {
            self.is_linear(e.poly as usize) && (e.zmin > zmax || (e.zmin == zmax && e.poly > s))
        });
        if let Some(k) = cut {
            self.list.truncate(start + k);
        }
    }

    /// A surrounding polygon that beats every other listed polygon at every sample the other
    /// covers in the area (the fourth case), if there is one.
    fn front_surrounding(&self, start: usize, r: &Rect) -> Option<usize> {
        let list = self.list.get(start..).unwrap_or(&[]);
        if !list.iter().all(|e| self.is_linear(e.poly as usize)) {
            return None;
        }
        list.iter()
            .filter(|e| e.rel == Relation::Surrounding)
            .map(|e| e.poly as usize)
            .find(|&s| {
                list.iter().all(|q| {
                    let q = q.poly as usize;
                    q == s
                        || clip_to_box(r, self.table.get(q))
                            .corners()
                            .iter()
                            .all(|&(x, y)| self.table.beats(s, q, x, y))
                })
            })
    }

    /// Fills the area with polygon `poly` (its colour and plane depth) or the background.
    fn fill(&mut self, f: &Frame, r: &Rect, poly: Option<usize>) {
        for y in r.y0..r.y1 {
            let row = (y - f.band_y0) as usize;
            let (Some(c), Some(d)) = (self.color.get_mut(row), self.depth.get_mut(row)) else {
                continue;
            };
            // In bounds: `cfg.validate(W)` checked width <= W.
            let (c, d) = (&mut c[..f.w as usize], &mut d[..f.w as usize]);
            match poly {
                Some(i) => {
                    let p = self.table.get(i);
                    paint_span(d, c, p, &self.cue, y, r.x0, r.x1);
                }
                None => {
                    if let Some(c) = c.get_mut(r.x0 as usize..r.x1 as usize) {
                        c.fill(f.background);
                    }
                    if let Some(d) = d.get_mut(r.x0 as usize..r.x1 as usize) {
                        d.fill(N::MAX);
                    }
                }
            }
        }
    }

    /// Paints polygon `i`'s covered samples in the area (its spans clipped to the area).
    fn scan_convert(&mut self, f: &Frame, r: &Rect, i: usize) {
        let (table, color, depth, cue) = (&self.table, &mut self.color, &mut self.depth, &self.cue);
        let p = table.get(i);
        table.walk(i, r.y0, r.y1 - 1, |y, xl, xr| {
            let row = (y - f.band_y0) as usize;
            if let (Some(c), Some(d)) = (color.get_mut(row), depth.get_mut(row)) {
                let (c, d) = (&mut c[..f.w as usize], &mut d[..f.w as usize]);
                let (x0, x1) = (xl.max(r.x0), xr.min(r.x1));
                paint_span(d, c, p, cue, y, x0, x1);
            }
            true
        });
    }
}

/// The polygon's relation to the area, or `None` when it is disjoint from it (exact on the
/// area's corner samples; see the module doc).
fn classify<N: Scalar, const P: usize, const E: usize>(
    t: &PolygonTable<N, P, E>,
    i: usize,
    r: &Rect,
    s: u32,
) -> Option<Relation> {
    let p = t.get(i);
    let (c0, c1, r0, r1) = (
        p.first_col as i32,
        p.last_col as i32,
        p.first_row as i32,
        p.last_row as i32,
    );
    // Test 1, min-max: the sample boxes do not overlap.
    if c1 < r.x0 || c0 >= r.x1 || r1 < r.y0 || r0 >= r.y1 {
        return None;
    }
    // Tests 2 and 3 on the corner samples, with the top-left rule of `covers`.
    let h = 1i64 << s >> 1;
    let corners = r
        .corners()
        .map(|(x, y)| (((x as i64) << s) + h, ((y as i64) << s) + h));
    let mut all_in = r0 <= r.y0 && r1 >= r.y1 - 1;
    for e in t.edges_of(i) {
        let inside = corners.iter().filter(|&&(xs, ys)| {
            let f = (xs - e.x0 as i64) * e.dy as i64 - (ys - e.y0 as i64) * e.dx as i64;
            match e.side {
                Side::Left => f >= 0,
                Side::Right => f < 0,
            }
        });
        match inside.count() {
            0 => return None,
            4 => {}
            _ => all_in = false,
        }
    }
    Some(if all_in {
        Relation::Surrounding
    } else if c0 >= r.x0 && c1 < r.x1 && r0 >= r.y0 && r1 < r.y1 {
        Relation::Contained
    } else {
        Relation::Intersecting
    })
}

/// The area clipped to a polygon's sample box (which holds every sample it covers).
fn clip_to_box<N: Scalar>(r: &Rect, p: &Stored<N>) -> Rect {
    let b = sample_box(p);
    Rect {
        x0: r.x0.max(b.x0),
        y0: r.y0.max(b.y0),
        x1: r.x1.min(b.x1),
        y1: r.y1.min(b.y1),
    }
}

/// The least (or, with `max`, the greatest) plane depth at the rectangle's corner samples.
fn extreme<N: Scalar>(plane: &DepthPlane<N>, r: &Rect, max: bool) -> N {
    let [(x, y), rest @ ..] = r.corners();
    rest.iter().fold(plane.at(x, y), |m, &(x, y)| {
        let z = plane.at(x, y);
        if (max && z > m) || (!max && z < m) {
            z
        } else {
            m
        }
    })
}

/// Whether the plane's stored depths are linear over the rectangle: its corners lie on the
/// line through the first one with the plane's steps.
///
/// Exact for Q16.16: the model is computed in `f64` without rounding (depths and steps are
/// multiples of 2^-16 below 2^15, pixel offsets below 2^11), and a corner that wrapped is off
/// by a multiple of 2^16, while the tolerance stays below 2^14 (1e-4 of at most
/// 2^15 + 2·2^15·2^11). f32 never wraps; its rounding is far inside the tolerance. NaN fails.
fn linear_over<N: Scalar>(plane: &DepthPlane<N>, r: &Rect) -> bool {
    const TOLERANCE: f64 = 1e-4;
    let [(xa, ya), rest @ ..] = r.corners();
    let a = plane.at(xa, ya).to_f64();
    let (dzdx, dzdy) = (plane.dzdx.to_f64(), plane.dzdy.to_f64());
    rest.iter().all(|&(x, y)| {
        let (u, v) = (dzdx * (x - xa) as f64, dzdy * (y - ya) as f64);
        let model = a + u + v;
        let scale = a.abs() + u.abs() + v.abs();
        (plane.at(x, y).to_f64() - model).abs() <= TOLERANCE * scale
    })
}

impl<N: Scalar, const W: usize, const B: usize, const P: usize, const E: usize, const L: usize>
    Renderer<N> for Warnock<N, W, B, P, E, L>
{
    const NAME: &'static str = "warnock";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        Warnock::render(self, scene, cfg, sink)
    }
}
