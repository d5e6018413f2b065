//! Frame coherence on the wire, checked on the panel model: over 200 consecutive frames of
//! each demo scene (the board's sequence of angles), sending only the changed rows leaves the
//! panel's memory equal to a full render after every frame — through the blocking
//! `CoherentRows` sink and through a sender built like the firmware's DMA one (`Coherence`
//! and `open_run` with its own command writes) — with fewer bytes on the wire. The first
//! frame, and the frame after a send error or a command, go whole.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{FrameBuffer, Row, RowSink, Scanline, Q16_16};
use zrow_st7789::coherence::{open_run, Coherence, RowAction};
use zrow_st7789::mock::MockBus;
use zrow_st7789::model::St7789Model;
use zrow_st7789::{encode_row, init_sequence, CoherentRows, Window};

const WINDOW: Window = Window::new(240, 240);
/// One full frame on the wire: the window, RAMWR and 240 rows of 480 bytes.
const FULL_FRAME_BYTES: u64 = 5 + 5 + 1 + 240 * 480;

/// What `firmware/src/dma_rows.rs` does per row: encode, ask `Coherence`, and for a run's
/// first row send the window (command byte DC low, parameters DC high) before the row.
struct DmaLike {
    model: St7789Model,
    coherence: Coherence<240>,
    line: [u8; 480],
}

impl DmaLike {
    fn new() -> Self {
        let mut model = St7789Model::new();
        for &(cmd, params, delay_ms) in init_sequence() {
            model.feed(false, &[cmd]);
            model.feed(true, params);
            model.advance_ns(delay_ms as u64 * 1_000_000);
        }
        DmaLike {
            model,
            coherence: Coherence::new(),
            line: [0; 480],
        }
    }
}

impl<N> RowSink<N> for DmaLike {
    type Error = ();
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        let n = encode_row(row.color, &mut self.line);
        match self.coherence.row(row.y, &self.line[..n]) {
            RowAction::Skip => return Ok(()),
            RowAction::Continue => {}
            RowAction::Open { caset } => {
                let model = &mut self.model;
                open_run(&WINDOW, row.y, caset, |c, p| -> Result<(), ()> {
                    model.feed(false, &[c]);
                    model.feed(true, p);
                    Ok(())
                })?;
            }
        }
        self.model.feed(true, &self.line[..n]);
        Ok(())
    }
}

/// Every row to a frame buffer and to both coherent senders, so one render feeds all three.
struct Tee<'a, S> {
    full: FrameBuffer<'a>,
    coherent: &'a mut S,
    dma: &'a mut DmaLike,
}

impl<N, S: RowSink<N>> RowSink<N> for Tee<'_, S>
where
    S::Error: core::fmt::Debug,
{
    type Error = ();
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        self.full.write_row(row).map_err(|_| ())?;
        self.coherent.write_row(row).expect("coherent sink");
        self.dma.write_row(row)
    }
}

#[test]
fn two_hundred_frames_of_each_demo_equal_a_full_render_every_frame() {
    let mut renderer = Box::new(Scanline::<Q16_16, 240, 4096, 1024, 512>::new());
    for name in zrow_scenes::DEMOS {
        let bus = MockBus::new();
        let mut rows =
            CoherentRows::<_, _, 480, 240>::new(bus.spi(), bus.dc(), WINDOW).expect("window");
        rows.init(&mut bus.delay()).expect("init");
        let mut dma = DmaLike::new();
        let (mut coherent_bytes, mut dma_bytes) = (0u64, 0u64);
        let (mut least_rows, mut partial_frames) = (u16::MAX, 0);
        for frame in 0..200u32 {
            // The firmware's angles (0.03 rad a frame).
            let angle = frame as f32 * 0.03;
            let mut want = vec![Rgb565::BLACK; 240 * 240];
            let (before, dma_before) = (bus.model().wire_bytes(), dma.model.wire_bytes());
            rows.begin_frame();
            zrow_scenes::with_demo::<Q16_16, _>(name, angle, |scene, cfg, _| {
                let mut tee = Tee {
                    full: FrameBuffer::new(&mut want, 240),
                    coherent: &mut rows,
                    dma: &mut dma,
                };
                renderer.render(scene, cfg, &mut tee).expect("render");
            })
            .expect("a demo scene");
            assert_eq!(
                bus.model().read_window(&WINDOW),
                want,
                "{name} frame {frame}"
            );
            assert_eq!(
                dma.model.read_window(&WINDOW),
                want,
                "{name} frame {frame} (DMA)"
            );
            let (sent, dma_sent) = (
                bus.model().wire_bytes() - before,
                dma.model.wire_bytes() - dma_before,
            );
            // Both senders send the same bytes (the same decisions, the same commands).
            assert_eq!(sent, dma_sent, "{name} frame {frame}");
            if frame == 0 {
                assert_eq!(sent, FULL_FRAME_BYTES, "{name}: the first frame goes whole");
            } else {
                // Never more than whole rows plus 11 bytes of window per run (at most 120).
                assert!(sent <= FULL_FRAME_BYTES + 120 * 11, "{name} frame {frame}");
                least_rows = least_rows.min(rows.rows_sent());
                partial_frames += usize::from(rows.rows_sent() < 240);
            }
            coherent_bytes += sent;
            dma_bytes += dma_sent;
        }
        assert!(
            bus.model().errors().is_empty(),
            "{:?}",
            bus.model().errors()
        );
        assert!(dma.model.errors().is_empty(), "{:?}", dma.model.errors());
        let full = 200 * FULL_FRAME_BYTES;
        eprintln!(
            "{name}: {} bytes a frame coherent vs {FULL_FRAME_BYTES} whole ({:.0} %), \
             fewest rows sent {least_rows}, {partial_frames} of 199 frames partial",
            coherent_bytes / 200,
            100.0 * coherent_bytes as f64 / full as f64
        );
        // The demos leave rows above and below the object unchanged.
        assert_eq!(partial_frames, 199, "{name}");
        assert!(coherent_bytes < full, "{name}");
        assert_eq!(coherent_bytes, dma_bytes);
    }
}

/// A 240-row frame: black, with rows `band` white.
fn frame_with(band: core::ops::Range<u16>) -> Vec<Vec<Rgb565>> {
    (0..240u16)
        .map(|y| {
            let c = if band.contains(&y) {
                Rgb565::WHITE
            } else {
                Rgb565::BLACK
            };
            vec![c; 240]
        })
        .collect()
}

fn send_frame<S: RowSink<Q16_16>>(sink: &mut S, frame: &[Vec<Rgb565>]) -> Result<(), S::Error> {
    for (y, px) in frame.iter().enumerate() {
        sink.write_row(&Row {
            y: y as u16,
            color: px,
            depth: &[],
        })?;
    }
    Ok(())
}

#[test]
fn only_changed_rows_go_and_an_error_or_a_command_sends_the_next_frame_whole() {
    let bus = MockBus::new();
    let mut rows = CoherentRows::<_, _, 480, 240>::new(bus.spi(), bus.dc(), WINDOW).unwrap();
    rows.init(&mut bus.delay()).unwrap();
    let sent = |rows: &mut CoherentRows<_, _, 480, 240>, frame: &[Vec<Rgb565>]| {
        let before = bus.model().wire_bytes();
        rows.begin_frame();
        send_frame(rows, frame).unwrap();
        let flat: Vec<Rgb565> = frame.concat();
        assert_eq!(bus.model().read_window(&WINDOW), flat);
        (rows.rows_sent(), bus.model().wire_bytes() - before)
    };
    assert_eq!(
        sent(&mut rows, &frame_with(10..20)),
        (240, FULL_FRAME_BYTES)
    );
    // Nothing changed: nothing on the wire.
    assert_eq!(sent(&mut rows, &frame_with(10..20)), (0, 0));
    // The band moves down by 5: rows 10..15 and 20..25 changed, two runs of 5 rows, each
    // with RASET and RAMWR (6 bytes), the first with CASET too (5).
    assert_eq!(
        sent(&mut rows, &frame_with(15..25)),
        (10, 10 * 480 + 5 + 2 * 6)
    );

    // An SPI error in the middle of a frame: the rows after it are sent (with the window
    // again), and the next frame whole.
    bus.fail_spi(true);
    rows.begin_frame();
    let frame = frame_with(100..110);
    assert!(send_frame(&mut rows, &frame).is_err());
    bus.fail_spi(false);
    assert_eq!(
        sent(&mut rows, &frame_with(100..110)),
        (240, FULL_FRAME_BYTES)
    );
    assert_eq!(sent(&mut rows, &frame_with(100..110)), (0, 0));

    // A command (someone else touched the panel): the next frame goes whole.
    rows.command(zrow_st7789::command::NORON, &[]).unwrap();
    assert_eq!(
        sent(&mut rows, &frame_with(100..110)),
        (240, FULL_FRAME_BYTES)
    );
    assert!(
        bus.model().errors().is_empty(),
        "{:?}",
        bus.model().errors()
    );
}

#[test]
fn a_refresh_period_sends_every_nth_frame_whole() {
    let bus = MockBus::new();
    let mut rows = CoherentRows::<_, _, 480, 240>::new(bus.spi(), bus.dc(), WINDOW)
        .unwrap()
        .with_refresh(4);
    rows.init(&mut bus.delay()).unwrap();
    let frame = frame_with(0..1);
    let mut counts = Vec::new();
    for _ in 0..9 {
        rows.begin_frame();
        send_frame(&mut rows, &frame).unwrap();
        counts.push(rows.rows_sent());
    }
    assert_eq!(counts, [240, 0, 0, 0, 240, 0, 0, 0, 240]);
}

#[test]
fn too_few_signatures_for_the_window_is_an_error() {
    let bus = MockBus::new();
    let e = CoherentRows::<_, _, 480, 200>::new(bus.spi(), bus.dc(), WINDOW).err();
    assert_eq!(
        e,
        Some(zrow_st7789::StreamError::TooFewSignatures {
            height: 240,
            capacity: 200
        })
    );
}

/// The panel sinks take colours only, so the renderer skips writing its depth row for them
/// (on the board that was a quarter of the mesh1k frame's cycles). Checked at compile time.
const _: () = {
    use zrow_st7789::mock::{MockDc, MockSpi};
    use zrow_st7789::St7789Rows;
    assert!(!<CoherentRows<MockSpi, MockDc, 480, 240> as RowSink<Q16_16>>::WANTS_DEPTH);
    assert!(!<St7789Rows<MockSpi, MockDc, 480> as RowSink<f32>>::WANTS_DEPTH);
};
