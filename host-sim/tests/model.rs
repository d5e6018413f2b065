//! Model mode: the demo models load (OBJ, STL, OFF), render to their golden frames, and every
//! malformed or oversized model gets a one-line error naming the file and where.
//!
//! Golden frames: `host-sim/tests/golden/model_NAME.FORMAT.png`, each demo model at 240x240
//! from the default view, `model_NAME.smooth.FORMAT.png` smooth shaded (`--smooth 45`), and
//! for the torus and the cube `model_NAME.lines.FORMAT.png` (`--lines hidden`) and
//! `model_NAME.outline.FORMAT.png` (`--smooth 45 --lines outline`). To accept a deliberate
//! change, re-bless and review the new PNGs:
//!
//! ```text
//! ZROW_BLESS=1 CARGO_TARGET_DIR=/work/target-model cargo test -p zrow-sim --test model
//! ```
//!
//! A differing frame is written next to its reference as `model_NAME.FORMAT.actual.png`.

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;
use zrow_sim::model::{self, Origin};
use zrow_sim::model_render::{render_model_image, render_model_lines, Lines, View};
use zrow_sim::png_io;
use zrow_sim::render::{Algo, Format, HOST_ACTIVE};

const SIZE: u16 = 240;

fn models_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models")
}

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// A fresh scratch directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("model-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const DEMOS: [&str; 3] = ["cube.obj", "icosphere.stl", "torus.off"];

// ---------------------------------------------------------------------------------------------
// Loading

#[test]
fn demo_models_load_normalised() {
    // (file, vertices, faces)
    for (name, vertices, faces) in [
        ("cube.obj", 8, 6),
        ("icosphere.stl", 162, 320),
        ("torus.off", 128, 128),
    ] {
        let m = model::load(&models_dir().join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(m.positions.len(), vertices, "{name}");
        assert_eq!(m.faces.len(), faces, "{name}");
        assert_eq!(m.vertex_origins.len(), vertices, "{name}");
        // Inside the unit sphere, and touching it (box corners or the sphere's poles).
        let radius = m
            .positions
            .iter()
            .map(|p| p.iter().map(|c| c * c).sum::<f32>().sqrt())
            .fold(0f32, f32::max);
        assert!(radius <= 1.0 + 1e-5 && radius > 0.5, "{name}: {radius}");
        assert!(m.faces.iter().all(|f| f.origin.is_some()), "{name}");
    }
}

#[test]
fn obj_faces_take_their_mtl_colour() {
    use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    let m = model::load(&models_dir().join("cube.obj")).unwrap();
    let colors: Vec<Rgb565> = m.faces.iter().map(|f| f.color).collect();
    // `usemtl red`: Kd 0.9 0.15 0.1.
    assert_eq!(
        colors[0],
        zrow_sim::off::rgb8_to_rgb565([230, 38, 26]),
        "{colors:?}"
    );
    assert!(colors.windows(2).all(|w| w[0] != w[1]));
    assert_eq!(m.faces[0].origin, Some(Origin::Line(13)));
    // Every vertex is blamed on one of the `v` lines (4..=11).
    assert!(m
        .vertex_origins
        .iter()
        .all(|o| matches!(o, Some(Origin::Line(4..=11)))));
    // Without its MTL, the default colour.
    let dir = scratch("nomtl");
    let obj = std::fs::read_to_string(models_dir().join("cube.obj")).unwrap();
    std::fs::write(dir.join("cube.obj"), obj).unwrap();
    let m = model::load(&dir.join("cube.obj")).unwrap();
    let grey = zrow_sim::off::rgb8_to_rgb565(model::DEFAULT_RGB);
    assert!(m.faces.iter().all(|f| f.color == grey));
    assert_ne!(grey, Rgb565::BLACK);
}

#[test]
fn ascii_and_binary_stl_give_the_same_model() {
    let bin = std::fs::read(models_dir().join("icosphere.stl")).unwrap();
    let n = u32::from_le_bytes(bin[80..84].try_into().unwrap()) as usize;
    let f = |o: usize| f32::from_le_bytes(bin[o..o + 4].try_into().unwrap());
    let mut text = String::from("solid ico\n");
    for t in 0..n {
        let o = 84 + 50 * t;
        text += &format!(
            "facet normal {} {} {}\nouter loop\n",
            f(o),
            f(o + 4),
            f(o + 8)
        );
        for v in 0..3 {
            let p = o + 12 + 12 * v;
            text += &format!("vertex {:e} {:e} {:e}\n", f(p), f(p + 4), f(p + 8));
        }
        text += "endloop\nendfacet\n";
    }
    text += "endsolid ico\n";
    let dir = scratch("ascii-stl");
    std::fs::write(dir.join("ico.stl"), &text).unwrap();
    // A binary file whose free-text header starts with `solid` is still binary.
    let mut tricky = bin.clone();
    tricky[..6].copy_from_slice(b"solid ");
    std::fs::write(dir.join("tricky.stl"), &tricky).unwrap();

    let want = model::load(&models_dir().join("icosphere.stl")).unwrap();
    for name in ["ico.stl", "tricky.stl"] {
        let got = model::load(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(got.positions, want.positions, "{name}");
        assert_eq!(
            got.faces.iter().map(|f| &f.indices).collect::<Vec<_>>(),
            want.faces.iter().map(|f| &f.indices).collect::<Vec<_>>()
        );
    }
    let ascii = model::load(&dir.join("ico.stl")).unwrap();
    assert_eq!(ascii.faces[1].origin, Some(Origin::Line(9)));
    assert_eq!(ascii.vertex_origins[0], Some(Origin::Line(4)));
    assert_eq!(
        want.faces[1].origin,
        Some(Origin::Triangle {
            index: 1,
            offset: 134
        })
    );
}

// ---------------------------------------------------------------------------------------------
// Malformed files

/// Writes `bytes` as `name` in a scratch directory and returns the load error's message.
fn load_error(name: &str, bytes: &[u8]) -> (String, String) {
    let dir = scratch(&format!("bad-{name}"));
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    let e = match model::load(&path) {
        Ok(m) => panic!("{name} loaded: {} faces", m.faces.len()),
        Err(e) => e.to_string(),
    };
    assert!(!e.contains('\n'), "{e:?} spans lines");
    (path.display().to_string(), e)
}

#[test]
fn malformed_obj_names_file_and_line() {
    let cases: &[(&str, &str)] = &[
        (
            "# bad number\nv 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n",
            "3: vertex y `zero` is not a number",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1e39 0\n",
            "3: vertex y `1e39` is not finite",
        ),
        (
            "v 0 0\n",
            "1: vertex needs 3 coordinates `v x y z`, found 2",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
            "4: vertex index 4 out of range: 3 defined before this line",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
            "4: vertex index -4 out of range",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
            "4: vertex index 0: OBJ indices start at 1",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
            "4: vertex index `x` is not an integer",
        ),
        (
            "v 0 0 0\nv 1 0 0\n\nf 1 2\n",
            "4: face has 2 vertices, need at least 3",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n",
            "4: texture coordinate index 1 out of range: 0 defined",
        ),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "the model has no faces"),
    ];
    for (text, want) in cases {
        let (file, got) = load_error("bad.obj", text.as_bytes());
        let want = if want.as_bytes()[0].is_ascii_digit() {
            format!("{file}:{want}")
        } else {
            format!("{file}: {want}")
        };
        assert!(
            got.starts_with(&want),
            "{text:?}\n got: {got}\nwant: {want}"
        );
    }
    let (file, got) = load_error("bad.obj", b"v 0 0 0\n\xFF\n");
    assert_eq!(got, format!("{file}:2: line is not valid UTF-8"));
}

#[test]
fn malformed_stl_names_the_line_or_the_triangle() {
    let bin = std::fs::read(models_dir().join("icosphere.stl")).unwrap();
    // Cut in the middle of triangle 7.
    let (file, got) = load_error("cut.stl", &bin[..84 + 50 * 7 + 20]);
    assert_eq!(
        got,
        format!(
            "{file}:triangle 7 (byte offset 434): truncated binary STL: the header declares 320 \
             triangles (16084 bytes) but the file has 454 bytes; this triangle is cut short"
        )
    );
    let (file, got) = load_error("tiny.stl", &bin[..40]);
    assert!(
        got.starts_with(&format!("{file}: truncated binary STL: 40 bytes")),
        "{got}"
    );
    let mut nan = bin.clone();
    let o = 84 + 50 * 3 + 12 + 12 + 4; // triangle 3, vertex 2 y
    nan[o..o + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let (file, got) = load_error("nan.stl", &nan);
    assert_eq!(
        got,
        format!("{file}:triangle 3 (byte offset 234): vertex 2 y is not finite")
    );

    let facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
    let cases: Vec<(String, &str)> = vec![
        (
            format!("solid s\n{facet}facet normal 0 0 1\nouter loop\nvertex 0 0\n"),
            "11: vertex needs 3 numbers, found 2 values",
        ),
        (
            format!("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 x\n{facet}"),
            "4: vertex z `x` is not a number",
        ),
        (
            "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
                .to_owned(),
            "6: expected `vertex X Y Z` (a facet has exactly 3 vertices in STL`, found `endloop`",
        ),
        (
            format!("solid s\n{facet}"),
            "8: unexpected end of file: expected `facet normal` or `endsolid`",
        ),
        (
            format!("solid s\n{facet}endsolid s\nsolid t\n"),
            "10: unexpected content after `endsolid`",
        ),
        (
            format!("solid s\nfacet norml 0 0 1\n{facet}"),
            "2: expected `facet normal NX NY NZ`",
        ),
    ];
    for (text, want) in &cases {
        let (file, got) = load_error("bad.stl", text.as_bytes());
        let want = format!("{file}:{want}");
        assert!(
            got.starts_with(&want),
            "{text:?}\n got: {got}\nwant: {want}"
        );
    }
}

#[test]
fn malformed_off_and_unknown_formats() {
    let (file, got) = load_error(
        "bad.off",
        b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1 255 0 0\n",
    );
    assert_eq!(
        got,
        format!("{file}:6: face has 2 vertices, need at least 3")
    );
    let (file, got) = load_error("bad.off", b"OFF\n3 1 0\n0 0 0\n1 0 x\n");
    assert_eq!(got, format!("{file}:4: vertex z `x` is not a number"));
    let (file, got) = load_error("model.ply", b"ply\n");
    assert_eq!(
        got,
        format!("{file}: unknown model format: expected a file ending in .obj, .stl or .off")
    );
}

#[test]
fn a_non_convex_face_is_blamed_on_its_line() {
    let dir = scratch("w");
    let path = dir.join("w.obj");
    std::fs::write(
        &path,
        "v -1 1 0\nv -0.5 -1 0\nv 0 0.5 0\nv 0.5 -1 0\nv 1 1 0\n# a W\nf 1 2 3 4 5\n",
    )
    .unwrap();
    let m = model::load(&path).unwrap();
    let view = View {
        yaw_deg: 0.0,
        pitch_deg: 0.0,
        distance: 3.0,
    };
    for &(_, format) in Format::ALL {
        let e = render_model_image(&m, &view, 64, 64, Algo::Scanline, format).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("{}:7: face 0: not convex", path.display())
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Capacity

#[test]
fn a_model_beyond_the_host_capacities_names_the_capacity_and_its_need() {
    // HOST_ACTIVE + 100 triangles facing the camera, stacked in depth, all crossing the
    // middle row.
    let n = HOST_ACTIVE + 100;
    let mut text = format!("OFF\n{} {n} 0\n", 3 * n);
    for k in 0..n {
        let z = k as f32 / n as f32 - 0.5;
        text += &format!("-1 -1 {z}\n1 -1 {z}\n0 1 {z}\n");
    }
    for k in 0..n {
        text += &format!("3 {} {} {}\n", 3 * k, 3 * k + 1, 3 * k + 2);
    }
    let dir = scratch("capacity");
    let path = dir.join("stack.off");
    std::fs::write(&path, text).unwrap();
    let m = model::load(&path).unwrap();
    let view = View {
        yaw_deg: 0.0,
        pitch_deg: 0.0,
        distance: 3.0,
    };
    let e = render_model_image(&m, &view, 240, 240, Algo::Scanline, Format::Q16_16).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}: active list holds {HOST_ACTIVE} but this scene needs {n}: raise that capacity (the renderer's const parameter A to at least {n})",
            path.display()
        )
    );
    // From behind, every triangle is culled: nothing is needed, nothing drawn.
    let behind = View {
        yaw_deg: 180.0,
        ..view
    };
    let img = render_model_image(&m, &behind, 32, 32, Algo::Scanline, Format::F32).unwrap();
    assert!(img.to_rgb8().iter().all(|&b| b == 0));
}

// ---------------------------------------------------------------------------------------------
// Golden frames

/// How a golden frame is drawn, and the part of its name that says so.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    /// `model_NAME.FORMAT.png`: flat shaded.
    Flat,
    /// `model_NAME.smooth.FORMAT.png`: smooth shading (`--smooth 45`).
    Smooth,
    /// `model_NAME.lines.FORMAT.png`: a hidden-line drawing (`--lines hidden`).
    Lines,
    /// `model_NAME.outline.FORMAT.png`: smooth shaded with its visible edges
    /// (`--smooth 45 --lines outline`).
    Outline,
}

fn check_golden(name: &str, format: Format, kind: Kind, bless: bool) -> Result<(), String> {
    let stem = name.split('.').next().unwrap();
    let stem = match kind {
        Kind::Flat => stem.to_owned(),
        Kind::Smooth => format!("{stem}.smooth"),
        Kind::Lines => format!("{stem}.lines"),
        Kind::Outline => format!("{stem}.outline"),
    };
    let reference = golden_dir().join(format!("model_{stem}.{}.png", format.name()));
    let actual_path = golden_dir().join(format!("model_{stem}.{}.actual.png", format.name()));
    let mut m = model::load(&models_dir().join(name)).map_err(|e| e.to_string())?;
    if matches!(kind, Kind::Smooth | Kind::Outline) {
        m = m.smoothed(45.0);
    }
    let lines = match kind {
        Kind::Lines => Lines::Hidden,
        Kind::Outline => Lines::Outline,
        _ => Lines::Off,
    };
    let image = render_model_lines(
        &m,
        &View::default(),
        (SIZE, SIZE),
        Algo::Scanline,
        format,
        lines,
    )
    .map_err(|e| e.to_string())?;
    support::compare_golden(&image, &reference, &actual_path, bless)
}

#[test]
fn golden_model_frames() {
    let bless = std::env::var_os("ZROW_BLESS").is_some_and(|v| v == "1");
    let mut failures = Vec::new();
    for name in DEMOS {
        for &(_, format) in Format::ALL {
            let mut kinds = vec![Kind::Flat, Kind::Smooth];
            if name.starts_with("torus") || name.starts_with("cube") {
                kinds.extend([Kind::Lines, Kind::Outline]);
            }
            for kind in kinds {
                if let Err(e) = check_golden(name, format, kind, bless) {
                    failures.push(e);
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} golden model frame(s) differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn renders_are_lit_and_seen_from_outside() {
    // The icosphere from the default view: the disc is drawn, its top (towards the light) is
    // brighter than its bottom (ambient only there), and nothing is drawn outside it.
    let m = model::load(&models_dir().join("icosphere.stl")).unwrap();
    let img = render_model_image(
        &m,
        &View::default(),
        SIZE,
        SIZE,
        Algo::Scanline,
        Format::Q16_16,
    )
    .unwrap();
    let rgb = img.to_rgb8();
    let lum = |x: usize, y: usize| rgb[3 * (y * SIZE as usize + x)] as u32;
    assert!(lum(120, 120) > 100, "centre {}", lum(120, 120));
    assert!(
        lum(125, 90) > lum(120, 155),
        "top {} bottom {}",
        lum(125, 90),
        lum(120, 155)
    );
    assert_eq!(lum(5, 5), 0);
}

// ---------------------------------------------------------------------------------------------
// The command

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_zrow-sim"))
}

#[test]
fn render_model_writes_a_png_of_the_requested_size() {
    let dir = scratch("cli-ok");
    for name in DEMOS {
        let png = dir.join(format!("{name}.png"));
        let out = bin()
            .args([
                "render-model",
                "--size",
                "200x120",
                "--yaw",
                "-30",
                "--model",
            ])
            .arg(models_dir().join(name))
            .args([
                "--format",
                "f32",
                "--pitch=10",
                "--distance",
                "2.5",
                "--out",
            ])
            .arg(&png)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(out.stderr.is_empty());
        let img = png_io::decode(&std::fs::read(&png).unwrap()).unwrap();
        assert_eq!((img.width, img.height), (200, 120), "{name}");
        assert!(img.data.iter().any(|&b| b != 0), "{name}: blank");
    }
}

#[test]
fn render_model_fails_on_one_line() {
    let dir = scratch("cli-bad");
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n").unwrap();
    let png = dir.join("out.png");
    let run = |args: &[&std::ffi::OsStr]| bin().args(args).output().unwrap();
    let out = run(&[
        "render-model".as_ref(),
        "--model".as_ref(),
        bad.as_os_str(),
        "--out".as_ref(),
        png.as_os_str(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        err.lines().collect::<Vec<_>>(),
        [format!(
            "error: {}:4: face has 2 vertices, need at least 3",
            bad.display()
        )]
    );
    assert!(!png.exists(), "no PNG on failure");
    // A bad view is a usage error (exit 2), also on one line.
    let out = run(&[
        "render-model".as_ref(),
        "--model".as_ref(),
        bad.as_os_str(),
        "--pitch".as_ref(),
        "90".as_ref(),
        "--out".as_ref(),
        png.as_os_str(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("error: bad view: pitch 90"), "{err}");
}

/// Smooth shading: every method draws a smoothed model as the scan-line method does, in both
/// formats, and the picture is not the flat one.
#[test]
fn every_method_draws_the_same_smooth_model() {
    for name in ["icosphere.stl", "torus.off"] {
        let flat = model::load(&models_dir().join(name)).unwrap();
        let smooth = flat.smoothed(45.0);
        assert_eq!(
            smooth.vertex_normals.len(),
            smooth.positions.len(),
            "{name}"
        );
        for &(_, format) in Format::ALL {
            let draw = |m: &model::LoadedModel, algo| {
                render_model_image(m, &View::default(), 96, 96, algo, format)
                    .unwrap_or_else(|e| panic!("{name} {algo:?}: {e}"))
                    .to_rgb8()
            };
            let reference = draw(&smooth, Algo::Scanline);
            assert_ne!(
                reference,
                draw(&flat, Algo::Scanline),
                "{name}: smooth is flat"
            );
            for &(algo_name, algo) in Algo::ALL {
                // The painters are exact only where nothing overlaps: the torus overlaps.
                if matches!(algo, Algo::CullOnly | Algo::Ordered | Algo::Auto) {
                    continue;
                }
                let differ = draw(&smooth, algo)
                    .chunks(3)
                    .zip(reference.chunks(3))
                    .filter(|(a, b)| a != b)
                    .count();
                assert_eq!(differ, 0, "{name} {algo_name} {format:?}: pixels differ");
            }
        }
    }
}

/// Hidden lines: every method draws the same hidden-line and outline drawings of the torus and
/// the icosphere as the scan-line method does, in both formats; a hidden-line drawing has
/// lines and nothing else (ink on paper), and an outline drawing is the shaded frame with the
/// same lines over it.
#[test]
fn every_method_draws_the_same_lines() {
    use zrow_sim::model_render::{INK, OUTLINE_INK, PAPER};
    for name in ["icosphere.stl", "torus.off"] {
        let flat = model::load(&models_dir().join(name)).unwrap();
        for &(_, format) in Format::ALL {
            let draw = |algo, lines| {
                render_model_lines(&flat, &View::default(), (96, 96), algo, format, lines)
                    .unwrap_or_else(|e| panic!("{name} {algo:?}: {e}"))
            };
            let hidden = draw(Algo::Scanline, Lines::Hidden);
            let ink = hidden.pixels.iter().filter(|&&p| p == INK).count();
            assert!(ink > 200, "{name}: {ink} line pixels");
            assert!(hidden.pixels.iter().all(|&p| p == INK || p == PAPER));
            let shaded =
                render_model_image(&flat, &View::default(), 96, 96, Algo::Scanline, format)
                    .unwrap();
            let outline = draw(Algo::Scanline, Lines::Outline);
            for ((&o, &h), &s) in outline
                .pixels
                .iter()
                .zip(&hidden.pixels)
                .zip(&shaded.pixels)
            {
                assert_eq!(o, if h == INK { OUTLINE_INK } else { s });
            }
            for &(algo_name, algo) in Algo::ALL {
                if matches!(algo, Algo::CullOnly | Algo::Ordered | Algo::Auto) {
                    continue; // exact only where nothing overlaps: the torus overlaps
                }
                let differ = draw(algo, Lines::Hidden)
                    .pixels
                    .iter()
                    .zip(&hidden.pixels)
                    .filter(|(a, b)| a != b)
                    .count();
                assert_eq!(
                    differ, 0,
                    "{name} {algo_name} {format:?}: line pixels differ"
                );
            }
        }
    }
}

/// `--smooth DEG --dither`: the smoothed torus dithered, by every method the same, not the
/// undithered frame; without vertex normals `dither` changes nothing (flat).
#[test]
fn dithered_smooth_model_is_the_same_in_every_method() {
    use zrow_sim::model_render::Style;
    let flat = model::load(&models_dir().join("torus.off")).unwrap();
    let smooth = flat.smoothed(45.0);
    let dithered = Style {
        lines: Lines::Off,
        dither: true,
    };
    let draw = |m: &model::LoadedModel, algo, style: Style| {
        render_model_lines(m, &View::default(), (96, 96), algo, Format::Q16_16, style).unwrap()
    };
    let reference = draw(&smooth, Algo::Scanline, dithered);
    assert_ne!(reference, draw(&smooth, Algo::Scanline, Style::default()));
    assert_eq!(
        draw(&flat, Algo::Scanline, dithered),
        draw(&flat, Algo::Scanline, Style::default())
    );
    for &(algo_name, algo) in Algo::ALL {
        if matches!(algo, Algo::CullOnly | Algo::Ordered | Algo::Auto) {
            continue; // exact only where nothing overlaps: the torus overlaps
        }
        assert_eq!(draw(&smooth, algo, dithered), reference, "{algo_name}");
    }
}
