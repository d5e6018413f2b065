//! `docs/extremes.md` items 12, 13 (clip space) and 15, on every method in every format
//! (the format list is [`for_formats!`]; see tests/extremes.rs for where the other items are).
//!
//! - 12: needles one sub-pixel wide spanning the whole guard band at all angles match the exact
//!   integer reference bit for bit (which is stricter than dEQP STRICT); needles reaching far
//!   beyond the guard band (clipped) draw only pixels within the clipping error of the needle
//!   (dEQP STRICT: a needle has no FULL pixel, and no NONE pixel may be drawn). Every frame
//!   goes through a [`Capture`], which asserts that rows arrive top to bottom, each once, and
//!   are as long as the screen (no out-of-bounds row); debug builds panic on any overflow.
//! - 13 (clip space): huge objects under a perspective camera — vertices at ±1e5 in view
//!   space, slivers out to ±41000, objects crossing the near and far planes — against an f64
//!   ray cast within a 3×3 neighbourhood. Q16.16 cannot hold 1e5: the conversion refuses it,
//!   and a transform that pushes a vertex there must be a typed error.
//! - 15: coverage has no 32/64-bit switch in the core (edge setup and exact sample tests are
//!   64-bit throughout, the per-row walk 32-bit for every size: raster.rs, polygons.rs), so
//!   triangles whose bounding boxes are 2^k pixels ± one sub-pixel, k = 0..12, must match the
//!   exact reference for every k. The one width switch the core has is `div_round` in
//!   number.rs (a 64-bit division when the numerator is below 2^62, else 128-bit), used by the
//!   fixed-point depth plane: planes whose numerators straddle ±2^62 must be rounded exactly.

mod common;
use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::raster::{RasterVertex, GUARD_BAND};
use zrow::{Affine, Camera, Config, Error, Face, Mesh, ModelScene, Object, RenderError, Scalar};
use zrow::{Light, Vec3, Q16_16, Q24_8};

/// Runs a generic item for every number format (adding a format is one line here).
macro_rules! for_formats {
    ($f:ident $(, $a:expr)*) => {{
        $f::<Q16_16>($($a),*);
        $f::<Q24_8>($($a),*);
        $f::<f32>($($a),*);
    }};
}

const S: f64 = 256.0; // sub-pixels per pixel (8 bits, the default)

/// A needle along `d` (sub-pixels) through the point `c` (sub-pixels), from `-t0·d` to `t1·d`:
/// the parallelogram one sub-pixel wide (offset `e` across it) and the triangle tapering to
/// a point, as f32 pixels (exact: multiples of 1/256 below 2^24/256).
fn needle(c: [i64; 2], d: [i64; 2], t0: i64, t1: i64) -> [Vec<[f32; 3]>; 2] {
    let e = if d[0].abs() >= d[1].abs() {
        [0, 1]
    } else {
        [1, 0]
    };
    let p = |t: i64, k: i64| {
        [
            ((c[0] + t * d[0] + k * e[0]) as f64 / S) as f32,
            ((c[1] + t * d[1] + k * e[1]) as f64 / S) as f32,
            1.0,
        ]
    };
    [
        vec![p(-t0, 0), p(t1, 0), p(t1, 1), p(-t0, 1)],
        vec![p(-t0, 0), p(t1, 0), p(-t0, 1)],
    ]
}

/// Largest `t ≥ 0` with `c + t·d` inside `[lo, hi]²` (sub-pixels).
fn reach(c: [i64; 2], d: [i64; 2], lo: i64, hi: i64) -> i64 {
    let mut t = i64::MAX;
    for a in 0..2 {
        if d[a] > 0 {
            t = t.min((hi - c[a]) / d[a]);
        } else if d[a] < 0 {
            t = t.min((c[a] - lo) / -d[a]);
        }
    }
    t
}

/// Directions: every primitive whole-pixel vector up to 7 px (its line meets a pixel centre
/// every step), and random sub-pixel ones, each both ways.
fn directions(rng: &mut Rng) -> Vec<[i64; 2]> {
    let gcd = |mut a: i64, mut b: i64| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a.abs()
    };
    let mut out = Vec::new();
    for p in -7i64..=7 {
        for q in -7i64..=7 {
            if gcd(p, q) == 1 {
                out.push([p * 256, q * 256]);
            }
        }
    }
    for _ in 0..60 {
        let a = rng.f(0.0, std::f32::consts::TAU) as f64;
        let r = rng.f(1.0, 2000.0) as f64;
        let d = [(r * a.cos()).round() as i64, (r * a.sin()).round() as i64];
        if d != [0, 0] {
            out.push(d);
        }
    }
    out
}

// 12. Needles spanning the guard band: exactly the integer reference, on every method.
fn needles_in_band<N: Scalar>() {
    let (w, h) = (32u16, 32u16);
    let cfg = Config::screen(w, h);
    let g = GUARD_BAND as i64 * 256;
    let (lo, hi) = (-g, (w as i64) * 256 + g); // the band is square here (w = h)
    let mut rng = Rng(12);
    let mut methods = all_methods::<N>();
    let mut drawn = 0;
    for (n, d) in directions(&mut rng).into_iter().enumerate() {
        // Through a pixel centre (so whole-pixel directions meet a centre every step).
        let c = [
            rng.below(w as u64) as i64 * 256 + 128,
            rng.below(h as u64) as i64 * 256 + 128,
        ];
        // Both ends on the guard band's edge (one sub-pixel inside, for the offset).
        let (t0, t1) = (
            reach(c, [-d[0], -d[1]], lo + 1, hi - 1),
            reach(c, d, lo + 1, hi - 1),
        );
        for poly in needle(c, d, t0, t1) {
            let p = Polys::new(vec![poly]);
            let refr = reference::<N>(&p, &cfg, 0.0);
            // Scan-line on every needle, the other methods in turn.
            let k = if n % 2 == 0 {
                0
            } else {
                1 + (n / 2) % (methods.len() - 1)
            };
            let m = &mut methods[k];
            let cap = m.polys(&p, &cfg).unwrap();
            drawn += cap.drawn();
            let bad = mismatches(&cap, &refr);
            assert!(
                bad.is_empty(),
                "{} {}: needle {:?}: {} pixels differ, first {:?}",
                m.name,
                N::NAME,
                p.polys[0],
                bad.len(),
                &bad[..bad.len().min(4)]
            );
        }
    }
    // Not vacuous: needles through pixel centres draw (the top-left rule decides them).
    assert!(drawn > 100, "{drawn}");
}

#[test]
fn e12_needles_across_the_guard_band_are_exact() {
    for_formats!(needles_in_band);
}

/// Squared distance from `p` to segment `a`–`b`.
fn dist2(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
    ex * ex + ey * ey
}

// 12 beyond the band: needles from the format's limit to its limit, clipped. dEQP STRICT:
// a drawn pixel's centre lies within the needle's width plus the clipping error of it.
fn needles_beyond_band<N: Scalar>() {
    let (w, h) = (32u16, 32u16);
    let cfg = Config::screen(w, h);
    let limit = (max_f32::<N>() as f64).min(1.0e6);
    let g = ((limit - 64.0) * S) as i64;
    // Clipping rounds the cut vertex in the format (f32: a few ulps of the far coordinate)
    // and snaps it: the needle moves by at most that on screen.
    let tol = 2.0 / S + 8.0 * lsb_at::<N>(limit);
    let mut rng = Rng(1212);
    let mut methods = all_methods::<N>();
    for (n, d) in directions(&mut rng).into_iter().enumerate() {
        let c = [
            rng.below(w as u64) as i64 * 256 + 128,
            rng.below(h as u64) as i64 * 256 + 128,
        ];
        let (t0, t1) = (reach(c, [-d[0], -d[1]], -g, g), reach(c, d, -g, g));
        let count = methods.len();
        let m = &mut methods[n % count];
        for poly in needle(c, d, t0, t1) {
            let cap = m.polys(&Polys::new(vec![poly.clone()]), &cfg).unwrap();
            let (a, b) = (
                [poly[0][0] as f64, poly[0][1] as f64],
                [poly[1][0] as f64, poly[1][1] as f64],
            );
            for y in 0..h as usize {
                for x in 0..w as usize {
                    if cap.at(x, y) != Rgb565::BLACK {
                        let d2 = dist2([x as f64 + 0.5, y as f64 + 0.5], a, b);
                        assert!(
                            d2.sqrt() <= tol,
                            "{} {}: ({x},{y}) drawn {} px from the needle {poly:?}",
                            m.name,
                            N::NAME,
                            d2.sqrt()
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn e12_needles_beyond_the_guard_band_are_strict() {
    for_formats!(needles_beyond_band);
}

// 15. Bounding boxes 2^k px ± 1 sub-pixel (k = 0..12): exactly the reference for every k.
fn power_of_two_boxes<N: Scalar>() {
    let cfg = Config::screen(32, 32);
    let mut rng = Rng(15);
    let mut methods = all_methods::<N>();
    let mut drawn = 0;
    for k in 0..=12 {
        for dl in [-1i64, 0, 1] {
            let l = (256i64 << k) + dl; // extent in sub-pixels
            for shape in 0..8 {
                // The box's corner: centred on the screen, or at a random pixel, so that its
                // edges cross the screen at every size.
                let o = if shape < 4 {
                    [16 * 256 - l / 2, 16 * 256 - l / 2]
                } else {
                    [
                        rng.below(32 * 256) as i64 - l + rng.below(l as u64 + 1) as i64,
                        rng.below(32 * 256) as i64 - l + rng.below(l as u64 + 1) as i64,
                    ]
                };
                let r = |rng: &mut Rng| rng.below(l as u64 + 1) as i64;
                // Three vertices spanning exactly l in x and in y, in one of 4 layouts.
                let v = match shape % 4 {
                    0 => [[0, 0], [l, r(&mut rng)], [r(&mut rng), l]],
                    1 => [[l, 0], [0, r(&mut rng)], [r(&mut rng), l]],
                    2 => [[0, r(&mut rng)], [l, 0], [r(&mut rng), l]],
                    _ => [[r(&mut rng), 0], [l, l], [0, r(&mut rng)]],
                };
                let tri: Vec<[f32; 3]> = v
                    .iter()
                    .map(|p| {
                        [
                            ((o[0] + p[0]) as f64 / S) as f32,
                            ((o[1] + p[1]) as f64 / S) as f32,
                            rng.f(0.0, 64.0),
                        ]
                    })
                    .collect();
                let p = Polys::new(vec![tri]);
                let refr = reference::<N>(&p, &cfg, 0.0);
                for m in &mut methods {
                    let cap = m.polys(&p, &cfg).unwrap();
                    drawn += cap.drawn();
                    let bad = mismatches(&cap, &refr);
                    assert!(
                        bad.is_empty(),
                        "{} {}: box 2^{k}{dl:+} sub-px {:?}: first {:?}",
                        m.name,
                        N::NAME,
                        p.polys[0],
                        &bad[..bad.len().min(4)]
                    );
                }
            }
        }
    }
    assert!(drawn > 10_000);
}

#[test]
fn e15_bounding_boxes_either_side_of_powers_of_two() {
    for_formats!(power_of_two_boxes);
}

/// `n / d` rounded to nearest, ties away from zero (`d > 0`), in exact integers.
fn round_div(n: i128, d: i128) -> i128 {
    let q = n.abs() / d;
    let r = n.abs() % d;
    let q = if 2 * r >= d { q + 1 } else { q };
    if n < 0 {
        -q
    } else {
        q
    }
}

/// Newell's normal of `v` in (sub-pixel, sub-pixel, raw depth) units.
fn newell(v: &[(i128, i128, i128)]) -> (i128, i128, i128) {
    let (mut a, mut b, mut c) = (0, 0, 0);
    for k in 0..v.len() {
        let ((x0, y0, z0), (x1, y1, z1)) = (v[k], v[(k + 1) % v.len()]);
        a += (y0 - y1) * (z0 + z1);
        b += (z0 - z1) * (x0 + x1);
        c += (x0 - x1) * (y0 + y1);
    }
    (a, b, c)
}

// 15, the switch: a fixed-point depth plane whose numerator at its reference pixel straddles
// ±2^62 (64-bit division below, 128-bit above) is rounded exactly either side.
fn plane_switch<N: Scalar>() {
    let Some(lsb) = fixed_lsb::<N>() else {
        return; // f32 planes have no integer path
    };
    let bits = |z: N| (z.to_f64() / lsb).round() as i128;
    let mut rng = Rng(0x62);
    let mut straddled = [0u32; 2];
    for _ in 0..400 {
        // A triangle far from the reference pixel (large x0, y0) with a steep plane.
        let sx = |r: &mut Rng| {
            let m = r.below(1000 * 256) as i128 + 1000 * 256;
            if r.below(2) == 0 {
                m
            } else {
                -m
            }
        };
        let (x0, y0) = (sx(&mut rng), sx(&mut rng));
        let v1 = (
            x0 + rng.below(30000) as i128 + 1,
            y0 + rng.below(3000) as i128,
        );
        let v2 = (
            x0 - rng.below(3000) as i128,
            y0 + rng.below(30000) as i128 + 1,
        );
        let zmax = (max_f32::<N>() as f64 * 0.9 / lsb) as i128;
        let z0 = rng.below(zmax as u64) as i128 - zmax / 2;
        let z2 = z0 + rng.below(1000) as i128 - 500;
        // The numerator −(a·(h − x0) + b·(h − y0)) is linear in z1: solve for ±2^62.
        let num = |z1: i128| {
            let (a, b, _) = newell(&[(x0, y0, z0), (v1.0, v1.1, z1), (v2.0, v2.1, z2)]);
            -(a * (128 - x0) + b * (128 - y0))
        };
        let (n0, n1) = (num(z0), num(z0 + 1) - num(z0));
        if n1 == 0 {
            continue;
        }
        for target in [1i128 << 62, -(1i128 << 62)] {
            let z1c = z0 + (target - n0) / n1;
            for z1 in z1c - 3..=z1c + 3 {
                if z1.abs() > zmax {
                    continue;
                }
                let vs = [(x0, y0, z0), (v1.0, v1.1, z1), (v2.0, v2.1, z2)];
                let raster: Vec<RasterVertex<N>> = vs
                    .iter()
                    .map(|&(x, y, z)| RasterVertex {
                        x: x as i32,
                        y: y as i32,
                        z: N::from_f32((z as f64 * lsb) as f32).unwrap(),
                    })
                    .collect();
                // The vertices as the format holds them (f32 carries 24 bits: re-read them).
                let held: Vec<(i128, i128, i128)> = raster
                    .iter()
                    .map(|v| (v.x as i128, v.y as i128, bits(v.z)))
                    .collect();
                let Some(plane) = N::depth_plane(&raster, 8) else {
                    continue;
                };
                let (a, b, c) = newell(&held);
                let (a, b, c) = if c < 0 { (-a, -b, -c) } else { (a, b, c) };
                let (xr, yr) = (
                    (plane.i_ref as i128) * 256 + 128,
                    (plane.j_ref as i128) * 256 + 128,
                );
                let n = -(a * (xr - held[0].0) + b * (yr - held[0].1));
                let want = held[0].2 + round_div(n, c);
                let got = bits(plane.z_ref);
                // The reference depth may wrap (exact modulo 2^32, see Scalar::step).
                assert_eq!(
                    want as i32,
                    got as i32,
                    "{}: z_ref, numerator {n} (2^62 = {})",
                    N::NAME,
                    1i128 << 62
                );
                let sat = |v: i128| v.clamp(i32::MIN as i128, i32::MAX as i128);
                assert_eq!(sat(round_div(-(a << 8), c)), bits(plane.dzdx), "dzdx");
                assert_eq!(sat(round_div(-(b << 8), c)), bits(plane.dzdy), "dzdy");
                if n.abs() < 1 << 62 {
                    straddled[0] += 1;
                } else {
                    straddled[1] += 1;
                }
            }
        }
    }
    // Both sides of the switch were exercised, many times.
    assert!(straddled.iter().all(|&k| k >= 50), "{straddled:?}");
}

#[test]
fn e15_depth_plane_either_side_of_the_64_128_bit_switch() {
    for_formats!(plane_switch);
}

/// Renders one model-mode mesh with `m` under a perspective camera at the origin looking down
/// −z (fov 1.5 rad, square `size` screen), culling off, full ambient light.
fn perspective<N: Scalar>(
    m: &mut Method<N>,
    verts: &[Vec3<N>],
    faces: &[Face],
    near: f32,
    far: f32,
    size: u16,
) -> Result<Capture<N>, RenderError<()>> {
    let camera = Camera::look_at(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0],
        Camera::<N>::perspective(1.5, near, far).unwrap(),
    )
    .unwrap();
    let mut cfg = Config::model(size, size);
    cfg.cull = zrow::Cull::None;
    with_model(verts, faces, camera, |s| m.scene(s, &cfg)).map(|r| r.0)
}

/// The focal length the camera above uses (micromath's tan, as `Camera::perspective`).
fn focal() -> f64 {
    (1.0 / micromath::F32Ext::tan(0.75f32)) as f64
}

// 13 (clip space): huge objects, 3×3 match to an f64 ray cast (a hit beyond the near plane
// and before the far plane).
fn huge_clip_space<N: Scalar>() {
    let big = 1.0e5f32;
    let (near, far) = (0.5f32, 2.0e5f32);
    let cases: Vec<[[f32; 3]; 3]> = vec![
        // Covers the whole view.
        [[-big, -big, -10.0], [big, -big, -10.0], [0.0, big, -10.0]],
        // Slivers from near the centre out to ±41000 (dEQP's long lines), at 4 angles.
        [
            [0.3, 0.2, -5.0],
            [41000.0, 4000.0, -5.0],
            [41000.0, 4010.0, -5.0],
        ],
        [
            [-0.2, 0.1, -5.0],
            [-41000.0, -41000.0, -5.0],
            [-40990.0, -41000.0, -5.0],
        ],
        [
            [0.1, -0.3, -5.0],
            [5.0, 41000.0, -5.0],
            [-5.0, 41000.0, -5.0],
        ],
        [
            [0.4, 0.4, -3.0],
            [-41000.0, 30000.0, -3.0],
            [-41000.0, 30020.0, -3.0],
        ],
        // Crossing the near plane and the far plane at once, and the eye's plane.
        [[-big, -1.0, big], [big, -1.0, -big], [0.0, 2.0, -big]],
        [[-3.0, -big, -1.0], [3.0, -big, -1.0], [0.0, big, -big]],
        // Reaching beyond the far plane from in front of the near plane.
        [[-1.0, -1.0, -0.1], [1.0, -1.0, -0.1], [0.0, 1.0, -4.0e5]],
    ];
    let size = 40u16;
    let mut methods = all_methods::<N>();
    let f = focal();
    for tri in &cases {
        let verts: Option<Vec<Vec3<N>>> = tri.iter().map(|v| Vec3::from_f32(*v)).collect();
        let Some(verts) = verts else {
            // The format cannot hold the coordinates: its conversion refuses them (Q16.16
            // holds ±32768, not 1e5 or 41000).
            assert!(tri.iter().flatten().any(|c| c.abs() > max_f32::<N>()));
            continue;
        };
        let faces = [Face::new(&[0, 1, 2], Rgb565::WHITE)];
        let t: [[f64; 3]; 3] = tri.map(|v| v.map(|c| c as f64));
        let hit = |x: f64, y: f64| {
            let d = ray_dir(x, y, size as f64, size as f64, f);
            ray_hits(&t, d).is_some_and(|t| t > near as f64 && t < far as f64)
        };
        for m in &mut methods {
            let cap = perspective(m, &verts, &faces, near, far, size).unwrap();
            let mut agree = 0;
            for y in 0..size as usize {
                for x in 0..size as usize {
                    let drawn = cap.at(x, y) != Rgb565::BLACK;
                    let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
                    agree += (hit(cx, cy) == drawn) as usize;
                    let ok = (-1i32..=1).any(|dy| {
                        (-1i32..=1).any(|dx| hit(cx + dx as f64, cy + dy as f64) == drawn)
                    });
                    assert!(
                        ok,
                        "{} {}: {tri:?} at ({x},{y}) drawn={drawn}",
                        m.name,
                        N::NAME
                    );
                    let z = cap.z(x, y).to_f64();
                    assert!(!drawn || (-0.01..=256.01).contains(&z), "depth {z}");
                }
            }
            // Sane coverage: all but the pixels along edges agree exactly.
            assert!(
                agree as f64 >= 0.9 * (size as f64).powi(2),
                "{} {agree}",
                m.name
            );
        }
    }
}

#[test]
fn e13_huge_objects_in_clip_space() {
    for_formats!(huge_clip_space);
}

/// A representable model pushed beyond the format by its object transform (×16: a vertex at
/// 3000 lands at 48000): the frame must be a typed error before any row, or right (3×3 match
/// to the f64 ray cast of the true triangle) — not a silently saturated, wrong picture.
fn transform_beyond_range<N: Scalar>() {
    let s = 16.0f32;
    let v = [
        [-1000.0, -25.0, -40.0],
        [3000.0, -25.0, -40.0],
        [-1000.0, 25.0, -40.0],
    ];
    let verts: Vec<Vec3<N>> = v.iter().map(|p| Vec3::from_f32(*p).unwrap()).collect();
    let faces = [Face::new(&[0, 1, 2], Rgb565::WHITE)];
    let mesh = Mesh::new(&verts, &faces);
    let objects = [Object {
        mesh: &mesh,
        transform: Affine::from_f32([[s, 0.0, 0.0, 0.0], [0.0, s, 0.0, 0.0], [0.0, 0.0, s, 0.0]])
            .unwrap(),
    }];
    let (near, far, size) = (1.0f32, 1000.0f32, 32u16);
    let camera = Camera::look_at(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0],
        Camera::<N>::perspective(1.5, near, far).unwrap(),
    )
    .unwrap();
    let scene = ModelScene {
        objects: &objects,
        camera,
        light: Light {
            direction: Vec3::from_f32([0.0, 1.0, 0.0]).unwrap(),
            ambient: N::ONE,
        },
    };
    let mut cfg = Config::model(size, size);
    cfg.cull = zrow::Cull::None;
    let t: [[f64; 3]; 3] = v.map(|p| p.map(|c| c as f64 * s as f64));
    let f = focal();
    let hit = |x: f64, y: f64| {
        let d = ray_dir(x, y, size as f64, size as f64, f);
        ray_hits(&t, d).is_some_and(|t| t > near as f64 && t < far as f64)
    };
    for m in &mut every_method::<N>() {
        match m.scene(&scene, &cfg) {
            Err(e) => assert_eq!(e, RenderError::Scene(Error::NonFinite { face: 0 })),
            Ok((cap, ..)) => {
                let mut wrong = 0;
                for y in 0..size as usize {
                    for x in 0..size as usize {
                        let drawn = cap.at(x, y) != Rgb565::BLACK;
                        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
                        wrong += !(-1i32..=1).any(|dy| {
                            (-1i32..=1).any(|dx| hit(cx + dx as f64, cy + dy as f64) == drawn)
                        }) as usize;
                    }
                }
                assert_eq!(
                    wrong,
                    0,
                    "{} {}: a transform beyond the format's range drew {wrong} wrong pixels \
                     and no error",
                    m.name,
                    N::NAME
                );
            }
        }
    }
}

#[test]
fn e13_transform_beyond_the_format_is_a_typed_error() {
    for_formats!(transform_beyond_range);
}
