//! Every demo scene renders, fits the board's renderer over a full turn, and (for
//! `interlocked`) really interpenetrates: the visible surface changes at crossings.

use zrow::{requirements, Requirements, Scanline, Q16_16};

#[test]
fn demos_fit_the_board_renderer_over_a_full_turn() {
    for name in zrow_scenes::DEMOS {
        let mut worst = Requirements::default();
        for k in 0..64 {
            let angle = k as f32 * core::f32::consts::TAU / 64.0;
            let req = zrow_scenes::with_scene::<Q16_16, _>(name, angle, |scene, cfg, _| {
                let mut rows = vec![0u32; cfg.height as usize + 1];
                requirements(scene, cfg, &mut rows).unwrap()
            })
            .unwrap();
            worst = worst.max(req);
        }
        // firmware/src/main.rs: Scanline<Q16_16, 240, 1344, 480, 72>.
        assert!(
            worst.polygons <= 480 && worst.edges <= 1344 && worst.active_polygons <= 72,
            "{name}: {worst:?}"
        );
        assert!(worst.polygons > 0, "{name} draws nothing");
    }
}

#[test]
fn interlocked_rings_intersect() {
    let mut r = Box::new(Scanline::<Q16_16, 240, 4096, 1024, 256>::new());
    let stats = zrow_scenes::with_scene::<Q16_16, _>("interlocked", 0.5, |scene, cfg, faces| {
        assert_eq!(faces, 2 * 256 + 6);
        r.render(scene, cfg, &mut zrow_scenes::FrameHash::default())
            .unwrap()
    })
    .unwrap();
    assert!(stats.crossings > 0, "{stats:?}");
}
