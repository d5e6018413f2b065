//! Bytes on the wire per frame, whole frames against only the changed rows
//! ([`CoherentRows`]), for each demo scene over the board's first 200 frames (0.03 rad a
//! frame), counted by the panel model; and the time those bytes take on SPI at 50 MHz
//! (8 clocks a byte, back to back as DMA sends them; DC changes and the command writes'
//! polling not counted). Prints the README's table:
//!
//! ```sh
//! cargo run --release -p zrow-st7789 --example wire
//! ```

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{FrameBuffer, Row, RowSink, Scanline, Q16_16};
use zrow_st7789::mock::MockBus;
use zrow_st7789::{CoherentRows, Window};

const WINDOW: Window = Window::new(240, 240);
const FRAMES: u32 = 200;
const SPI_HZ: f64 = 50e6;

/// The coherent sink, and a copy of the frame to check the panel against.
struct Both<'a, S> {
    sink: &'a mut S,
    copy: FrameBuffer<'a>,
}

impl<N, S: RowSink<N>> RowSink<N> for Both<'_, S> {
    type Error = S::Error;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), S::Error> {
        let _ = self.copy.write_row(row);
        self.sink.write_row(row)
    }
}

fn main() {
    let mut renderer = Box::new(Scanline::<Q16_16, 240, 4096, 1024, 512>::new());
    let ms = |bytes: f64| bytes * 8.0 / SPI_HZ * 1e3;
    // A whole frame: CASET, RASET (5 bytes each), RAMWR and 240 rows of 480 bytes.
    let whole = (5 + 5 + 1 + 240 * 480) as f64;
    println!(
        "| demo scene ({FRAMES} frames) | whole frame | changed rows only: mean | min | max | \
         SPI at 50 MHz, whole → mean |"
    );
    println!("|---|---|---|---|---|---|");
    for name in zrow_scenes::DEMOS {
        let bus = MockBus::new();
        let mut rows = CoherentRows::<_, _, 480, 240>::new(bus.spi(), bus.dc(), WINDOW)
            .expect("a 240x240 window");
        rows.init(&mut bus.delay())
            .expect("the mock bus does not fail");
        let (mut total, mut least, mut most) = (0u64, u64::MAX, 0u64);
        for frame in 0..FRAMES {
            let before = bus.model().wire_bytes();
            let mut want = vec![Rgb565::BLACK; 240 * 240];
            rows.begin_frame();
            zrow_scenes::with_demo::<Q16_16, _>(name, frame as f32 * 0.03, |scene, cfg, _| {
                let mut both = Both {
                    sink: &mut rows,
                    copy: FrameBuffer::new(&mut want, 240),
                };
                renderer.render(scene, cfg, &mut both).expect("render");
            })
            .expect("a demo scene");
            assert_eq!(bus.model().read_window(&WINDOW), want, "{name} {frame}");
            let sent = bus.model().wire_bytes() - before;
            // The first frame goes whole; the figures are for the frames after it.
            if frame > 0 {
                total += sent;
                least = least.min(sent);
                most = most.max(sent);
            }
        }
        let mean = total as f64 / (FRAMES - 1) as f64;
        println!(
            "| {name} | {} B | {} B ({:.0} %) | {} B | {} B | {:.1} → {:.1} ms |",
            whole as u64,
            mean.round() as u64,
            100.0 * mean / whole,
            least,
            most,
            ms(whole),
            ms(mean)
        );
    }
}
