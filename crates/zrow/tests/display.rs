//! A scan-line renderer without a depth row (`NoDepth`) and with 12-bit slots (`Slot12`), as
//! `scanline_for!(N, REQ, display)` builds it: a row's width of depths, the hierarchical depth
//! and 2 bytes a polygon less, the same colours bit for bit for a sink that takes colours only
//! — rows of heavy overlap included, which it sweeps instead of resolving against the depth
//! row — and a typed error, before any row, for a sink that reads depth or a frame with the
//! perspective-correct cue.

mod common;
use common::{Capture, Colours};
use zrow::pixelcolor::Rgb565;
use zrow::scanline::{ram_bytes_display, ram_bytes_uncued, Flat, NoDepth, Uncued};
use zrow::shading::Interpolation;
use zrow::{requirements, Error, RenderError, Scanline, Q16_16};

type Plain<N> = Scanline<N, 240, 8192, 4096, 1024, u16, Uncued>;
/// As `scanline_for!(N, REQ, display)` builds it (12-bit slots: 4,096 vertices at most).
type Display<N> = zrow::scanline::Display<N, 240, 4096, 4096, 1024>;
/// Without a depth row, with 16-bit slots (for foley2500's 7,500 vertices).
type DisplayWide<N> = Scanline<N, 240, 8192, 4096, 1024, u16, Uncued, Flat, NoDepth>;

#[test]
fn display_is_smaller_by_the_depth_row() {
    assert_eq!(
        Plain::<Q16_16>::RAM_BYTES - DisplayWide::<Q16_16>::RAM_BYTES,
        240 * 4 + 16 * 4
    );
    // 12-bit slots: 2 bytes less a polygon.
    assert_eq!(
        DisplayWide::<Q16_16>::RAM_BYTES - Display::<Q16_16>::RAM_BYTES,
        4096 * 12 + 4096 * 2
    );
    let req = zrow_scenes::with_scene::<Q16_16, _>("mesh1k", 0.3, |s, c, _| requirements(s, c))
        .unwrap()
        .unwrap();
    assert_eq!(
        ram_bytes_uncued::<Q16_16>(&req) - ram_bytes_display::<Q16_16>(&req),
        240 * 4 + 16 * 4 + 2 * req.polygons as usize
    );
    type Exact = zrow::scanline_for!(Q16_16, zrow_scenes::DEMO_MEASURED, display);
    let formula = ram_bytes_display::<Q16_16>(&zrow_scenes::DEMO_MEASURED);
    assert!(formula <= Exact::RAM_BYTES && Exact::RAM_BYTES <= formula + 32);
}

/// Both renderers' colours for scene `name` in format `N`.
fn both<N: zrow_scenes::Format, D: zrow::Renderer<N>>(
    plain: &mut Plain<N>,
    display: &mut D,
    name: &str,
) -> (Vec<Rgb565>, Vec<Rgb565>) {
    zrow_scenes::with_scene::<N, _>(name, 0.3, |s, c, _| {
        let (mut a, mut b) = (Colours(Vec::new()), Colours(Vec::new()));
        plain
            .render(s, c, &mut a)
            .expect("the renderer with a depth row");
        display.render(s, c, &mut b).expect("the renderer without");
        (a.0, b.0)
    })
    .unwrap()
}

#[test]
fn display_draws_the_same_colours_heavy_rows_included() {
    fn check<N: zrow_scenes::Format>() {
        let mut plain = Box::new(Plain::<N>::new());
        let (mut display, mut wide) = (
            Box::new(Display::<N>::new()),
            Box::new(DisplayWide::<N>::new()),
        );
        // random400 and foley2500 have rows of heavy overlap (the renderer with a depth row
        // resolves them against it); the cube has quads (a fourth corner, packed).
        let check = |name: &str, a: Vec<Rgb565>, b: Vec<Rgb565>| {
            assert_eq!(a.len(), 240 * 240, "{name}");
            assert!(a.iter().any(|&c| c != a[0]), "{name}: nothing drawn");
            assert!(a == b, "{name} ({}): the colours differ", N::NAME);
        };
        for name in zrow_scenes::NAMES {
            let (a, b) = both::<N, _>(&mut plain, &mut *display, name);
            check(name, a, b);
        }
        for name in zrow_scenes::FOLEY {
            let (a, b) = both::<N, _>(&mut plain, &mut *wide, name);
            check(name, a, b);
        }
    }
    check::<Q16_16>();
    check::<f32>();
}

#[test]
fn display_refuses_a_depth_sink_and_the_perspective_cue_before_any_row() {
    let mut display = Box::new(Display::<Q16_16>::new());
    let mut perspective = 0;
    for preset in zrow::presets::PRESETS
        .iter()
        .filter(|p| p.format == zrow::presets::Format::Q16_16)
    {
        for name in zrow_scenes::PRESET_SCENES {
            zrow_scenes::with_preset_scene::<Q16_16, _>(name, preset, |scene, cfg, _| {
                // A sink that reads depth: refused, whatever the frame.
                let mut cap = Capture::<Q16_16>::new(cfg.width as usize, cfg.height as usize);
                let got = display.render(scene, cfg, &mut cap);
                let Err(RenderError::Scene(Error::Unsupported { feature })) = got else {
                    panic!("{} {name}: a depth sink was not refused", preset.name);
                };
                assert!(feature.contains("NoDepth"), "{feature}");
                assert_eq!(cap.rows_received, 0);
                // Colours only: every preset has a depth cue. The perspective-correct one is
                // refused for want of the depth row (the affine one for want of its per-edge
                // state, as by any `Uncued` renderer).
                let mut colours = Colours(Vec::new());
                let got = display.render(scene, cfg, &mut colours);
                let Err(RenderError::Scene(Error::Unsupported { feature })) = got else {
                    panic!("{} {name}: the depth cue was not refused", preset.name);
                };
                assert!(colours.0.is_empty());
                if preset.intensity == Interpolation::PerspectiveCorrect {
                    assert!(feature.contains("perspective-correct") && feature.contains("NoDepth"));
                    perspective += 1;
                } else {
                    assert!(feature.contains("Uncued"), "{feature}");
                }
            })
            .unwrap();
        }
    }
    assert!(
        perspective > 0,
        "no preset uses the perspective-correct cue"
    );
}
