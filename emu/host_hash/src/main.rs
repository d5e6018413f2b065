//! The emulated bench's frames rendered on the host: for each standard scene and number
//! format, prints
//!
//! ```text
//! scene=NAME format=FMT tris=N hash=HEX
//! ```
//!
//! with the same renderer capacities, the same scenes (zrow-scenes, angle 0) and the same frame
//! hash ([`zrow_scenes::FrameHash`]: FNV-1a 64 over every row's Rgb565 pixels as
//! little-endian `u16`, top to bottom) as emu/src/main.rs. `emu/check.sh` compares these lines
//! with the bench's: same core, different instruction set, same pixels.
//!
//! `ram=` is not printed: the renderer's table entries may be laid out differently on a 64-bit
//! host, so RAM is the guest's figure alone.

use std::process::ExitCode;
use zrow::{Scanline, Q16_16};
use zrow_scenes::{Format, FrameHash, NAMES};

/// The bench's renderer (emu/src/main.rs): 240-pixel rows, 1024 polygons, 3072 edges, 512
/// active polygons.
type Renderer<N> = Scanline<N, 240, 1024, 3072, 512>;

/// Renders `name` in format `N` and prints its line; false on error.
fn line<N: Format>(name: &str) -> bool {
    let mut renderer = Box::new(Renderer::<N>::new());
    let mut sink = FrameHash::default();
    let result = zrow_scenes::with_scene::<N, _>(name, 0.0, |scene, cfg, tris| {
        renderer.render(scene, cfg, &mut sink).map(|_| tris)
    });
    match result {
        Some(Ok(tris)) => {
            println!(
                "scene={name} format={} tris={tris} hash={:016x}",
                N::NAME,
                sink.0
            );
            true
        }
        Some(Err(e)) => {
            eprintln!("error scene={name} format={}: {e:?}", N::NAME);
            false
        }
        None => {
            eprintln!("error: unknown scene {name}");
            false
        }
    }
}

fn main() -> ExitCode {
    let mut ok = true;
    for name in NAMES {
        ok &= line::<Q16_16>(name);
        ok &= line::<f32>(name);
    }
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
