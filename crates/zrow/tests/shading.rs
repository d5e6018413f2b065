//! The speed–accuracy knobs: depth cueing (affine and perspective-correct), the depth mapping,
//! the maths library. Their measured cost and error per preset: `crates/zrow-tradeoff`.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::abuffer::ABuffer;
use zrow::depthsort::DepthSort;
use zrow::geometry::{shade, DepthMapping};
use zrow::presets::{by_name, PRESETS};
use zrow::shading::{Cue, DepthCue, Interpolation, Shading};
use zrow::tiled::Tiled;
use zrow::warnock::Warnock;
use zrow::{Config, Error, FrameBuffer, MathLib, RenderError, Renderer, Scanline, ZBuffer, Q16_16};
use zrow_scenes::{with_preset_scene, PRESET_CUE};

const S: usize = 240;

fn frame<R: Renderer<Q16_16>>(r: &mut R, scene: &str, preset: &str) -> Result<Vec<Rgb565>, String> {
    let p = by_name(preset).unwrap();
    let mut px = vec![Rgb565::BLACK; S * S];
    with_preset_scene::<Q16_16, _>(scene, p, |sc, cfg, _| {
        r.render(sc, cfg, &mut FrameBuffer::new(&mut px, S))
            .map(|_| ())
            .map_err(|e| format!("{e:?}"))
    })
    .unwrap()?;
    Ok(px)
}

#[test]
fn perspective_cue_gives_every_method_the_same_frame() {
    let scan = frame(
        &mut *Box::new(Scanline::<Q16_16, S, 256, 64, 64>::new()),
        "cube",
        "q16",
    )
    .unwrap();
    let flat_cfg = {
        let mut c = Config::model(S as u16, S as u16);
        c.shading = Shading::Flat;
        c
    };
    // The cue changes the picture (the cube spans w ≈ 3.6..5.3, the cue 3..6).
    let mut flat = vec![Rgb565::BLACK; S * S];
    zrow_scenes::with_scene_math::<Q16_16, _>("cube", 0.0, MathLib::Libm, |sc, _, _| {
        Scanline::<Q16_16, S, 256, 64, 64>::new()
            .render(sc, &flat_cfg, &mut FrameBuffer::new(&mut flat, S))
            .unwrap();
    });
    let dimmed = flat.iter().zip(&scan).filter(|(f, s)| f != s).count();
    assert!(dimmed > 1000, "the depth cue changed only {dimmed} pixels");
    let others = [
        frame(
            &mut *Box::new(ZBuffer::<Q16_16, S, S>::new()),
            "cube",
            "q16",
        ),
        frame(
            &mut *Box::new(Tiled::<Q16_16, S, 16, 64, 256>::new()),
            "cube",
            "q16",
        ),
        frame(
            &mut *Box::new(DepthSort::<Q16_16, S, 64, 256, 512>::new()),
            "cube",
            "q16",
        ),
        frame(
            &mut *Box::new(Warnock::<Q16_16, S, 16, 64, 256, 4096>::new()),
            "cube",
            "q16",
        ),
        frame(
            &mut *Box::new(ABuffer::<Q16_16, S, 64, 256, 16>::new()),
            "cube",
            "q16",
        ),
    ];
    for (k, f) in others.into_iter().enumerate() {
        let f = f.unwrap();
        let diff = f.iter().zip(&scan).filter(|(a, b)| a != b).count();
        assert_eq!(
            diff, 0,
            "method {k}: {diff} pixels differ from the scan-line's"
        );
    }
}

#[test]
fn perspective_cue_on_rows_with_gaps_equals_the_z_buffer() {
    // The torus and the interlocked rings over a grey background: rows whose spans lie apart
    // with background between them (the hole, the gaps between the rings), painted by the
    // scan-line's span-by-span path with their depths. A gap's depths must be the
    // background's, whatever the row before left there, or the cue would shade the grey.
    let grey = Rgb565::new(12, 24, 12);
    type Draw<'a> = dyn FnMut(&dyn zrow::Scene<Q16_16>, &Config, &mut [Rgb565]) + 'a;
    let render = |r: &mut Draw<'_>, scene| {
        let mut px = vec![Rgb565::BLACK; S * S];
        with_preset_scene::<Q16_16, _>(scene, by_name("q16").unwrap(), |sc, cfg, _| {
            let cfg = Config {
                background: grey,
                ..*cfg
            };
            r(sc, &cfg, &mut px)
        })
        .unwrap();
        px
    };
    let (mut scan, mut z) = (
        Box::new(Scanline::<Q16_16, S, 1024, 1024, 128>::new()),
        Box::new(ZBuffer::<Q16_16, S, S>::new()),
    );
    for scene in ["mesh1k", "interlocked"] {
        let a = render(
            &mut |sc, cfg, px| {
                scan.render(sc, cfg, &mut FrameBuffer::new(px, S)).unwrap();
            },
            scene,
        );
        let b = render(
            &mut |sc, cfg, px| {
                z.render(sc, cfg, &mut FrameBuffer::new(px, S)).unwrap();
            },
            scene,
        );
        let diff = a.iter().zip(&b).filter(|(a, b)| a != b).count();
        assert_eq!(diff, 0, "{scene}: {diff} pixels differ from the z-buffer's");
        let background = a.iter().filter(|&&c| c == grey).count();
        assert!(
            background > S * S / 4,
            "{scene}: {background} background pixels"
        );
    }
}

#[test]
fn affine_cue_is_unsupported_off_the_scan_line_and_fails_before_any_row() {
    struct Count(usize);
    impl zrow::RowSink<Q16_16> for Count {
        type Error = ();
        fn write_row(&mut self, _: &zrow::Row<'_, Q16_16>) -> Result<(), ()> {
            self.0 += 1;
            Ok(())
        }
    }
    let p = by_name("q16-affine").unwrap();
    let mut rows = Count(0);
    let r = with_preset_scene::<Q16_16, _>("cube", p, |sc, cfg, _| {
        ZBuffer::<Q16_16, S, S>::new()
            .render(sc, cfg, &mut rows)
            .map(|_| ())
    })
    .unwrap();
    assert!(
        matches!(r, Err(RenderError::Scene(Error::Unsupported { .. }))),
        "{r:?}"
    );
    assert_eq!(rows.0, 0);
    // The scan-line method draws it.
    frame(
        &mut *Box::new(Scanline::<Q16_16, S, 256, 64, 64>::new()),
        "cube",
        "q16-affine",
    )
    .unwrap();
}

/// Channel-wise largest difference.
fn max_diff(a: &[Rgb565], b: &[Rgb565]) -> u8 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            x.r()
                .abs_diff(y.r())
                .max(x.g().abs_diff(y.g()))
                .max(x.b().abs_diff(y.b()))
        })
        .max()
        .unwrap_or(0)
}

#[test]
fn affine_and_perspective_cues_differ_where_depth_recedes_and_agree_where_it_is_screen_linear() {
    // Model mode: the cube's faces recede, w is not linear in screen space.
    let persp = frame(
        &mut *Box::new(Scanline::<Q16_16, S, 256, 64, 64>::new()),
        "cube",
        "q16",
    )
    .unwrap();
    let affine = frame(
        &mut *Box::new(Scanline::<Q16_16, S, 256, 64, 64>::new()),
        "cube",
        "q16-affine",
    )
    .unwrap();
    assert!(
        max_diff(&persp, &affine) >= 1,
        "affine equals perspective on a receding cube"
    );
    // Screen space: depth is the view distance and linear along each polygon, so the affine
    // factor equals the per-pixel one up to rounding (depths inside the cue's 3..6, where the
    // factor is not clamped).
    let v = [
        [10.0, 10.0, 3.2],
        [200.0, 30.0, 5.5],
        [60.0, 220.0, 4.0],
        [30.0, 200.0, 5.8],
        [230.0, 120.0, 3.0],
        [120.0, 5.0, 4.5],
    ]
    .map(|p| zrow::Vec3::<Q16_16>::from_f32(p).unwrap());
    let faces = [
        zrow::Face::new(&[0, 1, 2], Rgb565::WHITE),
        zrow::Face::new(&[3, 4, 5], Rgb565::new(20, 50, 10)),
    ];
    let scene = zrow::ScreenScene {
        mesh: zrow::Mesh::new(&v, &faces),
    };
    let draw = |interpolation| {
        let mut cfg = Config::screen(S as u16, S as u16);
        cfg.shading = Shading::DepthCue(DepthCue {
            interpolation,
            ..PRESET_CUE
        });
        let mut px = vec![Rgb565::BLACK; S * S];
        Scanline::<Q16_16, S, 32, 8, 8>::new()
            .render(&scene, &cfg, &mut FrameBuffer::new(&mut px, S))
            .unwrap();
        px
    };
    let (a, p) = (
        draw(Interpolation::Affine),
        draw(Interpolation::PerspectiveCorrect),
    );
    assert!(a.iter().filter(|&&c| c != Rgb565::BLACK).count() > 5000);
    assert!(
        max_diff(&a, &p) <= 1,
        "screen-linear cue: affine and per-pixel differ by {}",
        max_diff(&a, &p)
    );
}

#[test]
fn perspective_cue_is_the_flat_colour_times_the_factor_at_each_pixels_depth() {
    struct Rows(Vec<(Vec<Rgb565>, Vec<Q16_16>)>);
    impl zrow::RowSink<Q16_16> for Rows {
        type Error = ();
        fn write_row(&mut self, r: &zrow::Row<'_, Q16_16>) -> Result<(), ()> {
            self.0.push((r.color.to_vec(), r.depth.to_vec()));
            Ok(())
        }
    }
    let p = by_name("q16").unwrap();
    let (mut cued, mut flat) = (Rows(vec![]), Rows(vec![]));
    with_preset_scene::<Q16_16, _>("mesh1k", p, |sc, cfg, _| {
        let mut r = Box::new(Scanline::<Q16_16, S, 3072, 1024, 128>::new());
        r.render(sc, cfg, &mut cued).unwrap();
        let mut f = *cfg;
        f.shading = Shading::Flat;
        r.render(sc, &f, &mut flat).unwrap();
        let cue = Cue::for_frame(sc, cfg).unwrap().unwrap();
        let mut checked = 0;
        for (y, ((c, d), (fc, _))) in cued.0.iter().zip(&flat.0).enumerate() {
            for x in 0..S {
                if d[x] != Q16_16::MAX {
                    // The cue reads the stepped plane visibility is decided on; the sink is
                    // told the exact one (the `exact-depth` feature), within half a last place
                    // of which the stepped one lies within 0.5·(1 + x + y): the colour is the
                    // factor's at a depth that near, the factor being monotone in depth.
                    let near = |k: i32| {
                        let bits = d[x].to_bits() as i64 + k as i64 * (2 + x as i64 + y as i64) / 2;
                        shade(fc[x], cue.at_depth(Q16_16::from_bits(bits as i32)))
                    };
                    let (lo, hi) = (near(-1), near(1));
                    let within = |v: u8, a: u8, b: u8| a.min(b) <= v && v <= a.max(b);
                    assert!(
                        within(c[x].r(), lo.r(), hi.r())
                            && within(c[x].g(), lo.g(), hi.g())
                            && within(c[x].b(), lo.b(), hi.b()),
                        "({x}, {y}): {:?} outside {lo:?}..{hi:?}",
                        c[x]
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 5000);
    });
}

#[test]
fn bad_depth_cue_parameters_are_bad_config() {
    let base = Config::model(64, 64);
    for (near, far, floor) in [
        (3.0, 3.0, 0.2),
        (6.0, 3.0, 0.2),
        (3.0, 6.0, 1.5),
        (f32::NAN, 6.0, 0.2),
        (3.0, f32::INFINITY, 0.2),
        (3.0, 6.0, -0.1),
    ] {
        let mut cfg = base;
        cfg.shading = Shading::DepthCue(DepthCue {
            near,
            far,
            floor,
            interpolation: Interpolation::Affine,
        });
        assert_eq!(
            cfg.validate(64),
            Err(Error::BadConfig),
            "{near} {far} {floor}"
        );
    }
}

#[test]
fn linear_w_depth_is_wrong_between_vertices_and_inverse_w_is_not() {
    // The tradeoff tool measures this on whole scenes; here the mapping itself: one receding
    // face, depth at its pixels against the exact mapping of the exact w. Under 1/w the error
    // stays a few LSB of the geometry; linear in w it grows to many thousands in mid-face.
    let q16 = by_name("q16").unwrap();
    let lin = by_name("q16-linear-w").unwrap();
    assert_eq!(lin.depth, DepthMapping::LinearW);
    let spread = |p: &zrow::presets::Preset| {
        let mut depths = vec![];
        struct D<'a>(&'a mut Vec<Q16_16>);
        impl zrow::RowSink<Q16_16> for D<'_> {
            type Error = ();
            fn write_row(&mut self, r: &zrow::Row<'_, Q16_16>) -> Result<(), ()> {
                self.0.extend_from_slice(r.depth);
                Ok(())
            }
        }
        with_preset_scene::<Q16_16, _>("cube", p, |sc, cfg, _| {
            Scanline::<Q16_16, S, 256, 64, 64>::new()
                .render(sc, cfg, &mut D(&mut depths))
                .unwrap();
        });
        depths
    };
    let (a, b) = (spread(q16), spread(lin));
    // Same coverage, different depth values.
    assert_eq!(
        a.iter().filter(|&&z| z != Q16_16::MAX).count(),
        b.iter().filter(|&&z| z != Q16_16::MAX).count()
    );
    assert!(a.iter().zip(&b).any(|(x, y)| x != y));
}

#[test]
fn micromath_and_libm_error_bounds() {
    // The bounds MathLib's documentation states, checked on ±2π (trig) and 1e-6..1e6 (sqrt).
    let (mut sin_m, mut sin_l, mut tan_m, mut sqrt_m) = (0f64, 0f64, 0f64, 0f64);
    for k in -20_000..=20_000 {
        let x = k as f32 * (std::f32::consts::TAU / 20_000.0);
        let e = (x as f64).sin();
        sin_m = sin_m.max((MathLib::Micromath.sin(x) as f64 - e).abs());
        sin_l = sin_l.max((MathLib::Libm.sin(x) as f64 - e).abs());
        let xt = k as f32 * (1.4 / 20_000.0); // tan away from its poles: |x| ≤ 1.4
        let et = (xt as f64).tan();
        if et.abs() > 1e-3 {
            tan_m = tan_m.max(((MathLib::Micromath.tan(xt) as f64 - et) / et).abs());
        }
    }
    for k in 0..=12_000 {
        let v = 10f32.powf(-6.0 + k as f32 / 1000.0);
        let got = MathLib::Micromath.sqrt::<f32>(v) as f64;
        sqrt_m = sqrt_m.max(((got - (v as f64).sqrt()) / (v as f64).sqrt()).abs());
        let exact = MathLib::Libm.sqrt::<f32>(v) as f64;
        assert!(((exact - (v as f64).sqrt()) / (v as f64).sqrt()).abs() < 1.2e-7);
    }
    eprintln!("micromath: sin {sin_m:.2e} abs, tan {tan_m:.2e} rel, sqrt {sqrt_m:.2e} rel; libm sin {sin_l:.2e}");
    assert!(
        sin_m <= 0.002 && sin_m > 1e-5,
        "micromath sin error {sin_m}"
    );
    assert!(sin_l <= 2.4e-7, "libm sin error {sin_l}");
    assert!(tan_m <= 0.015, "micromath tan error {tan_m}");
    assert!(
        sqrt_m <= 0.07 && sqrt_m > 1e-3,
        "micromath sqrt error {sqrt_m}"
    );
    assert_eq!(PRESETS.len(), 10);
}
