//! Robustness: thousands of mangled scene files (the example scenes with tokens deleted,
//! duplicated, replaced by extreme values, lines dropped or swapped, bytes flipped, files cut)
//! go through the parser and, when they parse, through both renderers. Nothing may panic, and
//! every error must be one line; parse errors must name the file and a line that exists.
//!
//! The mutations come from a fixed-seed generator, so a failure reproduces; the failing input
//! is printed.

mod support;

use std::path::Path;
use support::Rng;
use zrow_sim::off;
use zrow_sim::render::{render_screen, Algo, Format};

const NASTY: &[&str] = &[
    "0",
    "-1",
    "1",
    "2",
    "3",
    "10",
    "11",
    "255",
    "256",
    "65535",
    "65536",
    "70000",
    "-0",
    "32767.99",
    "32768",
    "-32768",
    "-32769",
    "1e30",
    "-1e30",
    "1e39",
    "nan",
    "inf",
    "-inf",
    "1e-45",
    "0.5",
    "OFF",
    "#",
    "x",
    "",
    "\u{0}",
    "é",
    "18446744073709551616",
    "4294967296",
    "2047.5",
    "-2048",
    "4096",
    "1e9",
    "\t",
    "\r",
];

fn mutate(text: &str, rng: &mut Rng) -> Vec<u8> {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    for _ in 0..1 + rng.below(3) {
        let n = lines.len();
        let l = rng.below(n);
        match rng.below(8) {
            0 => {
                lines.remove(l);
            }
            1 => {
                let copy = lines[l].clone();
                lines.insert(rng.below(n + 1), copy);
            }
            2 => lines.swap(l, rng.below(n)),
            3..=5 => {
                // Replace, insert or delete one token.
                let mut toks: Vec<String> =
                    lines[l].split_whitespace().map(str::to_owned).collect();
                let t = rng.below(toks.len() + 1);
                let nasty = NASTY[rng.below(NASTY.len())].to_owned();
                match rng.below(3) {
                    0 if t < toks.len() => toks[t] = nasty,
                    1 if t < toks.len() => {
                        toks.remove(t);
                    }
                    _ => toks.insert(t, nasty),
                }
                lines[l] = toks.join(" ");
            }
            6 => lines.truncate(l),
            _ => lines.insert(l, String::new()),
        }
        if lines.is_empty() {
            break;
        }
    }
    let mut bytes = lines.join("\n").into_bytes();
    if rng.below(10) == 0 && !bytes.is_empty() {
        let i = rng.below(bytes.len());
        bytes[i] = rng.next() as u8; // any byte, including invalid UTF-8
    }
    if rng.below(10) == 0 {
        let cut = rng.below(bytes.len() + 1);
        bytes.truncate(cut);
    }
    bytes
}

#[test]
fn mangled_scenes_never_panic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut sources: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "off"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    sources.sort();
    assert!(!sources.is_empty());
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut parsed, mut rendered) = (0, 0);
    for case in 0..4000 {
        let bytes = mutate(&sources[case % sources.len()], &mut rng);
        let shown = String::from_utf8_lossy(&bytes).into_owned();
        let result = std::panic::catch_unwind(|| match off::parse("m.off", &bytes) {
            Err(e) => {
                let msg = e.to_string();
                let lines = bytes.split(|&b| b == b'\n').count();
                assert!(msg.starts_with("m.off:"), "{msg}");
                assert!(e.line >= 1 && e.line <= lines.max(1), "{msg}");
                assert!(!msg.contains('\n'), "{msg:?}");
                (false, false)
            }
            Ok(scene) => {
                let mut ok = false;
                for format in [Format::Q16_16, Format::F32] {
                    match render_screen(&scene, 48, 40, Algo::Scanline, format) {
                        Ok(img) => {
                            assert_eq!(img.pixels.len(), 48 * 40);
                            ok = true;
                        }
                        Err(e) => {
                            let msg = e.to_string();
                            assert!(msg.starts_with("m.off"), "{msg}");
                            assert!(!msg.contains('\n'), "{msg:?}");
                        }
                    }
                }
                (true, ok)
            }
        });
        match result {
            Ok((p, r)) => {
                parsed += p as u32;
                rendered += r as u32;
            }
            Err(_) => panic!("case {case} panicked on input:\n{shown}"),
        }
    }
    // The mutations must leave a fair share of valid files, or the renderers go untested.
    assert!(
        parsed > 400 && rendered > 400,
        "parsed {parsed}, rendered {rendered}"
    );
}
