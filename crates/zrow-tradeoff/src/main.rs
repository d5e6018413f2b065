//! # zrow-tradeoff — the presets' speed–accuracy trade, measured
//!
//! ```text
//! bash emu/run.sh m4      # the emulated Cortex-M4's instruction counts (optional, first)
//! cargo run --release -p zrow-tradeoff -- --out docs/presets
//! ```
//!
//! For every preset in [`zrow::presets::PRESETS`] and every scene in
//! [`zrow_scenes::PRESET_SCENES`] (240 × 240, depth cue [`zrow_scenes::PRESET_CUE`]):
//!
//! - **cost**: host time per frame (median of repeated renders on this machine, release) and
//!   the emulated Cortex-M4's instructions per frame (read from `emu/target/bench-m4.txt`,
//!   lines `method=preset:NAME`; instructions, not cycles);
//! - **error** against an exact `f64` reference ([`mod@reference`]): coverage errors judged with
//!   the dEQP three-state rule (missing FULL pixels, extra NONE pixels), pixels showing the
//!   wrong surface, depth error in LSB of the preset's depth format, intensity error in LSB of
//!   the Rgb565 channels; plus per preset the pixels drawn twice or missed by a watertight fan
//!   (`docs/extremes.md` item 4) and the depth-resolution threshold (item 17) beside its theory.
//!
//! Then smooth shading (dithered or not) and hidden lines on the torus, their cost and error
//! against the same kind of reference ([`mod@shading`]).
//!
//! It writes `OUT/presets.md` (the Pareto table and the details) and `OUT/presets.png` (cost
//! against error, one point per preset) and prints the table. Options: `--out DIR`,
//! `--emu FILE`, `--quick` (one scene, short timing: a smoke test, not a measurement).

/// The PNG font loader, zrow-compare's own file (one copy for both tools).
#[path = "../../zrow-compare/src/font.rs"]
mod font;
mod measure;
mod plot;
mod reference;
mod render;
mod shading;

use measure::{Errors, Threshold};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Duration;
use zrow::presets::{Preset, PRESETS};

/// One preset's results.
pub struct Row {
    /// The preset.
    pub preset: Preset,
    /// Per scene: errors, host time, instructions.
    pub scenes: Vec<(String, Errors, Duration, Option<u64>)>,
    /// RAM of the renderer as built (capacities for the largest scene).
    pub ram: usize,
    /// Fan: drawn twice, holes, extra.
    pub fan: (u32, u32, u32),
    /// Depth-resolution threshold.
    pub threshold: Threshold,
}

impl Row {
    /// Mean instructions per frame over the scenes (if all were measured).
    pub fn instructions(&self) -> Option<f64> {
        let v: Option<Vec<u64>> = self.scenes.iter().map(|s| s.3).collect();
        v.map(|v| v.iter().sum::<u64>() as f64 / v.len() as f64)
    }
    /// Mean host time per frame, µs.
    pub fn host_us(&self) -> f64 {
        self.scenes.iter().map(|s| s.2.as_secs_f64()).sum::<f64>() / self.scenes.len() as f64 * 1e6
    }
    /// Mean pixels in error per frame.
    pub fn error_pixels(&self) -> f64 {
        self.scenes.iter().map(|s| s.1.pixels() as f64).sum::<f64>() / self.scenes.len() as f64
    }
}

fn emu_counts(path: &PathBuf) -> BTreeMap<(String, String), u64> {
    let mut out = BTreeMap::new();
    let Ok(text) = std::fs::read_to_string(path) else {
        return out;
    };
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let field = |key: &str| {
            line.split_whitespace()
                .find_map(|kv| kv.strip_prefix(key)?.strip_prefix('='))
        };
        if let (Some(m), Some(s), Some(i)) =
            (field("method"), field("scene"), field("instructions"))
        {
            if let (Some(p), Ok(i)) = (m.strip_prefix("preset:"), i.parse()) {
                out.insert((p.to_string(), s.to_string()), i);
            }
        }
    }
    out
}

fn main() {
    if let Err(e) = run() {
        eprintln!("zrow-tradeoff: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let mut out = PathBuf::from("docs/presets");
    let mut emu = PathBuf::from("emu/target/bench-m4.txt");
    let mut quick = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--out" => out = args.next().ok_or("--out needs a directory")?.into(),
            "--emu" => emu = args.next().ok_or("--emu needs a file")?.into(),
            "--quick" => quick = true,
            _ => return Err(format!("unknown argument {a} (see the crate docs)")),
        }
    }
    plot::init_font()?;
    let counts = emu_counts(&emu);
    let scenes: &[&str] = if quick {
        &zrow_scenes::PRESET_SCENES[..1]
    } else {
        &zrow_scenes::PRESET_SCENES
    };
    let time_for = Duration::from_millis(if quick { 20 } else { 1500 });
    // References per (scene, sub-pixel bits).
    let mut refs = BTreeMap::new();
    let mut rows = vec![];
    for p in &PRESETS {
        let mut row_scenes = vec![];
        let mut ram = 0;
        for &name in scenes {
            let key = (name, p.subpixel_bits);
            if let std::collections::btree_map::Entry::Vacant(v) = refs.entry(key) {
                let r = measure::reference_of(name, p.subpixel_bits)
                    .ok_or(format!("no reference for {name}"))?;
                v.insert(r);
            }
            let (rs, rp) = &refs[&key];
            let got = render::run(p, name, time_for)?;
            ram = ram.max(got.ram);
            let e = measure::errors(p, rs, rp, &got);
            let instr = counts.get(&(p.name.to_string(), name.to_string())).copied();
            eprintln!(
                "{:14} {:12} {:>9.1} µs  missing {} extra {} wrong {} depth {:.2} LSB  intensity {:.2}",
                p.name,
                name,
                got.host.as_secs_f64() * 1e6,
                e.missing,
                e.extra,
                e.wrong_surface,
                e.depth_max_lsb,
                e.intensity_max
            );
            row_scenes.push((name.to_string(), e, got.host, instr));
        }
        let fan = measure::fan(p, 40, 0x5eed)?;
        let threshold = measure::threshold(p)?;
        rows.push(Row {
            preset: *p,
            scenes: row_scenes,
            ram,
            fan,
            threshold,
        });
    }
    let bench = std::fs::read_to_string(&emu).unwrap_or_default();
    let shaded = shading::rows(&bench, time_for)?;
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let md = report(&rows, &emu, quick) + &shading::report(&shaded);
    print!("{md}");
    let md_path = out.join("presets.md");
    std::fs::write(&md_path, md).map_err(|e| format!("{}: {e}", md_path.display()))?;
    plot::pareto(&rows, &out.join("presets.png"))?;
    eprintln!("wrote {} and presets.png", md_path.display());
    Ok(())
}

/// Presets no other preset beats on both cost and error. Cost is the emulated M4's
/// instructions where every preset has them, else host time; with M4 counts for only some
/// presets, those without are not judged (`None`).
fn pareto(rows: &[Row]) -> Vec<Option<bool>> {
    let any_m4 = rows.iter().any(|r| r.instructions().is_some());
    let cost = |r: &Row| {
        if any_m4 {
            r.instructions()
        } else {
            Some(r.host_us())
        }
    };
    rows.iter()
        .map(|a| {
            let ca = cost(a)?;
            Some(!rows.iter().any(|b| {
                cost(b).is_some_and(|cb| {
                    (cb <= ca && b.error_pixels() <= a.error_pixels())
                        && (cb < ca || b.error_pixels() < a.error_pixels())
                })
            }))
        })
        .collect()
}

fn knobs(p: &Preset) -> String {
    format!(
        "{:?} / S={} / {:?} / {:?} / {:?} / {:?}",
        p.format, p.subpixel_bits, p.store, p.depth, p.math, p.intensity
    )
}

fn report(rows: &[Row], emu: &std::path::Path, quick: bool) -> String {
    let mut s = String::new();
    let front = pareto(rows);
    let _ = writeln!(s, "# Presets: cost against error\n");
    let _ = writeln!(
        s,
        "Written by `cargo run --release -p zrow-tradeoff -- --out docs/presets` (after \
         `bash emu/run.sh m4` for the instruction counts){}. Scenes: {} at 240 × 240, depth cue \
         {:?}. Host: this machine, release build, median per frame (host figures on the 2-core CI \
         VM vary about ±30 % between runs). M4: QEMU mps2-an386 instruction counts from `{}` \
         (instructions, not cycles). Error: against an exact f64 reference (exact trig, no \
         snapping), dEQP three-state coverage with a tolerance of one sub-pixel.\n",
        if quick {
            " — QUICK RUN: one scene, short timing, not a measurement"
        } else {
            ""
        },
        zrow_scenes::PRESET_SCENES.join(", "),
        zrow_scenes::PRESET_CUE,
        emu.display()
    );
    let _ = writeln!(s, "## Pareto table (means over the scenes)\n");
    let _ = writeln!(
        s,
        "| preset | Pareto | M4 instr./frame | host µs/frame | RAM (B) | pixels in error | missing | extra | wrong surface | depth err. max (LSB) | intensity err. max / mean (LSB) | fan twice / holes | Δw threshold measured / theory |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (r, &f) in rows.iter().zip(&front) {
        let n = r.scenes.len() as f64;
        let mean = |g: &dyn Fn(&Errors) -> f64| r.scenes.iter().map(|x| g(&x.1)).sum::<f64>() / n;
        let max = |g: &dyn Fn(&Errors) -> f64| r.scenes.iter().map(|x| g(&x.1)).fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {:.0} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} / {:.3} | {} / {} | {:.2e} / {:.2e} |",
            r.preset.name,
            match f {
                Some(true) => "**yes**",
                Some(false) => "",
                None => "n/a (no M4 count)",
            },
            r.instructions().map_or("—".into(), |i| format!("{:.2} M", i / 1e6)),
            r.host_us(),
            r.ram,
            r.error_pixels(),
            mean(&|e| e.missing as f64),
            mean(&|e| e.extra as f64),
            mean(&|e| e.wrong_surface as f64),
            max(&|e| e.depth_max_lsb),
            max(&|e| e.intensity_max),
            mean(&|e| e.intensity_mean),
            r.fan.0,
            r.fan.1,
            r.threshold.measured,
            r.threshold.theory,
        );
    }
    let _ = writeln!(s, "\n## The presets\n");
    let _ = writeln!(s, "| preset | format / sub-pixel bits / depth store / depth mapping / maths / intensity | what for |");
    let _ = writeln!(s, "|---|---|---|");
    for r in rows {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} |",
            r.preset.name,
            knobs(&r.preset),
            r.preset.summary
        );
    }
    let _ = writeln!(s, "\n## Per scene\n");
    let _ = writeln!(s, "| preset | scene | M4 instr. | host µs | missing | extra | wrong surface | depth max / mean (LSB) | intensity max / mean (LSB) | intensity > 2 LSB |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        for (name, e, host, instr) in &r.scenes {
            let _ = writeln!(
                s,
                "| `{}` | {} | {} | {:.0} | {} | {} | {} | {:.2} / {:.3} | {:.2} / {:.3} | {} |",
                r.preset.name,
                name,
                instr.map_or("—".into(), |i| i.to_string()),
                host.as_secs_f64() * 1e6,
                e.missing,
                e.extra,
                e.wrong_surface,
                e.depth_max_lsb,
                e.depth_mean_lsb,
                e.intensity_max,
                e.intensity_mean,
                e.intensity_bad
            );
        }
    }
    let _ = writeln!(s, "\n## Depth resolution (docs/extremes.md, item 17)\n");
    let _ = writeln!(
        s,
        "Two parallel squares facing the eye at w = {} and {} + Δ (the far one first in the scene, \
         so it wins exact ties), a small square at w = {} stretching the frame's depth range. \
         Theory: Δw = depth LSB / (dz/dw at w = {}) — the format's LSB for a 32-bit row, \
         (z(15) − z(5)) / 65535 for 16-bit tiles. Measured: the smallest Δ of a half-octave \
         sweep (theory/16 … theory·16) above which the near square wins at every pixel. The \
         coordinate quantum bounds how finely a fixed-point vertex can be placed.\n",
        measure::PLANE_W,
        measure::PLANE_W,
        measure::FAR_W,
        measure::PLANE_W
    );
    let _ = writeln!(
        s,
        "| preset | theory Δw | measured Δw | measured / theory | coordinate quantum |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|");
    for r in rows {
        let t = &r.threshold;
        let _ = writeln!(
            s,
            "| `{}` | {:.3e} | {:.3e} | {:.2} | {:.1e} |",
            r.preset.name,
            t.theory,
            t.measured,
            t.measured / t.theory,
            t.coordinate_lsb
        );
    }
    s
}
