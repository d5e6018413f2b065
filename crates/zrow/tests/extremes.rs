//! The numerical extremes of `docs/extremes.md` as tests. Each test names its item; every item is a generic function
//! over `N: Scalar`, run through the one format list [`for_formats!`], and — where it is about
//! coverage or clipping — on every method ([`all_methods`]: scan-line, z-buffer, tiled 16-bit
//! z-buffer, depth-sort, Warnock, BSP, A-buffer, and cull-only and ordered, whose preconditions
//! a scene of one polygon meets).
//!
//! Where each catalogue item is tested:
//! - here: 1 golden split square, 2 samples on edges and vertices, 3 random triangles on and
//!   off the sub-pixel grid, 4–5 watertight fans (inside, clipped), 6 split quads, 7 closed
//!   mesh, 8 vertex order and winding, 9 translation, 10 repeatability, 11 zero area, 13
//!   (screen space: coordinates at the format's limits), 14 near plane, 21 debug vs release
//!   (frame hash; scan-line only, the blessed hash fixes its formats), 23 bad input
//!   (scan-line's exact errors), and depth ties (`docs/conventions.md`);
//! - tests/extremes_coverage.rs: 12 needles across the guard band, 13 (clip space: huge
//!   objects under a perspective camera, and Q16.16's typed refusal), 15 (bounding boxes
//!   either side of 2^k pixels, and the one width switch the core has: `div_round`'s 64/128-bit
//!   division in the Q16.16 depth plane);
//! - tests/extremes_depth.rs: 16 depth linearity, 17 depth resolution (measured thresholds,
//!   screen space and perspective, every method and the tiled 16-bit z-buffer), 18 depth at
//!   the ends of the range, 19 transforms (limits, 10^4 accumulated rotations), 20 every
//!   method against the z-buffer on cyclic overlap, interpenetration and coplanar pairs (with
//!   tests/methods.rs, which holds the exact methods to the reference on random, dense and
//!   cyclic scenes);
//! - tests/fuzzlike.rs: 23 for every method (typed errors before any row), and property tests
//!   feeding extreme, degenerate and non-finite scenes and extreme configurations to every
//!   method in every format;
//! - 22 (host vs the emulated Cortex-M4: identical frame hash) is checked by emu/check.sh.

mod common;
use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{
    Camera, Config, Error, Face, Mesh, RenderError, Scalar, Scanline, ScreenScene, Table, Vec3,
    Q16_16, Q24_8,
};

/// Runs a generic item for every number format (adding a format is one line here).
macro_rules! for_formats {
    ($f:ident $(, $a:expr)*) => {{
        $f::<Q16_16>($($a),*);
        $f::<Q24_8>($($a),*);
        $f::<f32>($($a),*);
    }};
}

// 1. Golden vector: the 5x5 square (0.5,0.5)-(5.5,5.5) split on its diagonal covers 15 + 10.
fn golden_square<N: Scalar>() {
    let cfg = Config::screen(8, 8);
    let (a, b, c, d) = (
        [0.5, 0.5, 0.],
        [5.5, 0.5, 0.],
        [5.5, 5.5, 0.],
        [0.5, 5.5, 0.],
    );
    for m in &mut all_methods::<N>() {
        for reversed in [false, true] {
            let mut t1 = vec![a, b, d];
            let mut t2 = vec![b, c, d];
            if reversed {
                t1.reverse();
                t2.reverse();
            }
            let n1 = coverage_counts_with(m, &[t1.clone()], &cfg)
                .iter()
                .sum::<u32>();
            let n2 = coverage_counts_with(m, &[t2.clone()], &cfg)
                .iter()
                .sum::<u32>();
            let mut counts = [n1, n2];
            counts.sort();
            assert_eq!(counts, [10, 15], "{} reversed={reversed}", m.name);
            let union = coverage_counts_with(m, &[t1, t2], &cfg);
            assert_eq!(union.iter().filter(|&&c| c == 1).count(), 25, "{}", m.name);
            assert!(union.iter().all(|&c| c <= 1), "{}: no pixel twice", m.name);
        }
    }
}

#[test]
fn e01_golden_split_square() {
    for_formats!(golden_square);
}

// 2. Samples exactly on an edge or a vertex: tiny triangles round a pixel centre, shifted by
// ±1/2^S, against the exact integer top-left reference.
fn on_edge<N: Scalar>() {
    let cfg = Config::screen(6, 6);
    let e = 1.0 / 256.0;
    let c = [2.5f32, 2.5f32];
    let mut polys = Vec::new();
    for dx in [-e, 0.0, e] {
        for dy in [-e, 0.0, e] {
            let (x, y) = (c[0] + dx, c[1] + dy);
            // Triangles with a vertex on the centre, and edges through it, in 8 directions.
            polys.push(vec![[x, y, 0.], [x + 1., y, 0.], [x, y + 1., 0.]]);
            polys.push(vec![[x, y, 0.], [x, y + 1., 0.], [x - 1., y, 0.]]);
            polys.push(vec![
                [x - 1., y - 1., 0.],
                [x + 1., y + 1., 0.],
                [x + 1., y - 1., 0.],
            ]);
            polys.push(vec![
                [x - 1., y - 1., 0.],
                [x - 1., y + 1., 0.],
                [x + 1., y + 1., 0.],
            ]);
            polys.push(vec![[x - 1., y, 0.], [x + 1., y, 0.], [x, y + 1., 0.]]);
            polys.push(vec![[x - 1., y, 0.], [x, y - 1., 0.], [x + 1., y, 0.]]);
        }
    }
    let mut methods = all_methods::<N>();
    for p in polys {
        let one = Polys::new(vec![p]);
        let refr = reference::<N>(&one, &cfg, 0.0);
        for m in &mut methods {
            let cap = m.polys(&one, &cfg).unwrap();
            let bad = mismatches(&cap, &refr);
            assert!(bad.is_empty(), "{} {}: {:?}", m.name, N::NAME, one.polys[0]);
        }
    }
}

#[test]
fn e02_samples_on_edges_and_vertices() {
    for_formats!(on_edge);
}

// 3. Random triangles on the sub-pixel grid (10k): exact. Off the grid: dEQP STRICT —
// a pixel whose sample lies farther than one sub-pixel from every edge must match the
// unsnapped triangle.
/// Triangles per method: the scan-line method (first in the list) takes the catalogue's 10k
/// in fixed point (2k in f32, whose snapping the fixed formats share bit for bit on this
/// grid); the other methods share its coverage code paths only in part, and take 400 each.
fn random_triangles<N: Scalar>() {
    let cfg = Config::screen(24, 24);
    let mut rng = Rng(3);
    let first = if fixed_lsb::<N>().is_some() {
        10_000
    } else {
        2_000
    };
    for (k, m) in all_methods::<N>().iter_mut().enumerate() {
        for _ in 0..if k == 0 { first } else { 400 } {
            let g = |r: &mut Rng| (r.f(-4.0, 28.0) * 256.0).round() / 256.0;
            let t = vec![
                [g(&mut rng), g(&mut rng), 0.],
                [g(&mut rng), g(&mut rng), 0.],
                [g(&mut rng), g(&mut rng), 0.],
            ];
            let one = Polys::new(vec![t]);
            let cap = m.polys(&one, &cfg).unwrap();
            let refr = reference::<N>(&one, &cfg, 0.0);
            let bad = mismatches(&cap, &refr);
            assert!(bad.is_empty(), "{} {}: {:?}", m.name, N::NAME, one.polys[0]);
        }
    }
}

#[test]
fn e03_random_triangles_on_grid_exact() {
    for_formats!(random_triangles);
}

fn strict_off_grid<N: Scalar>() {
    let cfg = Config::screen(24, 24);
    let s = 1.0 / 256.0;
    let mut rng = Rng(33);
    let mut methods = all_methods::<N>();
    for n in 0..2_000 {
        let t: Vec<[f32; 3]> = (0..3)
            .map(|_| [rng.f(-4.0, 28.0), rng.f(-4.0, 28.0), 0.0])
            .collect();
        // Scan-line on every triangle, the others (in turn) on one in 4.
        let others = methods.len() - 1;
        let m = if n % 4 == 0 {
            &mut methods[1 + (n / 4) % others]
        } else {
            &mut methods[0]
        };
        let cap = m.polys(&Polys::new(vec![t.clone()]), &cfg).unwrap();
        let area = (t[1][0] - t[0][0]) as f64 * (t[2][1] - t[0][1]) as f64
            - (t[2][0] - t[0][0]) as f64 * (t[1][1] - t[0][1]) as f64;
        for y in 0..24 {
            for x in 0..24 {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let mut inside = true;
                let mut near = false;
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    let (dx, dy) = ((b[0] - a[0]) as f64, (b[1] - a[1]) as f64);
                    let f = (dx * (py - a[1] as f64) - dy * (px - a[0] as f64)) * area.signum();
                    let len = (dx * dx + dy * dy).sqrt();
                    if f.abs() <= 2.0 * s * len {
                        near = true;
                    }
                    inside &= f > 0.0;
                }
                if area.abs() < 1e-3 || near {
                    continue; // PARTIAL: either way is right
                }
                let drawn = cap.at(x, y) != Rgb565::BLACK;
                assert_eq!(drawn, inside, "{} {t:?} at ({x},{y})", m.name);
            }
        }
    }
}

#[test]
fn e03_random_triangles_off_grid_strict() {
    for_formats!(strict_off_grid);
}

/// A fan of triangles round `centre` with rim points on a circle, perimeter steps
/// `U(0.05, 1)·8·coarse` px (in angle), each as its own polygon.
fn fan(centre: [f32; 2], radius: f32, coarse: f32, rng: &mut Rng) -> Vec<Vec<[f32; 3]>> {
    let mut angles = vec![0.0f32];
    let step = coarse / radius;
    while *angles.last().unwrap() < std::f32::consts::TAU {
        let a = angles.last().unwrap() + rng.f(0.05, 1.0) * step * 8.0;
        angles.push(a.min(std::f32::consts::TAU));
    }
    let rim: Vec<[f32; 3]> = angles
        .iter()
        .map(|a| {
            [
                centre[0] + radius * a.cos(),
                centre[1] + radius * a.sin(),
                0.0,
            ]
        })
        .collect();
    let c = [centre[0], centre[1], 0.0];
    (0..rim.len() - 1)
        .map(|k| vec![c, rim[k], rim[k + 1]])
        .collect()
}

// 4. Watertight fan inside the screen: every pixel inside hit exactly once.
// 5. The same with centre and rim far outside the screen: clipping exercised.
/// The scan-line method (first in the list) draws the fan at `max(1, coarse/12)` times the
/// steps, every other method a coarser fan (`coarse` times: fewer, wider triangles, the same
/// shared-edge construction; near a far-away centre they are all slivers on screen).
fn watertight<N: Scalar>(centre: [f32; 2], radius: f32, seed: u64, coarse: f32) {
    let cfg = Config::screen(64, 64);
    for (k, m) in all_methods::<N>().iter_mut().enumerate() {
        let c = if k == 0 {
            (coarse / 12.0).max(1.0)
        } else {
            coarse
        };
        let mut tris = fan(centre, radius, c, &mut Rng(seed));
        // Triangles whose bounding box misses the screen: one in 32 is drawn (it must draw
        // nothing), the rest are left out to save time.
        let mut k = 0;
        tris.retain(|t| {
            let misses = [0, 1]
                .iter()
                .any(|&a| t.iter().all(|v| v[a] < -1.0) || t.iter().all(|v| v[a] > 65.0));
            k += 1;
            !misses || k % 32 == 0
        });
        let counts = coverage_counts_with(m, &tris, &cfg);
        assert!(
            counts.iter().all(|&c| c <= 1),
            "{}: a pixel drawn twice",
            m.name
        );
        // Inside the rim polygon (shrunk by the chords' sagitta and a pixel), every pixel once.
        let rim_inner = radius - 0.5 * (8.0 * c).powi(2) / radius - 1.0;
        for y in 0..64 {
            for x in 0..64 {
                let (dx, dy) = (x as f32 + 0.5 - centre[0], y as f32 + 0.5 - centre[1]);
                if (dx * dx + dy * dy).sqrt() < rim_inner {
                    assert_eq!(counts[y * 64 + x], 1, "{}: hole at ({x},{y})", m.name);
                }
            }
        }
        assert!(counts.contains(&1));
    }
}

fn fans_inside<N: Scalar>() {
    for seed in 1..4 {
        watertight::<N>([32.3, 31.7], 28.0, seed, 1.0);
    }
}

#[test]
fn e04_watertight_fan_inside() {
    for_formats!(fans_inside);
}

/// Centre and rim far outside the screen (all three fit Q16.16's ±32768).
fn fans_clipped<N: Scalar>() {
    watertight::<N>([-900.0, 40.0], 1500.0, 1, 4.0);
    watertight::<N>([5000.0, -3000.0], 9000.0, 2, 16.0);
    watertight::<N>([32.0, 32.0], 20000.0, 1, 48.0);
}

#[test]
fn e05_watertight_fan_clipped() {
    for_formats!(fans_clipped);
}

// 6. Quads split on a diagonal, one much larger than the screen: no pixel twice, no hole.
fn split_quads<N: Scalar>() {
    let cfg = Config::screen(40, 30);
    let quads = [
        ([3.2, 2.9], [17.7, 3.1], [18.1, 15.3], [2.6, 14.8]),
        (
            [-3000.0, -2000.0],
            [3100.0, -2500.0],
            [2900.0, 2700.0],
            [-3200.0, 2400.0],
        ),
    ];
    for m in &mut all_methods::<N>() {
        for (a, b, c, d) in quads {
            let z = |p: [f32; 2]| [p[0], p[1], 1.0];
            let tris = vec![vec![z(a), z(b), z(c)], vec![z(a), z(c), z(d)]];
            let counts = coverage_counts_with(m, &tris, &cfg);
            assert!(counts.iter().all(|&c| c <= 1), "{}", m.name);
            if a[0] < -100.0 {
                assert!(
                    counts.iter().all(|&c| c == 1),
                    "{}: the screen-covering quad leaves holes",
                    m.name
                );
            }
        }
    }
}

#[test]
fn e06_split_quads() {
    for_formats!(split_quads);
}

// 7. Closed mesh of shared-edge triangles: a jittered grid covers its outline once.
fn closed_grid<N: Scalar>() {
    let cfg = Config::screen(48, 48);
    let mut rng = Rng(77);
    let n = 6;
    let mut p = vec![[0.0f32; 3]; (n + 1) * (n + 1)];
    for j in 0..=n {
        for i in 0..=n {
            let border = i == 0 || j == 0 || i == n || j == n;
            let jit = if border { 0.0 } else { 2.5 };
            p[j * (n + 1) + i] = [
                4.0 + i as f32 * 6.7 + rng.f(-jit, jit),
                4.0 + j as f32 * 6.7 + rng.f(-jit, jit),
                rng.f(0.0, 5.0),
            ];
        }
    }
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b) = (p[j * (n + 1) + i], p[j * (n + 1) + i + 1]);
            let (c, d) = (p[(j + 1) * (n + 1) + i], p[(j + 1) * (n + 1) + i + 1]);
            tris.push(vec![a, b, d]);
            tris.push(vec![a, d, c]);
        }
    }
    for m in &mut all_methods::<N>() {
        let counts = coverage_counts_with(m, &tris, &cfg);
        let (lo, hi) = (4.0, 4.0 + n as f32 * 6.7);
        for y in 0..48 {
            for x in 0..48 {
                let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                let inside = px > lo && px < hi && py > lo && py < hi;
                let c = counts[y * 48 + x];
                assert!(c <= 1, "{}: twice at ({x},{y})", m.name);
                if inside {
                    assert_eq!(c, 1, "{}: hole at ({x},{y})", m.name);
                }
            }
        }
    }
}

#[test]
fn e07_closed_mesh_covers_once() {
    for_formats!(closed_grid);
}

// 8. Vertex rotation (3 cyclic orders) and reversed winding, culling off: identical coverage
// and depth bits.
fn rotation_invariance<N: Scalar>() {
    let cfg = Config::screen(32, 32);
    let mut rng = Rng(8);
    // 200 triangles on the scan-line method, 30 on each other one.
    for (n, m) in all_methods::<N>().iter_mut().enumerate() {
        for _ in 0..if n == 0 { 200 } else { 30 } {
            let t: Vec<[f32; 3]> = (0..3)
                .map(|_| [rng.f(-5.0, 37.0), rng.f(-5.0, 37.0), rng.f(0.0, 50.0)])
                .collect();
            let base = m.polys(&Polys::new(vec![t.clone()]), &cfg).unwrap();
            for k in 1..6 {
                let mut v = t.clone();
                v.rotate_left(k % 3);
                if k >= 3 {
                    v.reverse();
                }
                let other = m.polys(&Polys::new(vec![v]), &cfg).unwrap();
                assert_eq!(base.color, other.color, "{}: coverage, order {k}", m.name);
                // Planes are set up from a canonical vertex order: identical depth bits.
                assert!(
                    base.depth
                        .iter()
                        .zip(&other.depth)
                        .all(|(a, b)| a.to_f64().to_bits() == b.to_f64().to_bits()),
                    "{}: depth bits, order {k}",
                    m.name
                );
            }
        }
    }
}

#[test]
fn e08_vertex_order_and_winding_invariance() {
    for_formats!(rotation_invariance);
}

// 9. Translation by whole pixels: coverage translates exactly.
// 10. Draw, then redraw identical geometry: identical depth bits.
fn translate_and_repeat<N: Scalar>() {
    let cfg = Config::screen(40, 40);
    let mut rng = Rng(9);
    let mut methods = all_methods::<N>();
    for n in 0..200 + 30 * (methods.len() - 1) {
        let m = &mut methods[n.saturating_sub(170) / 30];
        let t: Vec<[f32; 3]> = (0..3)
            .map(|_| {
                // On a 1/1024 grid, so adding whole pixels is exact in f32.
                let g = |v: f32| (v * 1024.0).round() / 1024.0;
                [g(rng.f(0.0, 20.0)), g(rng.f(0.0, 20.0)), rng.f(0.0, 50.0)]
            })
            .collect();
        let (dx, dy) = (rng.below(15) as usize, rng.below(15) as usize);
        let moved: Vec<[f32; 3]> = t
            .iter()
            .map(|v| [v[0] + dx as f32, v[1] + dy as f32, v[2]])
            .collect();
        let a = m.polys(&Polys::new(vec![t.clone()]), &cfg).unwrap();
        let b = m.polys(&Polys::new(vec![moved]), &cfg).unwrap();
        for y in 0..25 {
            for x in 0..25 {
                assert_eq!(a.at(x, y), b.at(x + dx, y + dy), "{}", m.name);
                // Depth is within the stated error of the same plane (item 9 asks coverage
                // only: Q16.16 planes are referenced at pixel (0, 0), so bits may differ).
                let (za, zb) = (a.z(x, y).to_f32(), b.z(x + dx, y + dy).to_f32());
                assert!(
                    za == zb || (za - zb).abs() <= tie_tolerance::<N>(80) as f32,
                    "{} {za} {zb} {t:?}",
                    N::NAME
                );
            }
        }
        let again = m.polys(&Polys::new(vec![t]), &cfg).unwrap();
        assert_eq!(a, again, "{}: redraw is bit-identical", m.name);
    }
}

#[test]
fn e09_e10_translation_and_repeatability() {
    for_formats!(translate_and_repeat);
}

/// One renderer drawing the same scene twice gives the same frame and statistics (no state
/// leaks from one frame into the next), for every method.
fn same_renderer_twice<N: Scalar>() {
    let p = Polys::new(vec![
        vec![[1.0, 1.0, 3.0], [30.0, 4.0, 1.0], [9.0, 28.0, 9.0]],
        vec![[2.0, 25.0, 0.5], [28.0, 2.0, 7.0], [31.0, 31.0, 2.0]],
    ]);
    let other = Polys::new(vec![vec![
        [0.0, 0.0, 0.0],
        [32.0, 0.0, 1.0],
        [0.0, 32.0, 2.0],
    ]]);
    let cfg = Config::screen(32, 32);
    for m in &mut every_method::<N>() {
        let a = m.polys_full(&p, &cfg).unwrap();
        // Something else in between, so a renderer that kept state would show it.
        m.polys(&other, &cfg).unwrap();
        let b = m.polys_full(&p, &cfg).unwrap();
        assert_eq!(a.0, b.0, "{}", m.name);
        assert_eq!(a.1, b.1, "{}", m.name);
        if m.name == "scanline" {
            assert!(
                a.1.crossings > 0,
                "the two triangles intersect: the front changes at their crossing"
            );
        }
    }
}

#[test]
fn e10_same_renderer_twice_is_identical() {
    for_formats!(same_renderer_twice);
}

// 11. Zero area after snapping: collinear, vertices closer than 2^-S, slivers thinner than a
// sub-pixel: no pixels, no panic.
fn zero_area<N: Scalar>() {
    let cfg = Config::screen(16, 16);
    let s = 1.0 / 256.0;
    let cases = vec![
        vec![[1.0, 1.0, 0.], [8.0, 8.0, 5.], [15.0, 15.0, 9.]],
        vec![
            [4.5, 4.5, 0.],
            [4.5 + s / 4.0, 4.5, 1.],
            [4.5, 4.5 + s / 4.0, 2.],
        ],
        vec![
            [0.0, 3.5, 0.],
            [16.0, 3.5 + s / 3.0, 0.],
            [8.0, 3.5 + s / 5.0, 0.],
        ],
        vec![[3.0, 3.0, 0.], [3.0, 3.0, 0.], [3.0, 3.0, 0.]],
        vec![
            [2.0, 9.0, 0.],
            [2.0, 9.0, 1.],
            [14.0, 9.0, 2.],
            [14.0, 9.0, 3.],
        ],
    ];
    for m in &mut all_methods::<N>() {
        for t in &cases {
            let cap = m.polys(&Polys::new(vec![t.clone()]), &cfg).unwrap();
            assert_eq!(cap.drawn(), 0, "{} {t:?}", m.name);
        }
    }
}

#[test]
fn e11_zero_area_after_snapping() {
    for_formats!(zero_area);
}

// 13. Huge coordinates (screen-space part): just inside and outside ±32767 (Q16.16's range)
// and ±1e6 (f32), depth ±1e6: no overflow, no out-of-bounds write, a 3x3 match to the exact
// f64 reference.
fn huge<N: Scalar>(m: &mut Method<N>, big: f32, depth: f32) {
    let cfg = Config::screen(32, 32);
    let cases = vec![
        vec![[-big, -big, 0.], [big, -big, depth], [0.0, big, -depth]],
        vec![[16.0, 16.0, 1.], [big, 16.5, 1.], [16.5, big, 1.]],
        vec![[-big, 10.25, 0.], [big, 20.75, 0.], [big, -big, 0.]],
        vec![[3.0, 3.0, depth], [-big, big, depth], [big, big, -depth]],
    ];
    for t in cases {
        let cap = m.polys(&Polys::new(vec![t.clone()]), &cfg).unwrap();
        let (a, b, c) = (t[0], t[1], t[2]);
        let inside = |x: f64, y: f64| {
            let e = |p: [f32; 3], q: [f32; 3]| {
                (q[0] as f64 - p[0] as f64) * (y - p[1] as f64)
                    - (q[1] as f64 - p[1] as f64) * (x - p[0] as f64)
            };
            let (e0, e1, e2) = (e(a, b), e(b, c), e(c, a));
            (e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0)
        };
        for y in 0..32usize {
            for x in 0..32usize {
                let drawn = cap.at(x, y) != Rgb565::BLACK;
                // 3x3 rule: some pixel in the neighbourhood agrees with the reference.
                let ok = (-1i32..=1).any(|dy| {
                    (-1i32..=1).any(|dx| {
                        inside(x as f64 + 0.5 + dx as f64, y as f64 + 0.5 + dy as f64) == drawn
                    })
                });
                assert!(ok, "{} {t:?} at ({x},{y}) drawn={drawn}", m.name);
            }
        }
        assert!(cap.depth.iter().all(|z| !z.to_f32().is_nan()));
    }
}

/// Coordinates just inside and outside ±32767 (a 16-bit integer path's edge), ±1e6, and the
/// format's own limit (Q16.16: 32767.998; f32: 3e7, beyond which a pixel is below one ulp),
/// with depths ±min(0.9·limit, 1e6).
fn huge_all<N: Scalar>() {
    let limit = max_f32::<N>().min(3.0e7);
    let depth = (0.9 * limit).min(1.0e6);
    for m in &mut all_methods::<N>() {
        for big in [32767.0, 32768.0, 32769.0, 1.0e6, limit] {
            if big <= limit {
                huge(m, big, depth);
                huge(m, big, -depth);
            }
        }
    }
}

#[test]
fn e13_huge_screen_coordinates() {
    for_formats!(huge_all);
}

fn out_of_range<N: Scalar>() {
    // Beyond the format (Q16.16: 40000), and not a number: the conversion refuses it, so a
    // loader reports it.
    let beyond = 1.25 * max_f32::<N>();
    assert!(beyond.is_infinite() || Vec3::<N>::from_f32([beyond, 0.0, 0.0]).is_none());
    assert!(Vec3::<N>::from_f32([f32::NAN, 0.0, 0.0]).is_none());
    assert!(Vec3::<N>::from_f32([0.0, f32::NEG_INFINITY, 0.0]).is_none());
}

#[test]
fn e13_out_of_format_range_is_an_error_not_a_wrap() {
    for_formats!(out_of_range);
    assert!(Vec3::<Q16_16>::from_f32([40000.0, 0.0, 0.0]).is_none());
}

/// A model-mode scene with one triangle in view space (camera at the origin, looking −z).
fn near_plane_scene<N: Scalar>(m: &mut Method<N>, tri: [[f32; 3]; 3]) -> Capture<N> {
    let verts: Vec<Vec3<N>> = tri.iter().map(|v| Vec3::from_f32(*v).unwrap()).collect();
    let faces = [Face {
        indices: &[0, 1, 2],
        color: Rgb565::WHITE,
        alpha: 255,
    }];
    let camera = Camera::look_at(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0],
        Camera::<N>::perspective(1.5, 0.1, 100.0).unwrap(),
    )
    .unwrap();
    let mut cfg = Config::model(48, 48);
    cfg.cull = zrow::Cull::None;
    with_model(&verts, &faces, camera, |s| m.scene(s, &cfg))
        .unwrap()
        .0
}

// 14. Near plane: 1, 2 or 3 vertices behind the eye, and w → 0⁺: only w > 0 drawn, no NaN.
fn near_plane<N: Scalar>() {
    let near = 0.1f64;
    let cases = [
        [[-1.0, -1.0, -2.0], [1.0, -1.0, -2.0], [0.0, 1.0, 3.0]],
        [[-1.0, -1.0, 2.0], [1.0, -1.0, 2.0], [0.0, 1.0, -3.0]],
        [[-1.0, -1.0, 2.0], [1.0, -1.0, 2.0], [0.0, 1.0, 3.0]],
        [
            [-1.0, -1.0, -0.0001],
            [1.0, -1.0, -0.0001],
            [0.0, 1.0, -5.0],
        ],
        [[-3.0, -0.5, -0.1], [3.0, -0.5, -0.1], [0.0, -0.5, -9.0]],
    ];
    let mut methods = all_methods::<N>();
    let count = methods.len();
    for (tri, m) in cases.iter().flat_map(|t| (0..count).map(move |k| (*t, k))) {
        let m = &mut methods[m];
        let cap = near_plane_scene::<N>(m, tri);
        // Ray-cast reference in f64: the pixel's ray hits the triangle at distance > near.
        let f = 1.0 / (0.75f64).tan();
        let v: Vec<[f64; 3]> = tri
            .iter()
            .map(|p| [p[0] as f64, p[1] as f64, p[2] as f64])
            .collect();
        for y in 0..48usize {
            for x in 0..48usize {
                let covered = |x: f64, y: f64| {
                    let d = [(x / 24.0 - 1.0) / f, (1.0 - y / 24.0) / f, -1.0];
                    let e1 = [v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]];
                    let e2 = [v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]];
                    let cr = |a: [f64; 3], b: [f64; 3]| {
                        [
                            a[1] * b[2] - a[2] * b[1],
                            a[2] * b[0] - a[0] * b[2],
                            a[0] * b[1] - a[1] * b[0],
                        ]
                    };
                    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                    let p = cr(d, e2);
                    let det = dot(e1, p);
                    if det.abs() < 1e-12 {
                        return false;
                    }
                    let s = [-v[0][0], -v[0][1], -v[0][2]];
                    let u = dot(s, p) / det;
                    let q = cr(s, e1);
                    let w = dot(d, q) / det;
                    let t = dot(e2, q) / det;
                    u >= 0.0 && w >= 0.0 && u + w <= 1.0 && t > near
                };
                let drawn = cap.at(x, y) != Rgb565::BLACK;
                let ok = (-1i32..=1).any(|dy| {
                    (-1i32..=1).any(|dx| {
                        covered(x as f64 + 0.5 + dx as f64, y as f64 + 0.5 + dy as f64) == drawn
                    })
                });
                assert!(ok, "{} {tri:?} at ({x},{y}) drawn={drawn}", m.name);
                let z = cap.z(x, y).to_f32();
                assert!(!z.is_nan() && (!drawn || z >= -0.01), "depth {z}");
            }
        }
    }
    // All three behind the eye: nothing at all.
    for m in &mut methods {
        let behind =
            near_plane_scene::<N>(m, [[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [0.0, 1.0, 2.0]]);
        assert_eq!(behind.drawn(), 0, "{}", m.name);
    }
}

#[test]
fn e14_near_plane_clipping() {
    for_formats!(near_plane);
}

// 21. Debug versus release: no panic in debug (every test here runs in debug under
// `cargo test`), and release output bit-identical to debug: CI runs this test in both
// profiles against one checked-in frame hash. Bless with ZROW_BLESS=1.
#[test]
fn e21_debug_and_release_frames_hash_identically() {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for b in bytes {
            h = (h ^ *b as u64).wrapping_mul(0x100_0000_01b3);
        }
    };
    let mut rng = Rng(21);
    for _ in 0..20 {
        let polys: Vec<Vec<[f32; 3]>> = (0..12)
            .map(|_| {
                (0..3)
                    .map(|_| {
                        [
                            rng.f(-40.0, 100.0),
                            rng.f(-40.0, 100.0),
                            rng.f(-100.0, 100.0),
                        ]
                    })
                    .collect()
            })
            .collect();
        let p = Polys::new(polys);
        let cfg = Config::screen(64, 64);
        let q = p.render::<Q16_16>(&cfg).unwrap();
        let f = p.render::<f32>(&cfg).unwrap();
        for c in q.color.iter().chain(&f.color) {
            eat(&[c.r(), c.g(), c.b()]);
        }
        for z in &q.depth {
            eat(&z.to_bits().to_le_bytes());
        }
        for z in &f.depth {
            eat(&z.to_bits().to_le_bytes());
        }
    }
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden/e21_frames.hash");
    let got = format!("{h:016x}\n");
    if std::env::var_os("ZROW_BLESS").is_some() {
        std::fs::create_dir_all(std::path::Path::new(path).parent().unwrap()).unwrap();
        std::fs::write(path, &got).unwrap();
    }
    let want = std::fs::read_to_string(path).expect("bless with ZROW_BLESS=1");
    assert_eq!(
        got, want,
        "frames differ from the blessed ones (profile-dependent maths?)"
    );
}

// 23. Bad input: NaN/inf coordinates, indices out of range, faces with < 3 vertices, more
// polygons than the capacity → a typed error, never a panic, never a half-written frame.
fn bad_input<N: Scalar>() {
    let ok = Vec3::<N>::from_f32([1.0, 1.0, 1.0]).unwrap();
    let cfg = Config::screen(16, 16);
    let run = |verts: &[Vec3<N>], faces: &[Face]| {
        let scene = ScreenScene {
            mesh: Mesh::new(verts, faces),
        };
        let mut r = Box::new(Scanline::<N, 16, 12, 4, 2>::new());
        let mut cap = Capture::<N>::new(16, 16);
        let e = r.render(&scene, &cfg, &mut cap);
        (e, cap.rows_received)
    };
    let v = [
        ok,
        Vec3::from_f32([9.0, 1.0, 1.0]).unwrap(),
        Vec3::from_f32([1.0, 9.0, 1.0]).unwrap(),
    ];
    let tri = Face {
        indices: &[0, 1, 2],
        color: Rgb565::RED,
        alpha: 255,
    };

    let (e, rows) = run(
        &v,
        &[
            tri,
            Face {
                indices: &[0, 1, 7],
                color: Rgb565::RED,
                alpha: 255,
            },
        ],
    );
    assert_eq!(
        e,
        Err(RenderError::Scene(Error::IndexOutOfRange {
            face: 1,
            index: 7
        }))
    );
    assert_eq!(rows, 0);
    let (e, rows) = run(
        &v,
        &[Face {
            indices: &[0, 1],
            color: Rgb565::RED,
            alpha: 255,
        }],
    );
    assert_eq!(
        e,
        Err(RenderError::Scene(Error::TooFewVertices { face: 0 }))
    );
    assert_eq!(rows, 0);
    let (e, _) = run(
        &v,
        &[Face {
            indices: &[0; 12],
            color: Rgb565::RED,
            alpha: 255,
        }],
    );
    assert_eq!(
        e,
        Err(RenderError::Scene(Error::TooManyVertices { face: 0 }))
    );
    let (e, rows) = run(&v, &[tri; 5]);
    assert_eq!(
        e,
        Err(RenderError::Scene(Error::Capacity {
            table: Table::Polygons,
            needed: 5,
            capacity: 4
        }))
    );
    assert_eq!(rows, 0);
    let (e, rows) = run(&v, &[tri; 3]);
    assert_eq!(
        e,
        Err(RenderError::Scene(Error::Capacity {
            table: Table::ActivePolygons,
            needed: 3,
            capacity: 2
        }))
    );
    assert_eq!(rows, 0);
    // Exactly at capacity: fine.
    let (e, rows) = run(&v, &[tri; 2]);
    assert!(e.is_ok());
    assert_eq!(rows, 16);
    // A non-convex face.
    let w = [
        Vec3::from_f32([1.0, 1.0, 0.0]).unwrap(),
        Vec3::from_f32([8.0, 8.0, 0.0]).unwrap(),
        Vec3::from_f32([15.0, 1.0, 0.0]).unwrap(),
        Vec3::from_f32([8.0, 15.0, 0.0]).unwrap(),
        Vec3::from_f32([8.0, 4.0, 0.0]).unwrap(),
    ];
    let (e, rows) = run(
        &w,
        &[Face {
            indices: &[0, 3, 2, 1, 4],
            color: Rgb565::RED,
            alpha: 255,
        }],
    );
    assert_eq!(e, Err(RenderError::Scene(Error::NotConvex { face: 0 })));
    assert_eq!(rows, 0);
    // Bad configuration.
    let scene = ScreenScene {
        mesh: Mesh {
            vertices: zrow::Vectors::Format(&v),
            faces: zrow::Faces::List(&[tri]),
            normals: zrow::Vectors::Format(&[]),
            vertex_normals: zrow::Vectors::Format(&[]),
        },
    };
    let mut r = Box::new(Scanline::<N, 16, 12, 4, 2>::new());
    let mut cap = Capture::<N>::new(16, 16);
    assert_eq!(
        r.render(&scene, &Config::screen(17, 16), &mut cap),
        Err(RenderError::Scene(Error::Capacity {
            table: Table::RowWidth,
            needed: 17,
            capacity: 16
        }))
    );
    let mut c = Config::screen(16, 16);
    c.subpixel_bits = 9;
    assert_eq!(
        r.render(&scene, &c, &mut cap),
        Err(RenderError::Scene(Error::BadConfig))
    );
    assert_eq!(cap.rows_received, 0);
}

#[test]
fn e23_bad_input_is_a_typed_error_before_any_row() {
    for_formats!(bad_input);
    // Non-finite coordinates exist only in f32.
    let v = [
        Vec3::new(f32::NAN, 1.0, 1.0),
        Vec3::new(9.0, f32::INFINITY, 1.0),
        Vec3::new(1.0, 9.0, 1.0),
    ];
    let faces = [Face {
        indices: &[0u16, 1, 2],
        color: Rgb565::RED,
        alpha: 255,
    }];
    let scene = ScreenScene {
        mesh: Mesh::new(&v, &faces),
    };
    let mut r = Box::new(Scanline::<f32, 16, 12, 4, 2>::new());
    let mut cap = Capture::<f32>::new(16, 16);
    assert_eq!(
        r.render(&scene, &Config::screen(16, 16), &mut cap),
        Err(RenderError::Scene(Error::NonFinite { face: 0 }))
    );
    assert_eq!(cap.rows_received, 0);
}

// Depth ties (`docs/conventions.md`): the polygon that comes first in the scene wins, everywhere. Exact
// ties arise from the same polygon drawn twice (any vertex order), from constant-depth
// polygons, and — in Q16.16, whose planes are rounded once from exact integers at a common
// reference pixel — from any two polygons on the same plane.
fn first_wins<N: Scalar>(first: &[[f32; 3]], second: &[[f32; 3]]) {
    let cfg = Config::screen(32, 32);
    let p = Polys::new(vec![first.to_vec(), second.to_vec()]);
    for m in &mut every_method::<N>() {
        let cap = m.polys(&p, &cfg).unwrap();
        let alone = m.polys(&Polys::new(vec![first.to_vec()]), &cfg).unwrap();
        let mut n = 0;
        for k in 0..32 * 32 {
            if alone.color[k] != Rgb565::BLACK {
                n += 1;
                assert_eq!(
                    index_of(cap.color[k]),
                    Some(0),
                    "{} {}: the first polygon wins ties ({k})",
                    m.name,
                    N::NAME
                );
            }
        }
        assert!(n > 20);
    }
}

fn ties<N: Scalar>() {
    let a = vec![[2.0, 2.0, 5.0], [30.0, 4.0, 9.0], [6.0, 29.0, 1.0]];
    let mut b = a.clone();
    b.rotate_left(1);
    b.reverse();
    let quad = vec![
        [0.0, 0.0, 5.0],
        [32.0, 0.0, 5.0],
        [32.0, 32.0, 5.0],
        [0.0, 32.0, 5.0],
    ];
    let flat = vec![[-4.0, 3.0, 5.0], [40.0, 9.0, 5.0], [10.0, 40.0, 5.0]];
    first_wins::<N>(&a, &b);
    first_wins::<N>(&b, &a);
    first_wins::<N>(&quad, &flat);
    first_wins::<N>(&flat, &quad);
}

/// Different polygons on one tilted plane z = 0.5x + 0.25y + 3: exact ties in fixed point
/// (planes rounded once from exact integers at a common reference pixel). f32 planes are
/// referenced at each polygon's own first vertex, so they need not tie: not asserted there.
fn coplanar_ties<N: Scalar>() {
    if fixed_lsb::<N>().is_none() {
        return;
    }
    let z = |x: f32, y: f32| [x, y, 0.5 * x + 0.25 * y + 3.0];
    let t1 = [z(1.0, 1.0), z(31.0, 3.0), z(4.0, 30.0)];
    let t2 = [z(-5.0, 8.0), z(36.0, -2.0), z(20.0, 37.0), z(-3.0, 30.0)];
    let t2 = [t2[0], t2[1], t2[2]];
    first_wins::<N>(&t1, &t2);
    first_wins::<N>(&t2, &t1);
}

#[test]
fn depth_ties_go_to_the_first_polygon() {
    for_formats!(ties);
    for_formats!(coplanar_ties);
}
