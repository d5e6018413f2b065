//! The polygon table that methods which revisit polygons keep: every polygon set up once
//! ([`crate::raster::setup`]), with exact queries on its samples.
//!
//! The scan-line method walks polygons once, top to bottom, through its own edge table. The
//! other methods come back to a polygon many times and in any order — a band of rows
//! (tiled z-buffer), an area of the screen (Warnock), another polygon's plane (depth-sort,
//! BSP) — so they keep a [`PolygonTable`](crate::polygons::PolygonTable) and ask it:
//!
//! - [`PolygonTable::covers`](crate::polygons::PolygonTable::covers): does polygon `i` cover the sample of pixel (x, y)? Exactly the
//!   top-left rule, as integer edge functions: a left edge owns a sample on it, a right edge
//!   does not, and the row range (first and last sample row) stands for the horizontal edges.
//! - [`PolygonTable::span`](crate::polygons::PolygonTable::span) and [`PolygonTable::walk`](crate::polygons::PolygonTable::walk): the covered columns `xl..xr` of a row
//!   (exactly the scan-line method's, from the same [`crate::raster::Dda`]s), at one row or row after row.
//! - [`PolygonTable::beats`](crate::polygons::PolygonTable::beats): is `p` visible over `q` at a sample — nearer, or as near and
//!   first in the scene (README, Conventions)? Depth comes from the same [`DepthPlane`](crate::number::DepthPlane) bits every method
//!   uses, so every method breaks every tie the same way.
//!
//! Polygons keep their scene order: index `i` in the table is the `i`-th polygon the scene
//! produced that survived setup.

use crate::error::{Error, Table};
use crate::number::{DepthPlane, Scalar};
#[cfg(feature = "exact-depth")]
use crate::raster::exact_plane;
use crate::raster::{
    fill_run, paint_run, setup_into, signed_area2, Config, Cull, Edge, SetupPolygon, Side,
};
use crate::scene::{IntensityPlane, Scene, VertexBuffer};
use crate::sink::{Row, RowSink};
use embedded_graphics_core::pixelcolor::Rgb565;
use heapless::Vec;

/// One polygon of the table.
#[derive(Clone, Copy, Debug)]
pub struct Stored<N: Scalar> {
    /// Depth plane.
    pub plane: DepthPlane<N>,
    /// The exact plane a sink that reads depth is told depths from
    /// ([`Scalar::exact_plane`]), if the table was built for one (`exact-depth` feature).
    #[cfg(feature = "exact-depth")]
    pub exact: Option<N::ExactPlane>,
    /// Colour after shading.
    pub color: Rgb565,
    /// Smooth shading's intensity, or `None` (flat): kept only with the `gouraud` feature
    /// (24 bytes a polygon in a 32-bit format), read through [`Stored::intensity`].
    #[cfg(feature = "gouraud")]
    intensity: Option<IntensityPlane<N>>,
    /// Opacity (255 = opaque).
    pub alpha: u8,
    /// Whether it is clockwise on the display (a back face, when meshes are culled).
    pub back: bool,
    /// First row whose sample it may cover (on screen).
    pub first_row: i16,
    /// Last such row (inclusive).
    pub last_row: i16,
    /// First column whose sample it may cover (on screen; conservative).
    pub first_col: i16,
    /// Last such column (inclusive; conservative).
    pub last_col: i16,
    /// A pixel whose sample it covers (the first on screen, top to bottom, left to right;
    /// `(first_col, first_row)` if none): where its plane's depth is in range, the anchor of
    /// [`DepthPlane::at_unwrapped`](crate::number::DepthPlane::at_unwrapped).
    pub anchor: (i16, i16),
    edge_start: u32,
    edge_count: u8,
}

impl<N: Scalar> Stored<N> {
    /// Smooth shading's intensity over the polygon, or `None` (flat; always without the
    /// `gouraud` feature, whose geometry alone makes one).
    #[inline]
    pub fn intensity(&self) -> Option<&IntensityPlane<N>> {
        #[cfg(feature = "gouraud")]
        return self.intensity.as_ref();
        #[cfg(not(feature = "gouraud"))]
        None
    }
}

/// Polygons set up for a frame, with their edges; capacities `P` polygons and `E` edges.
pub struct PolygonTable<N: Scalar, const P: usize, const E: usize> {
    polys: Vec<Stored<N>, P>,
    edges: Vec<Edge, E>,
    subpixel_bits: u8,
}

impl<N: Scalar, const P: usize, const E: usize> Default for PolygonTable<N, P, E> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Scalar, const P: usize, const E: usize> PolygonTable<N, P, E> {
    /// An empty table.
    pub const fn new() -> Self {
        PolygonTable {
            polys: Vec::new(),
            edges: Vec::new(),
            subpixel_bits: 8,
        }
    }

    /// Runs the scene's geometry and sets every polygon up. With `keep_back`, polygons that
    /// `cfg.cull` would drop by winding are kept and marked [`Stored::back`] (BSP culls them on
    /// the fly); otherwise they are dropped as the scan-line method drops them.
    ///
    /// Past a capacity it keeps counting, so the error says what the scene needs.
    ///
    /// With `exact` (a sink that reads depth), each polygon keeps its exact plane too
    /// ([`Stored::exact`]).
    pub fn build(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        keep_back: bool,
        exact: bool,
    ) -> Result<(), Error> {
        self.polys.clear();
        self.edges.clear();
        self.subpixel_bits = cfg.subpixel_bits;
        let mut setup_cfg = *cfg;
        if keep_back {
            setup_cfg.cull = Cull::None;
        }
        let (s, h) = (cfg.subpixel_bits as u32, cfg.half());
        let (mut polys, mut edges) = (0u32, 0u32);
        let (table, edge_table) = (&mut self.polys, &mut self.edges);
        #[cfg(not(feature = "exact-depth"))]
        let _ = exact;
        let mut buf = VertexBuffer::new(&mut []);
        // Set up in place, polygon after polygon (no edge table moved by value).
        let mut sp = SetupPolygon::empty();
        scene.polygons(&setup_cfg, &mut buf, &mut |poly| {
            #[cfg(feature = "gouraud")]
            let intensity = poly.intensity;
            let poly = &poly.to_raster()?;
            if !setup_into(poly, &setup_cfg, &mut sp)? {
                return Ok(());
            }
            polys += 1;
            edges += sp.edges.len() as u32;
            let (mut xmin, mut xmax) = (i32::MAX, i32::MIN);
            for e in &sp.edges {
                xmin = xmin.min(e.x0).min(e.x0 + e.dx);
                xmax = xmax.max(e.x0).max(e.x0 + e.dx);
            }
            let col = |x: i32| -((-(x as i64 - h as i64)).div_euclid(1 << s));
            let (first_col, last_col) = (
                col(xmin).clamp(0, cfg.width as i64 - 1) as i16,
                (col(xmax) - 1).clamp(0, cfg.width as i64 - 1) as i16,
            );
            let mut anchor = (first_col, sp.first_row);
            let (y0, y1) = (sp.first_row as i32, sp.last_row as i32);
            walk_edges(&sp.edges, s, y0, y1, |y, xl, xr| {
                let (xl, xr) = (xl.max(0), xr.min(cfg.width as i32));
                if xl < xr {
                    // Both fit: on screen.
                    anchor = (xl as i16, y as i16);
                }
                xl >= xr
            });
            let entry = Stored {
                plane: sp.plane,
                #[cfg(feature = "exact-depth")]
                exact: match exact {
                    true => exact_plane(poly, &setup_cfg),
                    false => None,
                },
                color: sp.color,
                #[cfg(feature = "gouraud")]
                intensity,
                alpha: poly.alpha,
                back: signed_area2(&poly.vertices) > 0,
                first_row: sp.first_row,
                last_row: sp.last_row,
                first_col,
                last_col,
                anchor,
                edge_start: edge_table.len() as u32,
                edge_count: sp.edges.len() as u8,
            };
            if edge_table.len() + sp.edges.len() <= E && table.push(entry).is_ok() {
                for &e in &sp.edges {
                    // Cannot fail: room checked above.
                    let _ = edge_table.push(e);
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
        Ok(())
    }

    /// The depths a sink that reads depth is told along row `y`: each pixel's polygon (its
    /// index in `owner`; others are left as they are) evaluated on its exact plane, run by run
    /// (a table built with `exact`).
    #[cfg(feature = "exact-depth")]
    pub fn exact_row(&self, owner: &[u16], y: i32, depth: &mut [N]) {
        let w = owner.len().min(depth.len());
        let mut x = 0;
        while x < w {
            let o = owner[x];
            let end = owner[x..w]
                .iter()
                .position(|&q| q != o)
                .map_or(w, |n| x + n);
            if let Some(e) = self.polys.get(o as usize).and_then(|p| p.exact.as_ref()) {
                N::exact_run(e, x as i32, y, &mut depth[x..end]);
            }
            x = end;
        }
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.polys.len()
    }
    /// Whether the table is empty.
    pub fn is_empty(&self) -> bool {
        self.polys.is_empty()
    }
    /// Edges in the table.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }
    /// Polygon `i` (panics if out of range, like slice indexing: callers index what they
    /// stored).
    pub fn get(&self, i: usize) -> &Stored<N> {
        &self.polys[i]
    }
    /// All polygons, in scene order.
    pub fn polygons(&self) -> &[Stored<N>] {
        &self.polys
    }
    /// The edges of polygon `i`.
    pub fn edges_of(&self, i: usize) -> &[Edge] {
        let p = &self.polys[i];
        let a = p.edge_start as usize;
        &self.edges[a..a + p.edge_count as usize]
    }

    /// The edge of polygon `i` on `side` that crosses row `y`, if any.
    fn edge_at(&self, i: usize, side: Side, y: i32) -> Option<&Edge> {
        self.edges_of(i)
            .iter()
            .find(|e| e.side == side && e.first_row as i32 <= y && y <= e.last_row as i32)
    }

    /// Polygon `i`'s covered columns at row `y`: `xl..xr`, unclamped (empty if `xl >= xr` or
    /// the row is outside the polygon).
    pub fn span(&self, i: usize, y: i32) -> (i32, i32) {
        let s = self.subpixel_bits as u32;
        match (
            self.edge_at(i, Side::Left, y),
            self.edge_at(i, Side::Right, y),
        ) {
            (Some(l), Some(r)) => (l.x_at(y, s), r.x_at(y, s)),
            _ => (0, 0),
        }
    }

    /// Calls `f(y, xl, xr)` for polygon `i`'s rows in `y0..=y1` (clamped to its own rows), top
    /// to bottom, stepping the edges exactly; stops early when `f` returns `false`.
    pub fn walk(&self, i: usize, y0: i32, y1: i32, f: impl FnMut(i32, i32, i32) -> bool) {
        let p = &self.polys[i];
        let (y0, y1) = (y0.max(p.first_row as i32), y1.min(p.last_row as i32));
        walk_edges(self.edges_of(i), self.subpixel_bits as u32, y0, y1, f);
    }

    /// Whether polygon `i` covers the sample of pixel (`x`, `y`): the top-left rule as edge
    /// functions, `(X − x0)·dy − (Y − y0)·dx` ≥ 0 inside a left edge and < 0 inside a right
    /// one, at the sample (X, Y) in sub-pixels. Equals membership in [`Self::span`].
    pub fn covers(&self, i: usize, x: i32, y: i32) -> bool {
        let p = &self.polys[i];
        if y < p.first_row as i32 || y > p.last_row as i32 {
            return false;
        }
        let s = self.subpixel_bits as u32;
        let h = 1i64 << s >> 1;
        let (xs, ys) = (((x as i64) << s) + h, ((y as i64) << s) + h);
        self.edges_of(i).iter().all(|e| {
            let f = (xs - e.x0 as i64) * e.dy as i64 - (ys - e.y0 as i64) * e.dx as i64;
            match e.side {
                Side::Left => f >= 0,
                Side::Right => f < 0,
            }
        })
    }

    /// Whether polygon `p` is visible over polygon `q` at pixel (`x`, `y`) — judged on their
    /// planes, whether or not they cover it: nearer, or equally near and first in the scene.
    /// The planes are compared unwrapped ([`DepthPlane::at_unwrapped`] from each one's
    /// [`Stored::anchor`]), so along a row the
    /// answer changes at most once even far from either polygon, as splitting by a plane
    /// assumes; where both cover the pixel it is the per-sample rule.
    ///
    /// [`DepthPlane::at_unwrapped`]: crate::number::DepthPlane::at_unwrapped
    #[inline]
    pub fn beats(&self, p: usize, q: usize, x: i32, y: i32) -> bool {
        let plane = |k: usize| {
            let p = &self.polys[k];
            (p.plane).at_unwrapped((p.anchor.0 as i32, p.anchor.1 as i32), x, y)
        };
        let (zp, zq) = (plane(p), plane(q));
        zp < zq || (zp == zq && p < q)
    }

    /// Bytes of RAM a table with these capacities occupies.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();
}

/// Calls `f(y, xl, xr)` for the rows `y0..=y1` of a convex polygon with these edges (from
/// [`crate::raster::setup`]; `y0..=y1` within its rows), top to bottom, stepping each edge's
/// [`crate::raster::Dda`] exactly and switching edges at vertices; stops early when `f` returns `false`.
pub fn walk_edges(
    edges: &[Edge],
    subpixel_bits: u32,
    y0: i32,
    y1: i32,
    mut f: impl FnMut(i32, i32, i32) -> bool,
) {
    let start = |side, y| {
        edges
            .iter()
            .find(|e| e.side == side && e.first_row as i32 <= y && y <= e.last_row as i32)
            .map(|e| (e.dda_at(y, subpixel_bits), e.last_row as i32))
    };
    let (Some(mut l), Some(mut r)) = (start(Side::Left, y0), start(Side::Right, y0)) else {
        return;
    };
    for y in y0..=y1 {
        if y > l.1 {
            let Some(n) = start(Side::Left, y) else {
                return;
            };
            l = n;
        }
        if y > r.1 {
            let Some(n) = start(Side::Right, y) else {
                return;
            };
            r = n;
        }
        if !f(y, l.0.x(), r.0.x()) {
            return;
        }
        if y < l.1 {
            l.0.step();
        }
        if y < r.1 {
            r.0.step();
        }
    }
}

/// Paints `x0..x1` of a row (clamped to it) with polygon `p`: its colour (smooth shaded by its
/// intensity plane, if any), and its depth stepped one pixel at a time from its plane — the
/// same bits as the scan-line method. If `p` has its exact plane (a table built for a sink
/// that reads depth), the piece then gets the perspective cue of `cue`, if that is the cue,
/// from those depths, and the exact depths replace them: the caller leaves the row's cue out.
#[inline]
pub fn paint_span<N: Scalar>(
    depth: &mut [N],
    intensity: &mut [Rgb565],
    p: &Stored<N>,
    cue: &Option<crate::shading::Cue<N>>,
    y: i32,
    x0: i32,
    x1: i32,
) {
    let w = depth.len().min(intensity.len()) as i32;
    let (x0, x1) = (x0.max(0), x1.min(w));
    if x0 >= x1 {
        return;
    }
    let (depth, intensity) = (
        &mut depth[x0 as usize..x1 as usize],
        &mut intensity[x0 as usize..x1 as usize],
    );
    let plane = &p.plane;
    let mut z = plane.at(x0, y);
    for d in depth.iter_mut() {
        *d = z;
        z = z.step(plane.dzdx, 1);
    }
    paint_run(intensity, p.color, p.intensity(), x0, y);
    #[cfg(feature = "exact-depth")]
    if let Some(e) = &p.exact {
        crate::shading::Cue::shade_row_if_perspective(cue, depth, intensity);
        N::exact_run(e, x0, y, depth);
    }
    #[cfg(not(feature = "exact-depth"))]
    let _ = cue;
}

/// Paints and sends every row, top to bottom, with no depth test: in each row the polygons of
/// `order` that cross it, in that order, each over the ones before (the depth row gets each
/// painted pixel's depth when the sink or the cue reads it; else it is left out, as
/// [`RowSink::WANTS_DEPTH`] allows). For the methods whose order alone is exact
/// ([`crate::cullonly`], [`crate::ordered`]).
pub fn paint_in_order<N: Scalar, const P: usize, const E: usize, K: RowSink<N>>(
    t: &PolygonTable<N, P, E>,
    order: impl Iterator<Item = usize> + Clone,
    cfg: &Config,
    cue: &Option<crate::shading::Cue<N>>,
    depth: &mut [N],
    intensity: &mut [Rgb565],
    sink: &mut K,
) -> Result<(), K::Error> {
    let w = (cfg.width as usize).min(depth.len()).min(intensity.len());
    let (depth, intensity) = (&mut depth[..w], &mut intensity[..w]);
    // Depth only where someone reads it: the sink, or the perspective-correct cue.
    let want_depth = K::WANTS_DEPTH
        || cue
            .is_some_and(|c| c.interpolation == crate::shading::Interpolation::PerspectiveCorrect);
    for y in 0..cfg.height as i32 {
        if want_depth {
            depth.fill(N::MAX);
        }
        fill_run(intensity, cfg.background);
        for i in order.clone() {
            let Some(p) = t.polys.get(i) else { continue };
            if (p.first_row as i32..=p.last_row as i32).contains(&y) {
                let (xl, xr) = t.span(i, y);
                if want_depth {
                    paint_span(depth, intensity, p, cue, y, xl, xr);
                } else {
                    let (x0, x1) = (
                        xl.clamp(0, w as i32) as usize,
                        xr.clamp(0, w as i32) as usize,
                    );
                    if x0 < x1 {
                        let (shade, x) = (p.intensity(), x0 as i32);
                        paint_run(&mut intensity[x0..x1], p.color, shade, x, y);
                    }
                }
            }
        }
        if !(crate::sink::EXACT_DEPTH && K::WANTS_DEPTH) {
            // (For a sink that reads depth each piece had it: see `paint_span`.)
            crate::shading::Cue::shade_row_if_perspective(cue, depth, intensity);
        }
        sink.write_row(&Row {
            y: y as u16,
            color: intensity,
            depth: if want_depth { depth } else { &[] },
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec3;
    use crate::scene::{Face, Mesh, ScreenScene};
    use embedded_graphics_core::pixelcolor::RgbColor;

    #[test]
    fn covers_span_and_walk_agree_on_every_sample() {
        // A pentagon and a sliver, either winding, with edges through sample centres.
        let v = [
            Vec3::new(3.5f32, 0.5, 1.0),
            Vec3::new(17.25, 4.5, 2.0),
            Vec3::new(14.0, 19.5, 3.0),
            Vec3::new(2.0, 15.75, 1.0),
            Vec3::new(0.5, 6.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(19.0, 2.5, 0.0),
            Vec3::new(1.5, 3.0, 0.0),
        ];
        let faces = [
            Face::new(&[0, 1, 2, 3, 4], Rgb565::RED),
            Face::new(&[4, 3, 2, 1, 0], Rgb565::GREEN),
            Face::new(&[5, 6, 7], Rgb565::BLUE),
        ];
        let scene = ScreenScene {
            mesh: Mesh::new(&v, &faces),
        };
        let cfg = Config::screen(20, 20);
        let mut t = PolygonTable::<f32, 4, 16>::new();
        t.build(&scene, &cfg, false, false).unwrap();
        assert_eq!(t.len(), 3);
        let mut covered = 0;
        for i in 0..t.len() {
            let mut rows = [None; 20];
            t.walk(i, 0, 19, |y, xl, xr| {
                rows[y as usize] = Some((xl, xr));
                true
            });
            for y in 0..20 {
                for x in 0..20 {
                    let p = t.get(i);
                    let in_rows = (p.first_row as i32..=p.last_row as i32).contains(&y);
                    let (xl, xr) = t.span(i, y);
                    let by_span = in_rows && xl <= x && x < xr;
                    assert_eq!(t.covers(i, x, y), by_span, "poly {i} at ({x}, {y})");
                    if in_rows {
                        assert_eq!(rows[y as usize], Some((xl, xr)), "walk, row {y}");
                        assert!((p.first_col as i32..=p.last_col as i32).contains(&x) || !by_span);
                    }
                    covered += by_span as u32;
                }
            }
        }
        assert!(covered > 150, "the test polygons cover samples ({covered})");
    }
}
