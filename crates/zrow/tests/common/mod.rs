//! Test support: an exact reference renderer for screen-space scenes, scene builders and a
//! sink that keeps the whole frame (colours and depth bits) and counts what it receives.
#![allow(dead_code)]

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{
    Affine, Camera, Config, Face, Light, Mesh, ModelScene, Object, Renderer, Row, RowSink, Scalar,
    Scanline, ScreenScene, Vec3,
};

/// Host capacities big enough for every test scene.
pub type Big<N> = Scanline<N, 256, 16384, 4096, 1024>;

/// A whole frame captured from rows.
#[derive(Clone, Debug, PartialEq)]
pub struct Capture<N> {
    pub width: usize,
    pub height: usize,
    pub color: Vec<Rgb565>,
    pub depth: Vec<N>,
    pub rows_received: usize,
    /// Rows must arrive top to bottom, each once.
    pub next_row: u16,
}

impl<N: Scalar> Capture<N> {
    pub fn new(width: usize, height: usize) -> Self {
        Capture {
            width,
            height,
            color: vec![Rgb565::BLACK; width * height],
            depth: vec![N::MAX; width * height],
            rows_received: 0,
            next_row: 0,
        }
    }
    pub fn at(&self, x: usize, y: usize) -> Rgb565 {
        self.color[y * self.width + x]
    }
    pub fn z(&self, x: usize, y: usize) -> N {
        self.depth[y * self.width + x]
    }
    pub fn drawn(&self) -> usize {
        self.color.iter().filter(|&&c| c != Rgb565::BLACK).count()
    }
}

impl<N: Scalar> RowSink<N> for Capture<N> {
    type Error = ();
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        assert_eq!(row.y, self.next_row, "rows out of order");
        assert_eq!(row.color.len(), self.width, "row length");
        assert_eq!(row.depth.len(), self.width, "depth row length");
        self.next_row += 1;
        self.rows_received += 1;
        let o = row.y as usize * self.width;
        self.color[o..o + self.width].copy_from_slice(row.color);
        self.depth[o..o + self.width].copy_from_slice(row.depth);
        Ok(())
    }
}

/// A frame's colours, top to bottom, from a sink that reads no depth.
pub struct Colours(pub Vec<Rgb565>);

impl<N: Scalar> RowSink<N> for Colours {
    type Error = ();
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        assert!(
            row.depth.is_empty(),
            "depth handed to a sink that takes none"
        );
        self.0.extend_from_slice(row.color);
        Ok(())
    }
}

/// A distinct, non-black colour for polygon `i` (so a colour names its polygon).
pub fn color_of(i: usize) -> Rgb565 {
    let i = i + 1;
    Rgb565::new(
        (i % 32) as u8,
        ((i / 32) % 64) as u8,
        ((i / 2048) % 32) as u8,
    )
}

pub fn index_of(c: Rgb565) -> Option<usize> {
    if c == Rgb565::BLACK {
        return None;
    }
    Some(c.r() as usize + 32 * c.g() as usize + 2048 * c.b() as usize - 1)
}

/// Owned screen-space polygons, turned into a `ScreenScene` on demand.
#[derive(Clone, Debug)]
pub struct Polys {
    pub polys: Vec<Vec<[f32; 3]>>,
}

impl Polys {
    pub fn new(polys: Vec<Vec<[f32; 3]>>) -> Self {
        Polys { polys }
    }
    /// Renders with the scan-line method into a capture.
    pub fn render<N: Scalar>(&self, cfg: &Config) -> Result<Capture<N>, zrow::RenderError<()>> {
        self.render_with(&mut *Box::new(Big::<N>::new()), cfg)
    }

    /// Renders with any method into a capture (which checks that rows arrive in order).
    pub fn render_with<N: Scalar, R: Renderer<N>>(
        &self,
        r: &mut R,
        cfg: &Config,
    ) -> Result<Capture<N>, zrow::RenderError<()>> {
        self.render_stats(r, cfg).map(|(cap, _)| cap)
    }

    /// As [`Polys::render_with`], with the method's frame statistics.
    pub fn render_stats<N: Scalar, R: Renderer<N>>(
        &self,
        r: &mut R,
        cfg: &Config,
    ) -> Result<(Capture<N>, zrow::FrameStats), zrow::RenderError<()>> {
        self.with_scene(|scene| {
            let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
            let stats = r.render(scene, cfg, &mut cap)?;
            Ok((cap, stats))
        })
    }

    /// The colours alone, as a display takes them: rendered for a sink that reads no depth
    /// (the scan-line renderer then paints the spans of a row that meet no other as they
    /// come, not through the sweep a depth-reading sink's rows take).
    pub fn render_colours<N: Scalar>(
        &self,
        cfg: &Config,
    ) -> Result<Vec<Rgb565>, zrow::RenderError<()>> {
        let mut r = Box::new(Big::<N>::new());
        self.with_scene(|scene| {
            let mut sink = Colours(Vec::new());
            r.render(scene, cfg, &mut sink)?;
            Ok(sink.0)
        })
    }

    /// Calls `f` with the polygons as a screen-space scene in format `N` (polygon `i` in
    /// [`color_of`]`(i)`).
    pub fn with_scene<N: Scalar, T>(&self, f: impl FnOnce(&ScreenScene<'_, N>) -> T) -> T {
        let (verts, idx) = self.parts(|v: Vec3<N>| v);
        let faces = faces_of(&idx);
        f(&ScreenScene {
            mesh: Mesh::new(&verts, &faces),
        })
    }

    /// As [`Polys::with_scene`], the vertices snapped to `subpixel_bits` bits: the
    /// [`zrow::SnappedScene`] of the same polygons.
    pub fn with_snapped<N: Scalar, T>(
        &self,
        subpixel_bits: u8,
        f: impl FnOnce(&zrow::SnappedScene<'_, N>) -> T,
    ) -> T {
        let (vertices, idx) = self.parts(|v: Vec3<N>| {
            zrow::raster::RasterVertex::snapped(&v, subpixel_bits).expect("test vertex snaps")
        });
        let faces = faces_of(&idx);
        f(&zrow::SnappedScene {
            vertices: &vertices,
            faces: zrow::Faces::List(&faces),
            subpixel_bits,
        })
    }

    /// Every polygon's vertices in format `N` as `vertex` makes them, in order, and each
    /// polygon's indices into them.
    fn parts<N: Scalar, V>(&self, vertex: impl Fn(Vec3<N>) -> V) -> (Vec<V>, Vec<Vec<u16>>) {
        let mut verts = Vec::new();
        let mut idx: Vec<Vec<u16>> = Vec::new();
        for p in &self.polys {
            let mut f = Vec::new();
            for v in p {
                f.push(verts.len() as u16);
                verts.push(vertex(
                    Vec3::<N>::from_f32(*v).expect("test vertex fits format"),
                ));
            }
            idx.push(f);
        }
        (verts, idx)
    }
}

/// Faces over `idx`, polygon `i` in [`color_of`]`(i)`.
fn faces_of(idx: &[Vec<u16>]) -> Vec<Face<'_>> {
    idx.iter()
        .enumerate()
        .map(|(i, f)| Face {
            indices: f,
            color: color_of(i),
            alpha: 255,
        })
        .collect()
}

/// The exact reference's verdict for one pixel.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Nothing covers the sample.
    Empty,
    /// Polygon `i` is visible, at depth `z`.
    Visible(usize, f64),
    /// Polygons within the depth tolerance of the nearest one (nearest first, then by
    /// depth; two or more): any of them may win. With coarse depth (Q24.8) three or more
    /// polygons within the tolerance are common, and each is a legitimate winner.
    Tie(Vec<usize>),
}

/// Snaps like the renderer does (the convention, tested separately): round to the nearest
/// 2^-S, ties up, on the value the format holds.
pub fn snap<N: Scalar>(v: f32, s: u32) -> i64 {
    N::from_f32(v).unwrap().snap(s).unwrap() as i64
}

/// Exact reference for screen-space scenes.
///
/// Coverage: integer edge functions on the snapped vertices with the top-left rule written
/// directly from its definition (not the renderer's row/column walk). Depth: the plane through
/// the snapped vertices (Newell), in f64. Pixels where the two nearest polygons are within
/// `tie` of each other are ties.
pub fn reference<N: Scalar>(p: &Polys, cfg: &Config, tie: f64) -> Vec<Verdict> {
    let s = cfg.subpixel_bits as u32;
    let (w, h) = (cfg.width as usize, cfg.height as usize);
    let mut out = vec![Verdict::Empty; w * h];
    struct Snapped {
        v: Vec<(i64, i64, f64)>,
        normal: (f64, f64, f64),
    }
    let snapped: Vec<Option<Snapped>> = p
        .polys
        .iter()
        .map(|poly| {
            let mut v: Vec<(i64, i64, f64)> = poly
                .iter()
                .map(|q| {
                    (
                        snap::<N>(q[0], s),
                        snap::<N>(q[1], s),
                        N::from_f32(q[2]).unwrap().to_f32() as f64,
                    )
                })
                .collect();
            let area: i64 = (0..v.len())
                .map(|k| {
                    let (a, b) = (v[k], v[(k + 1) % v.len()]);
                    a.0 * b.1 - b.0 * a.1
                })
                .sum();
            if area == 0 {
                return None;
            }
            if area < 0 {
                v.reverse();
            }
            let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
            for k in 0..v.len() {
                let (p0, p1) = (v[k], v[(k + 1) % v.len()]);
                let (x0, y0, x1, y1) = (p0.0 as f64, p0.1 as f64, p1.0 as f64, p1.1 as f64);
                a += (y0 - y1) * (p0.2 + p1.2);
                b += (p0.2 - p1.2) * (x0 + x1);
                c += (x0 - x1) * (y0 + y1);
            }
            Some(Snapped {
                v,
                normal: (a, b, c),
            })
        })
        .collect();
    let half = 1i64 << s >> 1;
    for j in 0..h {
        for i in 0..w {
            let xs = ((i as i64) << s) + half;
            let ys = ((j as i64) << s) + half;
            let mut hits: Vec<(f64, usize)> = Vec::new();
            for (k, sp) in snapped.iter().enumerate() {
                let Some(sp) = sp else { continue };
                let n = sp.v.len();
                let inside = (0..n).all(|e| {
                    let (a, b) = (sp.v[e], sp.v[(e + 1) % n]);
                    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
                    let f = dx as i128 * (ys - a.1) as i128 - dy as i128 * (xs - a.0) as i128;
                    // Interior is where f > 0 (vertices ordered clockwise on the display).
                    // On the edge: a left edge (going up) or a top edge (horizontal, going
                    // right) owns the sample.
                    f > 0 || (f == 0 && (dy < 0 || (dy == 0 && dx > 0)))
                });
                if inside {
                    let (a, b, c) = sp.normal;
                    let (x0, y0, z0) = sp.v[0];
                    let z = z0 - (a * (xs - x0) as f64 + b * (ys - y0) as f64) / c;
                    hits.push((z, k));
                }
            }
            hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            out[j * w + i] = match hits.as_slice() {
                [] => Verdict::Empty,
                [(z0, k0), rest @ ..] => {
                    let near: Vec<usize> = rest
                        .iter()
                        .take_while(|(z, _)| z - z0 <= tie)
                        .map(|&(_, k)| k)
                        .collect();
                    if near.is_empty() {
                        Verdict::Visible(*k0, *z0)
                    } else {
                        Verdict::Tie([*k0].into_iter().chain(near).collect())
                    }
                }
            };
        }
    }
    out
}

/// Compares a capture with the reference; returns the mismatching pixels (x, y, want, got).
pub fn mismatches<N: Scalar>(
    cap: &Capture<N>,
    refr: &[Verdict],
) -> Vec<(usize, usize, Verdict, Option<usize>)> {
    let mut bad = Vec::new();
    for y in 0..cap.height {
        for x in 0..cap.width {
            let got = index_of(cap.at(x, y));
            let want = &refr[y * cap.width + x];
            let ok = match want {
                Verdict::Empty => got.is_none(),
                Verdict::Visible(k, _) => got == Some(*k),
                Verdict::Tie(ks) => got.is_some_and(|g| ks.contains(&g)),
            };
            if !ok {
                bad.push((x, y, want.clone(), got));
            }
        }
    }
    bad
}

/// The LSB of a fixed-point format, found from the format itself: the smallest power of two
/// it holds exactly (2^-16 for Q16.16, 2^-8 for Q24.8). `None` for floating point.
pub fn lsb<N: Scalar>() -> Option<f64> {
    if N::NAME == "f32" {
        return None;
    }
    let exact = |k: i32| {
        let v = 2f64.powi(-k);
        N::from_f32(v as f32).map(N::to_f64) == Some(v)
    };
    let frac = (0..32).take_while(|&k| exact(k)).last()?;
    Some(2f64.powi(-frac))
}

/// Depth tolerance of a format for frames up to `extent` pixels across (`extent` ≥ i + j at
/// every compared pixel): in fixed point a plane's depth at pixel (i, j) is within
/// 0.5·(1 + i + j) LSB (`Scalar::depth_plane`), so two planes' order is right wherever they
/// are more than (1 + extent) LSB apart. f32: 1e-3.
pub fn tie_tolerance<N: Scalar>(extent: usize) -> f64 {
    match lsb::<N>() {
        None => 1e-3,
        Some(lsb) => (1.0 + extent as f64) * lsb,
    }
}

/// A tiny deterministic generator (xorshift64*).
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [lo, hi).
    pub fn f(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * ((self.next() >> 40) as f32 / (1u64 << 24) as f32)
    }
    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// Renders one mesh in model mode at the origin with full ambient light, so every face keeps
/// its own colour unshaded.
pub fn render_model<N: Scalar>(
    vertices: &[Vec3<N>],
    faces: &[Face],
    camera: Camera<N>,
    cfg: &Config,
) -> Capture<N> {
    let mesh = Mesh::new(vertices, faces);
    let objects = [Object {
        mesh: &mesh,
        transform: Affine::identity(),
    }];
    let light = Light {
        direction: Vec3::from_f32([0.0, 1.0, 0.0]).unwrap(),
        ambient: N::ONE,
    };
    let scene = ModelScene {
        objects: &objects,
        camera,
        light,
    };
    let mut r = Box::new(Big::<N>::new());
    let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
    r.render(&scene, cfg, &mut cap).unwrap();
    cap
}

/// Scenes every method must draw as the reference does (every exact method gives the reference's picture; `docs/extremes.md` item 20).
pub mod scenes {
    use super::{Polys, Rng};

    /// `n` random triangles and parallelograms over a `w`×`h` screen (some reaching past
    /// it), vertices on the 1/256 grid, depths in 0..64.
    pub fn random(rng: &mut Rng, n: usize, w: f32, h: f32) -> Polys {
        let grid = |v: f32| (v * 256.0).round() / 256.0;
        let mut polys = Vec::new();
        for _ in 0..n {
            let v = |rng: &mut Rng| {
                [
                    grid(rng.f(-0.3 * w, 1.3 * w)),
                    grid(rng.f(-0.3 * h, 1.3 * h)),
                    grid(rng.f(0.0, 64.0)),
                ]
            };
            let (a, b, c) = (v(rng), v(rng), v(rng));
            if rng.below(3) == 0 {
                let d = [a[0] + c[0] - b[0], a[1] + c[1] - b[1], a[2] + c[2] - b[2]];
                polys.push(vec![a, b, c, d]);
            } else {
                polys.push(vec![a, b, c]);
            }
        }
        Polys::new(polys)
    }

    /// `n` large polygons stacked over the same area with random tilts: every pair
    /// interpenetrates somewhere (the worst case for depth-sort and BSP splitting).
    pub fn dense(rng: &mut Rng, n: usize, w: f32, h: f32) -> Polys {
        let grid = |v: f32| (v * 256.0).round() / 256.0;
        let mut polys = Vec::new();
        for _ in 0..n {
            let z = |rng: &mut Rng| grid(rng.f(8.0, 56.0));
            polys.push(vec![
                [
                    grid(rng.f(-4.0, 0.2 * w)),
                    grid(rng.f(-4.0, 0.2 * h)),
                    z(rng),
                ],
                [
                    grid(rng.f(0.8 * w, w + 4.0)),
                    grid(rng.f(-4.0, 0.3 * h)),
                    z(rng),
                ],
                [
                    grid(rng.f(0.3 * w, 0.7 * w)),
                    grid(rng.f(0.8 * h, h + 4.0)),
                    z(rng),
                ],
            ]);
        }
        Polys::new(polys)
    }

    /// `n` small, steep triangles (4 to 12 pixels across, depths anywhere in 0..30000) over a
    /// `w`×`h` screen: their planes leave the Q16.16 range within a few dozen pixels, so a
    /// plane's value at the screen's origin, or anywhere far from its polygon, has wrapped.
    /// Deciding sides of a plane far from its polygon (BSP's classification, splitting) must
    /// not depend on those wrapped values.
    pub fn steep(rng: &mut Rng, n: usize, w: f32, h: f32) -> Polys {
        steep_to(rng, n, w, h, 30000.0)
    }

    /// As [`steep`], depths in 0..`zmax` (for a format of another range: Q24.8's planes
    /// leave it the same way with `zmax` = 256 · 30000).
    pub fn steep_to(rng: &mut Rng, n: usize, w: f32, h: f32, zmax: f32) -> Polys {
        let grid = |v: f32| (v * 256.0).round() / 256.0;
        let mut polys = Vec::new();
        for _ in 0..n {
            let (cx, cy) = (rng.f(0.0, w), rng.f(0.0, h));
            let mut v = || {
                [
                    grid(cx + rng.f(-6.0, 6.0)),
                    grid(cy + rng.f(-6.0, 6.0)),
                    grid(rng.f(0.0, zmax)),
                ]
            };
            polys.push(vec![v(), v(), v()]);
        }
        Polys::new(polys)
    }

    /// Three long planar bars (parallelograms) in cyclic overlap: bar 1 lies over bar 0 at
    /// their crossing, bar 0 over bar 2, bar 2 over bar 1, so no painter's order of whole
    /// polygons exists; splitting one resolves it. Sized for a 48×48
    /// screen; `shift` moves it by whole sub-pixels.
    pub fn cyclic(shift: f32) -> Polys {
        let s = |x: f32| x + shift;
        Polys::new(vec![
            // Horizontal bar: near on the left, far on the right.
            vec![
                [s(2.0), s(10.0), 1.0],
                [s(46.0), s(10.0), 9.0],
                [s(46.0), s(18.0), 9.0],
                [s(2.0), s(18.0), 1.0],
            ],
            // Bar going down-left: near at the top right, far at the bottom left.
            vec![
                [s(38.0), s(2.0), 2.0],
                [s(46.0), s(6.0), 2.0],
                [s(18.0), s(46.0), 10.0],
                [s(10.0), s(42.0), 10.0],
            ],
            // Bar going down-right: far at the top left, near at the bottom right.
            vec![
                [s(4.0), s(4.0), 9.0],
                [s(12.0), s(2.0), 9.0],
                [s(44.0), s(40.0), 0.0],
                [s(36.0), s(42.0), 0.0],
            ],
        ])
    }
}

/// What one render gives back: the frame, the method's statistics, and the depth resolution
/// the method claims for that frame beyond its number format's own (0 for exact methods; the
/// tiled 16-bit z-buffer's [`zrow::tiled::Quantisation::resolution`]).
pub type Rendered<N> = (Capture<N>, zrow::FrameStats, f64);

/// A render's outcome and the capture (whatever reached it, also after an error).
pub type Outcome<N> = (
    Result<(zrow::FrameStats, f64), zrow::RenderError<()>>,
    Capture<N>,
);

type RenderFn<N> = Box<dyn FnMut(&dyn zrow::Scene<N>, &Config) -> Outcome<N>>;

/// One hidden-surface method, boxed once and reused for every frame it renders (as on the
/// device), behind one signature whatever its type and capacities.
pub struct Method<N: Scalar> {
    pub name: &'static str,
    render: RenderFn<N>,
}

impl<N: Scalar> Method<N> {
    /// Any method; its resolution beyond the format's is 0 (exact).
    pub fn new<R: Renderer<N> + Default + 'static>() -> Self {
        let mut r = Box::<R>::default();
        Method {
            name: R::NAME,
            render: Box::new(move |scene, cfg| {
                let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
                let stats = r.render(scene, cfg, &mut cap);
                (stats.map(|s| (s, 0.0)), cap)
            }),
        }
    }

    /// The tiled 16-bit z-buffer, reporting its frame's quantisation resolution.
    pub fn tiled<const W: usize, const B: usize, const P: usize, const E: usize>() -> Self {
        let mut r = Box::<zrow::tiled::Tiled<N, W, B, P, E>>::default();
        Method {
            name: "tiled",
            render: Box::new(move |scene, cfg| {
                let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
                let stats = r.render(scene, cfg, &mut cap);
                (stats.map(|s| (s, r.quantisation().resolution)), cap)
            }),
        }
    }

    /// Renders any scene (screen space or model).
    pub fn scene(
        &mut self,
        scene: &dyn zrow::Scene<N>,
        cfg: &Config,
    ) -> Result<Rendered<N>, zrow::RenderError<()>> {
        let (r, cap) = (self.render)(scene, cfg);
        r.map(|(stats, res)| (cap, stats, res))
    }

    /// Renders any scene and returns the outcome with whatever reached the capture (so a
    /// test can check that no row was sent before an error).
    pub fn outcome(&mut self, scene: &dyn zrow::Scene<N>, cfg: &Config) -> Outcome<N> {
        (self.render)(scene, cfg)
    }

    /// Renders owned screen-space polygons (polygon `i` in [`color_of`]`(i)`).
    pub fn polys(&mut self, p: &Polys, cfg: &Config) -> Result<Capture<N>, zrow::RenderError<()>> {
        self.polys_full(p, cfg).map(|r| r.0)
    }

    /// As [`Method::polys`], with statistics and resolution.
    pub fn polys_full(
        &mut self,
        p: &Polys,
        cfg: &Config,
    ) -> Result<Rendered<N>, zrow::RenderError<()>> {
        p.with_scene(|s| self.scene(s, cfg))
    }
}

/// Every method that must draw any opaque scene as the exact reference does, at capacities
/// for frames up to 64×64 and 256 polygons: scan-line (with 16-bit slots, then 12-bit ones),
/// z-buffer, tiled 16-bit z-buffer (exact beyond its resolution), depth-sort, Warnock, BSP,
/// A-buffer.
pub fn every_method<N: Scalar>() -> Vec<Method<N>> {
    vec![
        Method::new::<Scanline<N, 64, 1024, 256, 256>>(),
        Method::new::<Scanline<N, 64, 1024, 256, 256, zrow::scanline::Slot12>>(),
        Method::new::<zrow::ZBuffer<N, 64, 64>>(),
        Method::tiled::<64, 8, 256, 1024>(),
        Method::new::<zrow::depthsort::DepthSort<N, 64, 256, 1024, 4096>>(),
        Method::new::<zrow::warnock::Warnock<N, 64, 16, 256, 1024, 4096>>(),
        Method::new::<zrow::bsp::Bsp<N, 64, 256, 1024, 4096, 512>>(),
        Method::new::<zrow::abuffer::ABuffer<N, 64, 256, 1024, 64>>(),
    ]
}

/// The methods exact only under a precondition (cull-only: no two polygons share a sample;
/// ordered: no two polygons sharing a sample overlap in depth), same capacities. A scene of
/// one polygon meets both.
pub fn painters<N: Scalar>() -> Vec<Method<N>> {
    vec![
        Method::new::<zrow::cullonly::CullOnly<N, 64, 256, 1024>>(),
        Method::new::<zrow::ordered::Ordered<N, 64, 256, 1024>>(),
    ]
}

/// [`every_method`] and [`painters`]: for scenes of one polygon (coverage items).
pub fn all_methods<N: Scalar>() -> Vec<Method<N>> {
    let mut m = every_method::<N>();
    m.extend(painters::<N>());
    m
}

/// Per-pixel count of how many of `polys`, each drawn alone by `m`, cover it.
pub fn coverage_counts_with<N: Scalar>(
    m: &mut Method<N>,
    polys: &[Vec<[f32; 3]>],
    cfg: &Config,
) -> Vec<u32> {
    let mut n = vec![0u32; cfg.width as usize * cfg.height as usize];
    for p in polys {
        let cap = m.polys(&Polys::new(vec![p.clone()]), cfg).unwrap();
        for (k, c) in cap.color.iter().enumerate() {
            n[k] += (*c != Rgb565::BLACK) as u32;
        }
    }
    n
}

/// The largest `f32` the format holds (for f32 itself, `f32::MAX`).
pub fn max_f32<N: Scalar>() -> f32 {
    let m = N::MAX.to_f32();
    if N::from_f32(m).is_some() {
        m
    } else {
        f32::from_bits(m.to_bits() - 1)
    }
}

/// The format's least significant bit if it is fixed point (`None` for floating point).
pub fn fixed_lsb<N: Scalar>() -> Option<f64> {
    let m = N::MAX.to_f64();
    let lsb = m.ceil() - m;
    (lsb > 0.0).then_some(lsb)
}

/// One unit in the last place of the format at `z`: the fixed LSB, or f32's ulp at |z|.
pub fn lsb_at<N: Scalar>(z: f64) -> f64 {
    fixed_lsb::<N>().unwrap_or_else(|| {
        let a = (z.abs() as f32).max(f32::MIN_POSITIVE);
        (f32::from_bits(a.to_bits() + 1) - a) as f64
    })
}

/// A model scene of one mesh at the origin, full ambient light (faces keep their colours).
pub fn with_model<N: Scalar, T>(
    vertices: &[Vec3<N>],
    faces: &[Face],
    camera: Camera<N>,
    f: impl FnOnce(&ModelScene<'_, N>) -> T,
) -> T {
    let mesh = Mesh::new(vertices, faces);
    let objects = [Object {
        mesh: &mesh,
        transform: Affine::identity(),
    }];
    let light = Light {
        direction: Vec3::from_f32([0.0, 1.0, 0.0]).unwrap(),
        ambient: N::ONE,
    };
    f(&ModelScene {
        objects: &objects,
        camera,
        light,
    })
}

/// Ray–triangle intersection in f64 (Möller–Trumbore): the distance along `dir` from the
/// origin at which the ray meets `tri`, if it does (either side).
pub fn ray_hits(tri: &[[f64; 3]; 3], dir: [f64; 3]) -> Option<f64> {
    let v = tri;
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cr = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (e1, e2) = (sub(v[1], v[0]), sub(v[2], v[0]));
    let p = cr(dir, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-300 {
        return None;
    }
    let s = sub([0.0; 3], v[0]);
    let u = dot(s, p) / det;
    let q = cr(s, e1);
    let w = dot(dir, q) / det;
    let t = dot(e2, q) / det;
    (u >= 0.0 && w >= 0.0 && u + w <= 1.0).then_some(t)
}

/// The view-space direction of the ray through point (`x`, `y`) of a `w`×`h` screen, for a
/// camera at the origin looking down −z with `focal` = cot(fov_y/2) (square pixels).
pub fn ray_dir(x: f64, y: f64, w: f64, h: f64, focal: f64) -> [f64; 3] {
    let aspect = w / h;
    [
        (2.0 * x / w - 1.0) * aspect / focal,
        (1.0 - 2.0 * y / h) / focal,
        -1.0,
    ]
}

/// The property tests' configuration: `cases` cases drawn from a fixed seed, so `cargo test`
/// finds the same thing on every run (saved regressions are replayed first, as always). To
/// explore, set `PROPTEST_RNG_SEED` to another number; the fuzzer explores at random.
pub fn proptest_config(cases: u32) -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, RngSeed};
    /// "zrow" in ASCII.
    const SEED: u64 = 0x7a72_6f77;
    let default = Config::default(); // reads PROPTEST_* from the environment
    let rng_seed = match default.rng_seed {
        RngSeed::Random => RngSeed::Fixed(SEED),
        chosen => chosen,
    };
    Config {
        cases,
        rng_seed,
        ..default
    }
}
