//! The wire encoding, and every typed error the sink returns.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{Config, Face, Mesh, RenderError, Row, RowSink, Scanline, ScreenScene, Vec3, Q16_16};
use zrow_st7789::mock::{MockBus, MockDc, MockSpi, MockSpiError};
use zrow_st7789::{encode_row, line_bytes, Error, St7789Rows, StreamError, Window};

#[test]
fn encode_row_is_big_endian_rgb565() {
    let row = [
        Rgb565::new(31, 0, 0),
        Rgb565::new(0, 63, 0),
        Rgb565::new(0, 0, 31),
        Rgb565::new(0b10101, 0b110011, 0b01010),
        Rgb565::WHITE,
    ];
    let mut out = [0u8; 10];
    assert_eq!(encode_row(&row, &mut out), 10);
    assert_eq!(
        out,
        [
            0xF8,
            0x00,
            0x07,
            0xE0,
            0x00,
            0x1F,
            0b1010_1110,
            0b0110_1010,
            0xFF,
            0xFF
        ]
    );
    // A short buffer takes whole pixels only, and says how many bytes.
    let mut short = [0u8; 5];
    assert_eq!(encode_row(&row, &mut short), 4);
    assert_eq!(short, [0xF8, 0x00, 0x07, 0xE0, 0x00]);
    assert_eq!(encode_row(&[], &mut out), 0);
}

type Panel<const B: usize> = St7789Rows<MockSpi, MockDc, B>;

fn panel<const B: usize>(bus: &MockBus, window: Window) -> Result<Panel<B>, StreamError> {
    St7789Rows::new(bus.spi(), bus.dc(), window)
}

#[test]
fn buffer_too_small_and_bad_windows() {
    let bus = MockBus::new();
    assert_eq!(
        panel::<479>(&bus, Window::new(240, 240)).err(),
        Some(StreamError::BufferTooSmall {
            needed: 480,
            capacity: 479
        })
    );
    assert!(panel::<{ line_bytes(240) }>(&bus, Window::new(240, 240)).is_ok());
    assert!(panel::<480>(&bus, Window::new(240, 320)).is_ok());
    for bad in [
        Window::new(0, 10),
        Window::new(10, 0),
        Window::new(241, 10),
        Window::new(240, 321),
        Window::new(240, 240).with_offset(1, 0),
        Window::new(240, 240).with_offset(0, 81),
        Window::new(10, 10).with_offset(u16::MAX, u16::MAX),
    ] {
        assert_eq!(
            panel::<480>(&bus, bad).err(),
            Some(StreamError::BadWindow),
            "{bad:?}"
        );
    }
    assert!(panel::<480>(&bus, Window::new(240, 240).with_offset(0, 80)).is_ok());
    assert_eq!(bus.writes(), &[], "nothing sent");
    // The same check in a const context.
    const _: () = assert!(Window::new(135, 240).with_offset(52, 40).check(270).is_ok());
    const _: () = assert!(Window::new(135, 240).check(269).is_err());
}

fn row(y: u16, pixels: &[Rgb565], depth: &[f32]) -> Row<'static, f32> {
    // Leak for a 'static row in tests: small and bounded.
    Row {
        y,
        color: Vec::leak(pixels.to_vec()),
        depth: Vec::leak(depth.to_vec()),
    }
}

#[test]
fn rows_out_of_order_wrong_length_outside_a_frame() {
    let bus = MockBus::new();
    let mut p = panel::<32>(&bus, Window::new(16, 3)).unwrap();
    p.init(&mut bus.delay()).unwrap();
    let px = [Rgb565::RED; 16];
    let z = [0.0f32; 16];
    type E = Error<MockSpiError, core::convert::Infallible>;
    let no_frame: Result<(), E> = Err(Error::Stream(StreamError::NoFrame));
    assert_eq!(p.write_row(&row(0, &px, &z)), no_frame);

    p.begin_frame().unwrap();
    bus.clear_writes();
    assert_eq!(p.write_row(&row(0, &px, &z)), Ok(()));
    assert_eq!(
        p.write_row(&row(2, &px, &z)),
        Err(Error::Stream(StreamError::OutOfOrder {
            expected: 1,
            got: 2
        }))
    );
    assert_eq!(
        p.write_row(&row(0, &px, &z)),
        Err(Error::Stream(StreamError::OutOfOrder {
            expected: 1,
            got: 0
        }))
    );
    assert_eq!(
        p.write_row(&row(1, &px[..15], &z[..15])),
        Err(Error::Stream(StreamError::WrongLength {
            expected: 16,
            got: 15
        }))
    );
    assert_eq!(bus.writes().len(), 1, "a refused row sends nothing");
    assert_eq!(p.next_row(), Some(1), "still waiting for row 1");
    p.write_row(&row(1, &px, &z)).unwrap();
    p.write_row(&row(2, &px, &z)).unwrap();
    assert_eq!(p.next_row(), None);
    assert_eq!(
        p.write_row(&row(3, &px, &z)),
        no_frame,
        "after the last row"
    );
    assert_eq!(bus.model().errors(), &[]);
    assert_eq!(bus.model().writes_at(15, 2), 1);
    // Restarting a frame after an error works.
    p.begin_frame().unwrap();
    assert_eq!(p.next_row(), Some(0));
}

#[test]
fn renderer_reports_the_sink_error() {
    let q = |x, y| Vec3::<Q16_16>::from_f32([x, y, 1.0]).unwrap();
    let vertices = [q(0.0, 0.0), q(30.0, 0.0), q(0.0, 30.0)];
    let faces = [Face {
        indices: &[0u16, 1, 2],
        color: Rgb565::BLUE,
        alpha: 255,
    }];
    let scene = ScreenScene {
        mesh: Mesh::new(&vertices, &faces),
    };
    let mut r = Scanline::<Q16_16, 64, 8, 4, 4>::new();
    let bus = MockBus::new();
    let mut p = panel::<128>(&bus, Window::new(64, 32)).unwrap();
    p.init(&mut bus.delay()).unwrap();

    // No begin_frame.
    let e = r
        .render(&scene, &Config::screen(64, 32), &mut p)
        .unwrap_err();
    assert!(matches!(
        e,
        RenderError::Sink(Error::Stream(StreamError::NoFrame))
    ));
    // A frame narrower than the window.
    p.begin_frame().unwrap();
    let e = r
        .render(&scene, &Config::screen(48, 32), &mut p)
        .unwrap_err();
    assert!(matches!(
        e,
        RenderError::Sink(Error::Stream(StreamError::WrongLength {
            expected: 64,
            got: 48
        }))
    ));
    // The bus fails.
    p.begin_frame().unwrap();
    bus.fail_spi(true);
    let e = r
        .render(&scene, &Config::screen(64, 32), &mut p)
        .unwrap_err();
    assert!(matches!(
        e,
        RenderError::Sink(Error::Spi(MockSpiError::Injected))
    ));
    assert!(matches!(
        p.begin_frame(),
        Err(Error::Spi(MockSpiError::Injected))
    ));
    assert_eq!(
        p.next_row(),
        None,
        "a failed begin_frame leaves no frame open"
    );
    bus.fail_spi(false);
    p.begin_frame().unwrap();
    r.render(&scene, &Config::screen(64, 32), &mut p).unwrap();
    assert_eq!(bus.model().pixel(1, 1), Some(Rgb565::BLUE));
    assert_eq!(bus.model().pixel(40, 1), Some(Rgb565::BLACK));
    // Refused rows and failed writes reached the panel as nothing at all: a clean stream.
    assert_eq!(bus.model().errors(), &[]);
}

#[test]
fn errors_say_what_happened() {
    let e: Error<MockSpiError, core::convert::Infallible> = StreamError::BufferTooSmall {
        needed: 480,
        capacity: 240,
    }
    .into();
    assert_eq!(e.to_string(), "line buffer of 240 bytes, a row needs 480");
    assert_eq!(
        Error::<MockSpiError, core::convert::Infallible>::Spi(MockSpiError::Injected).to_string(),
        "SPI error: Injected"
    );
}
