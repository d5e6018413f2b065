//! The cheap exact methods `auto` chooses from the scene's structure:
//!
//! - back-face culling alone ([`CullOnly`]) for one closed convex solid — [`closed_convex`]
//!   says which meshes are one, and on them the picture equals the scan-line method's;
//! - ordering alone ([`Ordered`]) where polygons overlapping on screen never overlap in depth —
//!   [`Ordered::exact_for`] says when, and whenever it says so the picture equals the scan-line
//!   method's (the exact reference's, ties included).
//!
//! Each also fails where its structure is absent, so the checks are what make them exact.

mod common;
use common::Rng;
use common::*;
use embedded_graphics_core::pixelcolor::Rgb565;
use proptest::prelude::*;
use zrow::cullonly::CullOnly;
use zrow::ordered::Ordered;
use zrow::structure::closed_convex;
use zrow::{Config, Face, Mesh, Renderer, Scalar, Q16_16};

type Cull<N> = CullOnly<N, 256, 1024, 4096>;
type Order<N> = Ordered<N, 256, 1024, 4096>;

/// Renders the named zrow-scenes scene with `R`.
fn scene_with<N: zrow_scenes::Format, R: Renderer<N>>(
    name: &str,
    angle: f32,
    r: &mut R,
) -> Capture<N> {
    zrow_scenes::with_scene::<N, _>(name, angle, |scene, cfg, _| {
        let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
        r.render(scene, cfg, &mut cap).unwrap();
        cap
    })
    .unwrap()
}

#[test]
fn the_cube_is_closed_and_convex_the_torus_is_not() {
    let cube = zrow_scenes::mesh::<Q16_16>("cube").unwrap();
    assert!(closed_convex(&cube));
    assert!(closed_convex(&zrow_scenes::mesh::<f32>("cube").unwrap()));
    assert!(!closed_convex(
        &zrow_scenes::mesh::<Q16_16>("mesh1k").unwrap()
    ));
    // Open: one face missing.
    let rest: Vec<_> = cube.faces.iter().skip(1).collect();
    let open = Mesh::new(&[], &rest).with_positions(cube.vertices);
    assert!(!closed_convex(&open));
    // Inconsistent: one face turned over.
    let flipped: Vec<Vec<u16>> = cube
        .faces
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let mut v = f.indices.to_vec();
            if i == 0 {
                v.reverse();
            }
            v
        })
        .collect();
    let faces: Vec<Face> = flipped
        .iter()
        .map(|v| Face::new(v, Rgb565::new(31, 0, 0)))
        .collect();
    assert!(!closed_convex(
        &Mesh::new(&[], &faces).with_positions(cube.vertices)
    ));
    // Every face turned over: closed, but inside out (faces point inwards).
    let inside_out: Vec<Vec<u16>> = cube
        .faces
        .iter()
        .map(|f| f.indices.iter().rev().copied().collect())
        .collect();
    let faces: Vec<Face> = inside_out
        .iter()
        .map(|v| Face::new(v, Rgb565::new(31, 0, 0)))
        .collect();
    assert!(!closed_convex(
        &Mesh::new(&[], &faces).with_positions(cube.vertices)
    ));
    assert!(!closed_convex(&Mesh::<Q16_16>::new(&[], &[])));
}

fn cull_only_equals_scanline<N: zrow_scenes::Format>() {
    for k in 0..12 {
        let angle = k as f32 * 0.55;
        let want = scene_with::<N, _>("cube", angle, &mut *Box::new(Big::<N>::new()));
        let got = scene_with::<N, _>("cube", angle, &mut *Box::new(Cull::<N>::new()));
        assert!(
            want.color == got.color,
            "{} cube at {angle}: colour",
            N::NAME
        );
        if N::NAME == Q16_16::NAME {
            assert!(want.depth == got.depth, "cube at {angle}: depth bits");
        }
        assert!(want.drawn() > 1000, "the cube is on screen");
    }
}

#[test]
fn cull_only_draws_the_cube_as_the_scan_line_method_does() {
    cull_only_equals_scanline::<Q16_16>();
    cull_only_equals_scanline::<f32>();
    // What the choice saves in RAM, printed (its instructions: emu/run.sh, `cull-only`).
    type S = zrow::Scanline<Q16_16, 240, 2048, 512, 128>;
    type C = CullOnly<Q16_16, 240, 512, 2048>;
    type O = Ordered<Q16_16, 240, 512, 2048>;
    println!(
        "RAM at 240 px rows, 512 polygons, 2048 edges (Q16.16): scanline (128 active) {} B, \
         cull-only {} B, ordered {} B",
        S::RAM_BYTES,
        C::RAM_BYTES,
        O::RAM_BYTES
    );
}

/// Without its structure, culling alone is not enough: the torus hides parts of itself (its
/// inner ring behind its outer one).
#[test]
fn cull_only_is_wrong_on_the_torus() {
    let mut differ = 0;
    for k in 0..4 {
        let angle = k as f32 * 0.8;
        let want = scene_with::<Q16_16, _>("mesh1k", angle, &mut *Box::new(Big::<Q16_16>::new()));
        let got = scene_with::<Q16_16, _>("mesh1k", angle, &mut *Box::new(Cull::<Q16_16>::new()));
        differ += want
            .color
            .iter()
            .zip(&got.color)
            .filter(|(a, b)| a != b)
            .count();
    }
    assert!(differ > 0, "{differ} pixels differ");
    println!(
        "cull-only on the torus: {differ} pixels differ from the scan-line method over 4 views"
    );
}

/// `n` polygons in layers: polygon `k` lies within depths `8k .. 8k + 6` (tilted inside its
/// layer), anywhere on a `w`×`h` screen; layers are shuffled in scene order.
fn layers(rng: &mut Rng, n: usize, w: f32, h: f32) -> Polys {
    let grid = |v: f32| (v * 256.0).round() / 256.0;
    let mut order: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        order.swap(i, rng.below(i as u64 + 1) as usize);
    }
    let polys = order
        .iter()
        .map(|&k| {
            let z0 = 8.0 * k as f32;
            let v = |rng: &mut Rng| {
                [
                    grid(rng.f(-0.2 * w, 1.2 * w)),
                    grid(rng.f(-0.2 * h, 1.2 * h)),
                    grid(z0 + rng.f(0.0, 6.0)),
                ]
            };
            vec![v(rng), v(rng), v(rng)]
        })
        .collect();
    Polys::new(polys)
}

/// Ordered's picture against the scan-line method's: colour always, depth bits in Q16.16.
fn ordered_equals_scanline<N: Scalar>(p: &Polys, cfg: &Config, what: &str) {
    let want = p.render::<N>(cfg).unwrap();
    let got = p
        .render_with(&mut *Box::new(Order::<N>::new()), cfg)
        .unwrap();
    assert!(want.color == got.color, "{what} {}: colour", N::NAME);
    if N::NAME == Q16_16::NAME {
        if let Some(i) = (0..want.depth.len()).find(|&i| want.depth[i] != got.depth[i]) {
            panic!(
                "{what}: depth bits at {i} ({}, {}): scan {:?} ordered {:?}, colour {:?}",
                i % cfg.width as usize,
                i / cfg.width as usize,
                want.depth[i],
                got.depth[i],
                index_of(want.color[i])
            );
        }
    }
}

fn exact_for<N: Scalar>(p: &Polys, cfg: &Config) -> bool {
    p.with_scene::<N, _>(|scene| {
        let mut order = Box::new(Order::<N>::new());
        order.exact_for(scene, cfg)
    })
    .unwrap()
}

#[test]
fn layered_scenes_need_only_ordering() {
    let mut rng = Rng(0x1a7e5);
    let cfg = Config::screen(64, 48);
    for k in 0..16 {
        let p = layers(&mut rng, 4 + k, 64.0, 48.0);
        assert!(exact_for::<Q16_16>(&p, &cfg), "layers #{k}");
        assert!(exact_for::<f32>(&p, &cfg), "layers #{k}");
        ordered_equals_scanline::<Q16_16>(&p, &cfg, &format!("layers #{k}"));
        ordered_equals_scanline::<f32>(&p, &cfg, &format!("layers #{k}"));
    }
}

#[test]
fn interpenetrating_scenes_are_not_ordered() {
    let mut rng = Rng(0xde45e);
    let cfg = Config::screen(48, 40);
    for k in 0..6 {
        let p = scenes::dense(&mut rng, 6 + k, 48.0, 40.0);
        assert!(!exact_for::<Q16_16>(&p, &cfg), "dense #{k}");
        // And ordering alone would indeed be wrong there.
        let want = p.render::<Q16_16>(&cfg).unwrap();
        let got = p
            .render_with(&mut *Box::new(Order::<Q16_16>::new()), &cfg)
            .unwrap();
        assert!(want.color != got.color, "dense #{k}");
    }
    assert!(!exact_for::<Q16_16>(
        &scenes::cyclic(0.0),
        &Config::screen(48, 48)
    ));
}

/// Coplanar overlapping polygons at one depth: ordering alone is exact, the first polygon in
/// the scene wins (the tie rule), whichever way round they come.
#[test]
fn ties_go_to_the_first_polygon() {
    let cfg = Config::screen(16, 16);
    let a = vec![[1.0, 1.0, 5.0], [12.0, 1.0, 5.0], [1.0, 12.0, 5.0]];
    let b = vec![[3.0, 3.0, 5.0], [15.0, 3.0, 5.0], [3.0, 15.0, 5.0]];
    for p in [
        Polys::new(vec![a.clone(), b.clone()]),
        Polys::new(vec![b, a]),
    ] {
        assert!(exact_for::<Q16_16>(&p, &cfg));
        ordered_equals_scanline::<Q16_16>(&p, &cfg, "tie");
        ordered_equals_scanline::<f32>(&p, &cfg, "tie");
        let got = p.render::<Q16_16>(&cfg).unwrap();
        assert_eq!(index_of(got.at(4, 4)), Some(0), "the first polygon wins");
    }
}

proptest! {
    #![proptest_config(crate::common::proptest_config(64))]

    /// Whenever the check says ordering is exact, it is — on random scenes (few of which
    /// pass) and on sparse ones (many of which do).
    #[test]
    fn ordered_is_exact_whenever_the_check_says_so(seed in any::<u64>(), n in 1usize..10) {
        let mut rng = Rng(seed | 1);
        let cfg = Config::screen(40, 32);
        let p = if n % 2 == 0 {
            scenes::random(&mut rng, n, 40.0, 32.0)
        } else {
            layers(&mut rng, n, 40.0, 32.0)
        };
        if exact_for::<Q16_16>(&p, &cfg) {
            ordered_equals_scanline::<Q16_16>(&p, &cfg, "random");
        }
        if exact_for::<f32>(&p, &cfg) {
            ordered_equals_scanline::<f32>(&p, &cfg, "random");
        }
    }
}
