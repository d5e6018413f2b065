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
//! - an edge's crossing moves by 1/m per row (the seeds' `x' = x + 1/m`), kept exactly as an
//!   integer quotient and remainder ([`Dda`](crate::raster::Dda)), so no error accumulates down the edge.
//!
//! Zero area after snapping counts as back-facing and is dropped.
//!
//! Bit budget: geometry clips to a guard band of [`GUARD_BAND`](crate::raster::GUARD_BAND) pixels around the viewport and
//! viewports are at most [`MAX_VIEWPORT`](crate::raster::MAX_VIEWPORT) pixels a side, so coordinates stay below 2^13 pixels;
//! with at most 8 sub-pixel bits the per-row walk fits `i32` and setup uses `i64`.

use crate::error::Error;
use crate::number::{DepthPlane, Scalar};
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

/// First sample row at or below `y` (sub-pixels): `ceil((y − h)/2^S)`.
fn row_at_or_below(y: i32, s: u32, h: i32) -> i32 {
    div_ceil(y as i64 - h as i64, 1 << s) as i32
}

impl Edge {
    /// The state of the exact walk at `row` (which must lie in `first_row..=last_row`).
    pub fn dda_at(&self, row: i32, s: u32) -> Dda {
        let h = 1i64 << s >> 1;
        let den = (self.dy as i64) << s;
        let ys = ((row as i64) << s) + h;
        let num = (self.x0 as i64 - h) * self.dy as i64 + (ys - self.y0 as i64) * self.dx as i64;
        let q = div_ceil(num, den);
        let r = q * den - num;
        let step = (self.dx as i64) << s;
        let qs = step.div_euclid(den);
        let rs = step - qs * den;
        Dda {
            x: q as i32,
            r: r as i32,
            qs: qs as i32,
            rs: rs as i32,
            den: den as i32,
        }
    }
}

/// The exact per-row walk of one edge: `x` is the first pixel column whose centre is at or
/// right of the edge's crossing with the current row's sample line.
///
/// It is the seeds' `x += 1/m` with 1/m split into a whole step `qs` and a remainder `rs`
/// over `den`, as Bresenham does: `x − r/den` is exactly `(crossing − h)/2^S`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Dda {
    /// Current pixel column.
    pub x: i32,
    r: i32,
    qs: i32,
    rs: i32,
    den: i32,
}

impl Dda {
    /// Where the edge crosses the current row's sample line, in pixel columns (pixel `i`'s
    /// centre is `i`): `x − r/den`, rounded to the format.
    pub fn crossing<N: Scalar>(&self) -> N {
        // One conversion: this runs per span on the affine-cue path.
        N::from_f32(self.x as f32 - self.fraction_f32()).unwrap_or(N::ZERO)
    }

    /// How far left of column `x`'s centre the edge crosses the row: `r/den`, in `0..1`.
    pub fn fraction<N: Scalar>(&self) -> N {
        N::from_f32(self.fraction_f32()).unwrap_or(N::ZERO)
    }

    fn fraction_f32(&self) -> f32 {
        if self.den > 0 {
            self.r as f32 / self.den as f32
        } else {
            0.0
        }
    }

    /// Moves to the next row.
    #[inline]
    pub fn step(&mut self) {
        self.x += self.qs;
        self.r -= self.rs;
        if self.r < 0 {
            self.r += self.den;
            self.x += 1;
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

/// Sets a polygon up for rasterisation. `Ok(None)` when it draws nothing: zero area after
/// snapping, culled as a back face, or no sample on screen.
///
/// A convex polygon's outline goes down once and up once; one that does not (a non-convex
/// face) is [`Error::NotConvex`]. Snapping is monotone, so it never makes a convex polygon fail.
pub fn setup<N: Scalar>(
    poly: &RasterPolygon<N>,
    cfg: &Config,
) -> Result<Option<SetupPolygon<N>>, Error> {
    let v = &poly.vertices[..];
    if v.len() < 3 {
        return Ok(None);
    }
    let area = signed_area2(v);
    if area == 0 || (cfg.cull == Cull::Back && area > 0) {
        return Ok(None);
    }
    // y-monotone check: going round, the direction of travel in y changes sign at most twice.
    let dir = |k: usize| {
        let (p, q) = (&v[k], &v[(k + 1) % v.len()]);
        (q.y as i64 - p.y as i64).signum()
    };
    let mut last = (0..v.len()).rev().map(dir).find(|&d| d != 0).unwrap_or(0);
    let mut changes = 0;
    for d in (0..v.len()).map(dir).filter(|&d| d != 0) {
        changes += (d != last) as u32;
        last = d;
    }
    if changes > 2 {
        return Err(Error::NotConvex { face: poly.face });
    }
    // Reject polygons whose bounding box misses every sample.
    let s = cfg.subpixel_bits as u32;
    let h = cfg.half();
    let (mut xmin, mut xmax) = (i32::MAX, i32::MIN);
    for p in v {
        xmin = xmin.min(p.x);
        xmax = xmax.max(p.x);
    }
    let width = cfg.width as i32;
    let height = cfg.height as i32;
    if row_at_or_below(xmax, s, h) <= 0 || row_at_or_below(xmin, s, h) >= width {
        return Ok(None);
    }
    let mut edges = heapless::Vec::new();
    let (mut first, mut last_row) = (i32::MAX, i32::MIN);
    for k in 0..v.len() {
        let (p, q) = (v[k], v[(k + 1) % v.len()]);
        if p.y == q.y {
            continue;
        }
        let down = q.y > p.y;
        let (top, bottom) = if down { (p, q) } else { (q, p) };
        let r0 = row_at_or_below(top.y, s, h).max(0);
        let r1 = row_at_or_below(bottom.y, s, h).min(height) - 1;
        if r0 > r1 {
            continue;
        }
        // Clockwise on the display (area > 0): edges going down bound the right side.
        let side = if down == (area > 0) {
            Side::Right
        } else {
            Side::Left
        };
        first = first.min(r0);
        last_row = last_row.max(r1);
        // Cannot overflow: a polygon has at most MAX_POLYGON_VERTICES edges.
        let _ = edges.push(Edge {
            first_row: r0 as i16,
            last_row: r1 as i16,
            x0: top.x,
            y0: top.y,
            dx: bottom.x - top.x,
            dy: bottom.y - top.y,
            poly: 0,
            side,
        });
    }
    if edges.is_empty() {
        return Ok(None);
    }
    // Canonical order for the plane: from the top-left vertex, clockwise on the display.
    let start = (0..v.len()).min_by_key(|&k| (v[k].y, v[k].x)).unwrap_or(0);
    let mut canonical = [RasterVertex::default(); MAX_POLYGON_VERTICES];
    for (k, c) in canonical.iter_mut().take(v.len()).enumerate() {
        let at = if area > 0 {
            start + k
        } else {
            start + v.len() - k
        };
        *c = v[at % v.len()];
    }
    let Some(plane) = N::depth_plane(&canonical[..v.len()], s) else {
        return Ok(None);
    };
    Ok(Some(SetupPolygon {
        plane,
        color: poly.color,
        first_row: first as i16,
        last_row: last_row as i16,
        edges,
    }))
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
                assert_eq!(d.x as i64, want, "edge {x0},{y0}->{x1},{y1} row {row}");
                d.step();
            }
        }
    }
}
