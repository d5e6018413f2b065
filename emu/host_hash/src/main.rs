//! The emulated bench's frames rendered on the host: for each standard scene and number
//! format (scan-line), then for each comparison scene and compared method (Q16.16), then for
//! each preset the bench draws and preset scene (method `preset:NAME`), prints
//!
//! ```text
//! method=NAME scene=NAME format=FMT tris=N hash=HEX
//! ```
//!
//! with the same renderers (the standard one below, the compared ones from the bench's
//! `src/methods.rs` and the presets' from its `src/presets.rs`, included), the same scenes (zrow-scenes, angle 0) and the same frame
//! hash ([`zrow_scenes::FrameHash`]: FNV-1a 64 over every row's Rgb565 pixels as
//! little-endian `u16`, top to bottom) as emu/src/main.rs. `emu/check.sh` compares these lines
//! with the bench's: same core, different instruction set, same pixels.
//!
//! `ram=` is not printed: the renderer's table entries may be laid out differently on a 64-bit
//! host, so RAM is the guest's figure alone.

use std::process::ExitCode;
use zrow::presets::{DepthStore, Preset, PRESETS};
use zrow::{Renderer, Scanline, Q16_16};
use zrow_scenes::{Format, FrameHash, DEMOS, FOLEY, LINES, NAMES, PRESET_SCENES};

include!("../../src/methods.rs");
include!("../../src/presets.rs");

/// The bench's standard renderer (emu/src/main.rs): 240-pixel rows, 1024 polygons, 3072
/// edges, 512 active polygons.
type Standard<N> = Scanline<N, 240, 3072, 1024, 512>;

/// Renders `name` in format `N` with a new `R` and prints its line; false on error. Runs on
/// the caller's thread: main gives it a stack big enough for the renderers' inline tables.
fn line<N: Format, R: Renderer<N> + Default>(name: &str) -> bool {
    let mut renderer = Box::new(R::default());
    let mut sink = FrameHash::default();
    let result = zrow_scenes::with_scene::<N, _>(name, 0.0, |scene, cfg, tris| {
        if !cfg.shading.is_facets() {
            return renderer.render(scene, cfg, &mut sink).map(|_| tris);
        }
        // A frame of facets goes through the hidden-line sink, as on the bench.
        let (white, black) = (zrow::Rgb565::new(31, 63, 31), zrow::Rgb565::new(0, 0, 0));
        let mut lines = Lines::new(FrameHash::default(), cfg.height, white, black);
        let drawn = renderer.render(scene, cfg, &mut lines).map(|_| tris);
        sink = lines.into_inner();
        drawn
    });
    report::<N>("", R::NAME, name, result, sink)
}

/// Renders `preset` (its format is `N`) on every preset scene, each with a new renderer of the
/// type its depth store names, and prints a `method=preset:NAME` line per frame; false on error.
fn preset_lines<N: Format>(preset: &Preset) -> bool {
    /// One preset frame with a new `R`.
    fn draw<N: Format, R: Renderer<N> + Default>(preset: &Preset, name: &str) -> bool {
        let mut renderer = Box::new(R::default());
        let mut sink = FrameHash::default();
        let result = zrow_scenes::with_preset_scene::<N, _>(name, preset, |scene, cfg, tris| {
            renderer.render(scene, cfg, &mut sink).map(|_| tris)
        });
        report::<N>("preset:", preset.name, name, result, sink)
    }
    let mut ok = true;
    for name in PRESET_SCENES {
        ok &= match preset.store {
            DepthStore::Row32 => draw::<N, Standard<N>>(preset, name),
            DepthStore::Tile16 => draw::<N, PresetTiled<N>>(preset, name),
        };
    }
    ok
}

/// Prints a frame's line (method `{prefix}{method}`), or an error on stderr; false on error.
fn report<N: Format>(
    prefix: &str,
    method: &str,
    name: &str,
    result: Option<Result<usize, zrow::RenderError<core::convert::Infallible>>>,
    sink: FrameHash,
) -> bool {
    match result {
        Some(Ok(tris)) => {
            println!(
                "method={prefix}{method} scene={name} format={} tris={tris} hash={:016x}",
                N::NAME,
                sink.0
            );
            true
        }
        Some(Err(e)) => {
            eprintln!(
                "error method={prefix}{method} scene={name} format={}: {e:?}",
                N::NAME
            );
            false
        }
        None => {
            eprintln!("error: unknown scene {name}");
            false
        }
    }
}

fn all() -> bool {
    let mut ok = true;
    for name in NAMES {
        ok &= line::<Q16_16, Standard<Q16_16>>(name);
        ok &= line::<f32, Standard<f32>>(name);
    }
    macro_rules! run {
        ($t:ty) => {
            for name in FOLEY {
                ok &= line::<Q16_16, $t>(name);
            }
        };
    }
    for_each_method!(run);
    macro_rules! structured {
        ($t:ty, $n:ty, $scenes:expr) => {
            for name in $scenes {
                ok &= line::<$n, $t>(name);
            }
        };
    }
    for_each_structured!(structured);
    for name in LINES {
        ok &= line::<Q16_16, Standard<Q16_16>>(name);
        ok &= line::<f32, Standard<f32>>(name);
    }
    for preset in PRESETS.iter() {
        macro_rules! draw {
            ($t:ty) => {
                ok &= preset_lines::<$t>(preset)
            };
        }
        // Formats the bench skips print nothing: the lines stay the bench's.
        with_preset_format!(preset, draw, ());
    }
    for name in DEMOS.iter().filter(|name| !NAMES.contains(name)) {
        ok &= line::<Q16_16, Standard<Q16_16>>(name);
        ok &= line::<f32, Standard<f32>>(name);
    }
    ok
}

fn main() -> ExitCode {
    // `Box::new(R::default())` may build the renderer on the stack first (up to a megabyte).
    let ok = std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(all)
        .is_ok_and(|t| t.join().unwrap_or(false));
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
