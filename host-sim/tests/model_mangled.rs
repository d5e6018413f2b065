//! Robustness of model loading: the demo models (and an ASCII STL made from the binary one)
//! with bytes flipped, lines dropped or duplicated, tokens replaced by extreme values and
//! files cut go through the loader and, when they load, through a small render in both
//! formats. Nothing may panic, and every error must be one line naming the file.
//!
//! The mutations come from a fixed-seed generator, so a failure reproduces; the failing input
//! is printed. `ZROW_MANGLE_ROUNDS=N` runs N mutations per model instead of 300.

mod support;

use std::path::Path;
use support::Rng;
use zrow_sim::model::{self, ModelFormat};
use zrow_sim::model_render::{render_model_image, View};
use zrow_sim::render::{Algo, Format};

const NASTY: &[&str] = &[
    "0", "-1", "1", "3", "-4", "65536", "70000", "1e30", "-1e30", "1e39", "nan", "inf", "0.5", "f",
    "v", "vertex", "facet", "endloop", "endsolid", "solid", "usemtl", "mtllib", "o", "/", "1/",
    "1//2", "-0", "1e-45", "x", "", "#", "\u{0}", "é",
];

fn mutate(rng: &mut Rng, data: &[u8]) -> Vec<u8> {
    let mut out = data.to_vec();
    for _ in 0..1 + rng.below(3) {
        match rng.below(5) {
            0 if !out.is_empty() => {
                let cut = rng.below(out.len());
                out.truncate(cut);
            }
            1 if !out.is_empty() => {
                let i = rng.below(out.len());
                out[i] = rng.next() as u8;
            }
            _ => {
                // Token-level edits on the text (binary data goes through lossily).
                let text = String::from_utf8_lossy(&out).into_owned();
                let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
                if lines.is_empty() {
                    continue;
                }
                let l = rng.below(lines.len());
                match rng.below(3) {
                    0 => {
                        lines.remove(l);
                    }
                    1 => {
                        let dup = lines[l].clone();
                        lines.insert(l, dup);
                    }
                    _ => {
                        let mut tokens: Vec<String> =
                            lines[l].split(' ').map(str::to_owned).collect();
                        let t = rng.below(tokens.len());
                        tokens[t] = NASTY[rng.below(NASTY.len())].to_owned();
                        lines[l] = tokens.join(" ");
                    }
                }
                out = (lines.join("\n") + "\n").into_bytes();
            }
        }
    }
    out
}

fn ascii_stl(bin: &[u8]) -> Vec<u8> {
    let n = u32::from_le_bytes(bin[80..84].try_into().unwrap()) as usize;
    let f = |o: usize| f32::from_le_bytes(bin[o..o + 4].try_into().unwrap());
    let mut text = String::from("solid s\n");
    for t in 0..n.min(40) {
        let o = 84 + 50 * t;
        text += "facet normal 0 0 1\nouter loop\n";
        for v in 0..3 {
            let p = o + 12 + 12 * v;
            text += &format!("vertex {} {} {}\n", f(p), f(p + 4), f(p + 8));
        }
        text += "endloop\nendfacet\n";
    }
    (text + "endsolid s\n").into_bytes()
}

#[test]
fn mangled_models_never_panic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models");
    let read = |n: &str| std::fs::read(dir.join(n)).unwrap();
    let stl = read("icosphere.stl");
    let inputs = [
        ("cube.obj", ModelFormat::Obj, read("cube.obj")),
        ("torus.off", ModelFormat::Off, read("torus.off")),
        ("ascii.stl", ModelFormat::Stl, ascii_stl(&stl)),
        ("icosphere.stl", ModelFormat::Stl, stl),
    ];
    let mut rng = Rng(0x005e_ed0f_2026);
    let view = View::default();
    let (mut loaded, mut rejected) = (0, 0);
    let rounds: usize = std::env::var("ZROW_MANGLE_ROUNDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(300);
    for (name, format, data) in &inputs {
        for round in 0..rounds {
            let bad = mutate(&mut rng, data);
            let shown = String::from_utf8_lossy(&bad[..bad.len().min(2000)]).into_owned();
            let result = std::panic::catch_unwind(|| {
                let m = model::parse(name, *format, &bad, &dir)?;
                for &(_, f) in Format::ALL {
                    render_model_image(&m, &view, 24, 24, Algo::Scanline, f)?;
                }
                Ok::<_, zrow_sim::SimError>(())
            });
            match result {
                Err(_) => panic!("{name} round {round} panicked on:\n{shown}"),
                Ok(Ok(())) => loaded += 1,
                Ok(Err(e)) => {
                    rejected += 1;
                    let msg = e.to_string();
                    assert!(!msg.contains('\n'), "{name} round {round}: {msg:?}");
                    assert!(msg.starts_with(name), "{name} round {round}: {msg}");
                }
            }
        }
    }
    assert!(
        loaded > 50 && rejected > 50,
        "{loaded} loaded, {rejected} rejected"
    );
}
