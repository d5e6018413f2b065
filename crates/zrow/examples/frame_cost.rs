//! Renders one benchmark scene a given number of times, for counting instructions
//! deterministically with callgrind (instructions are not cycles):
//!
//! ```sh
//! cargo build --release -p zrow --example frame_cost
//! valgrind --tool=callgrind target/release/examples/frame_cost mesh1k q16.16 10
//! ```
//!
//! Prints the frame's statistics once; divide callgrind's total for `Scanline::render` by the
//! frame count. Scenes from `zrow-scenes`: cube, mesh1k, random400, foley100, foley2500.

use std::hint::black_box;
use zrow::{Row, RowSink, Scanline, Q16_16};

struct Sink(u32);
impl<N> RowSink<N> for Sink {
    type Error = ();
    /// A display's sink, as `cargo bench`'s: colours only (a sink that reads depth also gets
    /// each visible polygon's exact depths, which cost far more on the host).
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        self.0 = self.0.wrapping_add(black_box(row.color).len() as u32);
        Ok(())
    }
}

fn run<N: zrow_scenes::Format>(name: &str, frames: usize) {
    let mut r = Box::new(Scanline::<N, 240, 12288, 4096, 512>::new());
    let mut sink = Sink(0);
    zrow_scenes::with_scene::<N, _>(name, 0.0, |scene, cfg, _| {
        for k in 0..frames {
            let stats = r.render(scene, cfg, &mut sink).expect("render");
            if k == 0 {
                println!("{stats:?}");
            }
        }
    })
    .unwrap_or_else(|| panic!("unknown scene {name}: {}", zrow_scenes::NAMES.join(", ")));
    black_box(sink.0);
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("mesh1k", |s| s.as_str());
    let frames = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(10);
    match args.get(2).map_or("q16.16", |s| s.as_str()) {
        "f32" => run::<f32>(name, frames),
        _ => run::<Q16_16>(name, frames),
    }
}
