//! The scenes in every number format: the model meshes share one compact table, the
//! screen-space scenes' Q24.8 arrays are the f32 positions rounded to the nearest 1/256, and every scene renders in Q24.8, covering what Q16.16 covers wherever the
//! positions are on the 1/256 grid (coverage never depends on the format, `docs/conventions.md`).

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::raster::RasterVertex;
use zrow::{Config, FrameBuffer, Scalar, Scanline, ScreenScene, Vec3, Q16_16, Q24_8};
use zrow_scenes::Format;

/// Every screen-space position array of a format, by name.
fn arrays<N: Format>() -> [(&'static str, &'static [Vec3<N>]); 3] {
    [
        ("random400", N::random400()),
        ("foley100", N::foley100()),
        ("foley2500", N::foley2500()),
    ]
}

/// The model meshes' one compact table gives every format the same positions: f32 and
/// Q16.16 exactly (multiples of 2^-14), Q24.8 rounded to its nearest 1/256 (a tie up).
#[test]
fn model_positions_are_one_compact_table_in_every_format() {
    for name in ["cube", "mesh1k", "ring"] {
        let f = zrow_scenes::mesh::<f32>(name).unwrap().vertices;
        let q16 = zrow_scenes::mesh::<Q16_16>(name).unwrap().vertices;
        let q24 = zrow_scenes::mesh::<Q24_8>(name).unwrap().vertices;
        assert!(
            !f.is_empty() && f.len() == q16.len() && f.len() == q24.len(),
            "{name}"
        );
        let shift = f32::from_bits((127 - zrow_scenes::MODEL_SHIFT as u32) << 23);
        for ((a, b), c) in f.iter().zip(q16.iter()).zip(q24.iter()) {
            for (x, y, z) in [(a.x, b.x, c.x), (a.y, b.y, c.y), (a.z, b.z, c.z)] {
                assert_eq!((x / shift).fract(), 0.0, "{name}: {x} is on the 2^-14 grid");
                assert_eq!(x, y.to_f32(), "{name}");
                // Nearest, a tie up (`Scalar::from_scaled`).
                let nearest = (x as f64 * 256.0 + 0.5).floor() / 256.0;
                assert_eq!(z.to_f64(), nearest, "{name}: {x} as {z}");
            }
        }
    }
}

#[test]
fn fixed_positions_are_the_f32_positions_rounded_to_nearest() {
    fn check<N: Format>(lsb: f64) {
        for ((name, f), (_, q)) in arrays::<f32>().into_iter().zip(arrays::<N>()) {
            assert_eq!(f.len(), q.len(), "{name}");
            for (a, b) in f.iter().zip(q) {
                for (x, y) in [(a.x, b.x), (a.y, b.y), (a.z, b.z)] {
                    let (x, y) = (x as f64, y.to_f64());
                    // Nearest: within half an LSB, and on the format's grid.
                    assert!((x - y).abs() <= lsb / 2.0, "{name} {}: {x} as {y}", N::NAME);
                    assert_eq!((y / lsb).fract(), 0.0);
                }
            }
        }
    }
    check::<Q16_16>(1.0 / 65536.0);
    check::<Q24_8>(1.0 / 256.0);
    // The comparison scenes' x and y are on the 1/256 grid: Q24.8 holds them exactly.
    for (f, q) in [
        (f32::foley100(), Q24_8::foley100()),
        (f32::foley2500(), Q24_8::foley2500()),
    ] {
        assert!(f
            .iter()
            .zip(q)
            .all(|(a, b)| a.x == b.x.to_f32() && a.y == b.y.to_f32()));
    }
}

fn frame<N: Format>(name: &str) -> (Vec<Rgb565>, usize) {
    let mut px = vec![Rgb565::BLACK; 240 * 240];
    let mut r = Box::new(Scanline::<N, 240, 16384, 4096, 1024>::new());
    let faces = zrow_scenes::with_scene::<N, _>(name, 0.3, |s, c, faces| {
        r.render(s, c, &mut FrameBuffer::new(&mut px, 240))
            .unwrap_or_else(|e| panic!("{name} in {}: {e:?}", N::NAME));
        faces
    })
    .unwrap();
    (px, faces)
}

#[test]
fn every_scene_renders_in_q24_8() {
    let names = zrow_scenes::NAMES
        .iter()
        .chain(&zrow_scenes::FOLEY)
        .chain(&zrow_scenes::DEMOS);
    for &name in names {
        let (q24, faces24) = frame::<Q24_8>(name);
        let (q16, faces16) = frame::<Q16_16>(name);
        assert_eq!(faces24, faces16, "{name}");
        let drawn = |f: &[Rgb565]| f.iter().filter(|&&p| p != Rgb565::BLACK).count();
        assert!(drawn(&q24) > 0, "{name} draws nothing in q24.8");
        if zrow_scenes::FOLEY.contains(&name) {
            // Same snapped vertices in both formats: the same pixels are covered (only
            // which surface is nearest may differ, where depths are closer than Q24.8's
            // error).
            let covered = |f: &[Rgb565]| f.iter().map(|&p| p != Rgb565::BLACK).collect::<Vec<_>>();
            assert_eq!(covered(&q24), covered(&q16), "{name}");
        }
    }
}

/// `random400`, which [`zrow_scenes::with_scene`] lends the renderer snapped
/// ([`zrow::SnappedScene`]), holds its positions snapped as geometry snaps a screen scene's
/// ([`RasterVertex::snapped`]) on the grid of the configuration it comes with, in every
/// format; so the frame is the one the screen scene of those positions draws.
#[test]
fn random400_is_its_positions_snapped() {
    fn check<N: Format>() {
        let bits = zrow_scenes::with_scene::<N, _>("random400", 0.0, |_, cfg, _| cfg.subpixel_bits)
            .unwrap();
        let (positions, snapped) = (N::random400(), N::random400_snapped());
        assert_eq!(positions.len(), snapped.len());
        for (p, s) in positions.iter().zip(snapped) {
            assert_eq!(
                RasterVertex::snapped(p, bits).as_ref(),
                Some(s),
                "{}",
                N::NAME
            );
        }
        let (lent, _) = frame::<N>("random400");
        let mut px = vec![Rgb565::BLACK; 240 * 240];
        let mut r = Box::new(Scanline::<N, 240, 16384, 4096, 1024>::new());
        let scene = ScreenScene {
            mesh: zrow_scenes::mesh::<N>("random400").unwrap(),
        };
        r.render(
            &scene,
            &Config::screen(240, 240),
            &mut FrameBuffer::new(&mut px, 240),
        )
        .unwrap();
        assert!(lent == px, "{}", N::NAME);
        assert!(px.iter().filter(|&&p| p != Rgb565::BLACK).count() > 40_000);
    }
    check::<f32>();
    check::<Q16_16>();
    check::<Q24_8>();
}
