//! The decoded panel frame equals the core's render of the same scene, bit for bit: small
//! scenes at 240x240 and at a smaller, offset window, the standard scenes, both formats.

mod common;

use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{Config, Scalar, Q16_16};
use zrow_st7789::mock::MockBus;
use zrow_st7789::{St7789Rows, Window};

/// Windows: the whole 240x240 module, and a small window placed off the RAM's corner.
const WINDOWS: [Window; 2] = [
    Window::new(240, 240),
    Window::new(64, 48).with_offset(30, 100),
];

fn small_scenes<N: Scalar>() {
    for window in WINDOWS {
        let cfg = Config::screen(window.width, window.height);
        for (name, polys) in [
            ("seed pair", seed_pair(window.width, window.height)),
            ("overlapping", overlapping(window.width, window.height)),
        ] {
            let both = polys.with_scene::<N, _>(|scene| render_both(scene, &cfg, window));
            both.check();
            // Not a vacuous comparison: the scene draws, in several colours.
            assert!(
                both.drawn() > both.frame.len() / 4,
                "{name} {window:?}: {} drawn",
                both.drawn()
            );
            assert!(both.colours() >= 3, "{name} {window:?}");
        }
    }
}

#[test]
fn small_scenes_q16_16() {
    small_scenes::<Q16_16>();
}

#[test]
fn small_scenes_f32() {
    small_scenes::<f32>();
}

fn standard_scenes<N: zrow_scenes::Format>() {
    for name in zrow_scenes::NAMES {
        let both = zrow_scenes::with_scene::<N, _>(name, 0.0, |scene, cfg, _| {
            render_both(scene, cfg, Window::new(cfg.width, cfg.height))
        })
        .unwrap();
        both.check();
        assert!(both.drawn() > 1000, "{name}: {} drawn", both.drawn());
    }
}

#[test]
fn standard_scenes_q16_16() {
    standard_scenes::<Q16_16>();
}

#[test]
fn standard_scenes_f32() {
    standard_scenes::<f32>();
}

/// Two frames through one sink: the second overwrites the first exactly, with the window
/// set again (the address counter back at the top-left).
#[test]
fn consecutive_frames() {
    let window = WINDOWS[1];
    let cfg = Config::screen(window.width, window.height);
    let bus = MockBus::new();
    let mut panel = St7789Rows::<_, _, B>::new(bus.spi(), bus.dc(), window).unwrap();
    panel.init(&mut bus.delay()).unwrap();
    let mut renderer = Box::new(Big::<Q16_16>::new());
    let mut last = Vec::new();
    for polys in [overlapping(64, 48), seed_pair(64, 48)] {
        bus.model_mut().clear_write_counts();
        polys.with_scene::<Q16_16, _>(|scene| {
            panel.begin_frame().unwrap();
            renderer.render(scene, &cfg, &mut panel).unwrap();
            let mut frame = vec![Rgb565::BLACK; 64 * 48];
            renderer
                .render(scene, &cfg, &mut zrow::FrameBuffer::new(&mut frame, 64))
                .unwrap();
            last = frame;
        });
        let model = bus.model();
        assert_eq!(model.read_window(&window), last);
        assert_eq!(model.errors(), &[]);
        assert_eq!(model.writes_at(30, 100), 1);
        assert_eq!(model.writes_at(30 + 63, 100 + 47), 1);
    }
}

/// `encode_row` (two pixels a word) against the plain definition, pixel by pixel, and
/// `encode_row_signed` against it and `row_signature`: every length from 0 to 9 pixels,
/// buffers too short, exactly long enough and longer.
#[test]
fn encode_row_is_big_endian_rgb565_pixel_by_pixel() {
    use embedded_graphics_core::pixelcolor::IntoStorage;
    let pixels: Vec<Rgb565> = (0..9u16)
        .map(|i| {
            Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(
                0x1234u16.wrapping_mul(i + 7) ^ (i << 11),
            ))
        })
        .collect();
    for len in 0..=pixels.len() {
        for cap in [
            0,
            1,
            2 * len.saturating_sub(1),
            2 * len + 1,
            2 * len,
            2 * len + 3,
        ] {
            let row = &pixels[..len];
            let mut out = vec![0xAAu8; cap];
            let n = zrow_st7789::encode_row(row, &mut out);
            let whole = (cap / 2).min(len);
            assert_eq!(n, 2 * whole, "len {len} cap {cap}");
            for (k, px) in row[..whole].iter().enumerate() {
                assert_eq!(
                    out[2 * k..2 * k + 2],
                    px.into_storage().to_be_bytes(),
                    "len {len} px {k}"
                );
            }
            assert!(out[n..].iter().all(|&b| b == 0xAA), "wrote past {n}");
            // The same bytes with the signature of what was written, in one pass.
            let mut signed = vec![0xAAu8; cap];
            let (m, signature) = zrow_st7789::encode_row_signed(row, &mut signed);
            assert_eq!((m, &signed), (n, &out), "len {len} cap {cap}");
            assert_eq!(
                signature,
                zrow_st7789::coherence::row_signature(&out[..n]),
                "len {len} cap {cap}"
            );
        }
    }
}
