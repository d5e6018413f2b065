//! Renders one benchmark scene a given number of times, for counting instructions
//! deterministically with callgrind (instructions are not cycles):
//!
//! ```sh
//! cargo build --release -p zrow --example frame_cost
//! valgrind --tool=callgrind target/release/examples/frame_cost mesh1k q16.16 10
//! ```
//!
//! Prints the frame's statistics once; divide callgrind's total for `Scanline::render` by the
//! frame count. Scenes as in `benches/frame.rs`: cube, mesh1k, random400.

#[path = "../benches/scenes.rs"]
mod scenes;

use std::hint::black_box;
use zrow::{
    Config, Mesh, ModelScene, Object, Row, RowSink, Scalar, Scanline, Scene, ScreenScene, Q16_16,
};

struct Sink(u32);
impl<N> RowSink<N> for Sink {
    type Error = ();
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        self.0 = self.0.wrapping_add(black_box(row.intensity).len() as u32);
        Ok(())
    }
}

fn run<N: Scalar>(scene: &impl Scene<N>, cfg: &Config, frames: usize) {
    let mut r = Box::new(Scanline::<N, 240, 2048, 6144, 512>::new());
    let mut sink = Sink(0);
    for k in 0..frames {
        let stats = r.render(scene, cfg, &mut sink).expect("render");
        if k == 0 {
            println!("{stats:?}");
        }
    }
    black_box(sink.0);
}

fn scene_in<N: Scalar>(name: &str, frames: usize) {
    let data = match name {
        "cube" => scenes::cube::<N>(),
        "mesh1k" => scenes::torus::<N>(25, 20, 1.0, 0.4),
        "random400" => scenes::random_triangles::<N>(400, 240.0, 240.0, 100.0, 0x2545_f491),
        _ => panic!("scenes: cube, mesh1k, random400"),
    };
    let faces = data.faces();
    let mesh = Mesh {
        vertices: &data.vertices,
        faces: &faces,
    };
    if name == "random400" {
        run(&ScreenScene { mesh }, &Config::screen(240, 240), frames);
    } else {
        let objects = [Object {
            mesh: &mesh,
            transform: scenes::tilt(),
        }];
        let scene = ModelScene {
            objects: &objects,
            camera: scenes::camera(),
            light: scenes::light(),
        };
        run(&scene, &Config::model(240, 240), frames);
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("mesh1k", |s| s.as_str());
    let frames = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(10);
    match args.get(2).map_or("q16.16", |s| s.as_str()) {
        "f32" => scene_in::<f32>(name, frames),
        _ => scene_in::<Q16_16>(name, frames),
    }
}
