//! Snapped polygons, the exact edge walk and polygon setup — shared by every method.
//!
//! After geometry, a polygon's vertices are integers on a sub-pixel grid (`subpixel_bits`
//! fractional bits, 8 by default: 24.8 fixed point) and its depth is in the renderer's number
//! format. From here on coverage is exact integer arithmetic:
//!
//! - pixel (i, j) is sampled at its centre, (i·2^S + 2^(S−1), j·2^S + 2^(S−1)) in sub-pixels;
//! - a polygon covers rows `ceil((y_top − h)/2^S) .. ceil((y_bottom − h)/2^S)` (half-open, so a
//!   top edge owns a sample on it and a bottom edge does not) and, in each row, columns
//!   `ceil((x_left − h)/2^S) .. ceil((x_right − h)/2^S)` (a left edge owns its samples, a right
//!   edge does not): the top-left rule, so polygons sharing an edge never both cover, and never
//!   both miss, a sample on it;
//! - an edge's crossing moves by 1/m per row (the scan-line algorithm's `x' = x + 1/m`, Foley, van Dam, Feiner & Hughes §3.6), kept exactly as an
//!   integer quotient and remainder ([`Dda`](crate::raster::Dda)), so no error accumulates down the edge.
//!
//! Zero area after snapping counts as back-facing and is dropped.
//!
//! Bit budget: geometry clips to a guard band of [`GUARD_BAND`](crate::raster::GUARD_BAND) pixels around the viewport and
//! viewports are at most [`MAX_VIEWPORT`](crate::raster::MAX_VIEWPORT) pixels a side, so coordinates stay below 2^13 pixels;
//! with at most 8 sub-pixel bits the per-row walk fits `i32` and setup uses `i64`.

use crate::error::Error;
use crate::number::{DepthPlane, Scalar};
use crate::scene::IntensityPlane;
use embedded_graphics_core::pixelcolor::Rgb565;

/// Most vertices a polygon can have after clipping (input faces may have up to
/// [`MAX_FACE_VERTICES`]; each of the six clip planes can add one).
pub const MAX_POLYGON_VERTICES: usize = 16;
/// Most vertices an input face may have.
pub const MAX_FACE_VERTICES: usize = MAX_POLYGON_VERTICES - 6;
/// Pixels of guard band kept around the viewport by clipping.
pub const GUARD_BAND: i32 = 2048;
/// Largest viewport side, in pixels.
pub const MAX_VIEWPORT: u16 = 2048;
/// Largest supported number of sub-pixel bits.
pub const MAX_SUBPIXEL_BITS: u8 = 8;

/// A vertex snapped to the sub-pixel grid: `x`, `y` in sub-pixels, `z` in the number format.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct RasterVertex<N> {
    /// Column, in sub-pixels (`subpixel_bits` fractional bits).
    pub x: i32,
    /// Row, in sub-pixels.
    pub y: i32,
    /// Depth (smaller is nearer).
    pub z: N,
}

impl<N: Scalar> RasterVertex<N> {
    /// The screen-space point `p` (x right, y down, in pixels; z depth) snapped to the grid
    /// of `subpixel_bits` sub-pixel bits, to the bits geometry snaps a
    /// [`crate::ScreenScene`]'s vertex to: what a [`crate::SnappedScene`] is made of. `None`
    /// if a coordinate is not a number or beyond the grid's range.
    pub fn snapped(p: &crate::math::Vec3<N>, subpixel_bits: u8) -> Option<Self> {
        let s = subpixel_bits as u32;
        Some(RasterVertex {
            x: p.x.snap(s)?,
            y: p.y.snap(s)?,
            z: p.z.is_finite().then_some(p.z)?,
        })
    }
}

/// A convex polygon after geometry: clipped, projected and snapped.
#[derive(Clone, Debug)]
pub struct RasterPolygon<N> {
    /// Vertices in order (either winding).
    pub vertices: heapless::Vec<RasterVertex<N>, MAX_POLYGON_VERTICES>,
    /// Its colour after shading.
    pub color: Rgb565,
    /// Its opacity (255 = opaque), from [`crate::Face::alpha`].
    pub alpha: u8,
    /// Index of the face in the scene (for errors).
    pub face: u32,
}

/// Which polygons are dropped by the winding test on snapped coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Cull {
    /// Draw both windings (screen-space scenes, whose worked examples have either winding).
    None,
    /// Drop polygons that are clockwise on the display (back faces of meshes whose faces are
    /// counter-clockwise seen from outside, the OFF/OBJ convention).
    Back,
}

/// Everything a renderer needs to know about the frame besides the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    /// Width in pixels (at most the renderer's row capacity and [`MAX_VIEWPORT`]).
    pub width: u16,
    /// Height in pixels (at most [`MAX_VIEWPORT`]).
    pub height: u16,
    /// Sub-pixel bits of the snapping grid, 1..=8.
    pub subpixel_bits: u8,
    /// Back-face culling by winding.
    pub cull: Cull,
    /// Colour where nothing is drawn.
    pub background: Rgb565,
    /// How model-mode perspective depth is stored: affine in 1/w (exact, the default) or
    /// linear in w (see [`crate::geometry::DepthMapping`]).
    pub depth: crate::geometry::DepthMapping,
    /// Flat faces, or intensity falling with distance (depth cueing), interpolated affinely
    /// or perspective-correctly ([`crate::shading`]).
    pub shading: crate::shading::Shading,
    /// The square roots of lighting: exact or micromath ([`crate::math::MathLib`]).
    pub math: crate::math::MathLib,
}

impl Config {
    /// Screen-space defaults: 8 sub-pixel bits, no culling, black background, depth affine in
    /// 1/w, flat shading, exact square roots.
    pub const fn screen(width: u16, height: u16) -> Self {
        Config {
            width,
            height,
            subpixel_bits: 8,
            cull: Cull::None,
            background: Rgb565::new(0, 0, 0),
            depth: crate::geometry::DepthMapping::InverseW,
            shading: crate::shading::Shading::Flat,
            math: crate::math::MathLib::Libm,
        }
    }
    /// Model-mode defaults: as [`Config::screen`] with back faces culled.
    pub const fn model(width: u16, height: u16) -> Self {
        let mut c = Self::screen(width, height);
        c.cull = Cull::Back;
        c
    }
    /// Checks the configuration against a row capacity.
    pub fn validate(&self, row_capacity: usize) -> Result<(), Error> {
        if self.width == 0
            || self.height == 0
            || self.width > MAX_VIEWPORT
            || self.height > MAX_VIEWPORT
            || self.subpixel_bits == 0
            || self.subpixel_bits > MAX_SUBPIXEL_BITS
            || !self.shading.is_valid()
            || (self.shading.is_facets() && self.background != Rgb565::new(0, 0, 0))
        {
            return Err(Error::BadConfig);
        }
        if self.width as usize > row_capacity {
            return Err(Error::Capacity {
                table: crate::error::Table::RowWidth,
                needed: self.width as u32,
                capacity: row_capacity as u32,
            });
        }
        Ok(())
    }
    pub(crate) fn half(&self) -> i32 {
        1 << (self.subpixel_bits - 1)
    }
}

/// Which side of its polygon an edge bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Interior to the right: samples on it are inside.
    Left,
    /// Interior to the left: samples on it are outside.
    Right,
}

/// One non-horizontal edge that crosses at least one sample row on screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// First row whose sample line it crosses (clamped to the screen).
    pub first_row: i16,
    /// Last such row (inclusive).
    pub last_row: i16,
    /// Upper end, in sub-pixels.
    pub x0: i32,
    /// Upper end, in sub-pixels.
    pub y0: i32,
    /// x extent (lower end minus upper end).
    pub dx: i32,
    /// y extent (> 0).
    pub dy: i32,
    /// Index of the polygon it bounds, in the polygon table.
    pub poly: u16,
    /// Which side of that polygon it is.
    pub side: Side,
}

/// `ceil(a / b)` for `b > 0`.
fn div_ceil(a: i64, b: i64) -> i64 {
    -((-a).div_euclid(b))
}

/// `ceil(num / den)` for `den > 0` in 32 bits, as `−⌊−num / den⌋`: the truncated quotient
/// fixed up by the remainder's sign bit, without a branch (`div_euclid` cannot see that the
/// divisor is positive, and tests its sign). The walks' fast paths round their first
/// crossing with it.
#[inline(always)]
fn div_ceil_positive(num: i32, den: i32) -> i32 {
    let n = -num;
    let q = n / den;
    -(q + ((n - q * den) >> 31))
}

/// First sample row (or column) at or below `y` (sub-pixels): `ceil((y − h)/2^S)`, as a
/// shift: `−floor((h − y)/2^S)`.
#[inline]
pub(crate) fn row_at_or_below(y: i32, s: u32, h: i32) -> i32 {
    match h.checked_sub(y) {
        Some(d) => -(d >> s),
        None => (-((h as i64 - y as i64) >> s)) as i32,
    }
}

impl Edge {
    /// The state of the exact walk at `row` (which must lie in `first_row..=last_row`).
    pub fn dda_at(&self, row: i32, s: u32) -> Dda {
        match self.crossing_at(row, s) {
            Some((x, r, den)) => {
                // The step: dx·2^S over dy·2^S, the same quotient as dx over dy.
                let qs = self.dx.div_euclid(self.dy);
                let rs = (self.dx - qs * self.dy) << s;
                Dda::new(x, r, qs, rs, den)
            }
            None => self.dda_at_wide(row, s),
        }
    }

    /// The column of [`Edge::dda_at`]`(row, s)` ([`Dda::x`]) alone: where a method asks for a
    /// polygon's span at one row, the walk's step (a second division) is not needed.
    pub fn x_at(&self, row: i32, s: u32) -> i32 {
        match self.crossing_at(row, s) {
            Some((x, _, _)) => x as i16 as i32, // as `Dda::x` keeps it
            None => self.dda_at_wide(row, s).x(),
        }
    }

    /// The walk's first crossing at `row`: its column, remainder and denominator (`dy·2^S`),
    /// for an edge within the guard band (|x|, |y| < 2^21 sub-pixels with S ≤ 8, so `dy·2^S`
    /// fits 32 bits) at or below its top; `None` otherwise (the 64-bit walk then). Less than
    /// two rows below the top (every edge but those clamped to the top of the screen, or
    /// asked for a later row) the numerator fits 32 bits: one 32-bit division; further down
    /// it is 64-bit, divided by the 32-bit denominator in hardware digits
    /// ([`crate::number::divmod_u64_u32`]) instead of a 64-bit library division. The same
    /// results as [`Edge::dda_at_wide`].
    #[inline(always)]
    fn crossing_at(&self, row: i32, s: u32) -> Option<(i32, i32, i32)> {
        let (h, mask) = (1i32 << s >> 1, (1i32 << s) - 1);
        let t = (row << s) + h - self.y0; // how far below the top the sample line is
        let small = |v: i32| v.unsigned_abs() < 1 << 21;
        if !(t >= 0 && self.dy > 0 && small(self.dy) && small(self.dx) && small(self.x0) && s <= 8)
        {
            return None;
        }
        let den = self.dy << s;
        // x0 − h = qx·2^S + fx; the crossing's column is qx + ceil((fx·dy + t·dx) / den).
        let x0h = self.x0 - h;
        let (qx, fx) = (x0h >> s, x0h & mask);
        if t < 512 {
            let num = fx * self.dy + t * self.dx;
            let q = div_ceil_positive(num, den);
            return Some((qx + q, q * den - num, den));
        }
        let num = fx as i64 * self.dy as i64 + t as i64 * self.dx as i64;
        // ceil(num / den) = −floor(−num / den), from the magnitude's quotient and remainder.
        let (q, r) = crate::number::divmod_u64_u32(num.unsigned_abs(), den as u32);
        let q = match num > 0 {
            true => q as i64 + (r != 0) as i64,
            false => -(q as i64),
        };
        Some(((qx as i64 + q) as i32, (q * den as i64 - num) as i32, den))
    }

    /// [`Edge::dda_at`] in 64-bit arithmetic, for any row.
    fn dda_at_wide(&self, row: i32, s: u32) -> Dda {
        let h = 1i64 << s >> 1;
        let den = (self.dy as i64) << s;
        let ys = ((row as i64) << s) + h;
        let num = (self.x0 as i64 - h) * self.dy as i64 + (ys - self.y0 as i64) * self.dx as i64;
        let q = div_ceil(num, den);
        let r = q * den - num;
        let step = (self.dx as i64) << s;
        let qs = step.div_euclid(den);
        let rs = step - qs * den;
        Dda::new(
            q as i32,
            r as i32,
            qs.clamp(i32::MIN as i64, i32::MAX as i64) as i32, // `new` saturates it to 16 bits
            rs as i32,
            den as i32,
        )
    }
}

/// The exact per-row walk of one edge: `x` is the first pixel column whose centre is at or
/// right of the edge's crossing with the current row's sample line.
///
/// It is the textbook `x += 1/m` with 1/m split into a whole step `qs` and a remainder `rs`
/// over `den`, as Bresenham does: `x − r/den` is exactly `(crossing − h)/2^S`.
///
/// 16 bytes: the column and the whole step are 16-bit. Snapped vertices lie within the guard
/// band, so a crossing inside the edge's rows is below 2^13 pixels, and an edge that spans
/// two sample rows (the only kind ever stepped) is more than a row tall, so its step is below
/// 2^14 pixels (a taller step, of an edge one row tall, is kept saturated and never used).
/// The two share one word, the column in its high half: a step adds the word shifted up by
/// half (the step onto the column, wrapping as 16 bits) — one load, add and store for both.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Dda {
    /// `x` in the high 16 bits, `qs` in the low.
    xq: u32,
    r: i32,
    rs: i32,
    den: i32,
}

impl Dda {
    /// A walk at column 0 that stays there (a placeholder).
    pub const ZERO: Dda = Dda {
        xq: 0,
        r: 0,
        rs: 0,
        den: 0,
    };

    /// The walk at column `x` with remainder `r`, stepping `qs` and `rs` over `den` a row
    /// (the column as 16 bits, the step saturated to them: see [`Dda`]).
    #[inline]
    fn new(x: i32, r: i32, qs: i32, rs: i32, den: i32) -> Dda {
        let qs = qs.clamp(i16::MIN as i32, i16::MAX as i32) as i16;
        Dda {
            xq: (x as u32) << 16 | qs as u16 as u32,
            r,
            rs,
            den,
        }
    }

    /// Current pixel column.
    #[inline]
    pub fn x(&self) -> i32 {
        self.xq as i32 >> 16
    }

    /// Where the edge crosses the current row's sample line, in pixel columns (pixel `i`'s
    /// centre is `i`): `x − r/den`, the fraction rounded to the format ([`Scalar::from_ratio`]:
    /// in fixed point in integers, exact and rounded once).
    #[inline]
    pub fn crossing<N: Scalar>(&self) -> N {
        N::from_int(self.x()).sub(self.fraction())
    }

    /// How far left of column `x`'s centre the edge crosses the row: `r/den`, in `0..1`,
    /// rounded to the format ([`Scalar::from_ratio`]).
    #[inline]
    pub fn fraction<N: Scalar>(&self) -> N {
        N::from_ratio(self.r, self.den)
    }

    /// The walk of the edge from (`x0`, `y0`) down to (`x1`, `y1`) (sub-pixels, `y1 > y0`) at
    /// sample row `row`: [`Edge::dda_at`] without building the edge.
    #[inline]
    pub fn between(x0: i32, y0: i32, x1: i32, y1: i32, row: i32, s: u32) -> Dda {
        let mut d = Dda::ZERO;
        d.set_between(x0, y0, x1, y1, row, s);
        d
    }

    /// Sets this walk to [`Dda::between`]'s, written where it is kept (returned, it was
    /// written to the stack and copied: on an x86-64 host the copy's wide load waits for the
    /// narrow stores before it to retire).
    #[inline]
    pub fn set_between(&mut self, x0: i32, y0: i32, x1: i32, y1: i32, row: i32, s: u32) {
        // The fast path of `Edge::dda_at`, its conditions folded into unsigned comparisons.
        let (h, mask) = (1i32 << s >> 1, (1i32 << s) - 1);
        let (dx, dy) = (x1.wrapping_sub(x0), y1.wrapping_sub(y0));
        let t = (row << s).wrapping_add(h).wrapping_sub(y0);
        let small = |v: i32| (v.wrapping_add(1 << 21) as u32) < 1 << 22;
        if (t as u32) < 512 && small(dx) && small(x0) && dy > 0 && dy < 1 << 21 && s <= 8 {
            let den = dy << s;
            let qs = dx.div_euclid(dy);
            let rs = (dx - qs * dy) << s;
            let x0h = x0 - h;
            let num = (x0h & mask) * dy + t * dx;
            let q = div_ceil_positive(num, den);
            *self = Dda::new((x0h >> s) + q, q * den - num, qs, rs, den);
            return;
        }
        *self = Edge {
            first_row: 0,
            last_row: 0,
            x0,
            y0,
            dx: x1 - x0,
            dy: y1 - y0,
            poly: 0,
            side: Side::Left,
        }
        .dda_at_wide(row, s);
    }

    /// Moves to the next row.
    #[inline]
    pub fn step(&mut self) {
        self.xq = self.xq.wrapping_add(self.xq << 16);
        self.r -= self.rs;
        if self.r < 0 {
            self.r += self.den;
            self.xq = self.xq.wrapping_add(1 << 16);
        }
    }
}

/// A polygon ready for any method: its depth plane, colour, rows on screen and edges.
#[derive(Clone, Debug)]
pub struct SetupPolygon<N> {
    /// Depth plane.
    pub plane: DepthPlane<N>,
    /// Colour.
    pub color: Rgb565,
    /// First row with a covered sample line (clamped to the screen).
    pub first_row: i16,
    /// Last such row (inclusive).
    pub last_row: i16,
    /// Its edges; `poly` is left 0 for the caller to fill in.
    pub edges: heapless::Vec<Edge, MAX_POLYGON_VERTICES>,
}

impl<N: Scalar> SetupPolygon<N> {
    /// No polygon (zero plane, no rows' edges): what [`setup_into`] fills in.
    pub fn empty() -> Self {
        SetupPolygon {
            plane: DepthPlane {
                z_ref: N::ZERO,
                dzdx: N::ZERO,
                dzdy: N::ZERO,
                i_ref: 0,
                j_ref: 0,
            },
            color: Rgb565::new(0, 0, 0),
            first_row: 0,
            last_row: 0,
            edges: heapless::Vec::new(),
        }
    }
}

/// Twice the signed area of a snapped polygon (shoelace; positive = clockwise on the display,
/// whose y axis points down).
pub fn signed_area2(v: &[RasterVertex<impl Copy>]) -> i64 {
    let mut a = 0i64;
    for k in 0..v.len() {
        let (p, q) = (&v[k], &v[(k + 1) % v.len()]);
        a += p.x as i64 * q.y as i64 - q.x as i64 * p.y as i64;
    }
    a
}

/// A polygon's place on the sample grid: what every method checks before building anything.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outline {
    /// Clockwise on the display (positive signed area; y points down). Going round in vertex
    /// order from the top vertex then runs down the right side when `true`, the left when
    /// `false`.
    pub clockwise: bool,
    /// First row with a covered sample line (clamped to the screen).
    pub first_row: i16,
    /// Last such row (inclusive).
    pub last_row: i16,
}

/// Checks a snapped polygon and finds its rows. `Ok(None)` when it draws nothing: fewer than
/// three vertices, zero area after snapping, culled as a back face, or no sample on screen.
///
/// A convex polygon's outline goes down once and up once; one that does not (a non-convex
/// face) is [`Error::NotConvex`]. Snapping is monotone, so it never makes a convex polygon fail.
pub fn outline<T: Copy>(
    v: &[RasterVertex<T>],
    cfg: &Config,
    face: u32,
) -> Result<Option<Outline>, Error> {
    outline_of(v.len(), |k| &v[k], cfg, face)
}

/// [`outline`] of the `n` vertices `v(0)`, `v(1)`, … (read in place: from a vertex buffer
/// through corner indices, say).
#[inline]
pub fn outline_of<'a, T: Copy + 'a>(
    n: usize,
    v: impl Fn(usize) -> &'a RasterVertex<T>,
    cfg: &Config,
    face: u32,
) -> Result<Option<Outline>, Error> {
    if n < 3 {
        return Ok(None);
    }
    let area = if n == 3 {
        let (a, b, c) = (v(0), v(1), v(2));
        (b.x as i64 - a.x as i64) * (c.y as i64 - a.y as i64)
            - (c.x as i64 - a.x as i64) * (b.y as i64 - a.y as i64)
    } else {
        (0..n).fold(0i64, |a, k| {
            let (p, q) = (v(k), v((k + 1) % n));
            a + p.x as i64 * q.y as i64 - q.x as i64 * p.y as i64
        })
    };
    outline_with_area(n, v, area, cfg, face)
}

/// [`outline_of`] with the doubled signed area known ([`signed_area2`] of the same vertices,
/// as [`crate::scene::Polygon::area2`] carries it).
#[inline]
pub fn outline_with_area<'a, T: Copy + 'a>(
    n: usize,
    v: impl Fn(usize) -> &'a RasterVertex<T>,
    area: i64,
    cfg: &Config,
    face: u32,
) -> Result<Option<Outline>, Error> {
    if n < 3 {
        return Ok(None);
    }
    if area == 0 || (cfg.cull == Cull::Back && area > 0) {
        return Ok(None);
    }
    // y-monotone check (a triangle always is): going round, the direction of travel in y
    // changes sign at most twice.
    if n > 3 {
        let dir = |k: usize| {
            let (p, q) = (v(k), v((k + 1) % n));
            (q.y as i64 - p.y as i64).signum()
        };
        let mut last = (0..n).rev().map(dir).find(|&d| d != 0).unwrap_or(0);
        let mut changes = 0;
        for d in (0..n).map(dir).filter(|&d| d != 0) {
            changes += (d != last) as u32;
            last = d;
        }
        if changes > 2 {
            return Err(Error::NotConvex { face });
        }
    }
    // Reject polygons whose bounding box misses every sample.
    let s = cfg.subpixel_bits as u32;
    let h = cfg.half();
    let (mut xmin, mut xmax, mut ymin, mut ymax) = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
    for k in 0..n {
        let p = v(k);
        xmin = xmin.min(p.x);
        xmax = xmax.max(p.x);
        ymin = ymin.min(p.y);
        ymax = ymax.max(p.y);
    }
    if row_at_or_below(xmax, s, h) <= 0 || row_at_or_below(xmin, s, h) >= cfg.width as i32 {
        return Ok(None);
    }
    // The edges' row ranges tile the outline's from its top to its bottom (each edge
    // `ceil((top − h)/2^S) .. ceil((bottom − h)/2^S)`, half-open), so their union is this.
    let first = row_at_or_below(ymin, s, h).max(0);
    let last_row = row_at_or_below(ymax, s, h).min(cfg.height as i32) - 1;
    if first > last_row {
        return Ok(None);
    }
    Ok(Some(Outline {
        clockwise: area > 0,
        first_row: first as i16,
        last_row: last_row as i16,
    }))
}

/// [`outline_with_area`] of a triangle whose corners are at hand (the hot path of a mesh: no
/// loop, each corner read once), with its top-left corner (least y, then least x). A
/// triangle is always y-monotone, so there is no error to report.
#[inline]
pub(crate) fn outline_triangle<T>(
    v: [&RasterVertex<T>; 3],
    area: i64,
    cfg: &Config,
) -> Option<(Outline, usize)> {
    if area == 0 || (cfg.cull == Cull::Back && area > 0) {
        return None;
    }
    let [a, b, c] = v;
    let (s, h) = (cfg.subpixel_bits as u32, cfg.half());
    // `row_at_or_below` without its overflow path: snapped corners lie within the guard band
    // (below 2^21 sub-pixels), so `h − v` cannot overflow.
    let row = |v: i32| -(h.wrapping_sub(v) >> s);
    let (xmin, xmax) = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x));
    if row(xmax) <= 0 || row(xmin) >= cfg.width as i32 {
        return None;
    }
    let (ymin, ymax) = (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y));
    let first = row(ymin).max(0);
    let last_row = row(ymax).min(cfg.height as i32) - 1;
    if first > last_row {
        return None;
    }
    // (y, x) in one ordered integer: a single comparison each.
    let key = |v: &RasterVertex<T>| (v.y as i64) << 32 | (v.x as u32 ^ 0x8000_0000) as i64;
    let (ka, kb, kc) = (key(a), key(b), key(c));
    let top = match (ka <= kb, ka <= kc, kb <= kc) {
        (true, true, _) => 0,
        (false, _, true) => 1,
        _ => 2,
    };
    let outline = Outline {
        clockwise: area > 0,
        first_row: first as i16,
        last_row: last_row as i16,
    };
    Some((outline, top))
}

/// Fills a run of pixels with one colour, eight at a time (unrolled halfword stores: about
/// one instruction a pixel on a Cortex-M, against three for a plain loop, whatever the caller
/// inlined around it).
///
/// A 64-bit host takes the library's fill instead: the jump on the rest's length, one
/// instruction on a core without branch prediction, goes somewhere else span after span, and
/// its mispredictions cost an x86-64 host 12 % of the torus frame's time.
#[inline]
pub(crate) fn fill_run(run: &mut [Rgb565], c: Rgb565) {
    match cfg!(target_pointer_width = "64") {
        true => run.fill(c),
        false => fill_unrolled(run, c),
    }
}

/// [`fill_run`] on a 32-bit core: eight pixels a step, then the rest by its length.
#[inline]
fn fill_unrolled(run: &mut [Rgb565], c: Rgb565) {
    let mut rest = run;
    if rest.len() >= 8 {
        let mut chunks = rest.chunks_exact_mut(8);
        for ch in &mut chunks {
            // Eight stores of the colour. (Copied from a `[c; 8]`, a build for size — the
            // firmware's — made the array on the stack and called `memcpy` for it: 55 k
            // cycles a frame on the F411.)
            if let [a, b, d, e, f, g, h, i] = ch {
                (*a, *b, *d, *e) = (c, c, c, c);
                (*f, *g, *h, *i) = (c, c, c, c);
            }
        }
        rest = chunks.into_remainder();
    }
    // The rest (a mesh's spans are mostly shorter than eight) by its length: one jump, then
    // its stores.
    match rest {
        [a] => *a = c,
        [a, b] => (*a, *b) = (c, c),
        [a, b, d] => (*a, *b, *d) = (c, c, c),
        [a, b, d, e] => (*a, *b, *d, *e) = (c, c, c, c),
        [a, b, d, e, f] => (*a, *b, *d, *e, *f) = (c, c, c, c, c),
        [a, b, d, e, f, g] => (*a, *b, *d, *e, *f, *g) = (c, c, c, c, c, c),
        [a, b, d, e, f, g, h] => (*a, *b, *d, *e, *f, *g, *h) = (c, c, c, c, c, c, c),
        _ => {}
    }
}

/// `c` scaled by a level in 0..=255, each channel rounded to nearest: the colour of a lit
/// face (flat shading scales by its intensity once) or of one pixel of a smooth-shaded one.
#[inline]
pub fn shade_level(c: Rgb565, level: u8) -> Rgb565 {
    use embedded_graphics_core::pixelcolor::RgbColor;
    let i = level as u16;
    let s = |ch: u8| ((ch as u16 * i + 127) / 255) as u8;
    Rgb565::new(s(c.r()), s(c.g()), s(c.b()))
}

/// [`shade_level`] with ordered dithering at pixel (`x`, `y`): each channel is
/// `floor(c·level/255 + (b + 0.5)/16)` with `b` the pixel's entry of the 4 × 4 Bayer matrix,
/// so a 4 × 4 block averages `c·level/255` and no channel passes `c`.
#[inline]
pub fn shade_level_dithered(c: Rgb565, level: u8, x: i32, y: i32) -> Rgb565 {
    use embedded_graphics_core::pixelcolor::RgbColor;
    const BAYER: [[u16; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    let b = BAYER[(y & 3) as usize][(x & 3) as usize];
    let (i, t) = (level as u32, (255 * b + 127) as u32);
    let s = |ch: u8| ((ch as u32 * i * 16 + t) / (255 * 16)) as u8;
    Rgb565::new(s(c.r()), s(c.g()), s(c.b()))
}

/// The colour of pixel (`x`, `y`) of a smooth-shaded polygon at `level`.
#[inline]
fn shade_pixel(c: Rgb565, level: u8, dither: bool, x: i32, y: i32) -> Rgb565 {
    match dither {
        false => shade_level(c, level),
        true => shade_level_dithered(c, level, x, y),
    }
}

/// A polygon's colour at the centre of pixel (`i`, `j`): `color`, or, smooth shaded, `color`
/// at the level its intensity plane has there.
#[inline]
pub fn color_at<N: Scalar>(
    color: Rgb565,
    intensity: Option<&IntensityPlane<N>>,
    i: i32,
    j: i32,
) -> Rgb565 {
    match intensity {
        None => color,
        Some(p) => shaded_at(color, p, i, j),
    }
}

/// [`color_at`]'s smooth case, out of line so that the flat one stays a copy wherever it is
/// inlined.
#[inline(never)]
fn shaded_at<N: Scalar>(color: Rgb565, p: &IntensityPlane<N>, i: i32, j: i32) -> Rgb565 {
    shade_pixel(color, p.levels.at(i, j).to_level(), p.dither, i, j)
}

/// Paints `run`, columns `x0..` of row `y`, with a polygon's colour: one colour
/// ([`fill_run`]), or, smooth shaded, its intensity plane stepped along the row from `x0` as
/// depth is ([`DepthPlane::at`], then [`Scalar::step`] by one pixel), dithered if it says so.
#[inline]
pub(crate) fn paint_run<N: Scalar>(
    run: &mut [Rgb565],
    color: Rgb565,
    intensity: Option<&IntensityPlane<N>>,
    x0: i32,
    y: i32,
) {
    match intensity {
        None => fill_run(run, color),
        Some(p) => shade_run(run, color, p, x0, y),
    }
}

/// [`paint_run`]'s smooth case, out of line so that the flat one stays a fill wherever it is
/// inlined.
#[inline(never)]
fn shade_run<N: Scalar>(run: &mut [Rgb565], color: Rgb565, p: &IntensityPlane<N>, x0: i32, y: i32) {
    let (plane, dither) = (&p.levels, p.dither);
    let mut v = plane.at(x0, y);
    for (x, c) in (x0..).zip(run) {
        *c = shade_pixel(color, v.to_level(), dither, x, y);
        v = v.step(plane.dzdx, 1);
    }
}

/// The non-horizontal edge from `p` down to `q` (`q.y > p.y`) on `side`, with the sample
/// rows it crosses on screen; `None` if it crosses none.
pub(crate) fn edge_between<T: Copy>(
    p: &RasterVertex<T>,
    q: &RasterVertex<T>,
    side: Side,
    cfg: &Config,
) -> Option<Edge> {
    let (s, h) = (cfg.subpixel_bits as u32, cfg.half());
    let r0 = row_at_or_below(p.y, s, h).max(0);
    let r1 = row_at_or_below(q.y, s, h).min(cfg.height as i32) - 1;
    (r0 <= r1).then_some(Edge {
        first_row: r0 as i16,
        last_row: r1 as i16,
        x0: p.x,
        y0: p.y,
        dx: q.x - p.x,
        dy: q.y - p.y,
        poly: 0,
        side,
    })
}

/// The vertices of a polygon from its top-left vertex (least y, then least x), clockwise on
/// the display: the order [`Scalar::depth_plane`] wants, so the same polygon gets the same
/// plane bits whatever vertex it was listed from. Returns the count written to `out`.
pub fn canonical<N: Copy>(
    v: &[RasterVertex<N>],
    clockwise: bool,
    out: &mut [RasterVertex<N>; MAX_POLYGON_VERTICES],
) -> usize {
    let n = v.len().min(MAX_POLYGON_VERTICES);
    let start = (0..n).min_by_key(|&k| (v[k].y, v[k].x)).unwrap_or(0);
    for (k, c) in out.iter_mut().take(n).enumerate() {
        let at = if clockwise { start + k } else { start + n - k };
        *c = v[at % n];
    }
    n
}

/// [`canonical`] of a triangle, returned by value: no scratch of [`MAX_POLYGON_VERTICES`]
/// corners to clear for three.
#[inline]
pub(crate) fn canonical_triangle<N: Copy>(
    t: [RasterVertex<N>; 3],
    clockwise: bool,
) -> [RasterVertex<N>; 3] {
    let start = (0..3).min_by_key(|&k| (t[k].y, t[k].x)).unwrap_or(0);
    let (next, last) = match clockwise {
        true => ((start + 1) % 3, (start + 2) % 3),
        false => ((start + 2) % 3, (start + 1) % 3),
    };
    [t[start], t[next], t[last]]
}

/// [`canonical`] of the `n` corners `corner(0..n)`, read where they are (a polygon kept as
/// indices: no gathered copy of its corners, up to 216 bytes of stack in a 32-bit format).
#[inline]
pub(crate) fn canonical_with<N: Copy>(
    n: usize,
    corner: impl Fn(usize) -> RasterVertex<N>,
    clockwise: bool,
    out: &mut [RasterVertex<N>; MAX_POLYGON_VERTICES],
) -> usize {
    let n = n.min(MAX_POLYGON_VERTICES);
    let start = (0..n)
        .min_by_key(|&k| {
            let v = corner(k);
            (v.y, v.x)
        })
        .unwrap_or(0);
    for (k, c) in out.iter_mut().take(n).enumerate() {
        let at = if clockwise { start + k } else { start + n - k };
        *c = corner(at % n);
    }
    n
}

/// Sets a polygon up for rasterisation: [`outline`], then its edges and depth plane.
/// `Ok(None)` when it draws nothing.
pub fn setup<N: Scalar>(
    poly: &RasterPolygon<N>,
    cfg: &Config,
) -> Result<Option<SetupPolygon<N>>, Error> {
    let mut sp = SetupPolygon::empty();
    Ok(setup_into(poly, cfg, &mut sp)?.then_some(sp))
}

/// [`setup`] into `out`, which a method keeps from polygon to polygon: nothing a few hundred
/// bytes large is returned by value (on a 32-bit core each such move is a `memcpy` of the
/// edge table). `Ok(true)` where [`setup`] gives `Some` (then `out` is that polygon),
/// `Ok(false)` where it gives `None` (then `out` is not one to draw).
pub fn setup_into<N: Scalar>(
    poly: &RasterPolygon<N>,
    cfg: &Config,
    out: &mut SetupPolygon<N>,
) -> Result<bool, Error> {
    let v = &poly.vertices[..];
    let Some(o) = outline(v, cfg, poly.face)? else {
        return Ok(false);
    };
    out.edges.clear();
    for k in 0..v.len() {
        let (p, q) = (&v[k], &v[(k + 1) % v.len()]);
        if p.y == q.y {
            continue;
        }
        let down = q.y > p.y;
        let (top, bottom) = if down { (p, q) } else { (q, p) };
        // Clockwise on the display: edges going down bound the right side.
        let side = if down == o.clockwise {
            Side::Right
        } else {
            Side::Left
        };
        if let Some(e) = edge_between(top, bottom, side, cfg) {
            // Cannot overflow: a polygon has at most MAX_POLYGON_VERTICES edges.
            let _ = out.edges.push(e);
        }
    }
    let s = cfg.subpixel_bits as u32;
    let plane = if let [a, b, c] = *v {
        // (Without `canonical`'s 16-corner scratch, cleared per polygon: a `memset`.)
        N::depth_plane(&canonical_triangle([a, b, c], o.clockwise), s)
    } else {
        let mut ordered = [RasterVertex::default(); MAX_POLYGON_VERTICES];
        let n = canonical(v, o.clockwise, &mut ordered);
        N::depth_plane(&ordered[..n], s)
    };
    let Some(plane) = plane else {
        return Ok(false);
    };
    (out.plane, out.color) = (plane, poly.color);
    (out.first_row, out.last_row) = (o.first_row, o.last_row);
    Ok(true)
}

/// The exact plane ([`Scalar::exact_plane`]) of a polygon: the vertices [`setup`] fits its
/// [`SetupPolygon::plane`] to, in the same canonical order. What a method evaluates the depth
/// it hands a sink that reads depth from; `None` where `setup` has no plane.
pub fn exact_plane<N: Scalar>(poly: &RasterPolygon<N>, cfg: &Config) -> Option<N::ExactPlane> {
    let v = &poly.vertices[..];
    let area = signed_area2(v);
    if area == 0 {
        return None;
    }
    let mut ordered = [RasterVertex::default(); MAX_POLYGON_VERTICES];
    let n = canonical(v, area > 0, &mut ordered);
    N::exact_plane(&ordered[..n], cfg.subpixel_bits as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge(x0: i32, y0: i32, x1: i32, y1: i32) -> Edge {
        Edge {
            first_row: 0,
            last_row: 0,
            x0,
            y0,
            dx: x1 - x0,
            dy: y1 - y0,
            poly: 0,
            side: Side::Left,
        }
    }

    /// A fixed xorshift sequence: each call draws a value in `−m..=m`.
    fn uniform(mut seed: u64) -> impl FnMut(i64) -> i64 {
        move |m: i64| {
            let seed = crate::number::xorshift64(&mut seed);
            (seed % (2 * m as u64 + 1)) as i64 - m
        }
    }

    #[test]
    fn fill_run_fills_exactly_its_run() {
        // Every length to past two chunks, at every offset in a chunk: the run and nothing else.
        let (c, other) = (Rgb565::new(31, 0, 7), Rgb565::new(1, 2, 3));
        for len in 0..20 {
            for at in 0..8 {
                // Both paths, whichever this machine takes.
                for fill in [fill_run, fill_unrolled] {
                    let mut row = [other; 32];
                    fill(&mut row[at..at + len], c);
                    for (x, p) in row.iter().enumerate() {
                        let want = if (at..at + len).contains(&x) {
                            c
                        } else {
                            other
                        };
                        assert_eq!(*p, want, "length {len} from {at}, pixel {x}");
                    }
                }
            }
        }
    }

    #[test]
    fn dda_fast_path_equals_the_wide_one() {
        // Edges of every slope and position, first rows just below their tops (the 32-bit
        // path) and far below (a 64-bit numerator), every sub-pixel precision: the walk, and
        // its column alone, as the wide path gives them.
        let mut next = uniform(0x2545_f491_4f6c_dd1d);
        let (mut fast, mut far) = (0, 0);
        for _ in 0..20_000 {
            let s = 1 + (next(3) + 3) as u32 % 8;
            let (x0, y0) = (next(1 << 20) as i32, next(1 << 20) as i32);
            let (dx, dy) = (next(1 << 20) as i32, next(1 << 20).abs().max(1) as i32);
            let e = edge(x0, y0, x0 + dx, y0 + dy);
            let first = row_at_or_below(y0, s, 1 << s >> 1);
            for row in [first, first + 1, first + next(3000).abs() as i32] {
                let t = (row << s) + (1 << s >> 1) - y0;
                fast += (t < 512) as u32;
                far += (t >= 512) as u32;
                assert_eq!(
                    e.dda_at(row, s),
                    e.dda_at_wide(row, s),
                    "{e:?} row {row} s {s}"
                );
                assert_eq!(e.x_at(row, s), e.dda_at_wide(row, s).x(), "{e:?} row {row}");
                let (x1, y1) = (x0 + dx, y0 + dy);
                assert_eq!(Dda::between(x0, y0, x1, y1, row, s), e.dda_at_wide(row, s));
            }
        }
        assert!(
            fast > 20_000 && far > 10_000,
            "{fast} near the top, {far} far below"
        );
    }

    /// The corners read in place (and a triangle by value) come out as `canonical` orders a
    /// gathered copy: every corner count, both windings, ties in y broken by x (a grid of few
    /// values makes many).
    #[test]
    fn canonical_with_orders_as_canonical() {
        let mut next = uniform(0x6a09_e667_f3bc_c908);
        for _ in 0..5_000 {
            let n = 1 + next(MAX_POLYGON_VERTICES as i64 - 1).unsigned_abs() as usize;
            let mut v = [RasterVertex::default(); MAX_POLYGON_VERTICES];
            for (k, p) in v.iter_mut().take(n).enumerate() {
                *p = RasterVertex {
                    x: next(3) as i32,
                    y: next(3) as i32,
                    z: k as i32,
                };
            }
            for clockwise in [false, true] {
                let (mut want, mut got) = (
                    [RasterVertex::default(); MAX_POLYGON_VERTICES],
                    [RasterVertex::default(); MAX_POLYGON_VERTICES],
                );
                let m = canonical(&v[..n], clockwise, &mut want);
                assert_eq!(canonical_with(n, |k| v[k], clockwise, &mut got), m);
                assert_eq!(got[..m], want[..m], "{:?} clockwise {clockwise}", &v[..n]);
                if n == 3 {
                    let t = canonical_triangle([v[0], v[1], v[2]], clockwise);
                    assert_eq!(t[..], want[..3], "{:?} clockwise {clockwise}", &v[..3]);
                }
            }
        }
    }

    #[test]
    fn outline_triangle_equals_the_general_outline() {
        // Triangles of every size and place (on and off screen, degenerate ones too), both
        // windings, with and without culling: the same outline as the general path, and the
        // top-left corner is the least (y, x).
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        let (mut drawn, mut ties) = (0, 0);
        for k in 0..20_000 {
            let s = 1 + (k % 8) as u32;
            let cfg = Config {
                cull: if k % 3 == 0 { Cull::Back } else { Cull::None },
                subpixel_bits: s as u8,
                ..Config::screen(64 + (k % 7) as u16 * 30, 48 + (k % 5) as u16 * 40)
            };
            let scale = [3, 40, 300][k % 3] << s;
            let mut v = [RasterVertex {
                x: 0,
                y: 0,
                z: 0i32,
            }; 3];
            for p in &mut v {
                (p.x, p.y) = (
                    next(scale) as i32 + (100 << s),
                    next(scale) as i32 + (80 << s),
                );
            }
            if k % 10 == 0 {
                v[1].y = v[0].y; // a flat top or bottom: ties in y
                ties += 1;
            }
            let area = signed_area2(&v);
            let general = outline_with_area(3, |i| &v[i], area, &cfg, 0).unwrap();
            let fast = outline_triangle([&v[0], &v[1], &v[2]], area, &cfg);
            assert_eq!(general, fast.map(|(o, _)| o), "{v:?} {cfg:?}");
            if let Some((_, top)) = fast {
                let least = (0..3).min_by_key(|&i| (v[i].y, v[i].x)).unwrap();
                assert_eq!(top, least, "{v:?}");
                drawn += 1;
            }
        }
        assert!(drawn > 5_000 && ties > 1_000, "{drawn} drawn, {ties} ties");
    }

    #[test]
    fn row_at_or_below_is_the_ceiling() {
        for s in 1..=8u32 {
            let h = 1 << s >> 1;
            for y in -3000..3000 {
                assert_eq!(
                    row_at_or_below(y, s, h) as i64,
                    div_ceil(y as i64 - h as i64, 1 << s),
                    "y {y} s {s}"
                );
            }
        }
    }

    #[test]
    fn dda_matches_direct_ceiling_on_every_row() {
        let s = 4;
        let h = 8i64;
        for &(x0, y0, x1, y1) in &[
            (0, 0, 160, 160),
            (100, 3, -37, 999),
            (5, -40, 6, 4000),
            (-3000, 1, 3000, 17),
            (77, 0, 77, 500),
        ] {
            let e = edge(x0, y0, x1, y1);
            let first = row_at_or_below(y0, s, h as i32);
            let mut d = e.dda_at(first, s);
            for row in first..first + 60 {
                let ys = ((row as i64) << s) + h;
                // Crossing x at ys, then the first pixel centre at or right of it.
                let num = (x0 as i64) * (y1 - y0) as i64 + (ys - y0 as i64) * (x1 - x0) as i64
                    - h * (y1 - y0) as i64;
                let want = div_ceil(num, ((y1 - y0) as i64) << s);
                assert_eq!(d.x() as i64, want, "edge {x0},{y0}->{x1},{y1} row {row}");
                d.step();
            }
        }
    }
}
