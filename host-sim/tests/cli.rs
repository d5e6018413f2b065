//! The `zrow-sim` binary end to end: exit codes, the PNG it writes, its one-line errors.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_zrow-sim"))
}

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name)
}

/// A fresh scratch directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cli-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn stderr_lines(out: &Output) -> Vec<String> {
    String::from_utf8_lossy(&out.stderr)
        .lines()
        .map(str::to_owned)
        .collect()
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let dir = scratch("ok");
    let png = dir.join("out.png");
    // Flags out of the documented order.
    let out = bin()
        .args(["render", "--out"])
        .arg(&png)
        .args(["--algo", "scanline", "--size", "200x120", "--screen"])
        .arg(scene("seed002.off"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.stderr.is_empty());
    let img = zrow_sim::png_io::decode(&std::fs::read(&png).unwrap()).unwrap();
    assert_eq!((img.width, img.height), (200, 120));
    assert_eq!(&img.data[..3], &[255, 0, 0]); // s1 covers the top-left corner
    let last = img.data.len() - 3;
    assert_eq!(&img.data[last..], &[0, 0, 0]); // background
}

#[test]
fn malformed_file_gives_one_line_naming_file_and_line() {
    let dir = scratch("malformed");
    let bad = dir.join("bad.off");
    std::fs::write(
        &bad,
        "OFF\n3 1 0\n0 0 0\n10 0 0\n0 10 0\n# the face\n2 0 1 255 0 0\n",
    )
    .unwrap();
    let png = dir.join("out.png");
    let out = bin()
        .args(["render", "--screen"])
        .arg(&bad)
        .args(["--size", "240x240", "--algo", "scanline", "--out"])
        .arg(&png)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let lines = stderr_lines(&out);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert_eq!(
        lines[0],
        format!(
            "error: {}:7: face has 2 vertices, need at least 3",
            bad.display()
        )
    );
    assert!(!png.exists(), "no PNG on failure");
}

#[test]
fn core_errors_are_mapped_to_the_face_line() {
    let dir = scratch("nonconvex");
    let bad = dir.join("bowtie.off");
    std::fs::write(
        &bad,
        "OFF\n4 2 0\n0 0 0\n100 0 0\n20 20 0\n0 100 0\n3 0 1 3\n\n4 0 2 1 3 # bow tie\n",
    )
    .unwrap();
    let out = bin()
        .args(["render", "--screen"])
        .arg(&bad)
        .arg("--out")
        .arg(dir.join("out.png"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        stderr_lines(&out),
        [format!("error: {}:9: face 1: not convex", bad.display())]
    );
}

#[test]
fn unknown_algo_lists_the_accepted_names() {
    let dir = scratch("algo");
    let out = bin()
        .args(["render", "--screen"])
        .arg(scene("seed002.off"))
        .args(["--size", "240x240", "--algo", "raytrace", "--out"])
        .arg(dir.join("out.png"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let lines = stderr_lines(&out);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(
        lines[0].starts_with("error: unknown --algo `raytrace`: accepted names are scanline"),
        "{}",
        lines[0]
    );
}

#[test]
fn missing_file_and_bad_size_fail_on_one_line() {
    let dir = scratch("missing");
    for args in [
        vec!["render", "--screen", "no-such.off", "--out", "x.png"],
        vec![
            "render", "--screen", "a.off", "--out", "x.png", "--size", "0x0",
        ],
        vec!["render"],
    ] {
        let out = bin().current_dir(&dir).args(&args).output().unwrap();
        assert!(!out.status.success(), "{args:?}");
        let lines = stderr_lines(&out);
        assert_eq!(lines.len(), 1, "{args:?}: {lines:?}");
        assert!(lines[0].starts_with("error: "), "{}", lines[0]);
    }
}

#[test]
fn help_exits_zero() {
    let out = bin().arg("--help").output().unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("--screen"));
}
