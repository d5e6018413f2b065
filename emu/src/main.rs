//! zrow's emulated bench: renders each standard scene once per number format with the
//! scan-line method, then the comparison scenes (Foley & van Dam's Table 15.3 at 100 and 2,500
//! polygons) once with every compared method, then every preset (`zrow::presets::PRESETS`) once
//! on every preset scene (`zrow_scenes::PRESET_SCENES`), on a QEMU Cortex-M (mps2-an386 =
//! Cortex-M4F, mps2-an385 = Cortex-M3) and prints, per frame,
//!
//! ```text
//! method=NAME scene=NAME format=FMT tris=N instructions=? ram=BYTES hash=HEX
//! ```
//!
//! - `method`: the renderer's `Renderer::NAME`. The standard scenes (`cube`, `mesh1k`,
//!   `random400`, both formats) are drawn by `scanline`: `cube` and `mesh1k` by a renderer
//!   built as a display's is ([`Display`]: no depth row), `random400`, whose rows of heavy
//!   overlap a depth row resolves far faster ([`HEAVY`]), by [`Standard`]; the comparison scenes
//!   (zrow-scenes' `FOLEY`: `foley100`, `foley2500`, Q16.16) by every method in
//!   `src/methods.rs`, one line each there; a preset's frames are `preset:NAME`, drawn as
//!   `zrow_scenes::with_preset_scene` builds and configures the scene, by the renderer its
//!   depth store names (`src/presets.rs`; formats not listed there yet are skipped with a `#`
//!   line);
//! - `tris`: the scene's face count (zrow-scenes);
//! - `instructions`: printed as `?` by the guest, which cannot count itself. The frame is
//!   bracketed by calls to [`zrow_bench_start`] and [`zrow_bench_stop`]; the qemu-icount
//!   plugin (tools/qemu-icount) counts the guest instructions executed between them, one count
//!   per pair, in order, and `emu/run.sh` puts the k-th count into the k-th `instructions=?`;
//! - `ram`: for `scanline`, `zrow::scanline::ram_bytes::<N>(&req)` with
//!   `req = zrow::requirements(..)` measured here on the guest: the renderer's tables at
//!   exactly the sizes this frame needs, plus its two rows — `ram_bytes_uncued` when the
//!   frame does not use the affine depth cue (a renderer that draws it needs no per-edge
//!   cue state: `scanline_for!(N, REQ, uncued)`), `ram_bytes_display` for the frames
//!   [`Display`] draws (no depth row either: `scanline_for!(N, REQ, display)`, as the
//!   firmware builds). For the other methods, the
//!   renderer's `RAM_BYTES` as built (capacities in `src/methods.rs`, sized for `foley2500`,
//!   and `src/presets.rs`);
//! - `hash`: FNV-1a 64 over every row's Rgb565 pixels as little-endian `u16`, top to bottom
//!   ([`zrow_scenes::FrameHash`], the same function the host check uses), 16 hex digits.
//!
//! Lines starting with `#` are informational. Two calibration pairs come first: the two markers
//! called back to back (their own overhead, in every count) and the hash sink alone over 240
//! rows (the part of every frame's count that is the bench's sink, not the renderer).
//!
//! Output goes through semihosting; the bench ends with `debug::exit` (success, or failure
//! after an `error` line or a panic), which becomes QEMU's exit status.
#![no_std]
#![no_main]

use core::any::Any;
use core::hint::black_box;
use core::sync::atomic::{compiler_fence, AtomicU32, Ordering};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::presets::{DepthStore, Preset, PRESETS};
use zrow::{Config, Renderer, Scanline, Scene, Q16_16};
use zrow_scenes::{Format, FrameHash, DEMOS, FOLEY, LINES, NAMES, PRESET_SCENES};

include!("methods.rs");
include!("presets.rs");

/// The scan-line renderer the hidden-line scenes and the presets use: 240-pixel rows, 3072
/// vertices, 1024 polygons, 512 active polygons — generous for them (the `ram=` field is what
/// a frame really needs).
type Standard<N> = Scanline<N, 240, 3072, 1024, 512>;

/// The renderer of the standard scenes without heavy overlap (cube, mesh1k: not [`HEAVY`]):
/// as a display's renderer is built, without the affine cue's per-edge state or a depth row,
/// with 12-bit slots, 1024 vertices and polygons and 128 active polygons (room for the stack: the MPS2's
/// 4 MB of RAM are nearly all statics) (`zrow::scanline_for!(N, REQ, display)`, as the
/// firmware builds it): their frames are flat and the hash sink takes colours only.
type Display<N> = zrow::scanline::Display<N, 240, 1024, 1024, 128>;

/// How often the start marker ran (printed at the end: the optimiser cannot drop the counts,
/// and the two markers' bodies differ, so LLVM cannot merge them into one address).
static STARTS: AtomicU32 = AtomicU32::new(0);
/// How often the stop marker ran.
static STOPS: AtomicU32 = AtomicU32::new(0);

/// Start marker: the plugin opens a pair at this function's first instruction. Never inlined,
/// unmangled so that scripts find it by name, fenced so the optimiser keeps the frame's memory
/// accesses after it.
#[no_mangle]
#[inline(never)]
pub extern "C" fn zrow_bench_start() {
    compiler_fence(Ordering::SeqCst);
    // One core and no interrupts: a plain load and store, no read-modify-write loop.
    STARTS.store(
        STARTS.load(Ordering::Relaxed).wrapping_add(1),
        Ordering::Relaxed,
    );
    compiler_fence(Ordering::SeqCst);
}

/// Stop marker: the plugin closes the pair at this function's first instruction. Its body
/// differs from [`zrow_bench_start`]'s (another counter), so the two keep separate addresses.
#[no_mangle]
#[inline(never)]
pub extern "C" fn zrow_bench_stop() {
    compiler_fence(Ordering::SeqCst);
    STOPS.store(
        STOPS.load(Ordering::Relaxed).wrapping_add(1),
        Ordering::Relaxed,
    );
    compiler_fence(Ordering::SeqCst);
}

/// Hashes 240 rows of 240 pixels between the markers, as the sink does in every frame: the
/// share of each frame's count that is the bench's sink rather than the renderer (on the board
/// the sink is the SPI transfer instead).
fn hash_alone() {
    let row = black_box([Rgb565::BLACK; 240]);
    let mut sink = FrameHash::default();
    zrow_bench_start();
    for _ in 0..240 {
        sink.add(black_box(&row));
    }
    zrow_bench_stop();
    black_box(sink.0);
}

/// The board's sink work on a mesh1k frame (Q16.16, angle 0), between the markers: each of its
/// 240 rows encoded for the panel (`zrow_st7789::encode_row`) or, with `coherent`, encoded and
/// signed in one pass (`encode_row_signed`, the firmware's way) and the signature compared with
/// the last frame's (`Coherence::row_signed`, after a first frame that recorded them, so this
/// frame's rows are all unchanged). The frame is rendered into
/// memory first, outside the markers. Returns the rows the coherent sender would send.
fn board_sink(coherent: bool, shelf: &mut Shelf) -> u32 {
    let mut frame = [[Rgb565::BLACK; 240]; 240];
    let drawn = zrow_scenes::with_scene::<Q16_16, _>("mesh1k", 0.0, |scene, cfg, _| {
        let mut rows = RowsInto(&mut frame);
        // The shelf's renderer, not one on the stack: the frame takes 115 KB of it already.
        let r = shelf.get::<Display<Q16_16>>()?;
        Some(r.render(scene, cfg, &mut rows).is_ok())
    })
    .flatten();
    if drawn != Some(true) {
        hprintln!("error board sink: mesh1k did not render");
    }
    let mut coherence = zrow_st7789::Coherence::<240>::new();
    let mut line = [0u8; 480];
    let record = |coherence: &mut zrow_st7789::Coherence<240>, line: &mut [u8; 480]| {
        let mut sent = 0;
        for (y, row) in frame.iter().enumerate() {
            if coherent {
                let (_, signature) = zrow_st7789::encode_row_signed(black_box(row), line);
                if coherence.row_signed(y as u16, signature) != zrow_st7789::RowAction::Skip {
                    sent += 1;
                }
            } else {
                zrow_st7789::encode_row(black_box(row), line);
            }
            black_box(&line);
        }
        sent
    };
    record(&mut coherence, &mut line);
    zrow_bench_start();
    let sent = record(&mut coherence, &mut line);
    zrow_bench_stop();
    black_box(sent)
}

/// A sink that keeps every row (for [`board_sink`]).
struct RowsInto<'a>(&'a mut [[Rgb565; 240]; 240]);

impl<N> zrow::RowSink<N> for RowsInto<'_> {
    type Error = ();
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &zrow::Row<'_, N>) -> Result<(), ()> {
        let dst = self.0.get_mut(row.y as usize).ok_or(())?;
        for (d, s) in dst.iter_mut().zip(row.color) {
            *d = *s;
        }
        Ok(())
    }
}

/// One frame's report line, without the instruction count (which the host fills in).
struct Line {
    tris: usize,
    ram: usize,
    hash: u64,
}

/// The `ram=` figure: the scan-line's formula at the frame's requirements (with the affine
/// cue's per-edge state only if the frame uses that cue, an intensity plane per polygon only
/// if it is smooth shaded), else `RAM_BYTES`; a hidden-line frame adds its sink's rows
/// ([`bench_lines`]).
fn ram<N: Format + 'static, R: Renderer<N> + 'static>(
    req: &zrow::Requirements,
    affine_cue: bool,
    smooth: bool,
) -> usize {
    if core::any::TypeId::of::<R>() == core::any::TypeId::of::<Display<N>>() {
        zrow::scanline::ram_bytes_display::<N>(req)
    } else if R::NAME == "scanline" {
        if smooth {
            zrow::scanline::ram_bytes_gouraud::<N>(req)
        } else if affine_cue {
            zrow::scanline::ram_bytes::<N>(req)
        } else {
            zrow::scanline::ram_bytes_uncued::<N>(req)
        }
    } else {
        R::RAM_BYTES
    }
}

/// Renders `scene` with `renderer` once, between the markers, into the frame hash, and
/// reports it.
fn frame<N: Format + 'static, R: Renderer<N> + 'static>(
    renderer: &mut R,
    scene: &dyn Scene<N>,
    cfg: &Config,
    tris: usize,
) -> Result<Line, &'static str> {
    frame_into(renderer, scene, cfg, tris, FrameHash::default(), |s| s.0, 0)
}

/// [`frame`] into `sink`, whose hash `hash` takes at the end and whose rows add `sink_ram`
/// to the `ram=` figure (a hidden-line frame's [`Lines`]). A function of its own so that only
/// the renderers that draw hidden lines are built for a second sink (code the optimiser lays
/// out again changes other frames' counts).
fn frame_into<N: Format + 'static, R: Renderer<N> + 'static, S: zrow::RowSink<N>>(
    renderer: &mut R,
    scene: &dyn Scene<N>,
    cfg: &Config,
    tris: usize,
    mut sink: S,
    hash: impl FnOnce(S) -> u64,
    sink_ram: usize,
) -> Result<Line, &'static str> {
    let req = zrow::requirements(scene, cfg).map_err(|_| "requirements failed")?;
    let cue = zrow::shading::Cue::for_frame(scene, cfg).map_err(|_| "cue failed")?;
    let affine_cue = cue.is_some_and(|c| c.interpolation == zrow::shading::Interpolation::Affine);
    let renderer = black_box(renderer);
    zrow_bench_start();
    let result = renderer.render(scene, cfg, &mut sink);
    zrow_bench_stop();
    black_box(&sink);
    result.map_err(|_| "render failed (capacity or scene error)")?;
    Ok(Line {
        tris,
        ram: ram::<N, R>(&req, affine_cue, cfg.shading.is_smooth()) + sink_ram,
        hash: hash(sink),
    })
}

/// Prints a frame's line (method `{prefix}{method}`), or an error line; false after an error.
fn report<N: Format>(
    prefix: &str,
    method: &str,
    name: &str,
    line: Result<Line, &'static str>,
) -> bool {
    match line {
        Ok(l) => {
            hprintln!(
                "method={prefix}{method} scene={name} format={} tris={} instructions=? ram={} hash={:016x}",
                N::NAME,
                l.tris,
                l.ram,
                l.hash
            );
            true
        }
        Err(e) => {
            hprintln!(
                "error method={prefix}{method} scene={name} format={}: {e}",
                N::NAME
            );
            false
        }
    }
}

/// Benchmarks scene `name` in format `N` with `renderer`; false after an error line.
fn bench_format<N: Format + 'static, R: Renderer<N> + 'static>(renderer: &mut R, name: &str) -> bool {
    let line = zrow_scenes::with_scene::<N, _>(name, 0.0, |scene, cfg, tris| {
        frame(renderer, scene, cfg, tris)
    });
    report::<N>("", R::NAME, name, line.unwrap_or(Err("unknown scene")))
}

/// Benchmarks hidden-line scene `name` (zrow-scenes' `LINES`: facets) in format `N` with
/// `renderer`, through the [`Lines`] sink; false after an error line.
fn bench_lines<N: Format + 'static, R: Renderer<N> + 'static>(renderer: &mut R, name: &str) -> bool {
    let line = zrow_scenes::with_scene::<N, _>(name, 0.0, |scene, cfg, tris| {
        let lines = Lines::new(FrameHash::default(), cfg.height, Rgb565::WHITE, Rgb565::BLACK);
        let rows = core::mem::size_of::<Lines>() - core::mem::size_of::<FrameHash>();
        frame_into(renderer, scene, cfg, tris, lines, |l| l.into_inner().0, rows)
    });
    report::<N>("", R::NAME, name, line.unwrap_or(Err("unknown scene")))
}

/// Renders `preset` (its format is `N`) on every preset scene with the renderer its depth store
/// names, from `shelf`, and prints a `method=preset:NAME` line per frame; false after an error
/// line.
fn bench_preset<N: Format + 'static>(shelf: &mut Shelf, preset: &Preset) -> bool {
    /// One preset frame with `renderer`.
    fn draw<N: Format + 'static, R: Renderer<N> + 'static>(
        renderer: Option<&mut R>,
        preset: &Preset,
        name: &str,
    ) -> Result<Line, &'static str> {
        let renderer = renderer.ok_or("no renderer of this format on the shelf")?;
        zrow_scenes::with_preset_scene::<N, _>(name, preset, |scene, cfg, tris| {
            frame(renderer, scene, cfg, tris)
        })
        .unwrap_or(Err("unknown scene"))
    }
    let mut ok = true;
    for name in PRESET_SCENES {
        let line = match preset.store {
            DepthStore::Row32 => draw::<N, _>(shelf.get::<Standard<N>>(), preset, name),
            DepthStore::Tile16 => draw::<N, _>(shelf.get::<PresetTiled<N>>(), preset, name),
        };
        ok &= report::<N>("preset:", preset.name, name, line);
    }
    ok
}

/// Renderers made once, each in a `cortex_m::singleton!` static of its own, and found again by
/// type: the standard scan-line renderer and the presets' tiled renderer of each format in
/// `preset_formats!` (src/presets.rs). A shelf, so that a format's scan-line renderer serves both
/// the standard scenes and the presets (the MPS2 boards have 4 MB of RAM).
struct Shelf([Option<&'static mut dyn Any>; 8]);

impl Shelf {
    /// Puts `renderer` on the first free slot; false if there is none (or no renderer).
    fn put(&mut self, renderer: Option<&'static mut dyn Any>) -> bool {
        match (renderer, self.0.iter_mut().find(|s| s.is_none())) {
            (Some(r), Some(slot)) => {
                *slot = Some(r);
                true
            }
            _ => false,
        }
    }

    /// The renderer of type `T`, if one was put.
    fn get<T: Any>(&mut self) -> Option<&mut T> {
        self.0
            .iter_mut()
            .find_map(|s| s.as_deref_mut()?.downcast_mut::<T>())
    }
}

/// The standard scenes with rows of heavy overlap (spans covering more than twice the row),
/// drawn by [`Standard`], whose depth row resolves such rows pixel by pixel: swept instead, by
/// [`Display`], random400 took 35.2 M instructions instead of 13.5 M (Q16.16, `bash emu/run.sh
/// m4`).
const HEAVY: [&str; 1] = ["random400"];

/// The error line for a standard renderer missing from the shelf; false.
fn no_renderer(format: &str, name: &str) -> bool {
    hprintln!("error method=scanline scene={name} format={format}: no renderer on the shelf");
    false
}

/// Benchmarks scene `name` in both formats with the shelf's standard renderers, as a
/// hidden-line frame ([`bench_lines`]) if `lines`; false after an error line.
fn standard(shelf: &mut Shelf, name: &str, lines: bool) -> bool {
    let q16 = match (lines, HEAVY.contains(&name)) {
        (true, _) => shelf.get::<Standard<Q16_16>>().map(|r| bench_lines(r, name)),
        (false, true) => shelf.get::<Standard<Q16_16>>().map(|r| bench_format(r, name)),
        (false, false) => shelf.get::<Display<Q16_16>>().map(|r| bench_format(r, name)),
    };
    let mut ok = q16.unwrap_or_else(|| no_renderer("Q16.16", name));
    let f32 = match (lines, HEAVY.contains(&name)) {
        (true, _) => shelf.get::<Standard<f32>>().map(|r| bench_lines(r, name)),
        (false, true) => shelf.get::<Standard<f32>>().map(|r| bench_format(r, name)),
        (false, false) => shelf.get::<Display<f32>>().map(|r| bench_format(r, name)),
    };
    ok &= f32.unwrap_or_else(|| no_renderer("f32", name));
    ok
}

/// Renders every comparison scene with renderer type `$t`, built once in a static of its own
/// (`ok` becomes false after an error line).
macro_rules! compare {
    ($ok:ident, $t:ty) => {{
        match cortex_m::singleton!(: $t = <$t>::new()) {
            Some(r) => {
                for name in FOLEY {
                    $ok &= bench_format::<Q16_16, _>(r, name);
                }
            }
            None => unreachable!("each singleton is taken once"),
        }
    }};
}

#[entry]
fn main() -> ! {
    let mut ok = true;
    let mut shelf = Shelf([const { None }; 8]);
    // One scan-line and one tiled renderer per preset format, in statics of their own.
    macro_rules! shelve {
        ([] $($variant:ident => $t:ty),* $(,)?) => {
            $(
                ok &= shelf.put(
                    cortex_m::singleton!(: Standard<$t> = Standard::new())
                        .map(|r| r as &mut dyn Any),
                );
                ok &= shelf.put(
                    cortex_m::singleton!(: PresetTiled<$t> = PresetTiled::new())
                        .map(|r| r as &mut dyn Any),
                );
                ok &= shelf.put(
                    cortex_m::singleton!(: Display<$t> = Display::new())
                        .map(|r| r as &mut dyn Any),
                );
            )*
        };
    }
    preset_formats!(shelve,);
    hprintln!(
        "# zrow emulated bench, target {}, renderer {} B (Q16.16) / {} B (f32) as built",
        env!("BENCH_TARGET"),
        Standard::<Q16_16>::RAM_BYTES,
        Standard::<f32>::RAM_BYTES
    );
    zrow_bench_start();
    zrow_bench_stop();
    hprintln!("# calibration (the two markers back to back) instructions=?");
    hash_alone();
    hprintln!("# hash sink alone (240 rows of 240 pixels) instructions=?");
    for name in NAMES {
        ok &= standard(&mut shelf, name, false);
    }
    macro_rules! run {
        ($t:ty) => {
            compare!(ok, $t)
        };
    }
    for_each_method!(run);
    macro_rules! structured {
        ($t:ty, $n:ty, $scenes:expr) => {
            match cortex_m::singleton!(: $t = <$t>::new()) {
                Some(r) => {
                    for name in $scenes {
                        ok &= bench_format::<$n, _>(r, name);
                    }
                }
                None => unreachable!("each singleton is taken once"),
            }
        };
    }
    for_each_structured!(structured);
    // The hidden-line scenes, by the standard renderer (no static of their own: the bench's
    // RAM is nearly all taken).
    for name in LINES {
        ok &= standard(&mut shelf, name, true);
    }
    for preset in PRESETS.iter() {
        macro_rules! draw {
            ($t:ty) => {
                ok &= bench_preset::<$t>(&mut shelf, preset)
            };
        }
        with_preset_format!(
            preset,
            draw,
            hprintln!(
                "# preset {}: skipped (its format is not in preset_formats! yet)",
                preset.name
            )
        );
    }
    // The board's demo scenes the standard scenes lack (`interlocked`: rows where spans meet,
    // swept), drawn by the renderer the firmware draws them with. After the presets, so that
    // the pairs before keep their numbers.
    for name in DEMOS.iter().filter(|name| !NAMES.contains(name)) {
        ok &= standard(&mut shelf, name, false);
    }
    // Last, so that the pairs before keep their numbers (the profiler's scripts count them).
    board_sink(false, &mut shelf);
    hprintln!("# board sink, mesh1k: encoding 240 rows for the panel instructions=?");
    let sent = board_sink(true, &mut shelf);
    hprintln!(
        "# board sink, mesh1k: encoding 240 rows and comparing their signatures ({sent} to send) instructions=?"
    );
    hprintln!(
        "# pairs: starts={} stops={}",
        STARTS.load(Ordering::Relaxed),
        STOPS.load(Ordering::Relaxed)
    );
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::wfi();
    }
}

/// Panics print their message through semihosting and end QEMU with a failure status.
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    hprintln!("error panic: {info}");
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
