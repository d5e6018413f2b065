//! Every demo scene renders, fits the board's renderer over a full turn, and (for
//! `interlocked`) really interpenetrates: the visible surface changes at crossings.

use zrow::{requirements, Requirements, Scanline, Q16_16};

#[test]
fn demos_fit_the_board_renderer_over_a_full_turn() {
    let mut all = Requirements::default();
    for (name, each) in zrow_scenes::DEMOS
        .iter()
        .zip(zrow_scenes::DEMO_MEASURED_EACH)
    {
        let mut worst = Requirements::default();
        // A turn, and the board's own angles (0.03 rad a frame) over its first frames.
        let angles = (0..256)
            .map(|k| k as f32 * core::f32::consts::TAU / 256.0)
            .chain((0..400).map(zrow_scenes::board_angle));
        for angle in angles {
            let req = zrow_scenes::with_demo::<Q16_16, _>(name, angle, |scene, cfg, _| {
                requirements(scene, cfg).unwrap()
            })
            .unwrap();
            worst = worst.max(req);
        }
        assert!(worst.polygons > 0, "{name} draws nothing");
        // Within what was measured over 2,048 angles, and the meshes' own vertices exactly.
        assert!(
            worst.polygons <= each.polygons
                && worst.edges <= each.edges
                && worst.active_polygons <= each.active_polygons
                && worst.vertices == each.vertices,
            "{name}: {worst:?} vs {each:?}"
        );
        all = all.max(worst);
    }
    // Within what was measured over 2,048 angles (and the mesh's own 500 vertices exactly).
    let m = zrow_scenes::DEMO_MEASURED;
    assert!(
        all.polygons <= m.polygons
            && all.edges <= m.edges
            && all.active_polygons <= m.active_polygons
            && all.vertices == m.vertices,
        "{all:?} vs {m:?}"
    );
    // The firmware's renderer: zrow::scanline_for!(Q16_16, DEMO_REQUIREMENTS).
    let r = zrow_scenes::DEMO_REQUIREMENTS;
    assert!(r.polygons > m.polygons && r.active_polygons > m.active_polygons);
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

/// `with_demo` (the board's lookup, which links only the demos' meshes) draws what
/// `with_scene` draws, frame for frame.
#[test]
fn with_demo_draws_what_with_scene_draws() {
    let mut r = Box::new(Scanline::<Q16_16, 240, 4096, 1024, 256>::new());
    for name in zrow_scenes::DEMOS {
        for angle in [0.0, 0.7, 2.9] {
            let mut hash = |via_demo: bool| {
                let draw = |scene: &dyn zrow::Scene<Q16_16>, cfg: &zrow::Config, _| {
                    let mut h = zrow_scenes::FrameHash::default();
                    r.render(scene, cfg, &mut h).unwrap();
                    h
                };
                if via_demo {
                    zrow_scenes::with_demo::<Q16_16, _>(name, angle, draw)
                } else {
                    zrow_scenes::with_scene::<Q16_16, _>(name, angle, draw)
                }
                .unwrap()
            };
            assert_eq!(hash(true), hash(false), "{name} at {angle}");
        }
    }
    assert!(zrow_scenes::with_demo::<Q16_16, _>("foley100", 0.0, |_, _, _| ()).is_none());
}

/// The board's angle wraps to 0 after a whole number of turns, within 0.002 rad, so the wrap
/// does not show; the angle never grows past the period.
#[test]
fn board_angle_wraps_where_it_does_not_show() {
    use zrow_scenes::{board_angle, BOARD_PERIOD, BOARD_STEP};
    let span = BOARD_PERIOD as f64 * BOARD_STEP as f64;
    let off = span % core::f64::consts::TAU;
    assert!(off.min(core::f64::consts::TAU - off) < 0.002, "{off}");
    assert_eq!(board_angle(BOARD_PERIOD), 0.0);
    assert_eq!(board_angle(1), BOARD_STEP);
    assert!(board_angle(u32::MAX) < span as f32);
}
