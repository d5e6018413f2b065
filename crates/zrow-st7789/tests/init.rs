//! The power-on sequence, decoded by the model; and the model's own decoding rules (window
//! wrap, split pixels, refused settings, timing), so the frame tests rest on a checked model.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_hal::delay::DelayNs;
use zrow_st7789::command::*;
use zrow_st7789::mock::MockBus;
use zrow_st7789::model::{ModelError, St7789Model};
use zrow_st7789::{init, init_sequence, St7789Rows, Window};

#[test]
fn init_sequence_is_the_standard_one() {
    let expected: &[InitStep] = &[
        (0x01, &[], 150),
        (0x11, &[], 10),
        (0x3A, &[0x55], 0),
        (0x36, &[0x00], 0),
        (0x21, &[], 0),
        (0x13, &[], 0),
        (0x29, &[], 0),
    ];
    assert_eq!(init_sequence(), expected);
}

#[test]
fn init_ends_with_display_on_16_bit_inverted() {
    let bus = MockBus::new();
    let mut panel =
        St7789Rows::<_, _, 480>::new(bus.spi(), bus.dc(), Window::new(240, 240)).unwrap();
    panel.init(&mut bus.delay()).unwrap();
    let m = bus.model();
    assert_eq!(m.errors(), &[]);
    assert_eq!(m.commands(), &[0x01, 0x11, 0x3A, 0x36, 0x21, 0x13, 0x29]);
    assert!(m.display_on());
    assert_eq!(m.colmod(), 0x55);
    assert!(m.inverted());
    assert!(!m.sleeping());
    assert!(m.normal_mode());
    assert_eq!(m.madctl(), 0x00);
    assert!(m.now_ns() >= 160_000_000);
}

#[test]
fn init_free_function_on_raw_parts() {
    let bus = MockBus::new();
    let (mut spi, mut dc) = (bus.spi(), bus.dc());
    init(&mut spi, &mut dc, &mut bus.delay()).unwrap();
    let m = bus.model();
    assert_eq!(m.errors(), &[]);
    assert!(m.display_on() && m.inverted() && m.colmod() == 0x55);
}

/// A delay that does not wait: the model catches the commands sent too soon.
#[test]
fn model_checks_the_waits() {
    struct NoDelay;
    impl DelayNs for NoDelay {
        fn delay_ns(&mut self, _: u32) {}
    }
    let bus = MockBus::new();
    init(&mut bus.spi(), &mut bus.dc(), &mut NoDelay).unwrap();
    let e = bus.model().errors().to_vec();
    assert_eq!(
        e[0],
        ModelError::TooSoon {
            command: SLPOUT,
            wait_ns: 5_000_000
        }
    );
    assert!(e.contains(&ModelError::TooSoon {
        command: SLPOUT,
        wait_ns: 120_000_000
    }));
    assert!(e.contains(&ModelError::TooSoon {
        command: COLMOD,
        wait_ns: 5_000_000
    }));
}

fn ready() -> St7789Model {
    let mut m = St7789Model::new();
    m.feed(false, &[COLMOD]);
    m.feed(true, &[0x55]);
    m
}

fn px(i: u8) -> [u8; 2] {
    Rgb565::new(i, 0, 0).into_bytes_be()
}

trait Be {
    fn into_bytes_be(self) -> [u8; 2];
}
impl Be for Rgb565 {
    fn into_bytes_be(self) -> [u8; 2] {
        let mut out = [0; 2];
        zrow_st7789::encode_row(&[self], &mut out);
        out
    }
}

/// Writes advance the column, then the row, inside the window, and wrap to its start.
#[test]
fn model_address_counter_wraps_inside_the_window() {
    let mut m = ready();
    m.feed(false, &[CASET]);
    m.feed(true, &[0, 2, 0, 3]); // columns 2..=3
    m.feed(false, &[RASET]);
    m.feed(true, &[0x01, 0x00, 0x01, 0x01]); // rows 256..=257 (high bytes matter)
    m.feed(false, &[RAMWR]);
    let bytes: Vec<u8> = (1..=5).flat_map(px).collect();
    // Split in awkward places: mid-pixel, then the rest.
    m.feed(true, &bytes[..3]);
    m.feed(true, &bytes[3..]);
    assert_eq!(m.errors(), &[]);
    assert_eq!(m.pixel(2, 256), Some(Rgb565::new(5, 0, 0))); // wrapped onto the first pixel
    assert_eq!(m.pixel(3, 256), Some(Rgb565::new(2, 0, 0)));
    assert_eq!(m.pixel(2, 257), Some(Rgb565::new(3, 0, 0)));
    assert_eq!(m.pixel(3, 257), Some(Rgb565::new(4, 0, 0)));
    assert_eq!(m.writes_at(2, 256), 2);
    assert_eq!(m.writes_at(4, 256), 0);
    assert_eq!(m.address(), (3, 256));
    // RAMWRC goes on from there; RAMWR starts again at the corner.
    m.feed(false, &[RAMWRC]);
    m.feed(true, &px(9));
    assert_eq!(m.pixel(3, 256), Some(Rgb565::new(9, 0, 0)));
    m.feed(false, &[RAMWR]);
    m.feed(true, &px(7));
    assert_eq!(m.pixel(2, 256), Some(Rgb565::new(7, 0, 0)));
    assert_eq!(m.errors(), &[]);
}

#[test]
fn model_defaults_and_swreset() {
    let mut m = St7789Model::new();
    assert_eq!((m.caset(), m.raset()), ((0, 239), (0, 319)));
    assert_eq!(m.colmod(), 0x66);
    assert!(m.sleeping() && !m.display_on() && !m.inverted());
    m.feed(false, &[COLMOD]);
    m.feed(true, &[0x55]);
    m.feed(false, &[INVON, DISPON, RAMWR]);
    m.feed(true, &[0xFF, 0xFF]);
    m.advance_ns(10_000_000);
    m.feed(false, &[SWRESET]);
    assert_eq!(m.colmod(), 0x66);
    assert!(!m.display_on() && !m.inverted());
    assert_eq!(
        m.pixel(0, 0),
        Some(Rgb565::WHITE),
        "RAM survives a software reset"
    );
    assert_eq!(m.errors(), &[]);
}

#[test]
fn model_refuses_what_it_does_not_model() {
    let mut m = St7789Model::new();
    // Pixels before COLMOD: the reset default is 18-bit.
    m.feed(false, &[RAMWR]);
    m.feed(true, &[0, 0]);
    // 18-bit COLMOD, a rotated MADCTL, an unknown command.
    m.feed(false, &[COLMOD]);
    m.feed(true, &[0x66]);
    m.feed(false, &[MADCTL]);
    m.feed(true, &[0x60]);
    m.feed(false, &[0xB2]);
    // A window past the RAM, a backwards one, a short CASET, extra bytes.
    m.feed(false, &[CASET]);
    m.feed(true, &[0, 0, 0, 240]);
    m.feed(false, &[RASET]);
    m.feed(true, &[0, 9, 0, 8]);
    m.feed(false, &[CASET]);
    m.feed(true, &[0, 0]);
    m.feed(false, &[DISPON]);
    m.feed(true, &[1]);
    // Half a pixel cut off by a command; data before any command is also caught (new model).
    m.feed(false, &[COLMOD]);
    m.feed(true, &[0x55]);
    m.feed(false, &[RAMWR]);
    m.feed(true, &[0xAB]);
    m.feed(false, &[NOP]);
    assert_eq!(
        m.errors(),
        &[
            ModelError::PixelsNot16Bit { colmod: 0x66 },
            ModelError::UnsupportedColmod(0x66),
            ModelError::UnsupportedMadctl(0x60),
            ModelError::UnknownCommand(0xB2),
            ModelError::BadAddress { command: CASET },
            ModelError::BadAddress { command: RASET },
            ModelError::MissingParams {
                command: CASET,
                got: 2,
                needed: 4
            },
            ModelError::ExtraData { command: DISPON },
            ModelError::HalfPixel { command: RAMWR },
        ]
    );
    assert_eq!(
        (m.caset(), m.raset()),
        ((0, 239), (0, 319)),
        "refused windows not applied"
    );
    let mut fresh = St7789Model::new();
    fresh.feed(true, &[1, 2]);
    assert_eq!(fresh.errors(), &[ModelError::DataWithoutCommand]);
}
