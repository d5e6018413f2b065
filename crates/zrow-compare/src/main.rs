//! # zrow-compare — Foley & van Dam's Table 15.3 for zrow's methods
//!
//! Foley & van Dam's Table 15.3 (after Sutherland, Sproull & Schumacker 1974) gives the relative time of hidden-surface methods on the same scene at 100, 2,500 and
//! 60,000 polygons: depth sort 1 / 10 / 507, z-buffer 54 / 54 / 54, Warnock 11 / 64 / 307.
//! This program measures zrow's methods the same way and writes the comparison:
//!
//! ```text
//! cargo run --release -p zrow-compare -- --out docs/methods
//! ```
//!
//! from the repository root (under a minute on a 2-core machine once built; release mode
//! matters). It
//!
//! - builds the comparison scene ([`surfaces`]: two tori and two wavy sheets crossing each
//!   other) at 100, 2,500 and 60,000 triangles, 512 × 512 pixels, Q16.16;
//! - renders it with every method in [`bench::methods`] (one line per method) and times each
//!   frame: the median of several renders (at least 5, up to 31, about two seconds per
//!   frame; a frame slower than 5 s is rendered once);
//! - counts the pixels where each method's frame differs from the z-buffer's;
//! - normalises as Foley does, depth sort at 100 polygons = 1 (the z-buffer at 100 if
//!   depth sort is not in the list; the output says which);
//! - reads the emulated Cortex-M4's instruction counts for the 240 × 240 versions of the
//!   scene from `emu/target/bench-m4.txt` (made by `bash emu/run.sh m4`; `--run-emu` runs it
//!   first; without the file the table says how to make it);
//! - writes `OUT/foley.md` (tables, figures, discussion), `OUT/foley.png` (the plot) and
//!   `OUT/scenes.png` (the three scenes as the z-buffer draws them), and prints the tables.
//!
//! Options: `--out DIR` (default `docs/methods`), `--emu FILE` (default
//! `emu/target/bench-m4.txt`), `--run-emu`, `--quick` (100 and 2,500 polygons only, one render
//! each: a smoke test, not a measurement).
//!
//! Text in the PNGs is drawn by plotters' pure-Rust `ab_glyph` path (no fontconfig, no
//! freetype) from a TrueType file read at run time: `$ZROW_FONT` if set, else DejaVu Sans at
//! `/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf` (Debian package `fonts-dejavu-core`).

mod bench;
mod emu;
mod font;
mod plot;
mod report;
mod surfaces;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// Command-line options.
struct Args {
    out: PathBuf,
    emu: PathBuf,
    run_emu: bool,
    quick: bool,
}

fn args() -> Result<Args, String> {
    let mut a = Args {
        out: PathBuf::from("docs/methods"),
        emu: PathBuf::from("emu/target/bench-m4.txt"),
        run_emu: false,
        quick: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match flag.as_str() {
            "--out" => a.out = it.next().ok_or("--out needs a directory")?.into(),
            "--emu" => a.emu = it.next().ok_or("--emu needs a file")?.into(),
            "--run-emu" => a.run_emu = true,
            "--quick" => a.quick = true,
            "-h" | "--help" => {
                return Err(
                    "usage: zrow-compare [--out DIR] [--emu FILE] [--run-emu] [--quick]\n\
                     (see the crate documentation: cargo doc -p zrow-compare --open)"
                        .into(),
                )
            }
            other => return Err(format!("unknown argument {other:?} (try --help)")),
        }
    }
    Ok(a)
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("zrow-compare: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let args = args()?;
    let started = Instant::now();
    if args.run_emu {
        eprintln!("running `bash emu/run.sh m4` ...");
        let status = std::process::Command::new("bash")
            .args(["emu/run.sh", "m4"])
            .stdout(std::process::Stdio::null())
            .status()
            .map_err(|e| format!("bash emu/run.sh m4: {e}"))?;
        if !status.success() {
            return Err(format!("bash emu/run.sh m4 failed ({status})"));
        }
    }
    let counts: &[usize] = if args.quick {
        &surfaces::POLYGONS[..2]
    } else {
        &surfaces::POLYGONS
    };
    let scenes: Vec<_> = counts
        .iter()
        .map(|&n| surfaces::foley_scene(n, bench::SIZE as f32).expect("a Table 15.3 count"))
        .collect();
    let budget = if args.quick {
        bench::Budget {
            min_runs: 1,
            max_runs: 1,
            target: Duration::ZERO,
            slow: Duration::ZERO,
        }
    } else {
        bench::Budget {
            min_runs: 5,
            max_runs: 31,
            target: Duration::from_secs(2),
            slow: Duration::from_secs(5),
        }
    };
    let infos: Vec<_> = scenes.iter().map(report::SceneInfo::measure).collect();
    let mut results = vec![];
    for m in bench::methods() {
        eprintln!("{} ...", m.name);
        let outcomes = m.run(&scenes, &budget);
        results.push(report::MethodResult::new(m, outcomes, &infos));
    }
    report::check_against_zbuffer(&mut results);
    let emu = emu::read(&args.emu);
    if let Err(e) = &emu {
        eprintln!("zrow-compare: no emulated counts: {e}");
    }
    let rep = report::Report {
        machine: report::machine(),
        scenes: infos,
        methods: results,
        emu,
        emu_path: args.emu.display().to_string(),
        quick: args.quick,
    };
    std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
    let md = rep.markdown();
    let md_path = args.out.join("foley.md");
    std::fs::write(&md_path, &md).map_err(|e| format!("{}: {e}", md_path.display()))?;
    plot::init_font()?;
    plot::relative_times(&rep, &args.out.join("foley.png"))?;
    let frames: Vec<_> = rep.zbuffer_frames();
    plot::scenes(&frames, &args.out.join("scenes.png"))?;
    println!("{}", rep.tables());
    println!(
        "wrote {}, {}, {} in {:.1} s",
        md_path.display(),
        args.out.join("foley.png").display(),
        args.out.join("scenes.png").display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::surfaces::{foley_scene, POLYGONS};
    use zrow::Q16_16;

    #[test]
    fn every_scene_has_exactly_its_polygon_count_of_triangles_with_valid_indices() {
        for n in POLYGONS {
            let s = foley_scene(n, 512.0).unwrap();
            assert_eq!(s.faces.len(), n);
            assert!(s
                .faces
                .iter()
                .all(|(t, _)| t.iter().all(|&i| (i as usize) < s.vertices.len())));
            // Inside the frame, with depth well inside Q16.16.
            for v in &s.vertices {
                assert!(
                    (0.0..512.0).contains(&v[0]) && (0.0..512.0).contains(&v[1]),
                    "{v:?}"
                );
                assert!((0.0..1024.0).contains(&v[2]), "{v:?}");
            }
        }
        assert!(foley_scene(99, 512.0).is_none());
    }

    #[test]
    fn positions_are_on_the_grid_so_f32_and_q16_16_agree() {
        let s = foley_scene(2_500, 512.0).unwrap();
        for v in &s.vertices {
            for (c, k) in v.iter().zip([256.0, 256.0, 1024.0]) {
                assert_eq!((c * k).fract(), 0.0, "{v:?}");
            }
        }
    }

    /// The emulator's consts (zrow-scenes' build.rs, same generator) are this generator's
    /// output at 240 × 240, bit for bit, in both formats.
    #[test]
    fn zrow_scenes_consts_are_this_generator_at_240() {
        for (name, n) in crate::report::EMU_SCENES {
            let ours = foley_scene(n, 240.0).unwrap();
            let q = zrow_scenes::mesh::<Q16_16>(name).unwrap();
            let f = zrow_scenes::mesh::<f32>(name).unwrap();
            assert_eq!(q.vertices.len(), ours.vertices.len());
            for ((v, q), f) in ours
                .vertices
                .iter()
                .zip(q.vertices.iter())
                .zip(f.vertices.iter())
            {
                assert_eq!([f.x, f.y, f.z], *v);
                let bits = v.map(|c| (c as f64 * 65536.0) as i32);
                assert_eq!([q.x.to_bits(), q.y.to_bits(), q.z.to_bits()], bits);
            }
            assert_eq!(q.faces.len(), n);
            for (face, (idx, (r, g, b))) in q.faces.iter().zip(&ours.faces) {
                assert_eq!(face.indices, &idx[..]);
                use embedded_graphics_core::pixelcolor::RgbColor;
                assert_eq!(
                    (face.color.r(), face.color.g(), face.color.b()),
                    (*r, *g, *b)
                );
            }
        }
    }
}
