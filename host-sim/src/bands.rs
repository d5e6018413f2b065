//! Scenes larger than the host's tables, drawn band by band.
//!
//! Every method here decides each row from the polygons that cross that row alone, so a frame
//! can be cut into horizontal bands. Geometry runs once over the whole scene (clipped,
//! projected, snapped, culled and shaded by [`Scene::polygons`]) into memory sized to the
//! scene, [`Projected`]; the rows are then cut into bands that each fit the host capacities
//! ([`cut`]), and every band is drawn by the chosen method from the polygons reaching it, its
//! own rows kept. The polygons reaching a row, their colours and depths are those a single
//! render would see, so the pixels are those of one render with tables sized to the whole
//! scene: a model of any size renders, in memory proportional to its polygons.

use crate::render::{
    check_capacity, on_big_stack, Algo, HostABuffer, HostBsp, HostCullOnly, HostDepthSort,
    HostOrdered, HostScanline, HostTiled, HostWarnock, HostZBuffer, Image, HOST_EDGES,
    HOST_POLYGONS,
};
use crate::SimError;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use std::ops::Range;
use zrow::geometry::ViewDepth;
use zrow::raster::{RasterVertex, MAX_POLYGON_VERTICES};
use zrow::scene::{IntensityPlane, Polygon, VertexBuffer};
use zrow::{Config, RenderError, Renderer, Row, RowSink, Scalar, Scene};

/// A frame's polygons after geometry, kept for drawing band by band.
pub struct Projected<N> {
    vertices: Vec<RasterVertex<N>>,
    polygons: Vec<Stored<N>>,
}

/// One polygon of [`Projected`]: its corners are `vertices[start..start + len]`.
#[derive(Clone, Copy, Debug)]
struct Stored<N> {
    start: u32,
    len: u8,
    alpha: u8,
    color: Rgb565,
    intensity: Option<IntensityPlane<N>>,
    face: u32,
    area2: i64,
    /// The rows whose sample line (the pixel centres, `y + 0.5`) passes within one sub-pixel
    /// of its corners' extent, inclusive: the rows it may draw in (none: it draws nothing).
    rows: (i32, i32),
}

impl<N: Scalar> Projected<N> {
    /// Runs geometry over `scene` once, with a vertex buffer of `slots` (the scene's
    /// [`zrow::Requirements::vertices`]: each shared vertex projected once).
    pub fn of<S: Scene<N> + ?Sized>(
        scene: &S,
        cfg: &Config,
        slots: usize,
    ) -> Result<Self, zrow::Error> {
        let mut buffer = vec![RasterVertex::<N>::default(); slots];
        let mut buffer = VertexBuffer::new(&mut buffer);
        let mut out = Projected {
            vertices: Vec::new(),
            polygons: Vec::new(),
        };
        let s = u32::from(cfg.subpixel_bits);
        let (one, half) = (1i64 << s, 1i64 << s >> 1);
        // Rows r with top - 1 <= r·one + half <= bottom + 1, in sub-pixels.
        let first = |top: i32| (i64::from(top) - 1 - half).div_euclid(one) + 1;
        let last = |bottom: i32| (i64::from(bottom) + 1 - half).div_euclid(one);
        let row = |r: i64| r.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        scene.polygons(cfg, &mut buffer, &mut |p| {
            let start = u32::try_from(out.vertices.len()).map_err(|_| zrow::Error::BadConfig)?;
            let (mut top, mut bottom) = (i32::MAX, i32::MIN);
            for k in 0..p.corners.len() {
                let v = p.vertex(k).ok_or(zrow::Error::IndexOutOfRange {
                    face: p.face,
                    index: p.corners[k],
                })?;
                (top, bottom) = (top.min(v.y), bottom.max(v.y));
                out.vertices.push(v);
            }
            out.polygons.push(Stored {
                start,
                len: p.corners.len() as u8,
                alpha: p.alpha,
                color: p.color,
                intensity: p.intensity,
                face: p.face,
                area2: p.area2,
                rows: (row(first(top)), row(last(bottom))),
            });
            Ok(())
        })?;
        Ok(out)
    }

    /// Polygons kept.
    pub fn len(&self) -> usize {
        self.polygons.len()
    }

    /// Whether no polygon is kept.
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
    }
}

/// Cuts rows `0..height` into bands, top to bottom, each reached by at most `max_polygons`
/// polygons with at most `max_corners` corners between them (a single row may exceed that:
/// then drawing it reports the capacity), and lists the polygons reaching each band in scene
/// order.
pub fn cut<N>(
    projected: &Projected<N>,
    height: u16,
    max_polygons: usize,
    max_corners: usize,
) -> Vec<(Range<u16>, Vec<u32>)> {
    let h = usize::from(height);
    if h == 0 {
        return Vec::new();
    }
    let clamp = |r: i32| r.clamp(0, h as i32 - 1) as usize;
    // Polygons (and corners) whose first row is at or above r, and whose last row is above r.
    let (mut starts, mut ends) = (vec![(0usize, 0usize); h + 1], vec![(0usize, 0usize); h + 1]);
    let reaches = |p: &Stored<N>| p.rows.0 <= p.rows.1 && p.rows.1 >= 0 && p.rows.0 < h as i32;
    for p in projected.polygons.iter().filter(|p| reaches(p)) {
        let n = usize::from(p.len);
        let (a, b) = (clamp(p.rows.0), clamp(p.rows.1));
        starts[a].0 += 1;
        starts[a].1 += n;
        ends[b + 1].0 += 1;
        ends[b + 1].1 += n;
    }
    for r in 1..=h {
        starts[r] = (starts[r].0 + starts[r - 1].0, starts[r].1 + starts[r - 1].1);
        ends[r] = (ends[r].0 + ends[r - 1].0, ends[r].1 + ends[r - 1].1);
    }
    // Reaching rows a..b (b > a): first row at or above b - 1, last row at or below a.
    let reach = |a: usize, b: usize| {
        (
            starts[b - 1].0 - ends[a].0.min(starts[b - 1].0),
            starts[b - 1].1 - ends[a].1.min(starts[b - 1].1),
        )
    };
    let mut cuts = Vec::new();
    let mut a = 0;
    while a < h {
        let mut b = a + 1;
        while b < h && {
            let (p, c) = reach(a, b + 1);
            p <= max_polygons && c <= max_corners
        } {
            b += 1;
        }
        cuts.push(a as u16..b as u16);
        a = b;
    }
    let mut members = vec![Vec::new(); cuts.len()];
    for (i, p) in projected.polygons.iter().enumerate() {
        if !reaches(p) {
            continue;
        }
        let (a, b) = (clamp(p.rows.0) as u16, clamp(p.rows.1) as u16);
        let first = cuts.partition_point(|band| band.end <= a);
        for (band, list) in cuts[first..].iter().zip(&mut members[first..]) {
            if band.start > b {
                break;
            }
            list.push(i as u32);
        }
    }
    cuts.into_iter().zip(members).collect()
}

/// The polygons of [`Projected`] that reach one band, as a scene of their own: geometry
/// already done, they are handed over as they are.
struct Band<'a, N, S: ?Sized> {
    projected: &'a Projected<N>,
    members: &'a [u32],
    /// The scene they came from (for how depth maps back to distance).
    scene: &'a S,
}

impl<N: Scalar, S: Scene<N> + ?Sized> Scene<N> for Band<'_, N, S> {
    fn polygons(
        &self,
        _cfg: &Config,
        vertices: &mut VertexBuffer<'_, N>,
        f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), zrow::Error>,
    ) -> Result<(), zrow::Error> {
        let mut corners = [0u32; MAX_POLYGON_VERTICES];
        for &i in self.members {
            let p = self.projected.polygons[i as usize];
            let start = p.start as usize;
            let v = &self.projected.vertices[start..start + usize::from(p.len)];
            let n = v.len();
            let polygon = |vertices, corners, cached| Polygon {
                vertices,
                corners,
                cached,
                area2: p.area2,
                color: p.color,
                intensity: p.intensity,
                alpha: p.alpha,
                face: p.face,
            };
            match vertices.push(v) {
                Some(first) => {
                    for (k, c) in corners[..n].iter_mut().enumerate() {
                        *c = first + k as u32;
                    }
                    f(&polygon(vertices.as_slice(), &corners[..n], true))?;
                }
                None => {
                    for (k, c) in corners[..n].iter_mut().enumerate() {
                        *c = k as u32;
                    }
                    f(&polygon(v, &corners[..n], false))?;
                }
            }
        }
        Ok(())
    }

    fn view_depth(&self, cfg: &Config) -> Option<ViewDepth<N>> {
        self.scene.view_depth(cfg)
    }
}

/// Keeps the rows of one band.
struct BandRows<'a> {
    pixels: &'a mut [Rgb565],
    width: usize,
    rows: Range<u16>,
}

impl<N> RowSink<N> for BandRows<'_> {
    type Error = core::convert::Infallible;
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Self::Error> {
        if self.rows.contains(&row.y) {
            let start = usize::from(row.y) * self.width;
            let n = row.color.len().min(self.width);
            if let Some(dst) = self.pixels.get_mut(start..start + n) {
                dst.copy_from_slice(&row.color[..n]);
            }
        }
        Ok(())
    }
}

/// The host's band size: what one band's polygons may need of the host tables.
pub const BAND_POLYGONS: usize = HOST_POLYGONS;
/// Corners one band's polygons may have between them (edges and vertex slots).
pub const BAND_CORNERS: usize = HOST_EDGES;

/// Draws `scene` band by band with `algo` (not [`Algo::Auto`]: resolve it first), each band
/// reached by at most `max_polygons` polygons with `max_corners` corners (at most
/// [`BAND_POLYGONS`] and [`BAND_CORNERS`]); `slots` is the scene's vertex requirement.
pub fn draw<N: Scalar + Send + Sync, S: Scene<N> + Sync + ?Sized>(
    algo: Algo,
    scene: &S,
    cfg: &Config,
    slots: usize,
    max_polygons: usize,
    max_corners: usize,
    blame: impl FnOnce(zrow::Error) -> SimError,
) -> Result<Image, SimError> {
    let f = match algo {
        Algo::Scanline | Algo::Auto => draw_with::<N, S, HostScanline<N>>,
        Algo::CullOnly => draw_with::<N, S, HostCullOnly<N>>,
        Algo::Ordered => draw_with::<N, S, HostOrdered<N>>,
        Algo::ZBuffer => draw_with::<N, S, HostZBuffer<N>>,
        Algo::Tiled => draw_with::<N, S, HostTiled<N>>,
        Algo::Warnock => draw_with::<N, S, HostWarnock<N>>,
        Algo::DepthSort => draw_with::<N, S, HostDepthSort<N>>,
        Algo::Bsp => draw_with::<N, S, HostBsp<N>>,
        Algo::ABuffer => draw_with::<N, S, HostABuffer<N>>,
    };
    let limits = (
        max_polygons.min(BAND_POLYGONS),
        max_corners.min(BAND_CORNERS),
    );
    f(scene, cfg, slots, limits).map_err(|e| match e {
        Failure::Scene(e) => blame(e),
        Failure::Sim(e) => e,
    })
}

enum Failure {
    Scene(zrow::Error),
    Sim(SimError),
}

fn draw_with<N: Scalar + Send + Sync, S: Scene<N> + Sync + ?Sized, R: Renderer<N> + Default>(
    scene: &S,
    cfg: &Config,
    slots: usize,
    (max_polygons, max_corners): (usize, usize),
) -> Result<Image, Failure> {
    let projected = Projected::of(scene, cfg, slots).map_err(Failure::Scene)?;
    let bands = cut(&projected, cfg.height, max_polygons, max_corners);
    let (width, height) = (cfg.width, cfg.height);
    let mut pixels = vec![Rgb565::BLACK; usize::from(width) * usize::from(height)];
    on_big_stack(R::RAM_BYTES, || {
        let mut renderer = R::default();
        for (rows, members) in &bands {
            let band = Band {
                projected: &projected,
                members,
                scene,
            };
            let req = zrow::requirements(&band, cfg)?;
            check_capacity(&req)?;
            let mut sink = BandRows {
                pixels: &mut pixels,
                width: usize::from(width),
                rows: rows.clone(),
            };
            renderer
                .render(&band, cfg, &mut sink)
                .map_err(|e| match e {
                    RenderError::Scene(e) => e,
                    RenderError::Sink(never) => match never {},
                })?;
        }
        Ok(())
    })
    .map_err(Failure::Sim)?
    .map_err(Failure::Scene)?;
    Ok(Image {
        width,
        height,
        pixels,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::model::{parse, LoadedModel, ModelFormat};
    use crate::model_render::{render_model_image, with_scene, View};
    use crate::render::Format;
    use zrow::Q16_16;

    /// A torus of `2·nu·nv` triangles, from OFF text, coloured by band (the window's tests
    /// use it too).
    pub(crate) fn torus(nu: usize, nv: usize) -> LoadedModel {
        let mut off = format!("OFF\n{} {} 0\n", nu * nv, 2 * nu * nv);
        for i in 0..nu {
            let a = std::f64::consts::TAU * i as f64 / nu as f64;
            for j in 0..nv {
                let b = std::f64::consts::TAU * j as f64 / nv as f64;
                let r = 1.0 + 0.35 * b.cos();
                off += &format!("{} {} {}\n", r * a.cos(), 0.35 * b.sin(), r * a.sin());
            }
        }
        for i in 0..nu {
            for j in 0..nv {
                let at = |di: usize, dj: usize| ((i + di) % nu) * nv + (j + dj) % nv;
                let (p, q, p1, q1) = (at(0, 0), at(1, 0), at(0, 1), at(1, 1));
                // Colours by band so that a misplaced polygon shows.
                let c = 60 + 30 * (i % 6);
                off += &format!("3 {p} {p1} {q} {c} 200 90\n3 {q} {p1} {q1} 90 {c} 200\n");
            }
        }
        parse("torus.off", ModelFormat::Off, off.as_bytes(), ".".as_ref()).unwrap()
    }

    fn banded<N: Scalar + Send + Sync>(
        model: &LoadedModel,
        view: &View,
        (w, h): (u16, u16),
        algo: Algo,
        limits: (usize, usize),
    ) -> (Image, usize) {
        with_scene::<N, _>(model, view, w, h, |scene, cfg| {
            let req = zrow::requirements(scene, cfg).unwrap();
            let projected = Projected::of(scene, cfg, req.vertices as usize).unwrap();
            let bands = cut(&projected, h, limits.0, limits.1).len();
            let image = draw(
                algo,
                scene,
                cfg,
                req.vertices as usize,
                limits.0,
                limits.1,
                |e| panic!("{e}"),
            )
            .unwrap();
            (image, bands)
        })
        .unwrap()
    }

    #[test]
    fn bands_draw_every_method_as_one_pass_does() {
        let model = torus(24, 12);
        let size = (72, 60);
        let views = [
            View::default(),
            View {
                yaw_deg: -70.0,
                pitch_deg: 55.0,
                distance: 2.2,
            },
            // Near enough for the near plane to cut the torus.
            View {
                yaw_deg: 10.0,
                pitch_deg: 5.0,
                distance: 1.25,
            },
        ];
        let algos = [
            Algo::Scanline,
            Algo::ZBuffer,
            Algo::Tiled,
            Algo::DepthSort,
            Algo::Warnock,
            Algo::Bsp,
            Algo::ABuffer,
        ];
        for view in &views {
            for algo in algos {
                for format in [Format::Q16_16, Format::F32] {
                    let whole =
                        render_model_image(&model, view, size.0, size.1, algo, format).unwrap();
                    // Small tables: many bands, a polygon often in several.
                    let (parts, bands) = match format {
                        Format::Q16_16 => banded::<Q16_16>(&model, view, size, algo, (40, 150)),
                        Format::F32 => banded::<f32>(&model, view, size, algo, (40, 150)),
                    };
                    assert!(bands >= 6, "{bands} bands");
                    assert!(
                        whole.pixels == parts.pixels,
                        "{algo:?} {format:?} {view:?}: {} pixels differ",
                        whole
                            .pixels
                            .iter()
                            .zip(&parts.pixels)
                            .filter(|(a, b)| a != b)
                            .count()
                    );
                }
            }
        }
    }

    #[test]
    fn bands_cover_every_row_once_within_the_limits_unless_one_row_is_beyond() {
        let model = torus(24, 12);
        with_scene::<Q16_16, _>(&model, &View::default(), 72, 60, |scene, cfg| {
            let req = zrow::requirements(scene, cfg).unwrap();
            let projected = Projected::of(scene, cfg, req.vertices as usize).unwrap();
            for (max_polygons, max_corners) in [(1, 3), (40, 150), (usize::MAX, usize::MAX)] {
                let bands = cut(&projected, 60, max_polygons, max_corners);
                let mut next = 0;
                for (rows, members) in &bands {
                    assert_eq!(rows.start, next);
                    next = rows.end;
                    let corners: usize = members
                        .iter()
                        .map(|&i| usize::from(projected.polygons[i as usize].len))
                        .sum();
                    assert!(
                        rows.len() == 1
                            || (members.len() <= max_polygons && corners <= max_corners),
                        "{rows:?}: {} polygons, {corners} corners",
                        members.len()
                    );
                    // Exactly the polygons reaching the band, in scene order.
                    let want: Vec<u32> = (0..projected.len() as u32)
                        .filter(|&i| {
                            let (a, b) = projected.polygons[i as usize].rows;
                            a <= b && a < i32::from(rows.end) && b >= i32::from(rows.start)
                        })
                        .collect();
                    assert_eq!(members, &want, "{rows:?}");
                }
                assert_eq!(next, 60);
                if max_polygons == usize::MAX {
                    assert_eq!(bands.len(), 1);
                } else {
                    assert!(bands.len() > 6);
                }
            }
        })
        .unwrap();
    }
}
