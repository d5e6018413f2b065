//! Replays what a firmware clocked out of SPI (a stream file of `emu/board/f411.py` or
//! `f103.py`) through the panel model and checks every frame against the host's render of the
//! same demo frame, bit for bit; then prints, per demo scene, the frames checked, the bytes on
//! the wire and the cycles per frame with the estimated frames per second at the board's clock.
//!
//! ```sh
//! cargo run --release -p zrow-st7789 --example replay -- STREAM
//! ```
//!
//! The stream's lines: `fps N` (frames per demo scene), `scenes NAME...` (the demo scenes the
//! firmware shows, in order; default all of `zrow_scenes::DEMOS`), `hclk HZ` (its clock;
//! default 100 MHz), `t NS` (the time the next bytes start),
//! `c HEX` (bytes sent with DC low), `d HEX` (DC high), `r LEVEL` (the reset pin), `b LEVEL`
//! (the backlight),
//! `f FRAME CYCLES WAITED` (frame `FRAME` is on the panel, `CYCLES` after the previous one, of
//! which the firmware spent `WAITED` waiting for the SPI or its DMA: the sending rendering did
//! not hide). Frame `k` is scene `scenes[(k / N) % scenes.len()]` at angle `zrow_scenes::board_angle(k)`, as the
//! firmware draws it.
//!
//! Exits non-zero on a frame that differs, a frame shown with the backlight off, a protocol
//! error the model saw, a panel left asleep, off or not inverted, or a malformed stream.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use std::process::ExitCode;
use zrow::{FrameBuffer, Scanline, Q16_16};
use zrow_st7789::model::St7789Model;
use zrow_st7789::Window;

#[derive(Default)]
struct Scene {
    frames: u32,
    cycles: u64,
    waited: u64,
    bytes: u64,
}

fn main() -> ExitCode {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: replay STREAM");
        return ExitCode::from(2);
    };
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("replay: {path}: {e}");
            return ExitCode::from(2);
        }
    };
    let window = Window::new(240, 240);
    let mut model = St7789Model::new();
    let mut renderer = Box::new(Scanline::<Q16_16, 240, 4096, 1024, 512>::new());
    let mut per_scene = 1u32;
    // Instructions are taken as cycles at the firmware's clock (an estimate).
    let mut hclk = 100e6;
    let mut scenes: Vec<(&str, Scene)> = zrow_scenes::DEMOS
        .iter()
        .map(|&n| (n, Scene::default()))
        .collect();
    let (mut failures, mut checked, mut bytes_at_mark) = (0u32, 0u32, 0u64);
    let mut backlight = false;
    for (n, line) in text.lines().enumerate() {
        let bad = |why: &str| {
            eprintln!("replay: {path}:{}: {why}: {line}", n + 1);
            ExitCode::from(2)
        };
        let (kind, rest) = line.split_once(' ').unwrap_or((line, ""));
        match kind {
            "#" | "" => {}
            "fps" => match rest.parse() {
                Ok(v) if v > 0 => per_scene = v,
                _ => return bad("frames per scene"),
            },
            "hclk" => match rest.parse::<f64>() {
                Ok(v) if v > 0.0 => hclk = v,
                _ => return bad("clock"),
            },
            "scenes" => {
                let named: Option<Vec<&str>> = rest
                    .split(' ')
                    .map(|n| zrow_scenes::DEMOS.iter().copied().find(|&d| d == n))
                    .collect();
                match named {
                    Some(n) if !n.is_empty() => {
                        scenes = n.into_iter().map(|n| (n, Scene::default())).collect()
                    }
                    _ => return bad("demo scene names"),
                }
            }
            "t" => match rest.parse::<u64>() {
                Ok(ns) => model.advance_ns(ns.saturating_sub(model.now_ns())),
                Err(_) => return bad("time"),
            },
            "c" | "d" => match hex(rest) {
                Some(bytes) => model.feed(kind == "d", &bytes),
                None => return bad("hex bytes"),
            },
            "r" => {}
            "b" => backlight = rest == "1",
            "f" => {
                let mut it = rest.split(' ').map(str::parse::<u64>);
                let (Some(Ok(frame)), Some(Ok(cycles)), Some(Ok(waited))) =
                    (it.next(), it.next(), it.next())
                else {
                    return bad("frame marker");
                };
                let name = scenes[(frame as u32 / per_scene) as usize % scenes.len()].0;
                let mut want = vec![Rgb565::BLACK; 240 * 240];
                let drawn = zrow_scenes::with_demo::<Q16_16, _>(
                    name,
                    zrow_scenes::board_angle(frame as u32),
                    |s, c, _| renderer.render(s, c, &mut FrameBuffer::new(&mut want, 240)),
                );
                if !matches!(drawn, Some(Ok(_))) {
                    return bad("the host could not draw this frame");
                }
                let got = model.read_window(&window);
                let wrong = got.iter().zip(&want).filter(|(g, w)| g != w).count();
                if wrong > 0 {
                    eprintln!("replay: frame {frame} ({name}): {wrong} pixels differ from the host's render");
                    failures += 1;
                }
                if !backlight {
                    eprintln!("replay: frame {frame} ({name}) shown with the backlight off");
                    failures += 1;
                }
                checked += 1;
                let wire = model.wire_bytes();
                // Frame 0 includes the boot and the panel's initialisation: not a frame time.
                if frame > 0 {
                    let s = &mut scenes
                        .iter_mut()
                        .find(|(n, _)| *n == name)
                        .expect("a demo")
                        .1;
                    s.frames += 1;
                    s.cycles += cycles;
                    s.waited += waited;
                    s.bytes += wire - bytes_at_mark;
                }
                bytes_at_mark = wire;
            }
            _ => return bad("unknown line"),
        }
    }
    for e in model.errors() {
        eprintln!("replay: protocol error: {e:?}");
        failures += 1;
    }
    if model.sleeping() || !model.display_on() || !model.inverted() {
        eprintln!(
            "replay: the panel ends asleep {}, display on {}, inverted {} (want false, true, true)",
            model.sleeping(),
            model.display_on(),
            model.inverted()
        );
        failures += 1;
    }
    println!(
        "| demo scene | frames | bytes on the wire a frame | M cycles a frame | of which waiting \
         for SPI | estimated fps at {:.0} MHz |",
        hclk / 1e6
    );
    println!("|---|---|---|---|---|---|");
    for (name, s) in scenes.iter().filter(|(_, s)| s.frames > 0) {
        let f = s.frames as f64;
        let cycles = s.cycles as f64 / f;
        println!(
            "| {name} | {} | {} | {:.2} | {:.2} | {:.0} |",
            s.frames,
            (s.bytes as f64 / f).round() as u64,
            cycles / 1e6,
            s.waited as f64 / f / 1e6,
            hclk / cycles
        );
    }
    println!("replay: {checked} frames checked against the host's render, {failures} failures");
    if failures > 0 || checked == 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// `"0a1b"` → `[0x0a, 0x1b]`.
fn hex(s: &str) -> Option<Vec<u8>> {
    if s.len() % 2 != 0 {
        return None;
    }
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(s.get(i..i + 2)?, 16).ok())
        .collect()
}
