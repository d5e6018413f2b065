//! `docs/extremes.md` items 16–20 (depth and transforms), on every method in every format
//! (the format list is [`for_formats!`]; see tests/extremes.rs for where the other items are).
//! `cargo test -p zrow --test extremes_depth -- --nocapture` prints the measured figures.
//!
//! - 16: the depth handed to a sink at pixel centres against the exact plane through the
//!   snapped vertices, in units of the format's last place (f32: ulps of the plane's largest
//!   depth on screen): the catalogue's ≤ 1, and the documented bound, 0.5 and a hair (each
//!   depth is the exact plane rounded once: `Scalar::exact_plane`).
//! - 17: two parallel planes Δ apart, the farther first in the scene (so a tie shows it), Δ
//!   swept geometrically around the theoretical resolution Δz: the nearer must win everywhere
//!   once Δ ≥ 2·Δz. Screen space: Δz is the format's last place at the planes' depths (exact
//!   methods), or the tiled 16-bit z-buffer's step over the frame's depth range. Perspective:
//!   Δz = lsb(d)·w²/(k·n) for depth d = k·(1 − n/w) (k = 256·f/(f − n)), i.e. z²/(2^16·n)
//!   for the tiled 16-bit z-buffer over the full range (the catalogue's formula).
//! - 18: model-mode geometry just in front of the near plane and just behind the far plane,
//!   and crossing them: clipped, depths in [0, 256], never wrapped; screen-space planes
//!   spanning the format's whole range: every method draws the reference's picture.
//! - 19: affine products near the format's limits (exact or saturated, never wrapped, error
//!   per output measured) and 10^4 accumulated rotations (`Affine::then_after`; the core has
//!   no re-orthonormalisation): drift against the exact f64 product of the same matrices, and
//!   loss of orthonormality, measured and bounded.
//! - 20: every method against the z-buffer on cyclic overlap (three mutually overlapping
//!   polygons, under random common depth tilts, which keep every visibility relation),
//!   interpenetrating pairs and coplanar pairs: the same visible polygon wherever the two
//!   candidates' depths differ by more than the resolution. tests/methods.rs holds the exact
//!   methods to the reference on random, dense and cyclic scenes, tests/tiled.rs the tiled
//!   method, tests/auto.rs cull-only and ordered where their preconditions hold.
#![allow(clippy::unnecessary_lazy_evaluations, clippy::needless_range_loop)]

mod common;
use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::geometry::DEPTH_RANGE;
use zrow::{Affine, Camera, Config, Face, MathLib, Scalar, Vec3, Q16_16, Q24_8};

/// Runs a generic item for every number format (adding a format is one line here).
macro_rules! for_formats {
    ($f:ident $(, $a:expr)*) => {{
        $f::<Q16_16>($($a),*);
        $f::<Q24_8>($($a),*);
        $f::<f32>($($a),*);
    }};
}

/// The exact plane z(x, y) through a triangle's vertices as the format holds them (f64).
fn plane_of<N: Scalar>(t: &[[f32; 3]]) -> Option<impl Fn(f64, f64) -> f64> {
    let v: Vec<[f64; 3]> = t
        .iter()
        .map(|p| {
            [
                p[0] as f64,
                p[1] as f64,
                N::from_f32(p[2]).unwrap().to_f64(),
            ]
        })
        .collect();
    let e1 = [v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]];
    let e2 = [v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]];
    let (a, b, c) = (
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    );
    (c.abs() > 1e-9)
        .then_some(move |x: f64, y: f64| v[0][2] - (a * (x - v[0][0]) + b * (y - v[0][1])) / c)
}

/// Worst depth error of `m` on random planes (triangles on the 1/256 grid over a 64×64
/// screen, depths ±500), in units of the last place.
fn depth_errors<N: Scalar>(m: &mut Method<N>) -> f64 {
    let cfg = Config::screen(64, 64);
    let mut rng = Rng(16);
    let mut worst = 0.0f64;
    for _ in 0..60 {
        let g = |v: f32| (v * 256.0).round() / 256.0;
        let t: Vec<[f32; 3]> = (0..3)
            .map(|_| {
                [
                    g(rng.f(-20.0, 84.0)),
                    g(rng.f(-20.0, 84.0)),
                    g(rng.f(-500.0, 500.0)),
                ]
            })
            .collect();
        let Some(z) = plane_of::<N>(&t) else {
            continue;
        };
        // The unit: the format's last place at the plane's largest depth on screen.
        let mut big = t.iter().map(|v| v[2].abs() as f64).fold(0.0, f64::max);
        for (x, y) in [(0.5, 0.5), (63.5, 0.5), (0.5, 63.5), (63.5, 63.5)] {
            big = big.max(z(x, y).abs());
        }
        let unit = lsb_at::<N>(big);
        let cap = m.polys(&Polys::new(vec![t.clone()]), &cfg).unwrap();
        for y in 0..64 {
            for x in 0..64 {
                if cap.at(x, y) != Rgb565::BLACK {
                    let e = (cap.z(x, y).to_f64() - z(x as f64 + 0.5, y as f64 + 0.5)).abs() / unit;
                    worst = worst.max(e);
                }
            }
        }
    }
    worst
}

// 16. Depth linearity within the documented bound, every method: each depth is the exact
// plane rounded once, so within half a unit of the last place and a hair (fixed point
// 2^-20 LSB from its 32 extra fractional bits; f32 the f64 plane's few 2^-50 of the terms).
fn linearity<N: Scalar>() {
    for m in &mut every_method::<N>() {
        let worst = depth_errors(m);
        eprintln!(
            "e16 {} {:10}: worst depth error {worst:.6} last places",
            N::NAME,
            m.name
        );
        assert!(worst <= 0.5 + 1e-5, "{} {}: {worst}", N::NAME, m.name);
    }
}

#[test]
fn e16_depth_linearity_within_the_documented_bound() {
    for_formats!(linearity);
}

fn linearity_one_lsb<N: Scalar>() {
    for m in &mut every_method::<N>() {
        let worst = depth_errors(m);
        assert!(worst <= 1.0, "{} {}: {worst} last places", N::NAME, m.name);
    }
}

#[test]
fn e16_depth_within_one_lsb() {
    for_formats!(linearity_one_lsb);
}

/// Two parallel planes `delta` apart over a 64×16 screen, the farther first in the scene:
/// z = 10 + 1.5x + 0.5y (+ delta for the first), both covering every pixel. Depths stay below
/// 128 and `delta` is rounded up to a multiple of 2^-17, so the f32 input carries it exactly
/// at every vertex (the planes are exactly parallel in f32 input).
fn parallel(delta: f64) -> Polys {
    let delta = (delta * 131072.0).ceil() / 131072.0;
    let z = |x: f32, y: f32| 10.0 + 1.5 * x + 0.5 * y;
    let quad = |d: f64| {
        [(0.0, 0.0), (64.0, 0.0), (64.0, 16.0), (0.0, 16.0)]
            .iter()
            .map(|&(x, y)| [x, y, (z(x, y) as f64 + d) as f32])
            .collect()
    };
    Polys::new(vec![quad(delta), quad(0.0)])
}

/// Pixels where the farther polygon (index 0) shows.
fn far_shows<N: Scalar>(cap: &Capture<N>) -> usize {
    cap.color
        .iter()
        .filter(|&&c| index_of(c) == Some(0))
        .count()
}

/// Sweeps Δ = Δz·2^(k/4), k = 12 down to −8; `far_at(Δ)` renders and returns the pixels where
/// the farther plane shows and the Δ the format really holds. Asserts the nearer plane wins
/// everywhere whenever the held Δ ≥ 2·Δz; returns the least held Δ (in units of Δz) from
/// which it wins at every larger sweep point.
fn sweep(what: &str, dz: f64, mut far_at: impl FnMut(f64) -> (usize, f64)) -> f64 {
    let mut threshold = f64::INFINITY;
    for k in (-8..=12).rev() {
        let (far, held) = far_at(dz * 2f64.powf(k as f64 / 4.0));
        let f = held / dz;
        if f >= 2.0 {
            assert_eq!(far, 0, "{what}: far plane shows at Δ = {f:.3}·Δz ({held})");
        }
        if far > 0 {
            break;
        }
        threshold = f;
    }
    eprintln!("e17 {what}: Δz {dz:.3e}, nearer wins everywhere from Δ = {threshold:.3}·Δz");
    threshold
}

/// The format's value of `x`, in f64.
fn held<N: Scalar>(x: f64) -> f64 {
    N::from_f32(x as f32).unwrap().to_f64()
}

// 17. Depth resolution in screen space, every method.
fn resolution_screen<N: Scalar>() {
    let cfg = Config::screen(64, 16);
    let (zmin, zmax) = (10.0, 10.0 + 1.5 * 64.0 + 0.5 * 16.0);
    for m in &mut every_method::<N>() {
        let dz = if m.name == "tiled" {
            // The step over the frame's depth range (its own report, checked against it).
            let (_, _, res) = m.polys_full(&parallel(0.0), &cfg).unwrap();
            // Covered samples span [zmin + 0.5·(1.5 + 0.5), zmax − 0.5·(1.5 + 0.5)].
            let step = (zmax - zmin - 2.0) / 65534.0;
            assert!((res / step - 1.0).abs() < 0.02, "{res} vs {step}");
            res
        } else {
            lsb_at::<N>(zmax)
        };
        let what = format!("screen {} {}", N::NAME, m.name);
        let t = sweep(&what, dz, |d| {
            let p = parallel(d);
            // The Δ the format holds: the least over the four vertices.
            let real = (0..4)
                .map(|k| held::<N>(p.polys[0][k][2] as f64) - held::<N>(p.polys[1][k][2] as f64))
                .fold(f64::INFINITY, f64::min);
            (far_shows(&m.polys(&p, &cfg).unwrap()), real)
        });
        // The resolution is real: a quarter of Δz is not resolved everywhere.
        assert!(t > 0.25, "{what}: {t}");
    }
}

#[test]
fn e17_depth_resolution_screen_space() {
    for_formats!(resolution_screen);
}

/// A perspective scene (camera at the origin looking down −z, fov 1.5, square 32-pixel
/// screen): two quads facing the camera at distances `w + delta` (first) and `w`, over the
/// centre of the screen, and two small markers at 1.02·near (top-left corner) and 0.98·far
/// (bottom-right), so the frame's depth range is nearly the whole of [0, 256].
fn perspective_pair<N: Scalar>(
    m: &mut Method<N>,
    near: f32,
    far: f32,
    w: f32,
    delta: f32,
) -> Option<Rendered<N>> {
    let s = 0.3f32; // quads reach ±0.3·w: well inside the view
    let quad = |d: f32| [[-s, -s], [s, -s], [s, s], [-s, s]].map(|[x, y]| [x * d, y * d, -d]);
    // Markers: tiny triangles in the corners (x, y chosen in view units at their distance).
    let marker = |d: f32, sx: f32, sy: f32| {
        [[0.6, 0.6], [0.9, 0.6], [0.6, 0.9]].map(|[x, y]| [sx * x * d, sy * y * d, -d])
    };
    let mut pts = Vec::new();
    pts.extend(quad(w + delta));
    pts.extend(quad(w));
    pts.extend(marker(near * 1.02, -1.0, 1.0));
    pts.extend(marker(far * 0.98, 1.0, -1.0));
    let verts: Vec<Vec3<N>> = pts
        .iter()
        .map(|p| Vec3::from_f32(*p))
        .collect::<Option<_>>()?;
    let faces = [
        Face::new(&[0, 1, 2, 3], color_of(0)),
        Face::new(&[4, 5, 6, 7], color_of(1)),
        Face::new(&[8, 9, 10], color_of(2)),
        Face::new(&[11, 12, 13], color_of(3)),
    ];
    let camera = Camera::look_at(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0],
        Camera::<N>::perspective(1.5, near, far)?,
    )?;
    let mut cfg = Config::model(32, 32);
    cfg.cull = zrow::Cull::None;
    Some(with_model(&verts, &faces, camera, |sc| m.scene(sc, &cfg)).unwrap())
}

// 17. Depth resolution under perspective: near/far presets, distances, every method.
fn resolution_perspective<N: Scalar>() {
    for m in &mut every_method::<N>() {
        for (near, far, w) in [
            (0.1f32, 100.0f32, 10.0f32),
            (0.1, 100.0, 50.0),
            (1.0, 100.0, 50.0),
        ] {
            let k = DEPTH_RANGE as f64 * far as f64 / (far as f64 - near as f64);
            let (n, wf) = (near as f64, w as f64);
            let d = k * (1.0 - n / wf);
            // d'(w) = k·n/w²: one unit of depth resolution is Δz of distance.
            let per = wf * wf / (k * n);
            let dz = if m.name == "tiled" {
                let (cap, _, res) = perspective_pair(m, near, far, w, 0.0).unwrap();
                // The markers are drawn, so the frame spans [d(1.02·n), d(0.98·f)]: 65534
                // levels over nearly the whole range.
                assert!(cap.at(3, 3) != Rgb565::BLACK && cap.at(28, 28) != Rgb565::BLACK);
                let lo = k * (1.0 - 1.0 / 1.02);
                let hi = k * (1.0 - n / (0.98 * far as f64));
                let step = (hi - lo) / 65534.0;
                assert!((res / step - 1.0).abs() < 0.02, "{res} vs {step}");
                res * per
            } else {
                lsb_at::<N>(d) * per
            };
            let what = format!(
                "perspective n={near} f={far} w={w} {} {} (z²/(2^16·n) = {:.3e})",
                N::NAME,
                m.name,
                wf * wf / (65536.0 * n)
            );
            sweep(&what, dz, |delta| {
                let dl = delta as f32;
                // The distances the format holds: Δ between the converted depths.
                let real = held::<N>(-(w as f64)) - held::<N>(-(w + dl) as f64);
                let (cap, ..) = perspective_pair(m, near, far, w, dl).unwrap();
                // Both quads cover the centre: not vacuous.
                assert!(cap.at(16, 16) != Rgb565::BLACK);
                (far_shows(&cap), real)
            });
        }
    }
}

#[test]
fn e17_depth_resolution_perspective() {
    for_formats!(resolution_perspective);
}

/// Renders a model-mode scene of quads (each given by its 4 view-space corners, camera at the
/// origin looking down −z, fov 1.5, 32×32, culling off); quad `i` in [`color_of`]`(i)`.
fn model_quads<N: Scalar>(
    m: &mut Method<N>,
    quads: &[[[f32; 3]; 4]],
    near: f32,
    far: f32,
) -> Capture<N> {
    let verts: Vec<Vec3<N>> = quads
        .iter()
        .flatten()
        .map(|p| Vec3::from_f32(*p).unwrap())
        .collect();
    let idx: Vec<[u16; 4]> = (0..quads.len() as u16)
        .map(|k| [4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3])
        .collect();
    let faces: Vec<Face> = idx
        .iter()
        .enumerate()
        .map(|(k, i)| Face::new(i, color_of(k)))
        .collect();
    let camera = Camera::look_at(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.0, 1.0, 0.0],
        Camera::<N>::perspective(1.5, near, far).unwrap(),
    )
    .unwrap();
    let mut cfg = Config::model(32, 32);
    cfg.cull = zrow::Cull::None;
    with_model(&verts, &faces, camera, |s| m.scene(s, &cfg))
        .unwrap()
        .0
}

/// A quad facing the camera at distance `d`, covering ±`s`·d (so the same part of the view).
fn facing(d: f32, s: f32) -> [[f32; 3]; 4] {
    [[-s, -s], [s, -s], [s, s], [-s, s]].map(|[x, y]| [x * d, y * d, -d])
}

// 18. Depth at the ends of the range (model mode): geometry just in front of the near plane
// and just behind the far plane is clipped away; at them, depth is 0 and 256; crossing them,
// it is clipped, never wrapped (a wrapped depth would lose to, or beat, the wrong surface).
fn range_ends<N: Scalar>() {
    let (near, far) = (0.25f32, 64.0f32);
    // Steps that move a vertex by a few units of the format's last place.
    let e_near = 4.0 * lsb_at::<N>(near as f64) as f32;
    let e_far = 4.0 * lsb_at::<N>(far as f64) as f32;
    for m in &mut every_method::<N>() {
        let what = format!("{} {}", N::NAME, m.name);
        // In front of the near plane, behind the far plane: nothing.
        for d in [near - e_near, far + e_far] {
            let cap = model_quads(m, &[facing(d, 0.3)], near, far);
            assert_eq!(cap.drawn(), 0, "{what}: a quad at {d} is drawn");
        }
        // On the planes: drawn, at depth 0 and DEPTH_RANGE (within the format's rounding).
        for (d, want) in [(near, 0.0), (far, DEPTH_RANGE as f64)] {
            let cap = model_quads(m, &[facing(d, 0.3)], near, far);
            assert!(
                cap.drawn() > 50,
                "{what}: a quad on the plane at {d} is not drawn"
            );
            for (c, z) in cap.color.iter().zip(&cap.depth) {
                if *c != Rgb565::BLACK {
                    let tol = 4.0 * lsb_at::<N>(want);
                    assert!(
                        (z.to_f64() - want).abs() <= tol,
                        "{what}: depth {z:?} at {d}"
                    );
                }
            }
        }
        // Crossing both planes: a floor from 0.5·near to 2·far, under a wall at mid distance
        // that covers part of it; and a quad just behind the near plane over everything.
        let floor = [
            [-1.0, -0.5, -0.5 * near],
            [1.0, -0.5, -0.5 * near],
            [40.0, -20.0, -2.0 * far],
            [-40.0, -20.0, -2.0 * far],
        ];
        let wall = facing(8.0, 0.6);
        let front = [
            [-0.05, -0.4, -(near + e_near)],
            [0.05, -0.4, -(near + e_near)],
            [0.05, 0.1, -(near + e_near)],
            [-0.05, 0.1, -(near + e_near)],
        ];
        let cap = model_quads(m, &[floor, wall, front], near, far);
        let mut seen = [0usize; 3];
        for (c, z) in cap.color.iter().zip(&cap.depth) {
            if let Some(k) = index_of(*c) {
                seen[k] += 1;
                let z = z.to_f64();
                let tol = 4.0 * lsb_at::<N>(DEPTH_RANGE as f64);
                assert!(
                    (-tol..=DEPTH_RANGE as f64 + tol).contains(&z),
                    "{what}: depth {z} outside [0, 256] on polygon {k}"
                );
                if k == 2 {
                    // Its depth: k·(1 − n/w) at w = near + e_near, k = 256·f/(f − n).
                    let (n, w) = (near as f64, (near + e_near) as f64);
                    let want = DEPTH_RANGE as f64 * far as f64 / (far as f64 - n) * (1.0 - n / w);
                    assert!(
                        (z - want).abs() <= tol,
                        "{what}: the quad by the near plane has depth {z}, not {want}"
                    );
                }
            }
        }
        assert!(seen.iter().all(|&n| n > 10), "{what}: {seen:?}");
        // Where the wall is in front of the floor, the wall shows (no wrapped floor depth).
        let alone = model_quads(m, &[wall], near, far);
        for (k, (c, a)) in cap.color.iter().zip(&alone.color).enumerate() {
            if *a != Rgb565::BLACK && index_of(*c) == Some(0) {
                // The floor shows over the wall only where it is nearer.
                assert!(cap.depth[k] <= alone.depth[k], "{what}: pixel {k}");
            }
        }
    }
}

#[test]
fn e18_depth_at_the_ends_of_the_range_model() {
    for_formats!(range_ends);
}

// 18 (screen space): planes spanning the format's whole range — a plane from −limit to
// +limit across the screen through a flat plane at 0, and flat planes just inside ±limit —
// drawn as the reference draws them by every method, depths never wrapped.
fn range_ends_screen<N: Scalar>() {
    let limit = (0.999 * max_f32::<N>()).min(1.0e6);
    let cfg = Config::screen(48, 40);
    let (w, h) = (48.0f32, 40.0f32);
    let p = Polys::new(vec![
        vec![
            [0.0, 0.0, -limit],
            [w, 0.0, limit],
            [w, h, limit],
            [0.0, h, -limit],
        ],
        vec![[0.0, 0.0, 0.0], [w, 0.0, 0.0], [w, h, 0.0]],
        vec![[0.0, 20.0, limit], [w, 20.0, limit], [w, h, limit]],
        vec![[0.0, 30.0, -limit], [w, 30.0, -limit], [0.0, h, -limit]],
        // Steep and small: its plane leaves the range a few pixels away.
        vec![[20.0, 5.0, limit], [23.0, 5.0, -limit], [21.0, 8.0, 0.0]],
    ]);
    // The format's depth error here: fixed point, the tie tolerance (0.5 LSB a pixel);
    // f32, a few ulps of the largest depth (1e6: ulp 0.0625) per pixel stepped.
    let tol = match fixed_lsb::<N>() {
        Some(_) => 2.0 * tie_tolerance::<N>(4 * (w + h) as usize),
        None => 2.0 * (w + h) as f64 * lsb_at::<N>(limit as f64),
    };
    let refr = reference::<N>(&p, &cfg, tol);
    for m in &mut every_method::<N>() {
        let (cap, _, res) = m.polys_full(&p, &cfg).unwrap();
        let refr = if res > 0.0 {
            reference::<N>(&p, &cfg, tol + res)
        } else {
            refr.clone()
        };
        let bad = mismatches(&cap, &refr);
        assert!(
            bad.is_empty(),
            "{} {}: {:?}",
            N::NAME,
            m.name,
            &bad[..bad.len().min(4)]
        );
        for (y, row) in cap.depth.chunks(48).enumerate() {
            for (x, z) in row.iter().enumerate() {
                if let Verdict::Visible(_, want) = refr[y * 48 + x] {
                    let z = z.to_f64();
                    assert!(
                        (z - want).abs() <= tol,
                        "{} {}: depth {z}, exact {want} at ({x},{y})",
                        N::NAME,
                        m.name
                    );
                }
            }
        }
    }
}

#[test]
fn e18_depth_at_the_ends_of_the_range_screen() {
    for_formats!(range_ends_screen);
}

/// The exact (f64) value of row `r` of `a` applied to `p`, and the largest partial sum's
/// magnitude on the way (in the order `Affine::apply` adds: x, y, z terms, translation).
fn exact_row<N: Scalar>(a: &Affine<N>, r: usize, p: &Vec3<N>) -> (f64, f64) {
    let m = |c: usize| a.m[r][c].to_f64();
    let terms = [
        m(0) * p.x.to_f64(),
        m(1) * p.y.to_f64(),
        m(2) * p.z.to_f64(),
        m(3),
    ];
    let (mut acc, mut peak) = (0.0f64, 0.0f64);
    for t in terms {
        peak = peak.max(t.abs());
        acc += t;
        peak = peak.max(acc.abs());
    }
    (acc, peak)
}

/// A value of the format near `scale` in magnitude (random sign and mantissa).
fn near<N: Scalar>(rng: &mut Rng, scale: f32) -> N {
    let v = rng.f(-1.0, 1.0) * scale;
    N::from_f32(v.clamp(-max_f32::<N>(), max_f32::<N>())).unwrap()
}

/// Worst error of `Affine::apply` on products near the format's limits, in units of the last
/// place of the result: (cases whose partial sums all fit the format, all cases whose exact
/// result fits). Products are drawn so every product fits, half of them near the limit.
fn apply_errors<N: Scalar>() -> (f64, f64) {
    let limit = max_f32::<N>().min(1.0e18);
    let root = limit.sqrt();
    let mut rng = Rng(19);
    let (mut fits, mut all) = (0.0f64, 0.0f64);
    for _ in 0..20_000 {
        // Entries and coordinates near √limit (products near the limit) or mixed scales.
        let big = rng.below(2) == 0;
        let (sa, sp) = if big {
            (root * 0.57, root * 0.57)
        } else {
            (rng.f(0.0, 4.0), limit / 8.0)
        };
        let mut a = Affine::<N>::identity();
        for row in a.m.iter_mut() {
            for (c, e) in row.iter_mut().enumerate() {
                *e = near(&mut rng, if c == 3 { limit * 0.3 } else { sa });
            }
        }
        let p = Vec3::new(near(&mut rng, sp), near(&mut rng, sp), near(&mut rng, sp));
        let got = a.apply(p);
        same_when_prepared(&a, p);
        for (r, g) in [got.x, got.y, got.z].iter().enumerate() {
            let (want, peak) = exact_row(&a, r, &p);
            if want.abs() >= limit as f64 {
                // Beyond the format: saturated with the right sign, never wrapped.
                assert!(
                    g.to_f64() * want > 0.0,
                    "{} wrapped: {want} -> {g:?}",
                    N::NAME
                );
                continue;
            }
            let err = (g.to_f64() - want).abs() / lsb_at::<N>(want.abs().max(peak));
            all = all.max(err);
            if peak < limit as f64 {
                fits = fits.max(err);
            }
        }
    }
    (fits, all)
}

/// `Affine::prepare` (f32's entries split once per transform) gives the bits of each row summed
/// from the entries themselves (`Scalar::affine_row_as`), with either maths library.
fn same_when_prepared<N: Scalar>(a: &Affine<N>, p: Vec3<N>) {
    let bits = |v: Option<Vec3<N>>| v.map(|v| [v.x, v.y, v.z].map(|c| c.to_f64().to_bits()));
    for math in [MathLib::Libm, MathLib::Micromath] {
        // The unprepared reference: each row summed by `Scalar::affine_row_as` from the
        // entries themselves.
        let row = |r: &[N; 4]| N::affine_row_as(r, [p.x, p.y, p.z], math == MathLib::Micromath);
        let unprepared = (|| Some(Vec3::new(row(&a.m[0])?, row(&a.m[1])?, row(&a.m[2])?)))();
        assert_eq!(
            bits(a.prepare().apply_checked_with(math, p)),
            bits(unprepared),
            "{} {math:?} {a:?} {p:?}",
            N::NAME
        );
    }
}

/// Beyond f32's splitting range (entries above 2^115 overflow the split: the plain sum) and
/// at its edge, prepared and unprepared transforms agree too.
#[test]
fn prepared_transforms_beyond_the_splitting_range() {
    for big in [1.0e34f32, 4.0e34, 1.0e38, -3.0e38] {
        let mut a = Affine::<f32>::identity();
        a.m[0] = [big, 2.0, -big, 1.0];
        a.m[1] = [0.5, big, 3.0, big];
        for p in [[1.0, 1.0, 1.0], [1.0e-3, -2.0, 7.0], [0.0, 0.0, 0.0]] {
            same_when_prepared(&a, Vec3::new(p[0], p[1], p[2]));
        }
    }
}

/// Fixed point decides once per transform whether a row's linear entries are small enough
/// (below 2^30 in raw bits) to sum without an overflow check: rows on either side of that
/// line, and a row mixing both, give the bits of the unprepared sum, in range and beyond.
fn prepared_rows_either_side_of_the_fast_sum<N: Scalar>() {
    // 2^30 raw bits in the format's units (2^14 in Q16.16, 2^22 in Q24.8; f32 has no such
    // line, and takes the same entries).
    let line = (1u64 << 30) as f32 * fixed_lsb::<N>().unwrap_or(1.0 / 65536.0) as f32;
    let max = max_f32::<N>();
    let entries = [
        0.5,
        -3.25,
        line * 0.999,
        -line * 0.999,
        line,
        max * 0.95,
        -max * 0.95,
    ];
    let coords = [1.0, -100.0, line * 0.999, max * 0.95, -max * 0.95];
    let n = |v: f32| N::from_f32(v).unwrap();
    // Every row of these entries against every point of these coordinates (the first row
    // varied, the other two kept: one sum per call is what the rule decides).
    for &e0 in &entries {
        for &e1 in &entries {
            for &e2 in &entries {
                let mut a = Affine::<N>::identity();
                a.m[0] = [n(e0), n(e1), n(e2), n(-7.5)];
                for &x in &coords {
                    for &y in &coords {
                        for &z in &coords {
                            same_when_prepared(&a, Vec3::new(n(x), n(y), n(z)));
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn prepared_rows_on_both_sides_of_the_fast_sum() {
    for_formats!(prepared_rows_either_side_of_the_fast_sum);
}

// 19. Transforms near the format's limits: within 3 units of the last place per output
// wherever the partial sums fit (what three products and three sums each rounded once could
// lose), saturated with the right sign, never wrapped, beyond. The catalogue's rule, half a
// unit with wide accumulation, is the next two tests (every format measures 0.500: fixed point
// sums exactly, f32 is compensated).
fn transforms_at_limits<N: Scalar>() {
    let (fits, all) = apply_errors::<N>();
    eprintln!(
        "e19 {}: Affine::apply error {fits:.3} last places where partial sums fit, \
         {all:.3e} where only the result fits",
        N::NAME
    );
    assert!(fits <= 3.0, "{}: {fits}", N::NAME);
}

/// The catalogue's half a unit of the last place (plus, in f32, the compensated sum's
/// second-order term, about 2^-44 of the largest term: far below 0.001 of a unit).
const HALF_UNIT: f64 = 0.5 + 1e-3;

fn products_round_to_nearest<N: Scalar>() {
    let (fits, _) = apply_errors::<N>();
    assert!(fits <= HALF_UNIT, "{}: {fits} last places", N::NAME);
}

#[test]
fn e19_products_round_to_nearest() {
    for_formats!(products_round_to_nearest);
}

#[test]
fn e19_transforms_near_the_format_limits() {
    for_formats!(transforms_at_limits);
}

fn accumulation_exact_when_result_fits<N: Scalar>() {
    let (_, all) = apply_errors::<N>();
    assert!(all <= HALF_UNIT, "{}: {all} last places", N::NAME);
}

#[test]
fn e19_apply_accumulates_wide() {
    for_formats!(accumulation_exact_when_result_fits);
}

/// 10^4 accumulated rotations `M ← R ∘ M` (about y by 0.0123 rad then x by 0.0071 rad, R as
/// the format holds it): (largest entry error against E, the exact f64 product of the same R;
/// largest entry of MᵀM − EᵀE, the loss of orthonormality accumulation added; largest entry
/// of EᵀE − I, R's own, from its rounded sines and cosines).
fn rotation_drift<N: Scalar>(steps: usize) -> (f64, f64, f64) {
    let r = Affine::<N>::rotate_yx_translate(0.0123, 0.0071, [0.0; 3]).unwrap();
    let rf: Vec<Vec<f64>> =
        r.m.iter()
            .map(|row| row.iter().map(|v| v.to_f64()).collect())
            .collect();
    let mut m = Affine::<N>::identity();
    let mut e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0f64]];
    for _ in 0..steps {
        m = r.then_after(&m);
        let mut n = [[0.0f64; 3]; 3];
        for (i, row) in n.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (0..3).map(|k| rf[i][k] * e[k][j]).sum();
            }
        }
        e = n;
    }
    let (mut drift, mut ortho, mut own) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..3 {
        for j in 0..3 {
            drift = drift.max((m.m[i][j].to_f64() - e[i][j]).abs());
            let dot: f64 = (0..3)
                .map(|k| m.m[k][i].to_f64() * m.m[k][j].to_f64())
                .sum();
            let exact: f64 = (0..3).map(|k| e[k][i] * e[k][j]).sum();
            ortho = ortho.max((dot - exact).abs());
            own = own.max((exact - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    // Relative to E's own size (a format too coarse to hold R as a rotation makes E grow).
    let size = (1.0 + own).max(1.0);
    (drift, ortho / size, own)
}

// 19. 10^4 accumulated rotations: the drift the core leaves (it has no re-orthonormalisation),
// measured and bounded: at most 10^4 · 3 last places of 1 (three products per entry per step,
// each up to one unit low in Q16.16: steady one-way rounding, the worst case), and MᵀM
// within twice that of I.
fn accumulated_rotations<N: Scalar>() {
    let steps = 10_000;
    let (drift, ortho, own) = rotation_drift::<N>(steps);
    let unit = lsb_at::<N>(1.0);
    eprintln!(
        "e19 {}: after {steps} rotations: drift {drift:.3e} ({:.1} last places of 1), \
         |MᵀM − EᵀE|/(1 + |EᵀE − I|) {ortho:.3e} (R's own rounding alone: |EᵀE − I| {own:.3e})",
        N::NAME,
        drift / unit
    );
    let bound = steps as f64 * 3.0 * unit;
    assert!(drift <= bound, "{}: drift {drift} > {bound}", N::NAME);
    assert!(ortho <= 2.0 * bound, "{}: {ortho}", N::NAME);
}

#[test]
fn e19_accumulated_rotations_drift_is_bounded() {
    for_formats!(accumulated_rotations);
}

fn rotations_stay_rotations<N: Scalar>() {
    let (_, ortho, _) = rotation_drift::<N>(10_000);
    assert!(
        ortho <= 0.01,
        "{}: |MᵀM − EᵀE|/(1 + |EᵀE − I|) = {ortho}",
        N::NAME
    );
}

// 19. Accumulated rotations stay rotations: composed as they are in the formats that hold a
// small rotation (Q16.16, f32), and in every format when the accumulated transform is
// re-orthonormalised each step as `Affine::orthonormalized` documents. Q24.8 cannot hold the
// step R as a rotation (its entries are multiples of 1/256: |EᵀE − I| reaches 6.3 over 10^4
// products), so composing raw in Q24.8 is documented as unsupported, not tested.
#[test]
fn e19_accumulated_rotations_stay_rotations() {
    rotations_stay_rotations::<Q16_16>();
    rotations_stay_rotations::<f32>();
    for_formats!(orthonormalized_rotations_stay_rotations);
}

fn orthonormalized_rotations_stay_rotations<N: Scalar>() {
    let r = Affine::<N>::rotate_yx_translate(0.0123, 0.0071, [0.0; 3]).unwrap();
    let mut m = Affine::<N>::identity();
    for _ in 0..10_000 {
        m = r.then_after(&m).orthonormalized().unwrap();
    }
    // MᵀM against I: a rotation's columns are orthonormal.
    let mut worst = 0.0f64;
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3)
                .map(|k| m.m[k][i].to_f64() * m.m[k][j].to_f64())
                .sum();
            worst = worst.max((dot - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    eprintln!(
        "e19 {}: orthonormalised each step, |MᵀM − I| {worst:.3e}",
        N::NAME
    );
    // Within a few roundings of a unit entry in the format, far from the shrinking seen
    // before products were rounded to nearest (0.34).
    let bound = 4.0 * lsb_at::<N>(1.0).max(f32::EPSILON as f64);
    assert!(worst <= bound, "{}: |MᵀM − I| = {worst} > {bound}", N::NAME);
}

/// Each polygon's own depth at every pixel it covers (drawn alone by the z-buffer), in f64.
fn depths_alone<N: Scalar>(zb: &mut Method<N>, p: &Polys, cfg: &Config) -> Vec<Vec<Option<f64>>> {
    p.polys
        .iter()
        .map(|poly| {
            let cap = zb.polys(&Polys::new(vec![poly.clone()]), cfg).unwrap();
            cap.color
                .iter()
                .zip(&cap.depth)
                .map(|(c, z)| (*c != Rgb565::BLACK).then(|| z.to_f64()))
                .collect()
        })
        .collect()
}

/// Every method against the z-buffer: where they show different polygons, both must cover
/// the pixel and their depths there differ by at most `tol` plus the method's resolution;
/// where the z-buffer shows nothing, so does the method. Returns the pixels that differ.
fn against_zbuffer<N: Scalar>(p: &Polys, cfg: &Config, what: &str) -> usize {
    let mut methods = every_method::<N>();
    let zb = methods.iter().position(|m| m.name == "zbuffer").unwrap();
    let alone = depths_alone(&mut methods[zb], p, cfg);
    let want = methods[zb].polys(p, cfg).unwrap();
    let tol = 2.0 * tie_tolerance::<N>(4 * (cfg.width + cfg.height) as usize);
    let mut differ = 0;
    for m in &mut methods {
        let (cap, _, res) = m.polys_full(p, cfg).unwrap();
        for (k, (w, c)) in want.color.iter().zip(&cap.color).enumerate() {
            let (a, b) = (index_of(*w), index_of(*c));
            if a == b {
                continue;
            }
            differ += 1;
            let (Some(a), Some(b)) = (a, b) else {
                panic!(
                    "{what} {} {}: pixel {k}: z-buffer {a:?}, method {b:?}",
                    N::NAME,
                    m.name
                );
            };
            let (za, zb) = (alone[a][k].unwrap(), alone[b][k].unwrap());
            // f32's tie tolerance is relative.
            let allowed = match fixed_lsb::<N>() {
                Some(_) => tol,
                None => tol * (1.0 + za.abs().max(zb.abs())),
            } + res;
            assert!(
                (za - zb).abs() <= allowed,
                "{what} {} {}: pixel {k}: z-buffer shows {a} at {za}, method {b} at {zb}",
                N::NAME,
                m.name
            );
        }
    }
    differ
}

/// Adds the same plane `z += a·x + b·y + c` to every vertex: every difference of depths, so
/// every visibility relation, stays as it was.
fn tilt(p: &Polys, a: f32, b: f32, c: f32) -> Polys {
    let q = |v: f32| (v * 256.0).round() / 256.0;
    Polys::new(
        p.polys
            .iter()
            .map(|poly| {
                poly.iter()
                    .map(|v| [v[0], v[1], v[2] + q(a) * v[0] + q(b) * v[1] + q(c)])
                    .collect()
            })
            .collect(),
    )
}

/// Mirrors and transposes a 48×48 scene (keeps cyclic overlap cyclic).
fn flip(p: &Polys, k: u64) -> Polys {
    Polys::new(
        p.polys
            .iter()
            .map(|poly| {
                poly.iter()
                    .map(|v| {
                        let (mut x, mut y) = (v[0], v[1]);
                        if k & 1 != 0 {
                            x = 48.0 - x;
                        }
                        if k & 2 != 0 {
                            y = 48.0 - y;
                        }
                        if k & 4 != 0 {
                            (x, y) = (y, x);
                        }
                        [x, y, v[2]]
                    })
                    .collect()
            })
            .collect(),
    )
}

/// Three mutually overlapping triangles in a cycle (each over the next where they cross).
fn cyclic_triangles() -> Polys {
    Polys::new(vec![
        vec![[2.0, 8.0, 1.0], [46.0, 12.0, 9.0], [4.0, 22.0, 1.0]],
        vec![[38.0, 2.0, 2.0], [44.0, 6.0, 2.0], [12.0, 46.0, 10.0]],
        vec![[6.0, 4.0, 9.0], [40.0, 44.0, 0.0], [30.0, 46.0, 0.0]],
    ])
}

// 20. Cyclic overlap under random common tilts, mirrors and transposes; interpenetrating and
// coplanar pairs: every method shows the z-buffer's polygon except within the resolution.
fn against_zbuffer_all<N: Scalar>() {
    let cfg = Config::screen(48, 48);
    let mut rng = Rng(20);
    let mut differ = 0;
    for base in [cyclic_triangles(), scenes::cyclic(0.0), scenes::cyclic(0.5)] {
        for k in 0..8 {
            let t = tilt(
                &flip(&base, k),
                rng.f(-0.5, 0.5),
                rng.f(-0.5, 0.5),
                rng.f(0.0, 100.0),
            );
            differ += against_zbuffer::<N>(&t, &cfg, "cyclic");
        }
    }
    for _ in 0..12 {
        // Two large triangles crossing along a line (interpenetrating).
        let v = |rng: &mut Rng, z: f32| [rng.f(-8.0, 56.0), rng.f(-8.0, 56.0), z];
        let p = Polys::new(vec![
            vec![v(&mut rng, 0.0), v(&mut rng, 20.0), v(&mut rng, 40.0)],
            vec![v(&mut rng, 40.0), v(&mut rng, 20.0), v(&mut rng, 0.0)],
        ]);
        differ += against_zbuffer::<N>(&p, &cfg, "interpenetrating");
        // Coplanar pairs: two overlapping triangles on one random plane.
        let (a, b, c) = (rng.f(-2.0, 2.0), rng.f(-2.0, 2.0), rng.f(100.0, 200.0));
        let on = |rng: &mut Rng| {
            let (x, y) = (rng.f(-8.0, 56.0), rng.f(-8.0, 56.0));
            let g = |v: f32| (v * 256.0).round() / 256.0;
            let (x, y) = (g(x), g(y));
            [x, y, a * x + b * y + c]
        };
        let p = Polys::new(vec![
            vec![on(&mut rng), on(&mut rng), on(&mut rng)],
            vec![on(&mut rng), on(&mut rng), on(&mut rng)],
        ]);
        differ += against_zbuffer::<N>(&p, &cfg, "coplanar");
    }
    eprintln!(
        "e20 {}: {differ} pixel-method pairs differ from the z-buffer, all within the resolution",
        N::NAME
    );
}

#[test]
fn e20_every_method_against_the_zbuffer() {
    for_formats!(against_zbuffer_all);
}
