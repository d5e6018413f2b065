//! Warnock's area subdivision: the seed's Example 7, equivalence with the exact reference and
//! with the z-buffer, a picture written out as ASCII, capacity and extreme input.

mod common;
use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use proptest::prelude::*;
use zrow::warnock::Warnock;
use zrow::{
    Config, Error, Face, FrameStats, Mesh, RenderError, Renderer, Scalar, ScreenScene, Table, Vec3,
    ZBuffer, Q16_16,
};

/// Host capacities: rows up to 256 pixels, 512 polygons, 2048 edges, and list room for 512
/// polygons in one band at any `B` up to 64 (8 levels).
type Big<N, const B: usize> = Warnock<N, 256, B, 512, 2048, 4096>;

fn warnock<N: Scalar, const B: usize>(p: &Polys, cfg: &Config) -> (Capture<N>, zrow::FrameStats) {
    p.render_stats(&mut *Box::new(Big::<N, B>::new()), cfg)
        .expect("warnock renders")
}

fn zbuffer<N: Scalar>(p: &Polys, cfg: &Config) -> Capture<N> {
    p.render_with(&mut *Box::new(ZBuffer::<N, 256, 256>::new()), cfg)
        .expect("z-buffer renders")
}

/// Warnock at band size `B` against the exact reference (every pixel, except where the
/// reference calls a tie; depth within the format's error) and against the z-buffer: in
/// Q16.16 bit for bit, colour and depth (both apply the same per-sample rule, ties
/// included), in f32 depth within rounding.
fn check<N: Scalar, const B: usize>(p: &Polys, cfg: &Config, what: &str) {
    let (cap, stats) = warnock::<N, B>(p, cfg);
    assert_eq!(cap.rows_received, cfg.height as usize, "{what}: rows");
    let (w, h) = (cfg.width as usize, cfg.height as usize);
    let tol = tie_tolerance::<N>(w + h + 200);
    let refr = reference::<N>(p, cfg, 2.0 * tol);
    let bad = mismatches(&cap, &refr);
    assert!(
        bad.is_empty(),
        "{what}, {}, B = {B}: {} pixels differ from the reference, first {:?}",
        N::NAME,
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    let f32_close = |got: f64, z: f64| (got - z).abs() <= 1e-3 * (1.0 + z.abs());
    for y in 0..h {
        for x in 0..w {
            if let Verdict::Visible(_, z) = refr[y * w + x] {
                let got = cap.z(x, y).to_f64();
                let ok = if N::NAME == "f32" {
                    f32_close(got, z)
                } else {
                    (got - z).abs() <= tol
                };
                assert!(ok, "{what}: depth at ({x},{y}): got {got}, want {z}");
            }
        }
    }
    let z = zbuffer::<N>(p, cfg);
    if N::NAME == "q16.16" {
        assert!(
            cap.color == z.color,
            "{what}, B = {B}: colours differ from the z-buffer"
        );
        assert!(
            cap.depth == z.depth,
            "{what}, B = {B}: depths differ from the z-buffer"
        );
    } else {
        for (k, (a, b)) in cap.depth.iter().zip(&z.depth).enumerate() {
            let same_polygon = cap.color[k] == z.color[k];
            let (a, b) = (a.to_f64(), b.to_f64());
            assert!(
                !same_polygon || a == b || f32_close(a, b),
                "{what}: depth {k}"
            );
        }
    }
    assert!(stats.areas > 0, "{what}: areas counted");
}

fn check_all_bands<N: Scalar>(p: &Polys, cfg: &Config, what: &str) {
    check::<N, 1>(p, cfg, what);
    check::<N, 4>(p, cfg, what);
    check::<N, 16>(p, cfg, what);
    check::<N, 64>(p, cfg, what);
}

/// The picture as letters: `A` for polygon 0, `B` for 1, …, `.` for background.
fn ascii<N: Scalar>(cap: &Capture<N>) -> Vec<String> {
    (0..cap.height)
        .map(|y| {
            (0..cap.width)
                .map(|x| match index_of(cap.at(x, y)) {
                    None => '.',
                    Some(i) => (b'A' + i as u8) as char,
                })
                .collect()
        })
        .collect()
}

/// A cyclic-overlap example (P, Q, R in screen space, z = depth), scaled by 8 in x and y so each
/// triangle covers many pixels: which of the three obscures the other two?
fn example7() -> Polys {
    let s = |x: f32, y: f32, z: f32| [8.0 * x, 8.0 * y, z];
    Polys::new(vec![
        vec![s(1.0, 1.0, 1.0), s(4.0, 5.0, 2.0), s(5.0, 2.0, 5.0)], // P
        vec![s(2.0, 2.0, 0.5), s(3.0, 3.0, 1.75), s(6.0, 1.0, 0.5)], // Q
        vec![s(0.5, 2.0, 5.5), s(2.0, 5.0, 3.0), s(4.0, 4.0, 5.0)], // R
    ])
}

#[test]
fn example7_q_obscures_p_and_r() {
    let p = example7();
    let cfg = Config::screen(56, 48);
    check_all_bands::<Q16_16>(&p, &cfg, "example 7");
    check_all_bands::<f32>(&p, &cfg, "example 7");
    let (cap, _) = warnock::<Q16_16, 16>(&p, &cfg);
    for line in ascii(&cap) {
        println!("{line}");
    }
    // Each polygon alone, to know where it covers.
    let alone: Vec<Capture<Q16_16>> = (0..3)
        .map(|i| zbuffer(&Polys::new(vec![p.polys[i].clone()]), &cfg))
        .collect();
    let covers = |i: usize, x: usize, y: usize| alone[i].at(x, y) != Rgb565::BLACK;
    let (mut q_over_p, mut p_over_r, mut q_over_r) = (0, 0, 0);
    for y in 0..48 {
        for x in 0..56 {
            let got = index_of(cap.at(x, y));
            // Q is nearest where it covers, then P, then R: Q obscures the other two.
            let want = [1, 0, 2].into_iter().find(|&i| covers(i, x, y));
            assert_eq!(got, want, "pixel ({x}, {y})");
            q_over_p += (covers(0, x, y) && covers(1, x, y)) as u32;
            p_over_r += (covers(0, x, y) && covers(2, x, y)) as u32;
            q_over_r += (covers(1, x, y) && covers(2, x, y)) as u32;
        }
    }
    println!("overlaps: Q over P {q_over_p} px, P over R {p_over_r} px, Q over R {q_over_r} px");
    assert!(q_over_p > 20 && p_over_r > 20, "the overlaps are exercised");
}

#[test]
fn random_scenes_equal_reference_at_every_band_size() {
    let mut rng = Rng(0x3A4_0C3);
    for k in 0..24 {
        // 61×47: no band size divides it, so squares are clipped at both screen edges.
        let p = scenes::random(&mut rng, 1 + k % 30, 61.0, 47.0);
        let cfg = Config::screen(61, 47);
        check_all_bands::<Q16_16>(&p, &cfg, &format!("random #{k}"));
        check_all_bands::<f32>(&p, &cfg, &format!("random #{k}"));
    }
}

#[test]
fn dense_scenes_equal_reference_at_every_band_size() {
    let mut rng = Rng(0xDE45E);
    for k in 0..6 {
        let p = scenes::dense(&mut rng, 6 + 4 * k, 48.0, 40.0);
        let cfg = Config::screen(48, 40);
        check_all_bands::<Q16_16>(&p, &cfg, &format!("dense #{k}"));
        check_all_bands::<f32>(&p, &cfg, &format!("dense #{k}"));
    }
}

/// Lists longer than 32 entries are heapsorted, shorter ones insertion-sorted: 40 to 90
/// polygons over one area put every list of the top levels on the heapsort path.
#[test]
fn long_lists_equal_reference_at_every_band_size() {
    let mut rng = Rng(0x0010_0415);
    for k in 0..3 {
        let p = scenes::dense(&mut rng, 40 + 25 * k, 48.0, 40.0);
        let cfg = Config::screen(48, 40);
        check_all_bands::<Q16_16>(&p, &cfg, &format!("long #{k}"));
        check_all_bands::<f32>(&p, &cfg, &format!("long #{k}"));
    }
}

#[test]
fn cyclic_overlap_equals_reference_at_every_band_size() {
    let cfg = Config::screen(48, 48);
    for shift in [0.0, 0.25, 0.5, 1.0 / 256.0, 1.0, 3.25] {
        let p = scenes::cyclic(shift);
        check_all_bands::<Q16_16>(&p, &cfg, &format!("cyclic {shift}"));
        check_all_bands::<f32>(&p, &cfg, &format!("cyclic {shift}"));
    }
}

/// Three rectangles on a 12×8 screen, each pixel worked out by hand:
/// - A: columns 1..=8, rows 1..=6, depth 5;
/// - B: columns 4..=11, rows 0..=3, depth 1 (nearest wherever it covers);
/// - C: columns 2..=6, rows 3..=7, depth x + 1 at column x (3, 4, 5, 6, 7): in front of A at
///   columns 2 and 3, an exact tie with A at column 4 (A is first in the scene, so A wins),
///   behind A at 5 and 6.
#[test]
fn three_rectangles_picture() {
    let rect = |x0: f32, y0: f32, x1: f32, y1: f32, z0: f32, z1: f32| {
        vec![[x0, y0, z0], [x1, y0, z1], [x1, y1, z1], [x0, y1, z0]]
    };
    let p = Polys::new(vec![
        rect(1.0, 1.0, 9.0, 7.0, 5.0, 5.0),
        rect(4.0, 0.0, 12.0, 4.0, 1.0, 1.0),
        rect(2.0, 3.0, 7.0, 8.0, 2.5, 7.5),
    ]);
    let want = [
        "....BBBBBBBB",
        ".AAABBBBBBBB",
        ".AAABBBBBBBB",
        ".ACCBBBBBBBB",
        ".ACCAAAAA...",
        ".ACCAAAAA...",
        ".ACCAAAAA...",
        "..CCCCC.....",
    ];
    let cfg = Config::screen(12, 8);
    fn each<N: Scalar>(p: &Polys, cfg: &Config, want: &[&str]) {
        let pictures = [
            warnock::<N, 1>(p, cfg).0,
            warnock::<N, 2>(p, cfg).0,
            warnock::<N, 4>(p, cfg).0,
            warnock::<N, 8>(p, cfg).0,
            warnock::<N, 16>(p, cfg).0,
        ];
        for cap in pictures {
            assert_eq!(ascii(&cap), want, "{}", N::NAME);
            // The tie pixel keeps A's depth, 5, exactly.
            assert_eq!(cap.z(4, 4).to_f64(), 5.0);
            assert_eq!(cap.z(2, 7).to_f64(), 3.0);
            assert_eq!(cap.z(0, 0), N::MAX);
        }
    }
    each::<Q16_16>(&p, &cfg, &want);
    each::<f32>(&p, &cfg, &want);
}

/// A decal on a tilted wall, exactly coplanar (Q16.16 gives coplanar polygons identical
/// depth bits): every one of its samples is a depth tie, so it shows where it comes first in
/// the scene and nowhere where it comes second — in every decision (hidden test, front test,
/// pixel rule) at every band size.
#[test]
fn coplanar_ties_go_to_the_first_polygon() {
    // Depth 2 + x/4: exact in both formats.
    let wall = vec![
        [0.0, 0.0, 2.0],
        [32.0, 0.0, 10.0],
        [32.0, 24.0, 10.0],
        [0.0, 24.0, 2.0],
    ];
    let decal = vec![
        [8.0, 6.0, 4.0],
        [20.0, 6.0, 7.0],
        [20.0, 18.0, 7.0],
        [8.0, 18.0, 4.0],
    ];
    let cfg = Config::screen(32, 24);
    for decal_first in [true, false] {
        let p = if decal_first {
            Polys::new(vec![decal.clone(), wall.clone()])
        } else {
            Polys::new(vec![wall.clone(), decal.clone()])
        };
        let decal_index = if decal_first { 0 } else { 1 };
        check_all_bands::<Q16_16>(&p, &cfg, "decal");
        check_all_bands::<f32>(&p, &cfg, "decal");
        for cap in [
            warnock::<Q16_16, 1>(&p, &cfg).0,
            warnock::<Q16_16, 2>(&p, &cfg).0,
            warnock::<Q16_16, 8>(&p, &cfg).0,
            warnock::<Q16_16, 32>(&p, &cfg).0,
        ] {
            for y in 0..24 {
                for x in 0..32 {
                    let on_decal = (8..20).contains(&x) && (6..18).contains(&y);
                    let want = if on_decal && decal_first {
                        0
                    } else {
                        1 - decal_index
                    };
                    assert_eq!(
                        index_of(cap.at(x, y)),
                        Some(want),
                        "({x}, {y}), decal first: {decal_first}"
                    );
                }
            }
        }
    }
}

/// A tilted decal behind a flat wall except along its left column, where it touches it
/// (depth 5 − 1/8 + (x − 8)/4 from x = 8 to 20: exactly 5 at column 8's centres, in both
/// formats). Only those ties can show it, and only when it is first in the scene: the hidden
/// test (`zmin` of the decal equal to the wall's `zmax`) and the front test (the wall ties at
/// two corners) must both keep it.
#[test]
fn a_decal_touching_a_wall_shows_only_where_it_ties_first() {
    let wall = vec![
        [0.0, 0.0, 5.0],
        [32.0, 0.0, 5.0],
        [32.0, 24.0, 5.0],
        [0.0, 24.0, 5.0],
    ];
    let decal = vec![
        [8.0, 6.0, 4.875],
        [20.0, 6.0, 7.875],
        [20.0, 18.0, 7.875],
        [8.0, 18.0, 4.875],
    ];
    let cfg = Config::screen(32, 24);
    for decal_first in [true, false] {
        let p = if decal_first {
            Polys::new(vec![decal.clone(), wall.clone()])
        } else {
            Polys::new(vec![wall.clone(), decal.clone()])
        };
        check_all_bands::<Q16_16>(&p, &cfg, "touching decal");
        check_all_bands::<f32>(&p, &cfg, "touching decal");
        let wall_index = if decal_first { 1 } else { 0 };
        fn each<N: Scalar>(p: &Polys, cfg: &Config, decal_first: bool, wall_index: usize) {
            for cap in [
                warnock::<N, 1>(p, cfg).0,
                warnock::<N, 2>(p, cfg).0,
                warnock::<N, 8>(p, cfg).0,
                warnock::<N, 32>(p, cfg).0,
            ] {
                for y in 0..24 {
                    for x in 0..32 {
                        let tie = x == 8 && (6..18).contains(&y);
                        let want = if tie && decal_first { 0 } else { wall_index };
                        assert_eq!(
                            index_of(cap.at(x, y)),
                            Some(want),
                            "{} ({x}, {y}), decal first: {decal_first}",
                            N::NAME
                        );
                    }
                }
            }
        }
        each::<Q16_16>(&p, &cfg, decal_first, wall_index);
        each::<f32>(&p, &cfg, decal_first, wall_index);
    }
}

/// Ties on a steep sliver whose depth wraps inside its own box (so it is settled pixel by
/// pixel): along its upper edge it is exactly as deep as a flat wall, behind it elsewhere.
/// Pixels decided by the pixel rule must break those ties by scene order, as the z-buffer.
#[test]
fn ties_with_a_wrapping_sliver_follow_scene_order() {
    let wall = vec![
        [0.0, 0.0, 10.0],
        [64.0, 0.0, 10.0],
        [64.0, 64.0, 10.0],
        [0.0, 64.0, 10.0],
    ];
    let sliver = vec![
        [10.0, 0.0, 10.0],
        [64.0, 54.0, 10.0],
        [64.0, 53.0, 10.0 + 4000.0],
    ];
    let cfg = Config::screen(64, 64);
    for sliver_first in [true, false] {
        let p = if sliver_first {
            Polys::new(vec![sliver.clone(), wall.clone()])
        } else {
            Polys::new(vec![wall.clone(), sliver.clone()])
        };
        check_all_bands::<Q16_16>(&p, &cfg, "wrapping sliver ties");
        let (cap, _) = warnock::<Q16_16, 16>(&p, &cfg);
        let shown = cap
            .color
            .iter()
            .filter(|&&c| index_of(c) == Some(0))
            .count();
        let shown = if sliver_first { shown } else { 64 * 64 - shown };
        println!("sliver first: {sliver_first}, sliver pixels: {shown}");
        assert!(
            sliver_first == (shown > 20),
            "sliver first: {sliver_first}, {shown} px"
        );
    }
}

/// Renders into a capture that is kept when the render fails (to count the rows sent).
fn render_keeping<R: Renderer<f32>>(
    p: &Polys,
    r: &mut R,
    cfg: &Config,
) -> (Result<FrameStats, RenderError<()>>, Capture<f32>) {
    let verts: Vec<Vec3<f32>> = p
        .polys
        .iter()
        .flatten()
        .map(|v| Vec3::from_f32(*v).unwrap())
        .collect();
    let mut next = 0u16;
    let indices: Vec<Vec<u16>> = p
        .polys
        .iter()
        .map(|poly| {
            next += poly.len() as u16;
            (next - poly.len() as u16..next).collect()
        })
        .collect();
    let faces: Vec<Face> = indices
        .iter()
        .enumerate()
        .map(|(i, f)| Face::new(f, color_of(i)))
        .collect();
    let scene = ScreenScene {
        mesh: Mesh::new(&verts, &faces),
    };
    let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
    let result = r.render(&scene, cfg, &mut cap);
    (result, cap)
}

#[test]
fn capacity_errors_come_before_any_row() {
    // Five triangles reach every band: at B = 8 the list needs 5·(log2(8) + 2) = 25.
    let mut rng = Rng(7);
    let p = scenes::dense(&mut rng, 5, 32.0, 24.0);
    let cfg = Config::screen(32, 24);
    let (result, cap) = render_keeping(
        &p,
        &mut *Box::new(Warnock::<f32, 32, 8, 8, 32, 24>::new()),
        &cfg,
    );
    assert_eq!(
        result,
        Err(RenderError::Scene(Error::Capacity {
            table: Table::VisibleList,
            needed: 25,
            capacity: 24
        }))
    );
    assert_eq!(cap.rows_received, 0, "no row before the error");
    // With exactly the room it asked for, the same scene renders, as the z-buffer does.
    let (result, cap) = render_keeping(
        &p,
        &mut *Box::new(Warnock::<f32, 32, 8, 8, 32, 25>::new()),
        &cfg,
    );
    assert!(result.is_ok());
    assert_eq!(cap.color, zbuffer::<f32>(&p, &cfg).color);
    // Other tables report their own errors, also before any row.
    let (result, cap) = render_keeping(
        &p,
        &mut *Box::new(Warnock::<f32, 32, 8, 4, 32, 64>::new()),
        &cfg,
    );
    assert!(matches!(
        result,
        Err(RenderError::Scene(Error::Capacity {
            table: Table::Polygons,
            needed: 5,
            ..
        }))
    ));
    assert_eq!(cap.rows_received, 0);
    let (result, cap) = render_keeping(
        &p,
        &mut *Box::new(Warnock::<f32, 16, 8, 8, 32, 64>::new()),
        &cfg,
    );
    assert!(matches!(
        result,
        Err(RenderError::Scene(Error::Capacity {
            table: Table::RowWidth,
            ..
        }))
    ));
    assert_eq!(cap.rows_received, 0);
}

/// Q16.16 depth wraps modulo 2^32 LSB far from a steep polygon: there its stored depths are
/// not linear, and an area decision on them (the hidden test, the front test at the
/// corners) would drop the polygon where it is in front. A steep sliver along a diagonal
/// over a flat background, for several slopes and positions; each must equal the z-buffer
/// bit for bit (and the reference) at every band size. Without the linearity check every
/// one of these loses the sliver in some area at B = 16 or 64.
#[test]
fn steep_planes_that_wrap_in_q16_16_equal_the_z_buffer() {
    let cfg = Config::screen(64, 64);
    for (slope, d) in [
        (2000.0f32, 20.0f32),
        (4000.0, 10.0),
        (8000.0, 6.0),
        (10000.0, 30.0),
    ] {
        // Depth 10 on the line x − y = d, 10 + slope one pixel off it: wraps far away.
        let p = Polys::new(vec![
            vec![
                [0.0, 0.0, 20.0],
                [64.0, 0.0, 20.0],
                [64.0, 64.0, 20.0],
                [0.0, 64.0, 20.0],
            ],
            vec![
                [d, 0.0, 10.0],
                [64.0, 64.0 - d, 10.0],
                [64.0, 63.0 - d, 10.0 + slope],
            ],
        ]);
        let what = format!("sliver slope {slope}, x - y = {d}");
        check_all_bands::<Q16_16>(&p, &cfg, &what);
        check_all_bands::<f32>(&p, &cfg, &what);
        let (cap, _) = warnock::<Q16_16, 64>(&p, &cfg);
        let sliver = cap
            .color
            .iter()
            .filter(|&&c| index_of(c) == Some(1))
            .count();
        assert!(sliver > 20, "{what}: the sliver is visible ({sliver} px)");
    }
}

#[test]
fn extreme_input_renders_or_errs_without_panic() {
    let cfg = Config::screen(40, 30);
    // Empty scene: all background, depth at the maximum.
    let (cap, stats) = warnock::<Q16_16, 8>(&Polys::new(vec![]), &cfg);
    assert_eq!(cap.drawn(), 0);
    assert!(cap.depth.iter().all(|&z| z == Q16_16::MAX));
    // 4 bands of 8 rows, 5 squares each, every one decided at once (case a).
    assert_eq!((stats.polygons, stats.areas), (0, 20));
    // Zero area (collinear, a point), huge coordinates near Q16.16's limits, a polygon much
    // larger than the screen, depths at the ends of the range.
    let p = Polys::new(vec![
        vec![[1.0, 1.0, 1.0], [20.0, 20.0, 1.0], [39.0, 39.0, 1.0]],
        vec![[5.0, 5.0, 1.0], [5.0, 5.0, 1.0], [5.0, 5.0, 1.0]],
        vec![
            [-32000.0, -32000.0, 3.0],
            [32000.0, -31000.0, 3.0],
            [0.0, 32000.0, 3.0],
        ],
        vec![
            [10.0, -30000.0, -32000.0],
            [30.0, 25.0, 32000.0],
            [2.0, 29.0, 0.0],
        ],
        vec![[0.0, 0.0, 32767.0], [40.0, 0.0, -32768.0], [0.0, 30.0, 0.0]],
    ]);
    for cap in [
        warnock::<Q16_16, 1>(&p, &cfg).0,
        warnock::<Q16_16, 16>(&p, &cfg).0,
    ] {
        assert_eq!(cap.rows_received, 30);
        assert_eq!(cap.color, zbuffer::<Q16_16>(&p, &cfg).color);
    }
    let big = Polys::new(vec![
        vec![[-1e9, -1e9, 1e30], [1e9, -1e9, -3e38], [0.0, 1e9, 3e38]],
        vec![[0.0, 0.0, 3e38], [40.0, 0.0, -3e38], [0.0, 30.0, 3e38]],
        vec![[1.0, 1.0, 1e-40], [30.0, 2.0, -1e-40], [3.0, 29.0, 0.0]],
    ]);
    let (cap, _) = warnock::<f32, 4>(&big, &cfg);
    assert_eq!(cap.rows_received, 30);
    // NaN and infinity are typed errors, before any row.
    for bad in [f32::NAN, f32::INFINITY, -f32::INFINITY] {
        let verts = [
            Vec3::new(0.0f32, 0.0, 1.0),
            Vec3::new(bad, 5.0, 1.0),
            Vec3::new(3.0, 9.0, bad),
        ];
        let faces = [Face::new(&[0, 1, 2], Rgb565::RED)];
        let scene = ScreenScene {
            mesh: Mesh::new(&verts, &faces),
        };
        let mut cap = Capture::<f32>::new(40, 30);
        let mut w = Box::new(Warnock::<f32, 40, 4, 4, 16, 64>::new());
        let r = w.render(&scene, &cfg, &mut cap);
        assert!(
            matches!(r, Err(RenderError::Scene(Error::NonFinite { face: 0 }))),
            "{bad}: {r:?}"
        );
        assert_eq!(cap.rows_received, 0);
    }
}

/// Any bit patterns as vertices: a frame or a typed error, never a panic (run in debug,
/// where overflow would panic), never a row after an error.
mod no_panic {
    use super::*;

    fn run<N: Scalar>(verts: Vec<Vec3<N>>, faces: Vec<Vec<u16>>) {
        let f: Vec<Face> = faces
            .iter()
            .map(|i| Face {
                indices: i,
                color: Rgb565::new(31, 0, 0),
                alpha: 255,
            })
            .collect();
        let scene = ScreenScene {
            mesh: Mesh::new(&verts, &f),
        };
        let mut r = Box::new(Warnock::<N, 32, 8, 16, 64, 160>::new());
        let mut cap = Capture::<N>::new(32, 24);
        match r.render(&scene, &Config::screen(32, 24), &mut cap) {
            Ok(_) => assert_eq!(cap.rows_received, 24),
            Err(_) => assert_eq!(cap.rows_received, 0),
        }
    }

    fn faces() -> impl Strategy<Value = Vec<Vec<u16>>> {
        prop::collection::vec(prop::collection::vec(0u16..10, 0..8), 0..10)
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
    }
}

/// Reported, not asserted: areas examined on a 240×240 random scene of 100 polygons, per
/// band size (the picture is still checked against the z-buffer).
#[test]
fn report_areas_examined_240() {
    let mut rng = Rng(240);
    let p = scenes::random(&mut rng, 100, 240.0, 240.0);
    let cfg = Config::screen(240, 240);
    let z = zbuffer::<Q16_16>(&p, &cfg);
    let mut line = String::new();
    for (b, (cap, stats)) in [
        (1, warnock::<Q16_16, 1>(&p, &cfg)),
        (4, warnock::<Q16_16, 4>(&p, &cfg)),
        (16, warnock::<Q16_16, 16>(&p, &cfg)),
        (64, warnock::<Q16_16, 64>(&p, &cfg)),
    ] {
        assert_eq!(cap.color, z.color, "B = {b}");
        line += &format!(" B={b}: {} areas;", stats.areas);
    }
    println!(
        "warnock 240x240, 100 random polygons ({} on screen), 57600 pixels:{line}",
        warnock::<Q16_16, 16>(&p, &cfg).1.polygons
    );
    println!(
        "RAM_BYTES: Warnock<Q16_16, 240, 16, 256, 1024, 1536> = {}, <f32, 240, 32, 256, 1024, 1792> = {}",
        Warnock::<Q16_16, 240, 16, 256, 1024, 1536>::RAM_BYTES,
        Warnock::<f32, 240, 32, 256, 1024, 1792>::RAM_BYTES
    );
}
