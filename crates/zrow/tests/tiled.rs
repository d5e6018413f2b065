//! The tiled 16-bit z-buffer: equal to the exact reference wherever depths differ by more than
//! its stated resolution, whatever the band height; the resolution is real; exact ties go to
//! the first polygon; errors come before any row; no input makes it panic.

mod common;
use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use proptest::prelude::*;
use zrow::tiled::{Quantisation, Tiled};
use zrow::{
    Config, Error, Face, FrameStats, Mesh, RenderError, Renderer, Row, RowSink, Scalar,
    ScreenScene, Table, Vec3, ZBuffer, Q16_16,
};

/// Host capacities for the test scenes (frames up to 64 pixels wide).
type T<N, const B: usize> = Tiled<N, 64, B, 256, 1024>;

/// Renders with band height `B`; returns the frame, the stats and the quantisation.
fn run<N: Scalar, const B: usize>(
    p: &Polys,
    cfg: &Config,
) -> (Capture<N>, FrameStats, Quantisation) {
    let mut r = Box::new(T::<N, B>::new());
    let (cap, stats) = p.render_stats(&mut *r, cfg).unwrap();
    (cap, stats, r.quantisation())
}

/// Checks a frame against the reference, with ties up to the method's resolution plus the
/// number format's own depth error (for each of the two polygons), then against the z-buffer.
fn check<N: Scalar, const B: usize>(p: &Polys, w: u16, h: u16) -> Quantisation {
    let cfg = Config::screen(w, h);
    let (cap, _, q) = run::<N, B>(p, &cfg);
    let tie = q.resolution + 2.0 * tie_tolerance::<N>((w + h) as usize);
    let refr = reference::<N>(p, &cfg, tie);
    let bad = mismatches(&cap, &refr);
    assert!(
        bad.is_empty(),
        "{} B={B} {w}x{h}: {} pixels differ (tie {tie}), first {:?}",
        N::NAME,
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    check_zbuffer::<N, B>(p, w, h)
}

/// Checks a frame against the z-buffer: the same coverage; where another polygon shows, it is
/// nearer by at most the resolution (the tiled depth row is its owner's exact depth); depth
/// rows equal where the same polygon shows; the range and the statistics.
fn check_zbuffer<N: Scalar, const B: usize>(p: &Polys, w: u16, h: u16) -> Quantisation {
    let cfg = Config::screen(w, h);
    let (cap, stats, q) = run::<N, B>(p, &cfg);
    assert_eq!(
        stats.areas as usize,
        (h as usize).div_ceil(B),
        "bands filled"
    );
    let (scan, scan_stats) = p
        .render_stats(&mut *Box::new(Big::<N>::new()), &cfg)
        .unwrap();
    assert_eq!(scan.color.len(), cap.color.len());
    assert_eq!(
        (stats.polygons, stats.edges),
        (scan_stats.polygons, scan_stats.edges)
    );

    // Depth rows: the owner's own plane (the z-buffer's bits in Q16.16), N::MAX where empty.
    let zb = p
        .render_with(&mut *Box::new(ZBuffer::<N, 64, 64>::new()), &cfg)
        .unwrap();
    let mut nearest = f64::INFINITY;
    for y in 0..h as usize {
        for x in 0..w as usize {
            let (got, want) = (cap.z(x, y), zb.z(x, y));
            if index_of(cap.at(x, y)).is_none() {
                assert!(got == N::MAX, "empty pixel ({x},{y}) has depth {got:?}");
                continue;
            }
            nearest = nearest.min(want.to_f64());
            let (drawn, zb_drawn) = (index_of(cap.at(x, y)), index_of(zb.at(x, y)));
            assert_eq!(drawn.is_some(), zb_drawn.is_some(), "coverage at ({x},{y})");
            if drawn != zb_drawn {
                let (g, z) = (got.to_f64(), want.to_f64());
                let own = if N::NAME == "f32" {
                    1e-4 * (1.0 + z.abs())
                } else {
                    0.0
                };
                assert!(
                    g >= z - own && g - z <= q.resolution + own,
                    "({x},{y}): {drawn:?} at {g} shows over the z-buffer's {zb_drawn:?} at {z}"
                );
            } else {
                let (g, z) = (got.to_f64(), want.to_f64());
                let ok = if N::NAME == "f32" {
                    (g - z).abs() <= 1e-4 * (1.0 + z.abs())
                } else {
                    g == z
                };
                assert!(ok, "depth at ({x},{y}): {g} vs the z-buffer's {z}");
            }
        }
    }
    // The range is exact: the nearest covered sample is visible, so zmin is the least
    // visible depth (exactly, in Q16.16); the step is just over range/65534.
    if nearest.is_finite() {
        // f32: rounding; fixed point: zmin is the nearest covered depth of the stepped planes
        // visibility is decided on, and a sink is told the exact planes' (the `exact-depth`
        // feature), within half a last place of which the stepped ones lie within
        // 0.5·(1 + i + j).
        let slack = match lsb::<N>() {
            None => 1e-5 * (1.0 + nearest.abs()),
            Some(lsb) => (2.0 + w as f64 + h as f64) / 2.0 * lsb,
        };
        assert!(
            q.zmin <= nearest + slack && q.zmax >= q.zmin,
            "{} {q:?} {nearest}",
            N::NAME
        );
        if N::NAME != "f32" {
            assert!(
                (q.zmin - nearest).abs() <= slack,
                "zmin {} is not the nearest covered depth {nearest}",
                q.zmin
            );
            assert!(q.exact, "Q16.16 frames quantise exactly");
            assert_eq!(q.resolution, q.step);
        }
        let ideal = (q.zmax - q.zmin) / 65534.0;
        assert!(q.step >= ideal && q.step <= ideal * (1.0 + 1e-4), "{q:?}");
    }
    q
}

fn check_all_bands<N: Scalar>(p: &Polys, w: u16, h: u16) {
    check::<N, 1>(p, w, h);
    check::<N, 7>(p, w, h);
    check::<N, 16>(p, w, h);
    check::<N, 64>(p, w, h);
}

#[test]
fn equals_reference_on_random_dense_and_cyclic_scenes() {
    let mut rng = Rng(0x711e_d001);
    let mut rounded = 0;
    for _ in 0..12 {
        let n = 1 + rng.below(30) as usize;
        let p = scenes::random(&mut rng, n, 48.0, 40.0);
        check_all_bands::<Q16_16>(&p, 48, 40);
        check_all_bands::<f32>(&p, 48, 40);
        rounded += !check::<f32, 5>(&p, 48, 40).exact as u32;
    }
    assert!(rounded > 0, "some f32 frames take the rounded path");
    for _ in 0..6 {
        let n = 2 + rng.below(10) as usize;
        let p = scenes::dense(&mut rng, n, 48.0, 40.0);
        check_all_bands::<Q16_16>(&p, 48, 40);
        check_all_bands::<f32>(&p, 48, 40);
    }
    for shift in [0.0, 1.0] {
        let p = scenes::cyclic(shift);
        check_all_bands::<Q16_16>(&p, 48, 48);
        check_all_bands::<f32>(&p, 48, 48);
    }
    // At shift 0.25 the z-buffer and the scan-line method also differ from the reference, at 2
    // pixels in Q16.16: the third bar is not planar (its 4th vertex is off the plane of the
    // first three), and the reference's plane goes through its first vertex while the
    // renderers' goes through the top-left one. Compare with the z-buffer there.
    let p = scenes::cyclic(0.25);
    check_zbuffer::<Q16_16, 7>(&p, 48, 48);
    check_zbuffer::<f32, 7>(&p, 48, 48);
}

/// Depths across (almost) the whole Q16.16 format: one step is about one depth unit, and the
/// plane is still exact.
#[test]
fn full_q16_depth_range_equals_reference() {
    let p = Polys::new(vec![
        vec![
            [0.0, 0.0, -32760.0],
            [48.0, 0.0, 0.0],
            [48.0, 40.0, 32760.0],
            [0.0, 40.0, 0.0],
        ],
        vec![[0.0, 40.0, -100.0], [48.0, 0.0, 300.0], [48.0, 40.0, 50.0]],
        vec![[10.0, 5.0, 10.0], [30.0, 5.0, -10.0], [20.0, 35.0, 5.0]],
    ]);
    let q = check::<Q16_16, 7>(&p, 48, 40);
    assert!(q.zmax - q.zmin > 60000.0 && q.exact, "{q:?}");
    check::<f32, 7>(&p, 48, 40);
}

/// Two parallel planes `delta` apart, the farther first in the scene (so a tie shows it),
/// tilted so their depths fall at every phase of the 16-bit steps. Exact: gradients 8 and 2 on
/// a 64×16 quad, planes exact in both formats. Otherwise gradients 7.9 and 0.013 on a 65×18
/// quad (so the f32 plane's gradients are full-mantissa quotients), whose f32 bits are finer
/// than the quantiser's grid: its rounded path.
fn parallel(delta: f32, exact: bool) -> Polys {
    let (gx, gy, x0, y0, x1, y1) = if exact {
        (8.0, 2.0, 0.0, 0.0, 64.0, 16.0)
    } else {
        (7.9, 0.013, -0.25, -0.75, 64.75, 17.25)
    };
    let z = move |x: f32, y: f32| 100.0 + gx * x + gy * y;
    let quad = |d: f32| {
        vec![
            [x0, y0, z(x0, y0) + d],
            [x1, y0, z(x1, y0) + d],
            [x1, y1, z(x1, y1) + d],
            [x0, y1, z(x0, y1) + d],
        ]
    };
    Polys::new(vec![quad(delta), quad(0.0)])
}

/// Pixels (of 64×16) where the farther plane shows, and the frame's quantisation.
fn far_wins<N: Scalar>(delta: f32, exact: bool) -> (usize, Quantisation) {
    let cfg = Config::screen(64, 16);
    let (cap, _, q) = run::<N, 5>(&parallel(delta, exact), &cfg);
    let mut far = 0;
    for y in 0..16 {
        for x in 0..64 {
            match index_of(cap.at(x, y)) {
                Some(0) => far += 1,
                Some(1) => {}
                other => panic!("({x},{y}) shows {other:?}: both planes cover every pixel"),
            }
        }
    }
    (far, q)
}

/// Rounds up to a multiple of 2^-12 (exact in both formats at these depths).
fn grid_up(v: f64) -> f32 {
    ((v * 4096.0).ceil() / 4096.0) as f32
}

fn resolution_is_real<N: Scalar>(exact: bool) {
    let (_, q0) = far_wins::<N>(0.0, exact);
    assert!(q0.step > 0.0 && q0.zmax - q0.zmin > 400.0, "{q0:?}");
    assert_eq!(q0.exact, exact, "{q0:?}");
    // The planes' own error: none for the dyadic planes, a few f32 ulps at depth ~600 else.
    let own = if exact { 0.0 } else { 2e-4 };
    // Just above the stated resolution (which grows with delta through the range).
    let mut delta = grid_up(1.02 * q0.resolution + own);
    let (far, q) = loop {
        let (far, q) = far_wins::<N>(delta, exact);
        if delta as f64 > q.resolution + own {
            break (far, q);
        }
        delta += 1.0 / 4096.0;
    };
    assert_eq!(
        far,
        0,
        "{}: delta {delta} > resolution {}: nearer must win",
        N::NAME,
        q.resolution
    );
    // Well below one step the 16-bit depths tie at some pixels, and the tie shows the far one.
    let small = grid_up(0.25 * q0.step);
    let (far_small, _) = far_wins::<N>(small, exact);
    assert!(
        far_small > 0,
        "delta {small} (a quarter step) resolved everywhere: not 16-bit"
    );
    println!(
        "{} (exact {exact}): step {:.6}, resolution {:.6}, nearer always wins at delta {delta}; \
         far plane shows at {far_small}/1024 px at delta {small}",
        N::NAME,
        q.step,
        q.resolution
    );
    for k in [0.1, 0.5, 0.9, 1.0, 1.1] {
        let d = grid_up(k * q0.step);
        println!(
            "  delta {d:.6} ({k} step): far plane at {} px",
            far_wins::<N>(d, exact).0
        );
    }
}

#[test]
fn resolution_threshold_is_real_q16_16() {
    resolution_is_real::<Q16_16>(true);
}

#[test]
fn resolution_threshold_is_real_f32() {
    resolution_is_real::<f32>(true);
    resolution_is_real::<f32>(false);
}

#[test]
fn band_heights_give_identical_pictures() {
    let mut rng = Rng(0xba2d);
    for _ in 0..8 {
        let n = 1 + rng.below(40) as usize;
        let p = scenes::random(&mut rng, n, 64.0, 40.0);
        for (cfg, name) in [
            (Config::screen(64, 40), "64x40"),
            (Config::screen(33, 17), "33x17"),
        ] {
            let (a, _, qa) = run::<Q16_16, 1>(&p, &cfg);
            let (b, _, qb) = run::<Q16_16, 3>(&p, &cfg);
            let (c, _, qc) = run::<Q16_16, 64>(&p, &cfg);
            assert!(a == b && a == c && qa == qb && qa == qc, "Q16.16 {name}");
            let (a, _, _) = run::<f32, 1>(&p, &cfg);
            let (c, _, _) = run::<f32, 64>(&p, &cfg);
            assert!(a == c, "f32 {name}");
        }
    }
}

/// Coplanar polygons have identical plane bits in Q16.16, so their 16-bit depths are equal and
/// the first in the scene wins everywhere they overlap — the same picture as the z-buffer.
#[test]
fn coplanar_ties_go_to_the_first_polygon() {
    let z = |x: f32, y: f32| 3.0 + 0.25 * x + 0.125 * y;
    let v = |x: f32, y: f32| [x, y, z(x, y)];
    let p = Polys::new(vec![
        vec![v(2.0, 2.0), v(40.0, 6.0), v(10.0, 36.0)],
        vec![v(8.0, 4.0), v(46.0, 4.0), v(46.0, 30.0), v(8.0, 30.0)],
        vec![v(0.5, 20.0), v(47.5, 12.25), v(30.0, 39.5)],
        // A tilted polygon through them, so the range is not just their plane's.
        vec![[0.0, 0.0, 0.0], [48.0, 0.0, 30.0], [24.0, 40.0, 10.0]],
    ]);
    let cfg = Config::screen(48, 40);
    let zb = p
        .render_with(&mut *Box::new(ZBuffer::<Q16_16, 64, 64>::new()), &cfg)
        .unwrap();
    let (t, _, q) = run::<Q16_16, 7>(&p, &cfg);
    assert!(q.exact);
    assert!(t == zb, "tiled differs from the z-buffer on coplanar ties");
    // Where the second and first overlap, the first shows: count that it happens.
    let shared = (0..40)
        .flat_map(|y| (0..48).map(move |x| (x, y)))
        .filter(|&(x, y)| index_of(t.at(x, y)) == Some(0))
        .count();
    assert!(shared > 100, "{shared}");

    // Duplicates (identical planes in either format): the first copy wins everywhere.
    let tri = vec![v(3.0, 1.0), v(45.0, 9.0), v(12.0, 38.0)];
    let dup = Polys::new(vec![tri.clone(), tri]);
    let (a, _, _) = run::<Q16_16, 4>(&dup, &cfg);
    let (b, _, _) = run::<f32, 4>(&dup, &cfg);
    for c in [&a.color, &b.color] {
        assert!(c
            .iter()
            .all(|&c| c == Rgb565::BLACK || index_of(c) == Some(0)));
        assert!(c.iter().filter(|&&c| c != Rgb565::BLACK).count() > 500);
    }
}

/// Counts rows; optionally fails at one.
struct Rows {
    seen: usize,
    fail_at: Option<u16>,
}

impl<N> RowSink<N> for Rows {
    type Error = u16;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), u16> {
        if Some(row.y) == self.fail_at {
            return Err(row.y);
        }
        self.seen += 1;
        Ok(())
    }
}

fn triangles<N: Scalar>(n: usize) -> (Vec<Vec3<N>>, Vec<[u16; 3]>) {
    let mut v = Vec::new();
    let mut f = Vec::new();
    for i in 0..n {
        let x = 2.0 + 10.0 * (i % 6) as f32;
        let y = 2.0 + 10.0 * (i / 6) as f32;
        for p in [[x, y, 1.0], [x + 8.0, y, 2.0], [x, y + 8.0, 3.0]] {
            v.push(Vec3::from_f32(p).unwrap());
        }
        let k = 3 * i as u16;
        f.push([k, k + 1, k + 2]);
    }
    (v, f)
}

fn render_raw<N: Scalar, R: Renderer<N>>(
    r: &mut R,
    v: &[Vec3<N>],
    idx: &[Vec<u16>],
    cfg: &Config,
    sink: &mut Rows,
) -> Result<FrameStats, RenderError<u16>> {
    let faces: Vec<Face> = idx.iter().map(|i| Face::new(i, Rgb565::RED)).collect();
    let scene = ScreenScene {
        mesh: Mesh::new(v, &faces),
    };
    r.render(&scene, cfg, sink)
}

fn capacity_errors<N: Scalar>() {
    let (v, f) = triangles::<N>(5);
    let idx: Vec<Vec<u16>> = f.iter().map(|t| t.to_vec()).collect();
    let cfg = Config::screen(64, 24);
    let mut sink = Rows {
        seen: 0,
        fail_at: None,
    };
    let err = render_raw(
        &mut *Box::new(Tiled::<N, 64, 8, 4, 64>::new()),
        &v,
        &idx,
        &cfg,
        &mut sink,
    );
    let want = Error::Capacity {
        table: Table::Polygons,
        needed: 5,
        capacity: 4,
    };
    assert_eq!(err, Err(RenderError::Scene(want)));
    assert_eq!(sink.seen, 0);

    let err = render_raw(
        &mut *Box::new(Tiled::<N, 64, 8, 16, 8>::new()),
        &v,
        &idx,
        &cfg,
        &mut sink,
    );
    match err {
        Err(RenderError::Scene(Error::Capacity {
            table: Table::Edges,
            needed,
            capacity: 8,
        })) => {
            assert!(needed > 8)
        }
        other => panic!("want an edge-table error, got {other:?}"),
    }
    assert_eq!(sink.seen, 0);

    let wide = Config::screen(80, 24);
    let err = render_raw(
        &mut *Box::new(Tiled::<N, 64, 8, 16, 64>::new()),
        &v,
        &idx,
        &wide,
        &mut sink,
    );
    let want = Error::Capacity {
        table: Table::RowWidth,
        needed: 80,
        capacity: 64,
    };
    assert_eq!(err, Err(RenderError::Scene(want)));
    let err = render_raw(
        &mut *Box::new(Tiled::<N, 64, 8, 16, 64>::new()),
        &v,
        &idx,
        &Config::screen(0, 24),
        &mut sink,
    );
    assert_eq!(err, Err(RenderError::Scene(Error::BadConfig)));
    assert_eq!(sink.seen, 0);

    // A bad face after good ones: still nothing sent.
    let mut bad = idx.clone();
    bad.push(vec![0, 1, 99]);
    let err = render_raw(
        &mut *Box::new(Tiled::<N, 64, 8, 16, 64>::new()),
        &v,
        &bad,
        &cfg,
        &mut sink,
    );
    assert!(
        matches!(err, Err(RenderError::Scene(Error::IndexOutOfRange { .. }))),
        "{err:?}"
    );
    assert_eq!(sink.seen, 0);

    // The sink's own error stops the frame where it happened.
    let mut failing = Rows {
        seen: 0,
        fail_at: Some(11),
    };
    let err = render_raw(
        &mut *Box::new(Tiled::<N, 64, 8, 16, 64>::new()),
        &v,
        &idx,
        &cfg,
        &mut failing,
    );
    assert_eq!(err, Err(RenderError::Sink(11)));
    assert_eq!(failing.seen, 11);

    // And with room, the frame goes through.
    // (Each triangle has a horizontal edge, which is no edge of the walk.)
    let ok = render_raw(
        &mut *Box::new(Tiled::<N, 64, 8, 5, 10>::new()),
        &v,
        &idx,
        &cfg,
        &mut sink,
    )
    .unwrap();
    assert_eq!((ok.polygons, ok.edges, ok.areas, sink.seen), (5, 10, 3, 24));
}

#[test]
fn capacity_errors_are_typed_and_come_before_any_row() {
    capacity_errors::<Q16_16>();
    capacity_errors::<f32>();
}

/// Renders raw vertices (any bits) and checks the frame is whole or absent.
fn survives<N: Scalar>(v: Vec<Vec3<N>>, idx: Vec<Vec<u16>>) -> Option<Capture<N>> {
    let faces: Vec<Face> = idx.iter().map(|i| Face::new(i, Rgb565::RED)).collect();
    let scene = ScreenScene {
        mesh: Mesh::new(&v, &faces),
    };
    let mut r = Box::new(Tiled::<N, 32, 5, 64, 256>::new());
    let mut cap = Capture::<N>::new(32, 24);
    match r.render(&scene, &Config::screen(32, 24), &mut cap) {
        Ok(s) => {
            assert_eq!((cap.rows_received, s.areas), (24, 5));
            Some(cap)
        }
        Err(_) => {
            assert_eq!(cap.rows_received, 0);
            None
        }
    }
}

fn extremes<N: Scalar>(huge: f32) {
    let v3 = |p: [f32; 3]| Vec3::<N>::from_f32(p).unwrap();
    // Empty scene: background everywhere, depth the maximum.
    let cap = survives::<N>(vec![], vec![]).unwrap();
    assert!(
        cap.color.iter().all(|&c| c == Rgb565::BLACK) && cap.depth.iter().all(|&z| z == N::MAX)
    );
    // Zero area: collinear, all one point, a sliver thinner than a sub-pixel.
    let v = vec![
        v3([1.0, 1.0, 1.0]),
        v3([20.0, 20.0, 2.0]),
        v3([10.0, 10.0, 3.0]),
        v3([5.0, 5.0, 0.0]),
        v3([5.0, 1.0, 0.0]),
        v3([5.001, 20.0, 0.0]),
        v3([5.0, 20.0, 0.0]),
    ];
    let cap = survives::<N>(v, vec![vec![0, 1, 2], vec![3, 3, 3], vec![4, 5, 6]]).unwrap();
    assert_eq!(cap.drawn(), 0);
    // Huge coordinates and depths, and depths at the format's ends.
    let v = vec![
        v3([-huge, -huge, huge]),
        v3([huge, -huge, -huge]),
        v3([0.0, huge, huge]),
        v3([1.0, 1.0, -huge]),
        v3([30.0, 2.0, huge]),
        v3([2.0, 22.0, 0.0]),
    ];
    let cap = survives::<N>(v, vec![vec![0, 1, 2], vec![3, 4, 5]]);
    assert!(cap.is_none_or(|c| c.drawn() > 0));
    // One depth for the whole frame: every level 0, scene order decides.
    let v = vec![
        v3([0.0, 0.0, 5.0]),
        v3([32.0, 0.0, 5.0]),
        v3([0.0, 24.0, 5.0]),
    ];
    let cap = survives::<N>(v, vec![vec![0, 1, 2]]).unwrap();
    assert!(cap.drawn() > 300);
}

#[test]
fn no_panic_on_extreme_input() {
    extremes::<Q16_16>(32767.0);
    extremes::<f32>(3.0e38);
    // Non-finite f32 vertices: a typed error, no row.
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let v = vec![
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(bad, 0.0, 1.0),
            Vec3::new(0.0, 9.0, bad),
        ];
        assert!(survives::<f32>(v, vec![vec![0, 1, 2]]).is_none());
    }
    // f32 depths a few units in the last place apart: no panic, coverage exact.
    let p = Polys::new(vec![
        vec![
            [0.0, 0.0, 1000.0],
            [32.0, 0.0, 1000.0001],
            [0.0, 24.0, 1000.0],
        ],
        vec![
            [32.0, 24.0, 1000.0001],
            [0.0, 24.0, 1000.0],
            [32.0, 0.0, 1000.0],
        ],
    ]);
    let cfg = Config::screen(32, 24);
    let (cap, _, _) = run::<f32, 5>(&p, &cfg);
    assert!(mismatches(&cap, &reference::<f32>(&p, &cfg, 1e-3)).is_empty());
}

/// Any bits as Q16.16 and as f32, then the same bits scaled to small coordinates (so most
/// faces reach the raster stage), in both formats.
fn any_bits(bits: &[[u32; 3]], faces: Vec<Vec<u16>>) {
    let q = |b: u32| Q16_16::from_bits(b as i32);
    let v = bits.iter().map(|b| Vec3::new(q(b[0]), q(b[1]), q(b[2])));
    survives::<Q16_16>(v.collect(), faces.clone());
    let v = bits.iter().map(|b| b.map(f32::from_bits));
    survives::<f32>(
        v.map(|b| Vec3::new(b[0], b[1], b[2])).collect(),
        faces.clone(),
    );
    let small = |b: &[u32; 3]| {
        let s = |v: u32, d: f32| (v as i16) as f32 / d;
        [s(b[0], 512.0), s(b[1], 1024.0), s(b[2], 256.0)]
    };
    let f = bits.iter().map(|b| Vec3::from_f32(small(b)).unwrap());
    survives::<f32>(f.collect(), faces.clone());
    let q = bits.iter().map(|b| Vec3::from_f32(small(b)).unwrap());
    survives::<Q16_16>(q.collect(), faces);
}

proptest! {
    #![proptest_config(crate::common::proptest_config(300))]

    /// Any bits at all as vertices, any faces: a whole frame or a typed error before any row.
    #[test]
    fn any_input_renders_or_errs(
        bits in prop::collection::vec(any::<[u32; 3]>(), 0..9),
        faces in prop::collection::vec(prop::collection::vec(0u16..10, 0..8), 0..8),
    ) {
        any_bits(&bits, faces);
    }
}

/// RAM: the band costs 4 bytes a pixel (16-bit depth and 16-bit owner); the rest is the
/// polygon table, 24 bytes a polygon of integer planes and one output row.
#[test]
fn ram_figures() {
    type A = Tiled<Q16_16, 240, 16, 512, 1536>;
    type B8 = Tiled<Q16_16, 240, 8, 512, 1536>;
    type Table = zrow::polygons::PolygonTable<Q16_16, 512, 1536>;
    println!(
        "RAM_BYTES: Tiled<Q16_16, 240, 16, 512, 1536> = {}, Tiled<Q16_16, 240, 8, 512, 1536> = {} \
         (polygon table {}, z-buffer 240x240 {})",
        A::RAM_BYTES,
        B8::RAM_BYTES,
        Table::RAM_BYTES,
        ZBuffer::<Q16_16, 240, 240>::RAM_BYTES
    );
    assert_eq!(A::RAM_BYTES - B8::RAM_BYTES, 8 * 240 * 4);
    let rest = Table::RAM_BYTES + 512 * 24 + 16 * 240 * 4 + 240 * (2 + 4);
    assert!(
        A::RAM_BYTES >= rest && A::RAM_BYTES <= rest + 64,
        "{} vs {rest}",
        A::RAM_BYTES
    );
    assert_eq!(<A as Renderer<Q16_16>>::NAME, "tiled");
}
