//! A scan-line renderer without the affine depth cue's per-edge state (`Uncued`): 20 bytes
//! less per active slot (32-bit formats), the same frames bit for bit wherever it needs no
//! such state (flat shading, the perspective-correct cue), and a typed error, before any row,
//! for a frame that asks for the affine cue.

mod common;
use common::Capture;
use zrow::scanline::{ram_bytes, ram_bytes_uncued, Uncued};
use zrow::shading::Interpolation;
use zrow::{requirements, Error, RenderError, Scanline, Q16_16};

type Cued = Scanline<Q16_16, 240, 600, 600, 128>;
type Plain = Scanline<Q16_16, 240, 600, 600, 128, u16, Uncued>;

#[test]
fn uncued_is_smaller_by_the_cue_state() {
    assert_eq!(Cued::RAM_BYTES - Plain::RAM_BYTES, 128 * 20);
    let req = zrow_scenes::with_scene::<Q16_16, _>("mesh1k", 0.3, |s, c, _| requirements(s, c))
        .unwrap()
        .unwrap();
    assert_eq!(
        ram_bytes::<Q16_16>(&req) - ram_bytes_uncued::<Q16_16>(&req),
        20 * req.active_polygons as usize
    );
    type Exact = zrow::scanline_for!(Q16_16, zrow_scenes::DEMO_MEASURED, uncued);
    let formula = ram_bytes_uncued::<Q16_16>(&zrow_scenes::DEMO_MEASURED);
    assert!(formula <= Exact::RAM_BYTES && Exact::RAM_BYTES <= formula + 32);
}

fn frame<N: zrow_scenes::Format, R: zrow::Renderer<N>>(
    r: &mut R,
    name: &str,
    preset: &zrow::presets::Preset,
) -> Result<Capture<N>, RenderError<()>> {
    zrow_scenes::with_preset_scene::<N, _>(name, preset, |scene, cfg, _| {
        let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
        r.render(scene, cfg, &mut cap).map(|_| cap)
    })
    .unwrap()
}

#[test]
fn uncued_draws_what_it_can_bit_for_bit_and_refuses_the_affine_cue() {
    let (mut cued, mut plain) = (Box::new(Cued::new()), Box::new(Plain::new()));
    let mut refused = 0;
    for preset in zrow::presets::PRESETS
        .iter()
        .filter(|p| p.format == zrow::presets::Format::Q16_16)
    {
        for name in zrow_scenes::PRESET_SCENES {
            let want = frame::<Q16_16, _>(&mut *cued, name, preset).expect("the cued renderer");
            let got = frame::<Q16_16, _>(&mut *plain, name, preset);
            if preset.intensity == Interpolation::Affine {
                let Err(RenderError::Scene(Error::Unsupported { feature })) = got else {
                    panic!("{} {name}: the affine cue was not refused", preset.name);
                };
                assert!(feature.contains("Uncued"), "{feature}");
                refused += 1;
            } else {
                let got = got.expect("the uncued renderer");
                assert!(got.drawn() > 1000, "{} {name}", preset.name);
                assert_eq!(got.color, want.color, "{} {name}", preset.name);
            }
        }
    }
    assert!(refused > 0, "no preset uses the affine cue");
    // Flat shading, the demo's.
    for name in zrow_scenes::DEMOS {
        let draw = |r: &mut dyn FnMut(
            &dyn zrow::Scene<Q16_16>,
            &zrow::Config,
        ) -> Vec<zrow::pixelcolor::Rgb565>| {
            zrow_scenes::with_demo::<Q16_16, _>(name, 0.4, |s, c, _| r(s, c)).unwrap()
        };
        let a = draw(&mut |s, c| {
            let mut cap = Capture::<Q16_16>::new(240, 240);
            cued.render(s, c, &mut cap).unwrap();
            cap.color
        });
        let b = draw(&mut |s, c| {
            let mut cap = Capture::<Q16_16>::new(240, 240);
            plain.render(s, c, &mut cap).unwrap();
            cap.color
        });
        assert_eq!(a, b, "{name}");
    }
}
