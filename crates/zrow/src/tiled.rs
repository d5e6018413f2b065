//! The tiled 16-bit z-buffer: the z-buffer (Catmull 1974; Foley, van Dam, Feiner &
//! Hughes §15.4) one band of rows at a time, with
//! depth quantised to 16 bits over the frame's depth range — its form for a microcontroller.
//!
//! The z-buffer keeps `depth[x][y]` (set to the maximum) and `intensity[x][y]` (set to
//! the background) for the whole frame, scan-converts each polygon in any order and keeps a
//! pixel where the polygon's `z < depth[x][y]`. For 240×240 that is more RAM than an
//! STM32F411 has ([`crate::zbuffer`]). Here the frame is cut into **bands** of `B` full rows —
//! a band is a tile as wide as the frame, the smallest tile that can still hand whole rows to
//! the sink top to bottom — and each band is a small z-buffer of its own:
//!
//! 1. The scene is set up once into a [`PolygonTable`] (every band revisits the polygons);
//!    every scene and capacity error is raised here, before any row is sent.
//! 2. The frame's depth range `[zmin, zmax]` is found exactly: the depth of every covered
//!    sample on screen lies between those at the two ends of its row's span (depth is linear
//!    along a row), so walking each polygon's spans once gives the least and greatest depth any
//!    polygon has at any pixel it covers.
//! 3. Each polygon's depth plane becomes an integer plane on a grid of `2^-f` depth units,
//!    `f` the largest with the range spanning at most 2^32 grid units (`f64`, once per
//!    polygon). A pixel's 16-bit depth is `q = floor(Zi·M / 2^32)`, with `Zi` its grid depth
//!    above `zmin` and `M = floor(65534·2^32 / range)` (integers): levels `0..=65534`, one
//!    **step** = `2^32 / (M·2^f)` depth units, just over `(zmax − zmin) / 65534`; `0xFFFF` is
//!    "nothing drawn", which every polygon beats. The plane is 64-bit (wrapping, so exact
//!    modulo 2^64), so a depth just off the range by rounding clamps instead of wrapping round.
//! 4. For each band, top to bottom: clear depth to `0xFFFF` and each pixel's owner to none;
//!    for each polygon whose rows meet the band, in scene order, walk its rows in the band
//!    ([`PolygonTable::walk`], the exact top-left rule every method uses) and keep a pixel
//!    where its `q` is strictly less. Per pixel: one 64-bit add, a clamp, one 32×32→64
//!    multiply and a compare — no floating point.
//! 5. Send the band's rows: each pixel's colour is its owner's, and its depth is the owner's
//!    own depth plane at the pixel ([`DepthPlane::at`], stepped along runs) — the same bits as
//!    the z-buffer's in Q16.16, not a dequantised 16-bit value — or `N::MAX` where nothing is
//!    drawn. The band keeps the owner's index rather than its colour: the same two bytes, and
//!    the exact depth comes back for free.
//!
//! **How it was made exact.** In Q16.16 every depth is a multiple of `2^-16` and every range
//! is below 2^16 units, so `f ≥ 16` and `Zi` is the depth bits times a power of two: the
//! integer plane is exact, and `q = floor((z − zmin) / step)` of the very depth bits
//! [`DepthPlane::at`] gives, a monotone function of depth. So two depths at least one step
//! apart are always in the right order, and equal depths (coplanar polygons have identical
//! plane bits) get equal `q`, where the strict `<` and scene order give the pixel to the
//! polygon first in the scene (README, Conventions), as in every method. Nearer than one step, two
//! polygons may tie and the earlier wins: that is the resolution a 16-bit buffer has.
//! [`Quantisation::exact`] reports it.
//!
//! **Resolution** ([`Quantisation::resolution`]): a polygon nearer than another by *more*
//! than it always wins. Exact frames (every Q16.16 frame): one step. Otherwise (f32 depths
//! with bits finer than the grid) each polygon's grid plane is rounded once at a covered
//! reference sample and in its gradients: at most `(1 + |Δx| + |Δy|)/2` grid units at a sample
//! `Δx`, `Δy` pixels away, and one grid unit is less than `2^-15` steps (`M < 2^17`), so the
//! bound is `step · (1 + (w + h)/2^15)`. That is on top of f32's own error in the plane, as for
//! every method; and a polygon whose depth changes by more than 2^31 frame depth ranges per
//! pixel — an edge-on sliver whose f32 depth means nothing — is quantised flat at its reference
//! sample. A frame whose covered samples all have one depth quantises everything to 0: scene
//! order decides, correctly.
//!
//! RAM ([`Tiled::RAM_BYTES`]): the polygon table, 24 bytes a polygon of integer planes,
//! `4·W·B` bytes of band (16-bit depth and owner) and one output row, `W·(2 + size_of::<N>())`.
//!
//! [`PolygonTable`]: crate::polygons::PolygonTable
//! [`PolygonTable::walk`]: crate::polygons::PolygonTable::walk
//! [`DepthPlane::at`]: crate::number::DepthPlane::at
//! [`Quantisation::exact`]: crate::tiled::Quantisation::exact
//! [`Quantisation::resolution`]: crate::tiled::Quantisation::resolution
//! [`Tiled::RAM_BYTES`]: crate::tiled::Tiled::RAM_BYTES
//!
//! ```
//! use zrow::tiled::Tiled;
//! use zrow::{Config, Face, FrameBuffer, Mesh, Q16_16, ScreenScene, Vec3};
//! use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
//!
//! let q = |x: f32, y: f32, z: f32| Vec3::<Q16_16>::from_f32([x, y, z]).unwrap();
//! let v = [q(0.0, 0.0, 1.0), q(8.0, 0.0, 1.0), q(0.0, 8.0, 1.0), // far, first
//!          q(0.0, 0.0, 0.5), q(8.0, 0.0, 0.5), q(8.0, 8.0, 0.5)]; // near
//! let faces = [Face::new(&[0, 1, 2], Rgb565::RED), Face::new(&[3, 4, 5], Rgb565::GREEN)];
//! let scene = ScreenScene { mesh: Mesh::new(&v, &faces) };
//! // 8-pixel rows in bands of 3 rows, 2 polygons, 8 edges.
//! let mut r = Tiled::<Q16_16, 8, 3, 2, 8>::new();
//! let mut pixels = [Rgb565::BLACK; 64];
//! let mut frame = FrameBuffer::new(&mut pixels, 8);
//! let stats = r.render(&scene, &Config::screen(8, 8), &mut frame).unwrap();
//! assert_eq!(stats.areas, 3); // bands of 3, 3 and 2 rows
//! assert_eq!(pixels[8 * 1 + 5], Rgb565::GREEN); // the near triangle, on both
//! assert_eq!(pixels[8 * 5 + 1], Rgb565::RED); // the far one, alone
//! ```

use crate::error::RenderError;
use crate::method::{FrameStats, Renderer};
use crate::number::Scalar;
use crate::polygons::PolygonTable;
use crate::raster::{color_at, Config};
use crate::scene::Scene;
use crate::shading::Interpolation;
use crate::sink::{Row, RowSink};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};

/// Owner of a pixel nothing covers (and depth of such a pixel: beaten by every level).
const NONE: u16 = u16::MAX;
/// Highest quantised depth level.
const TOP_LEVEL: u64 = 65534;
/// Largest range in grid units.
const WINDOW: f64 = 4_294_967_296.0;

/// A polygon's depth as a grid plane (wrapping, so exact modulo 2^64): its grid depth above
/// `zmin` is `z00 + zx·x + zy·y` at pixel (x, y).
#[derive(Clone, Copy, Debug, Default)]
struct GridPlane {
    z00: i64,
    zx: i64,
    zy: i64,
}

impl GridPlane {
    const ZERO: Self = GridPlane {
        z00: 0,
        zx: 0,
        zy: 0,
    };
    #[inline]
    fn at(&self, x: i32, y: i32) -> i64 {
        self.z00
            .wrapping_add(self.zx.wrapping_mul(x as i64))
            .wrapping_add(self.zy.wrapping_mul(y as i64))
    }
}

/// Grid depth → 16-bit level: `floor(clamp(Zi, 0, range)·M / 2^32)`, at most 65534.
#[derive(Clone, Copy, Debug)]
struct Levels {
    range: i64,
    mul: u64,
}

impl Levels {
    #[inline]
    fn level(&self, z: i64) -> u16 {
        // range ≤ 2^32 and range·mul ≤ 65534·2^32: no overflow, and the level is below 0xFFFF
        ((z.clamp(0, self.range) as u64 * self.mul) >> 32) as u16
    }
}

/// How the last frame's depths were quantised to 16 bits.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quantisation {
    /// Least depth of any covered sample on screen.
    pub zmin: f64,
    /// Greatest such depth.
    pub zmax: f64,
    /// Depth units per level: just over `(zmax − zmin)/65534`; 0 when the range is one depth
    /// (then every depth is level 0).
    pub step: f64,
    /// Whether every polygon's 16-bit depth is exactly `floor((z − zmin)/step)` of its depth
    /// plane (always in Q16.16).
    pub exact: bool,
    /// A polygon nearer than another by more than this always wins: `step` when exact, else
    /// `step·(1 + (w + h)/2^15)`.
    pub resolution: f64,
}

impl Quantisation {
    const EMPTY: Self = Quantisation {
        zmin: 0.0,
        zmax: 0.0,
        step: 0.0,
        exact: true,
        resolution: 0.0,
    };
}

/// The tiled 16-bit z-buffer renderer.
///
/// - `N`: number format ([`crate::Q16_16`] or `f32`);
/// - `W`: row capacity (the widest frame, in pixels);
/// - `B`: band height in rows (the tile is `W`×`B`; any frame height is drawn, band by band);
/// - `P`: polygon-table capacity (below 65535); `E`: edge-table capacity.
pub struct Tiled<N: Scalar, const W: usize, const B: usize, const P: usize, const E: usize> {
    table: PolygonTable<N, P, E>,
    planes: [GridPlane; P],
    depth: [[u16; W]; B],
    owner: [[u16; W]; B],
    color_row: [Rgb565; W],
    depth_row: [N; W],
    quant: Quantisation,
}

impl<N: Scalar, const W: usize, const B: usize, const P: usize, const E: usize> Default
    for Tiled<N, W, B, P, E>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Scalar, const W: usize, const B: usize, const P: usize, const E: usize>
    Tiled<N, W, B, P, E>
{
    /// Bytes of RAM the renderer occupies: the polygon table, 24 bytes a polygon, `4·W·B` of
    /// band and `W·(2 + size_of::<N>())` of output row (plus a few words).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer (all zero, so a `static` one sits in `.bss`).
    pub const fn new() -> Self {
        const {
            assert!(B >= 1, "band height must be at least 1 row");
            assert!(P < NONE as usize, "polygon capacity must be below 65535");
        }
        Tiled {
            table: PolygonTable::new(),
            planes: [GridPlane::ZERO; P],
            depth: [[0; W]; B],
            owner: [[0; W]; B],
            color_row: [Rgb565::BLACK; W],
            depth_row: [N::ZERO; W],
            quant: Quantisation::EMPTY,
        }
    }

    /// How the last frame's depths were quantised (its range, step and resolution).
    pub fn quantisation(&self) -> Quantisation {
        self.quant
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
        cfg.validate(W)?;
        self.table.build(scene, cfg, false, K::WANTS_DEPTH)?;
        let cue = crate::shading::Cue::for_rows(scene, cfg)?;
        let (w, h) = (cfg.width as usize, cfg.height as usize);
        let levels = self.quantise(cfg);
        let mut stats = FrameStats {
            polygons: self.table.len() as u32,
            edges: self.table.edge_count() as u32,
            ..FrameStats::default()
        };
        let mut y0 = 0;
        while y0 < h {
            let y1 = (y0 + B).min(h);
            self.fill_band(y0, y1, w, &levels);
            stats.areas += 1;
            self.send_band(y0, y1, w, cfg.background, &cue, sink)
                .map_err(RenderError::Sink)?;
            y0 = y1;
        }
        Ok(stats)
    }

    /// Finds the frame's depth range and turns every polygon's plane into a grid plane.
    fn quantise(&mut self, cfg: &Config) -> Levels {
        let w = cfg.width as i32;
        let table = &self.table;
        // The range: each covered row's span, clamped to the screen, at both ends.
        let mut range: Option<(N, N)> = None;
        for (i, p) in table.polygons().iter().enumerate() {
            let (first, last) = (p.first_row as i32, p.last_row as i32);
            table.walk(i, first, last, |y, xl, xr| {
                let (a, b) = (xl.max(0), xr.min(w));
                if a < b {
                    for z in [p.plane.at(a, y), p.plane.at(b - 1, y)] {
                        if z.is_finite() {
                            range = Some(match range {
                                None => (z, z),
                                Some((lo, hi)) => {
                                    (if z < lo { z } else { lo }, if z > hi { z } else { hi })
                                }
                            });
                        }
                    }
                }
                true
            });
        }
        let flat = Levels { range: 0, mul: 0 };
        let Some((lo, hi)) = range else {
            self.quant = Quantisation::EMPTY;
            self.planes.fill(GridPlane::ZERO);
            return flat;
        };
        let (zmin, zmax) = (lo.to_f64(), hi.to_f64());
        let span = zmax - zmin;
        self.quant = Quantisation {
            zmin,
            zmax,
            ..Quantisation::EMPTY
        };
        // Not `span > 0` (one depth, or f64 overflow of an f32 range): one level, scene order.
        if !(span > 0.0 && span < f64::MAX) {
            self.planes.fill(GridPlane::ZERO);
            return flat;
        }
        // Grid: 2^f per depth unit, the largest with span·2^f ≤ 2^32 (so f ≥ 16 in Q16.16,
        // whose spans are below 2^16).
        let mut f = floor_log2(WINDOW / span);
        let mut grid_span = span * pow2(f);
        if grid_span > WINDOW {
            f -= 1;
            grid_span = span * pow2(f);
        }
        let scale = pow2(f);
        // ceil(grid_span): in 2^31..=2^32.
        let mut r = grid_span as u64;
        if (r as f64) < grid_span {
            r += 1;
        }
        let mul = (TOP_LEVEL << 32) / r.max(1);
        let levels = Levels {
            range: r as i64,
            mul,
        };
        let mut exact = true;
        // Fixed point: every depth and gradient is its bits times a power of two on the grid
        // (f at least the fractional bits, see the module), so the grid plane is integer
        // arithmetic, the same integers as the `f64` way (a Cortex-M has no `f64` unit:
        // ~1,700 instructions a polygon there).
        let zmin_grid = lo.scaled_exact(f);
        for ((i, p), g) in table.polygons().iter().enumerate().zip(&mut self.planes) {
            // Reference: the polygon's first covered sample on screen (none: it draws nothing).
            let mut at = None;
            table.walk(i, p.first_row as i32, p.last_row as i32, |y, xl, xr| {
                let a = xl.max(0);
                if a < xr.min(w) {
                    at = Some((a, y));
                }
                at.is_none()
            });
            let Some((xr, yr)) = at else {
                *g = GridPlane::ZERO;
                continue;
            };
            let z = p.plane.at(xr, yr);
            let on_grid = |v: N| v.scaled_exact(f);
            let grid = match (
                zmin_grid,
                on_grid(z),
                on_grid(p.plane.dzdx),
                on_grid(p.plane.dzdy),
            ) {
                (Some(z0), Some(zr), Some(gx), Some(gy)) => Some((zr - z0, gx, gy)),
                _ => None,
            };
            let (zr, gx, gy) = grid.unwrap_or_else(|| {
                let (d, err) = two_diff(z.to_f64(), zmin);
                let (zr, e0) = round(d * scale);
                let (gx, e1) = round(p.plane.dzdx.to_f64() * scale);
                let (gy, e2) = round(p.plane.dzdy.to_f64() * scale);
                exact &= err == 0.0 && e0 && e1 && e2;
                (zr, gx, gy)
            });
            let z00 = zr
                .wrapping_sub(gx.wrapping_mul(xr as i64))
                .wrapping_sub(gy.wrapping_mul(yr as i64));
            *g = GridPlane {
                z00,
                zx: gx,
                zy: gy,
            };
        }
        let step = 4_294_967_296.0 / (mul as f64 * scale);
        let slack = (cfg.width as f64 + cfg.height as f64) / 32768.0;
        self.quant.step = step;
        self.quant.exact = exact;
        self.quant.resolution = if exact { step } else { step * (1.0 + slack) };
        levels
    }

    /// Draws the rows `y0..y1` (at most `B`) into the band.
    fn fill_band(&mut self, y0: usize, y1: usize, w: usize, levels: &Levels) {
        let Tiled {
            table,
            planes,
            depth,
            owner,
            ..
        } = self;
        // w ≤ W: checked by `cfg.validate(W)`.
        for (d, o) in depth.iter_mut().zip(owner.iter_mut()).take(y1 - y0) {
            d[..w].fill(NONE);
            o[..w].fill(NONE);
        }
        let (top, bottom) = (y0 as i32, y1 as i32 - 1);
        for ((i, p), g) in table.polygons().iter().enumerate().zip(planes.iter()) {
            if (p.last_row as i32) < top || (p.first_row as i32) > bottom {
                continue;
            }
            table.walk(i, top, bottom, |y, xl, xr| {
                let (a, b) = (xl.max(0) as usize, xr.min(w as i32).max(0) as usize);
                let row = (y - top) as usize;
                let (Some(drow), Some(orow)) = (depth.get_mut(row), owner.get_mut(row)) else {
                    return true;
                };
                let (Some(ds), Some(os)) = (drow.get_mut(a..b), orow.get_mut(a..b)) else {
                    return true;
                };
                let mut z = g.at(a as i32, y);
                for (d, o) in ds.iter_mut().zip(os) {
                    let q = levels.level(z);
                    if q < *d {
                        *d = q;
                        *o = i as u16;
                    }
                    z = z.wrapping_add(g.zx);
                }
                true
            });
        }
    }

    /// Sends the band's rows `y0..y1`: colours from the owners, depths from their planes
    /// where they are read.
    fn send_band<K: RowSink<N>>(
        &mut self,
        y0: usize,
        y1: usize,
        w: usize,
        background: Rgb565,
        cue: &Option<crate::shading::Cue<N>>,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        let polys = self.table.polygons();
        // Depths only where they are read: by the sink, or by the perspective-correct cue.
        let perspective = cue.filter(|c| c.interpolation == Interpolation::PerspectiveCorrect);
        let depths = K::WANTS_DEPTH || perspective.is_some();
        for (k, orow) in self.owner.iter().enumerate().take(y1 - y0) {
            let y = (y0 + k) as i32;
            if !depths {
                for (x, (&o, c)) in orow.iter().zip(&mut self.color_row).enumerate().take(w) {
                    *c = match polys.get(o as usize) {
                        None => background,
                        Some(p) => color_at(p.color, p.intensity(), x as i32, y),
                    };
                }
                sink.write_row(&Row {
                    y: y as u16,
                    color: &self.color_row[..w],
                    depth: &[],
                })?;
                continue;
            }
            depth_row(
                polys,
                orow,
                (&mut self.color_row[..w], &mut self.depth_row[..w]),
                y,
                background,
                perspective.as_ref(),
            );
            #[cfg(feature = "exact-depth")]
            if crate::sink::EXACT_DEPTH && K::WANTS_DEPTH {
                // The sink's depths: each visible polygon's exact plane.
                self.table
                    .exact_row(&orow[..w], y, &mut self.depth_row[..w]);
            }
            sink.write_row(&Row {
                y: y as u16,
                color: &self.color_row[..w],
                depth: &self.depth_row[..w],
            })?;
        }
        Ok(())
    }
}

/// One row's colours and depths from its owners (`orow`, [`NONE`] where no polygon is): each
/// pixel its polygon's colour and plane depth (stepped along a run of one owner), or the
/// background at the format's maximum depth; shaded by the perspective-correct cue if there
/// is one. Out of line: the band's loops keep their registers.
#[inline(never)]
fn depth_row<N: Scalar>(
    polys: &[crate::polygons::Stored<N>],
    orow: &[u16],
    (colors, depths): (&mut [Rgb565], &mut [N]),
    y: i32,
    background: Rgb565,
    perspective: Option<&crate::shading::Cue<N>>,
) {
    let (mut last, mut z) = (NONE, N::MAX);
    for (x, ((&o, c), d)) in orow.iter().zip(colors).zip(depths).enumerate() {
        // NONE ≥ P > every index, so an empty pixel finds no polygon.
        match polys.get(o as usize) {
            None => (*c, z) = (background, N::MAX),
            Some(p) => {
                z = if o == last {
                    z.step(p.plane.dzdx, 1)
                } else {
                    p.plane.at(x as i32, y)
                };
                let color = color_at(p.color, p.intensity(), x as i32, y);
                *c = match perspective {
                    Some(cue) => crate::geometry::shade(color, cue.at_depth(z)),
                    None => color,
                };
            }
        }
        *d = z;
        last = o;
    }
}

impl<N: Scalar, const W: usize, const B: usize, const P: usize, const E: usize> Renderer<N>
    for Tiled<N, W, B, P, E>
{
    const NAME: &'static str = "tiled";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        Tiled::render(self, scene, cfg, sink)
    }
}

/// `floor(log2(v))` of a positive normal `v`, from its exponent bits.
fn floor_log2(v: f64) -> i32 {
    ((v.to_bits() >> 52) & 0x7ff) as i32 - 1023
}

/// `2^e` for `e` in −1022..=1023 (the frame's grid exponent is well inside).
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e.clamp(-1022, 1023) + 1023) as u64) << 52)
}

/// `a − b` and its rounding error (Knuth's two-sum): the error is 0 when the difference is exact.
fn two_diff(a: f64, b: f64) -> (f64, f64) {
    let s = a - b;
    let bb = s - a;
    (s, (a - (s - bb)) - (b + bb))
}

/// `v` rounded to the nearest integer (halves up), and whether that was exact. Beyond ±2^63
/// (or NaN) it is 0, inexact: only an f32 plane that steep (see the module doc).
fn round(v: f64) -> (i64, bool) {
    const LIMIT: f64 = 9_223_372_036_854_775_808.0; // 2^63
    if !(v > -LIMIT && v < LIMIT) {
        return (0, false);
    }
    // Below 2^52 in magnitude v + 0.5 is exact; above, v is already an integer.
    let t = if v > -4.5e15 && v < 4.5e15 {
        v + 0.5
    } else {
        v
    };
    let mut i = t as i64;
    if (i as f64) > t {
        i -= 1;
    }
    (i, i as f64 == v)
}
