//! The A-buffer: all opaque it equals the exact reference (and the z-buffer, bit for bit);
//! with translucent faces it equals a brute-force per-pixel blend; a hand-checked picture;
//! its fragment capacity is checked, exactly, before any row.

mod common;
use common::Rng;
use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use proptest::prelude::*;
use zrow::abuffer::ABuffer;
use zrow::polygons::PolygonTable;
use zrow::{
    Config, Error, Face, Mesh, RenderError, Scalar, ScreenScene, Table, Vec3, ZBuffer, Q16_16,
};

type Ab<N> = ABuffer<N, 64, 256, 1024, 4096>;

/// Compares an all-opaque scene with the exact reference and with the z-buffer. Returns the
/// pixels tolerated because the scan-line method differs from the reference there in the same
/// way: `scenes::cyclic`'s third bar is not planar (its fourth vertex is 0.5 deep off the
/// plane of the first three), so its depth at a pixel depends on which vertex its plane goes
/// through — the reference's first vertex or the renderers' canonical one. At pixels (23, 23)
/// and (24, 23) of `cyclic(0.25)` that decides which bar is in front (6.03 or 6.26 against
/// 6.24), in both formats.
fn check_opaque<N: Scalar>(p: &Polys, w: u16, h: u16) -> usize {
    let cfg = Config::screen(w, h);
    let (cap, stats) = p
        .render_stats(&mut *Box::new(Ab::<N>::new()), &cfg)
        .unwrap();
    let tol = tie_tolerance::<N>(4 * (w + h) as usize);
    let refr = reference::<N>(p, &cfg, 2.0 * tol);
    let scanline = mismatches(&p.render::<N>(&cfg).unwrap(), &refr);
    let (shared, bad): (Vec<_>, Vec<_>) = mismatches(&cap, &refr)
        .into_iter()
        .partition(|m| scanline.contains(m));
    if !shared.is_empty() {
        println!("{}: as the scan-line method: {shared:?}", N::NAME);
    }
    assert!(
        bad.is_empty(),
        "{}: {} pixels differ, first {:?}",
        N::NAME,
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    // Same coverage, same depth bits, same tie rule as the z-buffer: the same frame exactly,
    // ties included, depth included.
    let (z, zstats) = p
        .render_stats(&mut *Box::new(ZBuffer::<N, 64, 48>::new()), &cfg)
        .unwrap();
    assert!(
        cap.color == z.color,
        "{}: colours differ from the z-buffer",
        N::NAME
    );
    assert!(
        cap.depth
            .iter()
            .zip(&z.depth)
            .all(|(a, b)| a.to_f64().to_bits() == b.to_f64().to_bits()),
        "{}: depths differ from the z-buffer",
        N::NAME
    );
    assert_eq!(
        (stats.polygons, stats.edges),
        (zstats.polygons, zstats.edges)
    );
    shared.len()
}

#[test]
fn all_opaque_equals_the_reference_and_the_zbuffer() {
    let mut rng = Rng(0xab0f_0001);
    for _ in 0..40 {
        let n = 1 + rng.below(30) as usize;
        let p = scenes::random(&mut rng, n, 48.0, 40.0);
        assert_eq!(check_opaque::<Q16_16>(&p, 48, 40), 0);
        assert_eq!(check_opaque::<f32>(&p, 48, 40), 0);
    }
    for _ in 0..10 {
        let n = 2 + rng.below(8) as usize;
        let p = scenes::dense(&mut rng, n, 48.0, 40.0);
        assert_eq!(check_opaque::<Q16_16>(&p, 48, 40), 0);
        assert_eq!(check_opaque::<f32>(&p, 48, 40), 0);
    }
    // Every polygon twice: exact ties everywhere, and the first copy must win each.
    for _ in 0..10 {
        let n = 1 + rng.below(12) as usize;
        let mut p = scenes::random(&mut rng, n, 48.0, 40.0);
        p.polys.extend(p.polys.clone());
        check_opaque::<Q16_16>(&p, 48, 40);
        check_opaque::<f32>(&p, 48, 40);
        let cfg = Config::screen(48, 40);
        let cap = p
            .render_with(&mut *Box::new(Ab::<Q16_16>::new()), &cfg)
            .unwrap();
        assert!(cap.color.iter().all(|&c| index_of(c).is_none_or(|i| i < n)));
    }
    let mut shared = 0;
    for shift in [0.0, 0.25, 1.0] {
        shared += check_opaque::<Q16_16>(&scenes::cyclic(shift), 48, 48);
        shared += check_opaque::<f32>(&scenes::cyclic(shift), 48, 48);
    }
    // The scenes are planar, so no pixel may differ from the reference, even where the
    // scan-line method would differ too.
    assert_eq!(
        shared, 0,
        "{shared} pixels differ from the reference as the scan-line's do"
    );
}

/// An owned screen-space scene with a colour and an alpha per face.
struct Owned<N> {
    vertices: Vec<Vec3<N>>,
    indices: Vec<Vec<u16>>,
    style: Vec<(Rgb565, u8)>,
}

impl<N: Scalar> Owned<N> {
    fn new(p: &Polys, style: Vec<(Rgb565, u8)>) -> Self {
        let (mut vertices, mut indices) = (Vec::new(), Vec::new());
        for poly in &p.polys {
            let mut f = Vec::new();
            for v in poly {
                f.push(vertices.len() as u16);
                vertices.push(Vec3::<N>::from_f32(*v).unwrap());
            }
            indices.push(f);
        }
        Owned {
            vertices,
            indices,
            style,
        }
    }
    fn with<T>(&self, f: impl FnOnce(&ScreenScene<'_, N>) -> T) -> T {
        let faces: Vec<Face> = self
            .indices
            .iter()
            .zip(&self.style)
            .map(|(i, &(c, a))| Face::translucent(i, c, a))
            .collect();
        f(&ScreenScene {
            mesh: Mesh::new(&self.vertices, &faces),
        })
    }
    fn render<const F: usize>(&self, cfg: &Config) -> Result<Capture<N>, RenderError<()>> {
        let mut r = Box::new(ABuffer::<N, 64, 256, 1024, F>::new());
        let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
        let res = self.with(|s| r.render(s, cfg, &mut cap));
        match res {
            Ok(_) => Ok(cap),
            Err(e) => {
                assert_eq!(cap.rows_received, 0, "a row was sent before the error");
                Err(e)
            }
        }
    }
}

/// The blend, written again from its definition: per channel
/// `round(u·(255 − a)/255 + o·a/255)`, to nearest (never halfway: 255 is odd).
fn blend_ref(u: Rgb565, o: Rgb565, a: u8) -> Rgb565 {
    let a = a as u32;
    let ch = |u: u8, o: u8| ((2 * (u as u32 * (255 - a) + o as u32 * a) + 255) / 510) as u8;
    Rgb565::new(ch(u.r(), o.r()), ch(u.g(), o.g()), ch(u.b(), o.b()))
}

/// What the brute force found at one pixel.
struct Expected<N> {
    color: Rgb565,
    depth: N,
    /// Two of the polygons covering the pixel are within `tie` of each other.
    near_tie: bool,
    fragments: usize,
}

/// Brute force, one pixel at a time: the nearest opaque polygon covering the sample (scene
/// order on equal depth), then every translucent polygon covering it that beats it (nearer,
/// or as near and earlier in the scene; any, if no opaque one), blended far to near (on equal
/// depth the earlier polygon on top). Coverage and depth from the polygon table's per-sample
/// queries (edge functions, the plane evaluated at the pixel), not the row walk; the depth a
/// sink is told, the opaque polygon's exact plane there.
fn brute_force<N: Scalar>(o: &Owned<N>, cfg: &Config, tie: f64) -> Vec<Expected<N>> {
    let mut t = Box::new(PolygonTable::<N, 256, 1024>::new());
    o.with(|s| t.build(s, cfg, false, true)).unwrap();
    let mut out = Vec::new();
    for y in 0..cfg.height as i32 {
        for x in 0..cfg.width as i32 {
            let covering: Vec<(usize, N)> = (0..t.len())
                .filter(|&i| t.get(i).alpha > 0 && t.covers(i, x, y))
                .map(|i| (i, t.get(i).plane.at(x, y)))
                .collect();
            let mut opaque: Option<(usize, N)> = None;
            for &(i, z) in covering.iter().filter(|(i, _)| t.get(*i).alpha == 255) {
                if opaque.is_none_or(|(_, zo)| z < zo) {
                    opaque = Some((i, z));
                }
            }
            let mut frags: Vec<(usize, N)> = covering
                .iter()
                .copied()
                .filter(|&(i, z)| {
                    t.get(i).alpha < 255
                        && match opaque {
                            None => true,
                            Some((io, zo)) => z < zo || (z == zo && i < io),
                        }
                })
                .collect();
            frags.sort_by(|a, b| b.1.partial_cmp(&a.1).unwrap().then(b.0.cmp(&a.0)));
            let mut color = opaque.map_or(cfg.background, |(i, _)| t.get(i).color);
            for &(i, _) in &frags {
                color = blend_ref(color, t.get(i).color, t.get(i).alpha);
            }
            let zs: Vec<f64> = covering.iter().map(|c| c.1.to_f64()).collect();
            let near_tie = zs
                .iter()
                .enumerate()
                .any(|(k, a)| zs[k + 1..].iter().any(|b| (a - b).abs() <= tie));
            out.push(Expected {
                color,
                depth: opaque.map_or(N::MAX, |(i, _)| {
                    let e = t.get(i).exact.expect("a table built with exact planes");
                    N::exact_at(&e, x, y)
                }),
                near_tie,
                fragments: frags.len(),
            });
        }
    }
    out
}

fn random_style(rng: &mut Rng, n: usize) -> Vec<(Rgb565, u8)> {
    const ALPHAS: [u8; 9] = [255, 255, 255, 0, 1, 64, 128, 200, 254];
    (0..n)
        .map(|_| {
            let c = Rgb565::new(
                rng.below(32) as u8,
                rng.below(64) as u8,
                rng.below(32) as u8,
            );
            (c, ALPHAS[rng.below(ALPHAS.len() as u64) as usize])
        })
        .collect()
}

/// Renders and compares with the brute force; returns (pixels compared, pixels skipped as
/// near-ties in f32, pixels with a translucent fragment over an opaque surface).
fn check_translucent<N: Scalar>(p: &Polys, style: Vec<(Rgb565, u8)>) -> (usize, usize, usize) {
    let cfg = Config::screen(48, 40);
    let o = Owned::<N>::new(p, style);
    let cap = o.render::<4096>(&cfg).unwrap();
    let exact = N::NAME != "f32";
    let want = brute_force(&o, &cfg, 1e-3);
    let (mut compared, mut skipped, mut layered) = (0, 0, 0);
    for (k, e) in want.iter().enumerate() {
        let (x, y) = (k % 48, k / 48);
        if !exact && e.near_tie {
            skipped += 1;
            continue;
        }
        compared += 1;
        if e.fragments > 0 && e.depth != N::MAX {
            layered += 1;
        }
        assert_eq!(cap.at(x, y), e.color, "{}: colour at ({x}, {y})", N::NAME);
        let (got, z) = (cap.z(x, y).to_f64(), e.depth.to_f64());
        if exact || e.depth == N::MAX {
            assert_eq!(
                got.to_bits(),
                z.to_bits(),
                "{}: depth at ({x}, {y})",
                N::NAME
            );
        } else {
            assert!(
                (got - z).abs() <= 1e-3 * (1.0 + z.abs()),
                "depth at ({x}, {y})"
            );
        }
    }
    (compared, skipped, layered)
}

#[test]
fn translucent_faces_equal_a_brute_force_blend() {
    let mut rng = Rng(0xab0f_0002);
    let mut totals = [(0, 0, 0); 2];
    for round in 0..60 {
        let n = 1 + rng.below(24) as usize;
        let p = if round % 4 == 3 {
            scenes::dense(&mut rng, n.min(10), 48.0, 40.0)
        } else {
            scenes::random(&mut rng, n, 48.0, 40.0)
        };
        let style = random_style(&mut rng, p.polys.len());
        for (k, r) in [
            check_translucent::<Q16_16>(&p, style.clone()),
            check_translucent::<f32>(&p, style),
        ]
        .into_iter()
        .enumerate()
        {
            totals[k] = (totals[k].0 + r.0, totals[k].1 + r.1, totals[k].2 + r.2);
        }
    }
    println!(
        "(compared, skipped near ties, layered) Q16.16 {:?}, f32 {:?}",
        totals[0], totals[1]
    );
    assert_eq!(totals[0].1, 0, "Q16.16 compares every pixel");
    assert!(
        totals[0].2 > 5000,
        "the scenes layer translucent faces over opaque ones"
    );
    assert!(
        totals[1].1 * 100 < totals[1].0,
        "f32 skips under 1 % as near ties"
    );
}

/// Pictures: one character per pixel.
fn picture(cap: &Capture<f32>, key: &[(char, Rgb565)]) -> Vec<String> {
    (0..cap.height)
        .map(|y| {
            (0..cap.width)
                .map(|x| {
                    let c = cap.at(x, y);
                    key.iter().find(|k| k.1 == c).map_or('?', |k| k.0)
                })
                .collect()
        })
        .collect()
}

/// Axis-aligned rectangle `x0..x1` × `y0..y1` at depth `z`.
fn rect(x0: f32, y0: f32, x1: f32, y1: f32, z: f32) -> Vec<[f32; 3]> {
    vec![[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]
}

#[test]
fn half_transparent_blue_over_red_by_hand() {
    let p = Polys::new(vec![
        rect(0.0, 0.0, 6.0, 4.0, 2.0), // red, opaque
        rect(3.0, 0.0, 8.0, 3.0, 1.0), // blue, alpha 128, in front
        rect(0.0, 2.0, 4.0, 4.0, 5.0), // green, alpha 128, behind the red: invisible
        rect(0.0, 0.0, 8.0, 4.0, 0.5), // white, alpha 0, in front of everything: nothing
        rect(6.0, 3.0, 8.0, 4.0, 9.0), // green, alpha 128, over the background
    ]);
    let style = vec![
        (Rgb565::RED, 255),
        (Rgb565::BLUE, 128),
        (Rgb565::GREEN, 128),
        (Rgb565::WHITE, 0),
        (Rgb565::GREEN, 128),
    ];
    let cap = Owned::<f32>::new(&p, style)
        .render::<16>(&Config::screen(8, 4))
        .unwrap();
    // By hand: red (31, 0, 0) under blue (0, 0, 31) at 128: r = round(31·127/255) =
    // round(15.44) = 15, b = round(31·128/255) = round(15.56) = 16. Blue over black: (0, 0, 16).
    // Green (0, 63, 0) over black: g = round(63·128/255) = round(31.62) = 32.
    let key = [
        ('R', Rgb565::RED),
        ('M', Rgb565::new(15, 0, 16)),
        ('b', Rgb565::new(0, 0, 16)),
        ('g', Rgb565::new(0, 32, 0)),
        ('.', Rgb565::BLACK),
    ];
    assert_eq!(
        picture(&cap, &key),
        ["RRRMMMbb", "RRRMMMbb", "RRRMMMbb", "RRRRRRgg"],
    );
    // Translucent faces do not write depth: the row holds the opaque surface's.
    assert_eq!(cap.z(4, 0), 2.0);
    assert_eq!(cap.z(7, 0), f32::MAX);
    assert_eq!(cap.z(7, 3), f32::MAX);
}

#[test]
fn ties_go_to_the_face_first_in_the_scene() {
    let cfg = Config::screen(4, 1);
    let render = |p: Vec<Vec<[f32; 3]>>, style| {
        let cap = Owned::<Q16_16>::new(&Polys::new(p), style)
            .render::<16>(&cfg)
            .unwrap();
        cap.at(0, 0)
    };
    let red = (Rgb565::RED, 255);
    let blue = (Rgb565::BLUE, 128);
    let full = || rect(0.0, 0.0, 4.0, 1.0, 3.0);
    // Two opaque faces at the same depth: the first.
    let green = (Rgb565::GREEN, 255);
    assert_eq!(render(vec![full(), full()], vec![red, green]), Rgb565::RED);
    assert_eq!(
        render(vec![full(), full()], vec![green, red]),
        Rgb565::GREEN
    );
    // A translucent face as deep as the opaque one shows if it comes first, not if it follows.
    assert_eq!(
        render(vec![full(), full()], vec![blue, red]),
        Rgb565::new(15, 0, 16)
    );
    assert_eq!(render(vec![full(), full()], vec![red, blue]), Rgb565::RED);
    // Two translucent faces at the same depth: the first in the scene is nearer (on top).
    // Blue then red on black: blue first gives (0, 0, 16); red over it at 128 gives
    // r = round(31·128/255) = 16, b = round(16·127/255) = round(7.97) = 8.
    let red_half = (Rgb565::RED, 128);
    assert_eq!(
        render(vec![full(), full()], vec![red_half, blue]),
        Rgb565::new(16, 0, 8)
    );
    assert_eq!(
        render(vec![full(), full()], vec![blue, red_half]),
        Rgb565::new(8, 0, 16)
    );
}

#[test]
fn fragment_capacity_is_exact_and_checked_before_any_row() {
    // Three translucent layers over an 8×4 screen (a bound of 24 fragments a row); an opaque
    // face in front of the left half of rows 0..2 hides half of them there (12 a row), so
    // the worst rows are 2 and 3, 24 each.
    let layers = || {
        vec![
            rect(0.0, 0.0, 8.0, 4.0, 3.0),
            rect(0.0, 0.0, 8.0, 4.0, 4.0),
            rect(0.0, 0.0, 8.0, 4.0, 5.0),
        ]
    };
    let style = vec![(Rgb565::BLUE, 100); 3];
    let mut p = layers();
    p.push(rect(0.0, 0.0, 4.0, 2.0, 1.0));
    let mut s = style.clone();
    s.push((Rgb565::RED, 255));
    let o = Owned::<f32>::new(&Polys::new(p), s);
    let cfg = Config::screen(8, 4);
    assert!(o.render::<24>(&cfg).is_ok());
    let over = Error::Capacity {
        table: Table::Fragments,
        needed: 24,
        capacity: 23,
    };
    assert_eq!(o.render::<23>(&cfg).unwrap_err(), RenderError::Scene(over));

    // Opaque in front of the left half of every row: the bound (24) is over, the exact count
    // (12) is not.
    let mut p = layers();
    p.push(rect(0.0, 0.0, 4.0, 4.0, 1.0));
    let mut s = style;
    s.push((Rgb565::RED, 255));
    let o = Owned::<f32>::new(&Polys::new(p), s);
    let cap = o.render::<12>(&cfg).unwrap();
    assert_eq!(cap.rows_received, 4);
    assert_eq!(cap.at(0, 3), Rgb565::RED);
    let over = Error::Capacity {
        table: Table::Fragments,
        needed: 12,
        capacity: 11,
    };
    assert_eq!(o.render::<11>(&cfg).unwrap_err(), RenderError::Scene(over));
}

#[test]
fn polygon_capacity_is_checked_before_any_row() {
    let p = Polys::new(vec![rect(0.0, 0.0, 8.0, 4.0, 3.0); 3]);
    let o = Owned::<f32>::new(&p, vec![(Rgb565::BLUE, 100); 3]);
    let mut r = ABuffer::<f32, 8, 2, 64, 64>::new();
    let mut cap = Capture::new(8, 4);
    let e = o.with(|s| r.render(s, &Config::screen(8, 4), &mut cap));
    let over = Error::Capacity {
        table: Table::Polygons,
        needed: 3,
        capacity: 2,
    };
    assert_eq!(e.unwrap_err(), RenderError::Scene(over));
    assert_eq!(cap.rows_received, 0);
}

/// Any input: every bit pattern, faces of any size and index, any alpha. A frame or a typed
/// error, never a panic, and no row before an error.
fn run<N: Scalar>(verts: Vec<Vec3<N>>, faces: Vec<(Vec<u16>, u8)>) {
    let f: Vec<Face> = faces
        .iter()
        .map(|(i, a)| Face::translucent(i, Rgb565::new(31, 7, 3), *a))
        .collect();
    let scene = ScreenScene {
        mesh: Mesh::new(&verts, &f),
    };
    let mut r = Box::new(ABuffer::<N, 32, 16, 64, 48>::new());
    let mut cap = Capture::<N>::new(32, 24);
    match r.render(&scene, &Config::screen(32, 24), &mut cap) {
        Ok(_) => assert_eq!(cap.rows_received, 24),
        Err(_) => assert_eq!(cap.rows_received, 0),
    }
}

fn faces() -> impl Strategy<Value = Vec<(Vec<u16>, u8)>> {
    let alpha = prop_oneof![Just(255u8), Just(0u8), any::<u8>()];
    prop::collection::vec((prop::collection::vec(0u16..10, 0..12), alpha), 0..10)
}

proptest! {
    #![proptest_config(crate::common::proptest_config(300))]

    #[test]
    fn any_q16_16_input(bits in prop::collection::vec(any::<[i32; 3]>(), 0..9), faces in faces()) {
        let v = bits.iter().map(|b| Vec3::new(Q16_16::from_bits(b[0]), Q16_16::from_bits(b[1]), Q16_16::from_bits(b[2]))).collect();
        run::<Q16_16>(v, faces);
    }

    #[test]
    fn any_f32_input(bits in prop::collection::vec(any::<[u32; 3]>(), 0..9), faces in faces()) {
        let v = bits.iter().map(|b| Vec3::new(f32::from_bits(b[0]), f32::from_bits(b[1]), f32::from_bits(b[2]))).collect();
        run::<f32>(v, faces);
    }

    #[test]
    fn small_coordinates(pts in prop::collection::vec(any::<[i16; 3]>(), 3..9), faces in faces()) {
        // ±128 px, so most faces reach the raster stage and many overlap.
        let v: Vec<Vec3<f32>> = pts.iter().map(|p| Vec3::new(p[0] as f32 / 256.0 + 16.0, p[1] as f32 / 256.0 + 12.0, p[2] as f32 / 256.0)).collect();
        let q: Vec<Vec3<Q16_16>> = v.iter().map(|p| Vec3::from_f32([p.x, p.y, p.z]).unwrap()).collect();
        run::<f32>(v, faces.clone());
        run::<Q16_16>(q, faces);
    }
}

#[test]
fn extreme_depths_and_coordinates() {
    // Huge f32 depths (gradients overflow to infinity and NaN far off the polygon) and
    // coordinates far outside the guard band.
    let big = 3.0e38f32;
    let v = vec![
        Vec3::new(-1.0e30f32, -1.0e30, big),
        Vec3::new(1.0e30, 0.0, -big),
        Vec3::new(0.0, 1.0e30, big),
        Vec3::new(0.5, 0.5, -big),
        Vec3::new(31.5, 0.5, big),
        Vec3::new(0.5, 23.5, 0.0),
    ];
    for alphas in [[255u8, 128], [128, 128], [1, 254]] {
        run::<f32>(
            v.clone(),
            vec![(vec![0, 1, 2], alphas[0]), (vec![3, 4, 5], alphas[1])],
        );
    }
    let q = |x: i32, y: i32, z: i32| {
        Vec3::new(
            Q16_16::from_bits(x),
            Q16_16::from_bits(y),
            Q16_16::from_bits(z),
        )
    };
    let v = vec![
        q(i32::MIN, i32::MIN, i32::MAX),
        q(i32::MAX, 0, i32::MIN),
        q(0, i32::MAX, i32::MAX),
        q(0, 0, i32::MIN),
        q(31 << 16, 0, i32::MAX),
        q(0, 23 << 16, 0),
    ];
    for alphas in [[255u8, 128], [128, 128], [1, 254]] {
        run::<Q16_16>(
            v.clone(),
            vec![(vec![0, 1, 2], alphas[0]), (vec![3, 4, 5], alphas[1])],
        );
    }
}
