//! The BSP tree equals the exact reference (`docs/extremes.md` item 20), culls back faces on the walk,
//! and bounds its depth.

mod common;
use common::*;
use zrow::bsp::Bsp;
use zrow::{Config, Error, RenderError, Renderer, Scalar, Scanline, Table, Q16_16};

type Tree<N> = Bsp<N, 240, 1024, 4096, 8192, 2048>;

fn check<N: Scalar>(p: &Polys, w: u16, h: u16) -> zrow::FrameStats {
    let cfg = Config::screen(w, h);
    let (cap, stats) = p
        .render_stats(&mut *Box::new(Tree::<N>::new()), &cfg)
        .unwrap();
    let tol = tie_tolerance::<N>(4 * (w + h) as usize);
    let bad = mismatches(&cap, &reference::<N>(p, &cfg, 2.0 * tol));
    assert!(
        bad.is_empty(),
        "{}: {} pixels differ, first {:?}",
        N::NAME,
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    stats
}

#[test]
fn cyclic_overlap_is_split_and_exact() {
    for shift in [0.0, 0.25, 1.0] {
        let s = check::<Q16_16>(&scenes::cyclic(shift), 48, 48);
        assert!(s.splits > 0, "a cyclic overlap needs a split");
        check::<f32>(&scenes::cyclic(shift), 48, 48);
    }
}

#[test]
fn random_and_dense_scenes_equal_the_reference() {
    let mut rng = Rng(0xb5b_0001);
    for _ in 0..40 {
        let n = 1 + rng.below(30) as usize;
        check::<Q16_16>(&scenes::random(&mut rng, n, 48.0, 40.0), 48, 40);
        check::<f32>(&scenes::random(&mut rng, n, 48.0, 40.0), 48, 40);
    }
    for _ in 0..10 {
        let n = 2 + rng.below(8) as usize;
        check::<Q16_16>(&scenes::dense(&mut rng, n, 48.0, 40.0), 48, 40);
        check::<f32>(&scenes::dense(&mut rng, n, 48.0, 40.0), 48, 40);
    }
}

/// Model mode with back faces culled on the walk: the same frame as the scan-line method
/// (which drops them before rasterising), bit for bit in Q16.16.
#[test]
fn culled_meshes_equal_the_scanline_frame() {
    for name in ["cube", "mesh1k", "interlocked"] {
        for angle in [0.0f32, 0.7, 2.1] {
            zrow_scenes::with_scene::<Q16_16, _>(name, angle, |scene, cfg, _| {
                let mut a = Capture::<Q16_16>::new(cfg.width as usize, cfg.height as usize);
                let mut b = a.clone();
                let scanline = &mut *Box::new(Scanline::<Q16_16, 240, 16384, 4096, 1024>::new());
                scanline.render(scene, cfg, &mut a).unwrap();
                let s = Renderer::render(&mut *Box::new(Tree::<Q16_16>::new()), scene, cfg, &mut b)
                    .unwrap();
                assert_eq!(a.color, b.color, "{name} at {angle}");
                assert_eq!(a.depth, b.depth, "{name} at {angle}");
                println!("{name} {angle}: {} drawn, {} splits", s.polygons, s.splits);
            })
            .unwrap();
        }
    }
}

#[test]
fn depth_beyond_the_bound_is_a_typed_error_before_any_row() {
    // A stack of parallel planes, each nearer than the last: every insertion goes one level
    // deeper, so 20 planes need depth 20.
    let polys = (0..20)
        .map(|i| {
            let z = 40.0 - i as f32;
            vec![[1.0, 1.0, z], [30.0, 2.0, z], [3.0, 30.0, z]]
        })
        .collect();
    let p = Polys::new(polys);
    let cfg = Config::screen(32, 32);
    let err = p
        .render_with(
            &mut *Box::new(Bsp::<Q16_16, 32, 64, 256, 256, 8>::new()),
            &cfg,
        )
        .unwrap_err();
    assert!(
        matches!(
            err,
            RenderError::Scene(Error::Capacity {
                table: Table::BspDepth,
                ..
            })
        ),
        "{err:?}"
    );
    // Deep enough, it draws the reference's picture.
    let cap = p
        .render_with(
            &mut *Box::new(Bsp::<Q16_16, 32, 64, 256, 256, 32>::new()),
            &cfg,
        )
        .unwrap();
    assert!(mismatches(&cap, &reference::<Q16_16>(&p, &cfg, 1e-3)).is_empty());
}
