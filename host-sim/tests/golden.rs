//! Golden frames: every scene in `scenes/` rendered at 240x240 with each method and number
//! format, compared pixel for pixel with `host-sim/tests/golden/NAME.FORMAT.png` — one
//! reference for all methods, since every exact method must draw the same picture.
//!
//! To accept a deliberate change, re-bless the references and review the new PNGs:
//!
//! ```text
//! ZROW_BLESS=1 CARGO_TARGET_DIR=/work/target-sim cargo test -p zrow-sim --test golden
//! ```
//!
//! When a reference differs, the test writes `NAME.FORMAT.actual.png` next to it (ignored by
//! git: look at it, then fix the code or bless) and fails with the number of differing pixels.
//! A missing reference is a failure too, unless blessing.

mod support;

use std::path::{Path, PathBuf};
use support::compare_golden;
use zrow_sim::render::{render_screen, Algo, Format};

const SIZE: u16 = 240;

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

fn scenes() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("scenes/ exists")
        .map(|e| e.expect("readable scenes/ entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "off"))
        .collect();
    v.sort();
    v
}

/// Renders one scene and compares it; `Err` describes the mismatch.
fn check(scene_path: &Path, algo: Algo, format: Format, bless: bool) -> Result<(), String> {
    let stem = scene_path
        .file_stem()
        .unwrap()
        .to_string_lossy()
        .into_owned();
    // One reference per scene and format for every method: exact methods draw the same
    // picture. Only the scan-line method blesses.
    let tag = format.name();
    let reference = golden_dir().join(format!("{stem}.{tag}.png"));
    let actual_path = golden_dir().join(format!("{stem}.{tag}.{}.actual.png", algo.name()));
    let bless = bless && algo == Algo::Scanline;

    let data = std::fs::read(scene_path).map_err(|e| format!("{stem}: {e}"))?;
    let scene = zrow_sim::off::parse(&stem, &data).map_err(|e| e.to_string())?;
    let image = render_screen(&scene, SIZE, SIZE, algo, format).map_err(|e| e.to_string())?;
    compare_golden(&image, &reference, &actual_path, bless)
        .map_err(|e| format!("{}: {e}", algo.name()))
}

#[test]
fn golden_frames() {
    let bless = std::env::var_os("ZROW_BLESS").is_some_and(|v| v == "1");
    let scenes = scenes();
    assert!(
        scenes.len() >= 4,
        "expected the example scenes in {}",
        scenes_dir().display()
    );
    let mut failures = Vec::new();
    for scene in &scenes {
        for &(_, algo) in Algo::ALL {
            for &(_, format) in Format::ALL {
                if let Err(e) = check(scene, algo, format, bless) {
                    failures.push(e);
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} golden frame(s) differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The picture the example asks about: at its point (3, 1) — pixel (90, 30) after the ×30
/// scale — both triangles are present and s1 (red) is in front; below s1, s2 (green) shows.
#[test]
fn seed002_red_in_front_of_green() {
    let data = std::fs::read(scenes_dir().join("seed002.off")).unwrap();
    let scene = zrow_sim::off::parse("seed002.off", &data).unwrap();
    for &(_, format) in Format::ALL {
        let rgb = render_screen(&scene, SIZE, SIZE, Algo::Scanline, format)
            .unwrap()
            .to_rgb8();
        let at = |x: usize, y: usize| &rgb[3 * (y * SIZE as usize + x)..][..3];
        assert_eq!(at(90, 30), [255, 0, 0], "{format:?}");
        assert_eq!(at(130, 90), [0, 255, 0], "{format:?}");
        assert_eq!(at(200, 200), [0, 0, 0], "{format:?}");
    }
}
