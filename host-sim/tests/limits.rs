//! What `zrow-sim` refuses or survives before it does any work: inputs that are not regular
//! files or are too large, material libraries that cannot be read, an `--out` that cannot be
//! written, a `--checks` too large, a standard output closed by its reader.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use zrow_sim::model::MAX_FILE_BYTES;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_zrow-sim"))
}

fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/models")
        .join(name)
}

/// A fresh scratch directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("limits-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// What a finished run said: success, stdout, stderr.
struct Run {
    ok: bool,
    stdout: String,
    stderr: String,
}

/// Waits for `child` at most `secs` seconds (a run that reads a device or a FIFO never ends
/// by itself): kills it and fails the test after that.
fn finish(mut child: Child, secs: u64, what: &str) -> Run {
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            let mut stdout = String::new();
            let mut stderr = String::new();
            if let Some(mut o) = child.stdout.take() {
                o.read_to_string(&mut stdout).unwrap();
            }
            if let Some(mut e) = child.stderr.take() {
                e.read_to_string(&mut stderr).unwrap();
            }
            return Run {
                ok: status.success(),
                stdout,
                stderr,
            };
        }
        if start.elapsed() > Duration::from_secs(secs) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{what}: still running after {secs} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn run(args: &[&str], secs: u64) -> Run {
    let child = bin()
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    finish(child, secs, &args.join(" "))
}

/// The three commands, each reading `input` (a scene for `render`, a model for the others)
/// and writing into `dir`.
fn commands(input: &str, dir: &Path) -> [Vec<String>; 3] {
    let out = |name: &str| dir.join(name).display().to_string();
    let v = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    [
        v(&["render", "--screen", input, "--out", &out("s.png")]),
        v(&["render-model", "--model", input, "--out", &out("m.png")]),
        v(&["convert", "--model", input, "--out", &out("m.rs")]),
    ]
}

#[test]
fn inputs_that_are_not_regular_files_are_refused_before_reading() {
    let dir = scratch("irregular");
    let fifo = dir.join("pipe.off");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let folder = dir.join("folder.obj");
    std::fs::create_dir(&folder).unwrap();
    // A model name that points at an endless device.
    let zero = dir.join("zero.obj");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    for input in [&zero, &fifo, &folder].map(|p| p.display().to_string()) {
        for args in commands(&input, &dir) {
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            let r = run(&args, 20);
            assert!(!r.ok, "{args:?}");
            assert_eq!(
                r.stderr.trim_end(),
                format!(
                    "error: {input}: cannot read: not a regular file (a directory, device, pipe \
                     or socket is never read)"
                ),
                "{args:?}"
            );
        }
    }
    // Nothing was written.
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 3);
}

#[test]
fn files_beyond_the_size_limit_are_refused_before_reading() {
    let dir = scratch("size");
    let big = dir.join("big.off");
    // Sparse: no disk space, but the size the limit looks at.
    std::fs::File::create(&big)
        .unwrap()
        .set_len(MAX_FILE_BYTES + 1)
        .unwrap();
    for args in commands(&big.display().to_string(), &dir) {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let r = run(&args, 20);
        assert!(!r.ok, "{args:?}");
        assert_eq!(
            r.stderr.trim_end(),
            format!(
                "error: {}: cannot read: {} bytes, more than the {MAX_FILE_BYTES} bytes an input \
                 file may have",
                big.display(),
                MAX_FILE_BYTES + 1
            ),
        );
    }
}

#[test]
fn an_unreadable_material_library_is_a_warning_naming_it() {
    let dir = scratch("mtl");
    let cube = std::fs::read_to_string(asset("cube.obj")).unwrap();
    assert!(
        cube.contains("mtllib cube.mtl"),
        "the asset names its library"
    );
    let png = dir.join("out.png").display().to_string();
    for (library, why) in [
        ("missing.mtl", "No such file or directory"),
        ("/dev/zero", "not a regular file"),
    ] {
        let obj = dir.join("cube.obj");
        std::fs::write(
            &obj,
            cube.replace("mtllib cube.mtl", &format!("mtllib {library}")),
        )
        .unwrap();
        let obj = obj.display().to_string();
        let r = run(&["render-model", "--model", &obj, "--out", &png], 60);
        assert!(r.ok, "{}", r.stderr);
        let path = dir.join(library).display().to_string();
        let lines: Vec<&str> = r.stderr.lines().collect();
        assert_eq!(lines.len(), 1, "{lines:?}");
        assert!(
            lines[0].starts_with(&format!("warning: {obj}: material library {path}: "))
                && lines[0].contains(why)
                && lines[0].ends_with("its faces are drawn in the default colour"),
            "{}",
            lines[0]
        );
    }
    // The library that is there: no warning.
    std::fs::copy(asset("cube.mtl"), dir.join("cube.mtl")).unwrap();
    std::fs::write(dir.join("cube.obj"), &cube).unwrap();
    let obj = dir.join("cube.obj").display().to_string();
    let r = run(&["render-model", "--model", &obj, "--out", &png], 60);
    assert!(r.ok && r.stderr.is_empty(), "{}", r.stderr);
}

#[test]
fn out_is_checked_before_the_input_is_read() {
    let dir = scratch("out");
    // The input is not even readable: the error is still about --out, so --out came first.
    for (out, why) in [
        (
            dir.join("no/such/folder/x.png"),
            "No such file or directory",
        ),
        (dir.clone(), "is a directory"),
    ] {
        let out = out.display().to_string();
        for args in [
            vec!["render", "--screen", "/nonexistent.off", "--out", &out],
            vec!["render-model", "--model", "/nonexistent.obj", "--out", &out],
            vec!["convert", "--model", "/nonexistent.obj", "--out", &out],
        ] {
            let r = run(&args, 20);
            assert!(!r.ok);
            assert!(
                r.stderr
                    .starts_with(&format!("error: {out}: cannot write: "))
                    && r.stderr.contains(why),
                "{args:?}: {}",
                r.stderr
            );
        }
    }
    // A failed render leaves the previous output as it was, and no temporary file.
    let png = dir.join("keep.png");
    std::fs::write(&png, b"previous").unwrap();
    let r = run(
        &[
            "render-model",
            "--model",
            "/nonexistent.obj",
            "--out",
            &png.display().to_string(),
        ],
        20,
    );
    assert!(!r.ok);
    assert_eq!(std::fs::read(&png).unwrap(), b"previous");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}

#[test]
fn checks_beyond_the_limit_are_a_usage_error() {
    let dir = scratch("checks");
    let out = dir.join("m.rs").display().to_string();
    let model = asset("cube.obj").display().to_string();
    for checks in ["1000000000000", "1000001"] {
        let r = run(
            &[
                "convert", "--model", &model, "--out", &out, "--checks", checks,
            ],
            20,
        );
        assert!(!r.ok);
        assert!(
            r.stderr
                .starts_with(&format!("error: bad --checks {checks}: at most 1000000")),
            "{}",
            r.stderr
        );
    }
    assert!(!dir.join("m.rs").exists());
}

#[test]
fn a_closed_standard_output_ends_the_program_quietly() {
    let dir = scratch("pipe");
    let out = dir.join("m.rs").display().to_string();
    let model = asset("cube.obj").display().to_string();
    for args in [
        vec![
            "convert", "--model", &model, "--out", &out, "--checks", "10",
        ],
        vec!["--help"],
    ] {
        let mut child = bin()
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // The reader goes away before the program writes (`… | head -0`).
        drop(child.stdout.take());
        let r = finish(child, 60, &args.join(" "));
        assert!(r.ok, "{args:?}: {}", r.stderr);
        assert!(r.stderr.is_empty(), "{args:?}: {}", r.stderr);
        assert!(r.stdout.is_empty());
    }
    assert!(dir.join("m.rs").exists(), "the Rust file was still written");
}
