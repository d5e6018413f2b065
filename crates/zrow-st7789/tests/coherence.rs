//! Frame coherence on the wire, checked on the panel model: over 200 consecutive frames of
//! each demo scene (the board's sequence of angles), sending only the changed rows leaves the
//! panel's memory equal to a full render after every frame — through the blocking
//! `CoherentRows` sink and through the firmwares' DMA sink (`zrow_st7789::dma::DmaRows`)
//! over a link that feeds the model as a DMA engine would — with fewer bytes on the wire. The
//! first frame, and the frame after a send error, a refused DMA transfer or a command, go
//! whole.

use std::cell::RefCell;
use std::rc::Rc;

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{FrameBuffer, Row, RowSink, Scanline, Q16_16};
use zrow_st7789::dma::{DmaLink, DmaRows, RowBuf};
use zrow_st7789::mock::MockBus;
use zrow_st7789::model::St7789Model;
use zrow_st7789::{init_sequence, CoherentRows, Window};

const WINDOW: Window = Window::new(240, 240);
/// One full frame on the wire: the window, RAMWR and 240 rows of 480 bytes.
const FULL_FRAME_BYTES: u64 = 5 + 5 + 1 + 240 * 480;

/// The panel behind a [`ModelLink`] and its DC pin.
struct Panel {
    model: St7789Model,
    dc: bool,
    /// A transfer is in flight (started, not yet waited for).
    busy: bool,
    /// DC changes while a transfer was in flight (a real panel would take its last bytes
    /// with the wrong level): the sender must flush first.
    dc_changed_in_flight: u32,
}

/// A DMA engine on the panel model: a transfer's bytes reach the panel when the next send or
/// flush waits for it, with the DC level it started with; like a HAL's transfer it keeps the
/// buffer until the next send hands it back. It refuses the sends numbered in `refuse`
/// (counted from 0), as an engine reporting an error would.
struct ModelLink {
    panel: Rc<RefCell<Panel>>,
    /// The last transfer's buffer, the DC level it started with, and whether it is done.
    last: Option<(RowBuf<480>, bool, bool)>,
    sends: u32,
    refuse: Vec<u32>,
}

impl ModelLink {
    /// Waits for the transfer in flight: its bytes reach the panel.
    fn complete(&mut self) {
        if let Some((buf, dc, done @ false)) = &mut self.last {
            let mut panel = self.panel.borrow_mut();
            panel.model.feed(*dc, &buf[..]);
            panel.busy = false;
            *done = true;
        }
    }
}

impl DmaLink<480> for ModelLink {
    fn send(&mut self, buf: RowBuf<480>) -> Result<Option<RowBuf<480>>, RowBuf<480>> {
        let n = self.sends;
        self.sends += 1;
        self.complete();
        if self.refuse.contains(&n) {
            return Err(buf);
        }
        let mut panel = self.panel.borrow_mut();
        panel.busy = true;
        Ok(self.last.replace((buf, panel.dc, false)).map(|(b, ..)| b))
    }
    fn flush(&mut self) {
        self.complete();
    }
    fn write(&mut self, bytes: &[u8]) {
        let mut panel = self.panel.borrow_mut();
        assert!(!panel.busy, "bytes written past a transfer in flight");
        let dc = panel.dc;
        panel.model.feed(dc, bytes);
    }
}

struct Dc(Rc<RefCell<Panel>>);

impl embedded_hal::digital::ErrorType for Dc {
    type Error = core::convert::Infallible;
}

impl embedded_hal::digital::OutputPin for Dc {
    fn set_low(&mut self) -> Result<(), Self::Error> {
        self.set(false);
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Self::Error> {
        self.set(true);
        Ok(())
    }
}

impl Dc {
    fn set(&mut self, level: bool) {
        let mut panel = self.0.borrow_mut();
        if panel.busy && panel.dc != level {
            panel.dc_changed_in_flight += 1;
        }
        panel.dc = level;
    }
}

type Dma = DmaRows<ModelLink, Dc, 480, 240>;

/// The firmwares' DMA sink on an initialised panel model, refusing the sends in `refuse`.
fn dma_on_model(refuse: Vec<u32>) -> (Dma, Rc<RefCell<Panel>>) {
    let mut model = St7789Model::new();
    for &(cmd, params, delay_ms) in init_sequence() {
        model.feed(false, &[cmd]);
        model.feed(true, params);
        model.advance_ns(delay_ms as u64 * 1_000_000);
    }
    let panel = Rc::new(RefCell::new(Panel {
        model,
        dc: true,
        busy: false,
        dc_changed_in_flight: 0,
    }));
    let link = ModelLink {
        panel: panel.clone(),
        last: None,
        sends: 0,
        refuse,
    };
    let buf = || -> RowBuf<480> { Box::leak(Box::new([0u8; 480])) };
    let dma = DmaRows::new(link, Dc(panel.clone()), WINDOW, buf(), buf()).expect("window");
    (dma, panel)
}

/// Every row to a frame buffer and to both coherent senders, so one render feeds all three.
struct Tee<'a, S> {
    full: FrameBuffer<'a>,
    coherent: &'a mut S,
    dma: &'a mut Dma,
}

impl<N, S: RowSink<N>> RowSink<N> for Tee<'_, S>
where
    S::Error: core::fmt::Debug,
{
    type Error = ();
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        self.full.write_row(row).map_err(|_| ())?;
        self.coherent.write_row(row).expect("coherent sink");
        let Ok(()) = self.dma.write_row(row);
        Ok(())
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
        let (mut dma, panel) = dma_on_model(Vec::new());
        let (mut coherent_bytes, mut dma_bytes) = (0u64, 0u64);
        let (mut least_rows, mut partial_frames) = (u16::MAX, 0);
        for frame in 0..200u32 {
            // The firmware's angles (0.03 rad a frame).
            let angle = frame as f32 * 0.03;
            let mut want = vec![Rgb565::BLACK; 240 * 240];
            let (before, dma_before) =
                (bus.model().wire_bytes(), panel.borrow().model.wire_bytes());
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
            // The last row leaves while the next frame renders: wait for it here.
            dma.flush();
            assert_eq!(
                bus.model().read_window(&WINDOW),
                want,
                "{name} frame {frame}"
            );
            let panel = panel.borrow();
            let got = panel.model.read_window(&WINDOW);
            let wrong: Vec<usize> = (0..got.len()).filter(|&i| got[i] != want[i]).collect();
            assert!(
                wrong.is_empty(),
                "{name} frame {frame} (DMA): {} pixels differ, the first at row {}",
                wrong.len(),
                wrong.first().map_or(0, |i| i / 240)
            );
            let (sent, dma_sent) = (
                bus.model().wire_bytes() - before,
                panel.model.wire_bytes() - dma_before,
            );
            assert_eq!(dma.rows_sent, u32::from(rows.rows_sent()), "{name} {frame}");
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
        let panel = panel.borrow();
        assert!(
            panel.model.errors().is_empty(),
            "{:?}",
            panel.model.errors()
        );
        assert_eq!(
            panel.dc_changed_in_flight, 0,
            "{name}: DC changed under a transfer"
        );
        assert_eq!(dma.dropped, 0);
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
fn a_refused_dma_transfer_loses_its_row_and_sends_the_next_frame_whole() {
    // Frame 0 is 240 sends (0..240); frame 1 changes rows 10..30 (sends from 240 on): the
    // engine refuses the third of them, row 12.
    let (mut dma, panel) = dma_on_model(vec![242]);
    let mut frame = |band: core::ops::Range<u16>| {
        let frame = frame_with(band);
        let Ok(()) = send_frame(&mut dma, &frame);
        dma.flush();
        let panel = panel.borrow();
        assert_eq!(panel.dc_changed_in_flight, 0);
        assert!(
            panel.model.errors().is_empty(),
            "{:?}",
            panel.model.errors()
        );
        let got = panel.model.read_window(&WINDOW);
        let wrong: Vec<usize> = (0..got.len())
            .filter(|&i| got[i] != frame[i / 240][i % 240])
            .map(|i| i / 240)
            .collect();
        (
            dma.rows_sent,
            dma.dropped,
            wrong.first().copied(),
            wrong.len(),
        )
    };
    assert_eq!(frame(10..20), (240, 0, None, 0));
    // Row 12 stays white on the panel (it should now be black): one row wrong; every row
    // after it goes, since the signatures are forgotten.
    assert_eq!(frame(20..30), (2 + 227, 1, Some(12), 240));
    // Then everything again, and the panel is right.
    assert_eq!(frame(20..30), (240, 1, None, 0));
    assert_eq!(frame(20..30), (0, 1, None, 0));
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
