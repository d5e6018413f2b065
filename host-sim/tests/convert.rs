//! The model converter (`zrow_sim::convert`, `zrow-sim convert`): what it emits, what it
//! reports, what it refuses.

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use std::path::{Path, PathBuf};
use std::process::Command;
use zrow_sim::convert::{
    convert, convert_model, measure_view, random_rotations, write_for_build, ConvertOptions,
    Converted, IndexType,
};
use zrow_sim::model::{load, parse, LoadedModel, ModelFormat};
use zrow_sim::model_render::{render_model_image, View};
use zrow_sim::render::{Algo, Format};

fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/models")
        .join(name)
}

/// A fresh scratch directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("convert-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Fewer views than the default, so that an unoptimised test build stays quick.
fn quick() -> ConvertOptions {
    ConvertOptions {
        directions: 48,
        rolls: 4,
        refine_starts: 3,
        refine_steps: 30,
        check_views: 100,
        ..ConvertOptions::default()
    }
}

fn obj(text: &str) -> LoadedModel {
    parse("t.obj", ModelFormat::Obj, text.as_bytes(), Path::new(".")).unwrap()
}

fn off(text: &str) -> LoadedModel {
    parse("t.off", ModelFormat::Off, text.as_bytes(), Path::new(".")).unwrap()
}

/// A flat strip of `n` vertices (n ≥ 3) as n − 2 triangles, plus `unused` vertices no face
/// uses, as OFF.
fn strip(n: usize, unused: usize) -> String {
    let mut s = format!("OFF\n{} {} 0\n", n + unused, n - 2);
    for k in 0..n + unused {
        s += &format!("{} {} 0\n", (k / 2) as f32 * 0.1, (k % 2) as f32);
    }
    for k in 0..n - 2 {
        // Keep every triangle counter-clockwise seen from +z.
        if k % 2 == 0 {
            s += &format!("3 {} {} {}\n", k, k + 2, k + 1);
        } else {
            s += &format!("3 {} {} {}\n", k, k + 1, k + 2);
        }
    }
    s
}

#[test]
fn index_type_is_u8_up_to_256_vertices_then_u16() {
    let opts = ConvertOptions {
        check_views: 0,
        directions: 4,
        rolls: 1,
        refine_starts: 0,
        ..quick()
    };
    let c = convert_model(&off(&strip(256, 0)), &opts).unwrap();
    assert_eq!((c.vertices.len(), c.index), (256, IndexType::U8));
    // A strip of triangles: emitted as a triangle list.
    assert!(c.rust.contains("pub static TRIANGLES: [[u8; 3]; 254]"));
    assert!(c.rust.contains("zrow::Mesh<'static, zrow::Q16_16, u8>"));
    let c = convert_model(&off(&strip(257, 0)), &opts).unwrap();
    assert_eq!((c.vertices.len(), c.index), (257, IndexType::U16));
    assert!(c.rust.contains("pub static TRIANGLES: [[u16; 3]; 255]"));
    // Unused vertices do not count: they are dropped, and the report says so.
    let c = convert_model(&off(&strip(256, 3)), &opts).unwrap();
    assert_eq!((c.vertices.len(), c.index), (256, IndexType::U8));
    assert!(
        c.report
            .notes
            .contains(&"t.off: 3 vertices no face uses dropped".to_owned()),
        "{:?}",
        c.report.notes
    );
}

#[test]
fn more_than_65536_vertices_is_an_error_naming_the_count() {
    // The loaders take any number of vertices (32-bit indices); the firmware's meshes index
    // with u8 or u16, so the converter refuses more than 65,536.
    let dir = scratch("big");
    let path = dir.join("big.off");
    std::fs::write(&path, strip(65_537, 0)).unwrap();
    let e = convert(&path, &quick()).unwrap_err().to_string();
    assert!(e.starts_with(&path.display().to_string()), "{e}");
    assert!(e.contains("65537"), "{e}");
    assert_eq!(IndexType::for_vertices(65_537), None);
}

fn quad_obj(z: f32) -> String {
    format!("v 0 0 0\nv 1 0 0\nv 1 1 {z}\nv 0 1 0\nf 1 2 3 4\n")
}

#[test]
fn a_non_planar_face_is_triangulated_and_reported_or_refused_under_strict() {
    let bent = obj(&quad_obj(0.2));
    let c = convert_model(&bent, &quick()).unwrap();
    assert_eq!(c.faces.len(), 2);
    assert!(c.faces.iter().all(|f| f.indices.len() == 3));
    let note = &c.report.notes[0];
    assert!(
        note.starts_with("t.obj:5: face with 4 vertices is not planar"),
        "{note}"
    );
    assert!(note.ends_with("split into 2 triangles (fan)"), "{note}");
    assert!(c.report.to_string().contains(note.as_str()));
    assert!(c.rust.contains(note.as_str()));
    let strict = ConvertOptions {
        strict: true,
        ..quick()
    };
    let e = convert_model(&bent, &strict).unwrap_err().to_string();
    assert!(
        e.starts_with("t.obj:5: face with 4 vertices is not planar") && e.ends_with("(--strict)"),
        "{e}"
    );
    // Within the tolerance: kept as it is, nothing reported.
    let flat = obj(&quad_obj(1e-5));
    let c = convert_model(&flat, &strict).unwrap();
    assert_eq!(c.faces.len(), 1);
    assert_eq!(
        c.report.notes,
        ["t.obj: open mesh: 4 edges belong to one face only (kept: holes show)"]
    );
}

#[test]
fn a_polygon_beyond_the_vertex_limit_is_reported_as_a_fan_or_refused() {
    let mut text = String::from("# a 14-gon\n");
    for k in 0..14 {
        let a = k as f32 * std::f32::consts::TAU / 14.0;
        text += &format!("v {} {} 0\n", a.cos(), a.sin());
    }
    text += "f";
    for k in 1..=14 {
        text += &format!(" {k}");
    }
    let model = obj(&text);
    let c = convert_model(&model, &quick()).unwrap();
    assert_eq!(c.faces.len(), 2);
    assert_eq!(
        c.report.notes,
        [
            "t.obj:16: polygon with 14 vertices (more than 10) split into a fan of 2 convex \
             polygons",
            // The split's inner edge is shared by the two pieces: only the rim is open.
            "t.obj: open mesh: 14 edges belong to one face only (kept: holes show)"
        ]
    );
    let strict = ConvertOptions {
        strict: true,
        ..quick()
    };
    let e = convert_model(&model, &strict).unwrap_err().to_string();
    assert!(e.starts_with("t.obj:16: polygon with 14 vertices"), "{e}");
}

#[test]
fn non_manifold_models_are_reported_with_the_first_face_or_refused() {
    // Three triangles on the edge 1-2.
    let fin = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\n\
               f 1 2 3\nf 2 4 3\nf 3 2 5\n";
    let c = convert_model(&obj(fin), &quick()).unwrap();
    let joined = c.report.notes.join("\n");
    assert!(
        joined.contains(
            "t.obj:8: non-manifold: 1 edges used by more than two faces; the first at face 2"
        ),
        "{joined}"
    );
    // Two triangles using the edge 1→2 in the same direction: inconsistent orientation.
    let flipped = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nf 1 2 3\nf 1 2 4\n";
    let c = convert_model(&obj(flipped), &quick()).unwrap();
    let joined = c.report.notes.join("\n");
    assert!(
        joined.contains("t.obj:6: non-manifold: 1 edges used twice in the same direction"),
        "{joined}"
    );
    assert!(joined.contains("open mesh: 4 edges belong to one face only"));
    let strict = ConvertOptions {
        strict: true,
        ..quick()
    };
    for (text, line) in [(fin, 8), (flipped, 6)] {
        let e = convert_model(&obj(text), &strict).unwrap_err().to_string();
        assert!(e.starts_with(&format!("t.obj:{line}: non-manifold")), "{e}");
    }
    // A closed, consistently oriented model: no finding.
    let c = convert(&asset("cube.obj"), &strict).unwrap();
    assert!(c.report.notes.is_empty(), "{:?}", c.report.notes);
}

#[test]
fn a_non_convex_face_is_an_error_naming_its_line() {
    let text = "v 0 0 0\nv 2 0 0\nv 1 0.2 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4 5\n";
    let e = convert_model(&obj(text), &quick()).unwrap_err().to_string();
    assert!(e.starts_with("t.obj:6: "), "{e}");
}

#[test]
fn bad_options_are_usage_errors() {
    let model = obj(&quad_obj(0.0));
    for (opts, want) in [
        (
            ConvertOptions {
                distance: 0.0,
                ..quick()
            },
            "bad view: distance 0",
        ),
        (
            ConvertOptions {
                name: "a b".into(),
                ..quick()
            },
            "bad name `a b`",
        ),
        (
            ConvertOptions {
                width: 0,
                ..quick()
            },
            "bad size 0x240",
        ),
    ] {
        let e = convert_model(&model, &opts).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains(want), "{e}");
    }
}

/// The recomputed position error of `c` against the loader's positions.
fn recomputed_error(model: &LoadedModel, c: &Converted) -> (f64, f64) {
    let mut max = 0.0f64;
    let mut sum = 0.0;
    for (v, &k) in c.vertices.iter().zip(&c.source) {
        let p = model.positions[k];
        let d: f64 = (0..3)
            .map(|i| (v[i] - f64::from(p[i])).powi(2))
            .sum::<f64>()
            .sqrt();
        max = max.max(d);
        sum += d;
    }
    (max, sum / c.vertices.len() as f64)
}

#[test]
fn the_reported_quantisation_error_is_the_recomputed_one() {
    for name in ["cube.obj", "icosphere.stl", "torus.off"] {
        let model = load(&asset(name)).unwrap();
        let c = convert_model(&model, &quick()).unwrap();
        let (max, mean) = recomputed_error(&model, &c);
        let e = c.report.position_error;
        assert_eq!((e.max, e.mean), (max, mean), "{name}");
        // Q16.16 rounds to nearest: at most half an LSB per coordinate.
        assert!(e.max_coordinate <= 0.5 / 65536.0, "{name}: {e:?}");
        assert!(e.max > 0.0, "{name}: nothing was rounded?");
        // f32 holds the loader's positions exactly.
        let f = ConvertOptions {
            format: Format::F32,
            ..quick()
        };
        let c = convert_model(&model, &f).unwrap();
        assert_eq!(recomputed_error(&model, &c), (0.0, 0.0));
        assert_eq!(c.report.position_error.max, 0.0);
    }
}

#[test]
fn normals_are_unit_and_outward() {
    let c = convert(&asset("icosphere.stl"), &quick()).unwrap();
    for (face, n) in c.faces.iter().zip(&c.normals) {
        let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((len - 1.0).abs() < 2e-5, "{len}");
        // The centroid of a face of a sphere centred on the origin points outward.
        let mut centroid = [0.0; 3];
        for &i in &face.indices {
            for (c, v) in centroid.iter_mut().zip(c.vertices[i as usize]) {
                *c += v;
            }
        }
        assert!(centroid.iter().zip(n).map(|(a, b)| a * b).sum::<f64>() > 0.0);
    }
}

/// The `static NAME: … = [` block of `rust`, one entry per line.
fn block<'a>(rust: &'a str, name: &str) -> Vec<&'a str> {
    let start = rust
        .find(&format!("pub static {name}:"))
        .unwrap_or_else(|| panic!("no {name}"));
    rust[start..]
        .lines()
        .skip(1)
        .take_while(|l| *l != "];")
        .map(str::trim)
        .collect()
}

#[test]
fn the_emitted_text_holds_exactly_the_converted_values() {
    let q = |x: f64| {
        let bits = x * 65536.0;
        assert_eq!(bits, bits.trunc(), "{x} is not a Q16.16 value");
        format!("zrow::Q16_16::from_bits({})", bits as i32)
    };
    let v3 = |v: &[f64; 3]| format!("zrow::Vec3::new({}, {}, {}),", q(v[0]), q(v[1]), q(v[2]));
    for name in ["cube.obj", "torus.off"] {
        let c = convert(&asset(name), &quick()).unwrap();
        let want: Vec<String> = c.vertices.iter().map(v3).collect();
        assert_eq!(block(&c.rust, "VERTICES"), want, "{name}");
        let want: Vec<String> = c.normals.iter().map(v3).collect();
        assert_eq!(block(&c.rust, "NORMALS"), want, "{name}");
        let faces = block(&c.rust, "FACES");
        assert_eq!(faces.len(), c.faces.len());
        for (line, f) in faces.iter().zip(&c.faces) {
            let (r, g, b) = (f.color.r(), f.color.g(), f.color.b());
            assert!(
                line.contains(&format!("indices: &{:?},", f.indices)),
                "{line}"
            );
            assert!(
                line.contains(&format!("Rgb565::new({r}, {g}, {b})")),
                "{line}"
            );
        }
        let cap = c.capacities;
        for (item, value) in [
            ("WIDTH", 240),
            ("HEIGHT", 240),
            ("POLYGONS", cap.polygons),
            ("EDGES", cap.edges),
            ("VERTEX_SLOTS", cap.vertices),
            ("ACTIVE", cap.active_polygons),
        ] {
            assert!(
                c.rust
                    .contains(&format!("pub const {item}: usize = {value};\n")),
                "{item}"
            );
        }
        assert!(c.rust.contains(
            "pub type Renderer = zrow::Scanline<zrow::Q16_16, WIDTH, VERTEX_SLOTS, POLYGONS, ACTIVE>;"
        ));
        // Every public item is documented.
        let lines: Vec<&str> = c.rust.lines().collect();
        for (k, l) in lines.iter().enumerate() {
            if l.starts_with("pub ") {
                assert!(lines[k - 1].starts_with("///"), "undocumented: {l}");
            }
        }
        // No inner attribute or doc (not allowed in an `include!`d file).
        assert!(!c.rust.contains("//!") && !c.rust.contains("#!["));
    }
}

/// `smooth` ([`ConvertOptions::smooth`], `--smooth`): one normal per vertex, emitted exactly;
/// the cube's corners split at a 45° crease (each copy its face's normal) and shared at 100°
/// (along the diagonals); an OBJ's own `vn` used; the split mesh draws what the flat one does.
#[test]
fn smooth_emits_one_normal_per_vertex() {
    let cube = load(&asset("cube.obj")).unwrap();
    let flat = convert_model(&cube, &quick()).unwrap();
    assert!(flat.vertex_normals.is_empty() && !flat.rust.contains("VERTEX_NORMALS"));
    let sharp = convert_model(
        &cube,
        &ConvertOptions {
            smooth: Some(45.0),
            ..quick()
        },
    )
    .unwrap();
    assert_eq!((sharp.vertices.len(), sharp.vertex_normals.len()), (24, 24));
    for (face, normal) in sharp.faces.iter().zip(&sharp.normals) {
        for &i in &face.indices {
            assert_eq!(sharp.vertex_normals[i as usize], *normal);
            assert_eq!(
                sharp.vertices[i as usize],
                flat.vertices[flat
                    .source
                    .iter()
                    .position(|&s| s == sharp.source[i as usize])
                    .unwrap()]
            );
        }
    }
    assert!(sharp.report.notes.iter().any(|n| n.contains(
        "smooth shading: vertex normals averaged from the faces, crease angle 45°; 8 vertices \
         become 24"
    )));
    let q = |x: f64| format!("zrow::Q16_16::from_bits({})", (x * 65536.0) as i32);
    let v3 = |v: &[f64; 3]| format!("zrow::Vec3::new({}, {}, {}),", q(v[0]), q(v[1]), q(v[2]));
    let want: Vec<String> = sharp.vertex_normals.iter().map(v3).collect();
    assert_eq!(block(&sharp.rust, "VERTEX_NORMALS"), want);
    assert_eq!(sharp.report.flash.normals, 12 * (6 + 24));
    // Still one closed convex solid (its corners' copies share positions): culling alone.
    assert!(flat.report.cull_only_ram.is_some());
    assert_eq!(sharp.report.cull_only_ram, flat.report.cull_only_ram);
    let round = convert_model(
        &cube,
        &ConvertOptions {
            smooth: Some(100.0),
            ..quick()
        },
    )
    .unwrap();
    assert_eq!(round.vertices.len(), 8);
    let d = (65536.0 / 3f64.sqrt()).round() / 65536.0;
    for (n, p) in round.vertex_normals.iter().zip(&round.vertices) {
        assert_eq!(*n, p.map(|c| d * c.signum()), "{p:?}");
    }
    // The split cube draws the flat cube's pixels (same positions, same face normals).
    let view = View::default();
    let a = zrow_sim::convert::render_converted(&flat, &view, 96, 80).unwrap();
    let b = zrow_sim::convert::render_converted(&sharp, &view, 96, 80).unwrap();
    assert!(a.pixels == b.pixels);
    // A file's own normals: a square of two triangles, one corner tilted.
    let m = obj(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 0.6 0.8\n\
                 f 1//1 2//1 3//1\nf 1//2 3//1 4//1\n",
    );
    let c = convert_model(
        &m,
        &ConvertOptions {
            smooth: Some(45.0),
            ..quick()
        },
    )
    .unwrap();
    assert_eq!(c.vertex_normals.len(), 5);
    assert!(c
        .report
        .notes
        .iter()
        .any(|n| n.contains("the file's normals (vn); 4 vertices become 5")));
}

#[test]
fn the_converted_mesh_draws_like_the_loaded_model() {
    let views = [
        View::default(),
        View {
            yaw_deg: -100.0,
            pitch_deg: -35.0,
            distance: 2.5,
        },
    ];
    for name in ["cube.obj", "icosphere.stl", "torus.off"] {
        let model = load(&asset(name)).unwrap();
        for format in [Format::Q16_16, Format::F32] {
            let opts = ConvertOptions { format, ..quick() };
            let c = convert_model(&model, &opts).unwrap();
            for view in &views {
                let want =
                    render_model_image(&model, view, 96, 80, Algo::Scanline, format).unwrap();
                let got = zrow_sim::convert::render_converted(&c, view, 96, 80).unwrap();
                assert!(want.pixels.iter().any(|&p| p != want.pixels[0]));
                // The converted mesh carries precomputed normals, which model mode culls and
                // shades with: same coverage (the background stays where it was), each
                // colour channel within 1 LSB of the cross product's shading.
                let mut differing = 0;
                for (k, (a, b)) in want.pixels.iter().zip(&got.pixels).enumerate() {
                    let bg = Rgb565::BLACK;
                    assert_eq!(*a == bg, *b == bg, "{name} {format:?} {view:?}: pixel {k}");
                    let close = |x: u8, y: u8| x.abs_diff(y) <= 1;
                    assert!(
                        close(a.r(), b.r()) && close(a.g(), b.g()) && close(a.b(), b.b()),
                        "{name} {format:?} {view:?}: pixel {k}: {a:?} vs {b:?}"
                    );
                    differing += usize::from(a != b);
                }
                // Most pixels are exactly equal.
                assert!(differing * 10 < want.pixels.len(), "{name}: {differing}");
            }
        }
    }
}

#[test]
fn random_views_never_need_more_than_the_emitted_capacities() {
    for name in ["icosphere.stl", "torus.off"] {
        let c = convert(&asset(name), &quick()).unwrap();
        let opts = quick();
        let cap = c.capacities;
        let mut worst = zrow::Requirements::default();
        c.with_mesh::<zrow::Q16_16, _>(|mesh| {
            // A seed the converter did not use.
            for rot in random_rotations(300, 0xDEC0DE) {
                let req = measure_view(mesh, &rot, &opts).unwrap();
                worst = worst.max(req);
            }
        })
        .unwrap();
        assert!(worst.polygons > 0);
        assert!(
            worst.polygons <= cap.polygons
                && worst.edges <= cap.edges
                && worst.active_polygons <= cap.active_polygons,
            "{name}: {worst:?} > {cap:?}"
        );
        // And the capacities are not padding: the margin is small.
        let searched = c.report.views.refined_max;
        assert!(
            cap.edges <= searched.edges + searched.edges / 20 + 1,
            "{name}"
        );
        assert!(searched.edges >= c.report.views.sampled_max.edges);
    }
}

#[test]
fn write_for_build_writes_name_rs() {
    let dir = scratch("build");
    let report = write_for_build(&asset("cube.obj"), &quick(), &dir, "cube").unwrap();
    let rust = std::fs::read_to_string(dir.join("cube.rs")).unwrap();
    assert!(rust.contains("pub const NAME: &str = \"cube\";"));
    assert!(rust.contains(&format!(
        "// {}",
        report.to_string().lines().next().unwrap()
    )));
}

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_zrow-sim"))
}

#[test]
fn cli_convert_writes_the_file_and_prints_the_report() {
    let dir = scratch("cli");
    let out = dir.join("cube.rs");
    let run = bin()
        .args(["convert", "--size", "120x100", "--checks", "20", "--out"])
        .arg(&out)
        .arg("--model")
        .arg(asset("cube.obj"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(
        stdout.contains("8 vertices (u8 indices), 6 faces, q16.16"),
        "{stdout}"
    );
    assert!(stdout.contains("views at 120x100"), "{stdout}");
    let rust = std::fs::read_to_string(&out).unwrap();
    // The same as the library's output with the same options.
    let opts = ConvertOptions {
        width: 120,
        height: 100,
        check_views: 20,
        name: "cube".into(),
        ..ConvertOptions::default()
    };
    assert_eq!(rust, convert(&asset("cube.obj"), &opts).unwrap().rust);
}

#[test]
fn cli_convert_bad_input_is_one_line_naming_file_and_line() {
    let dir = scratch("cli-bad");
    let model = dir.join("bent.obj");
    std::fs::write(&model, quad_obj(0.3)).unwrap();
    let run = bin()
        .args(["convert", "--strict", "--checks", "0", "--model"])
        .arg(&model)
        .arg("--out")
        .arg(dir.join("bent.rs"))
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&run.stderr);
    let want = format!(
        "error: {}:5: face with 4 vertices is not planar",
        model.display()
    );
    assert!(stderr.starts_with(&want), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(!dir.join("bent.rs").exists());
    // Usage errors exit 2.
    let run = bin()
        .args(["convert", "--strict=yes", "--model", "a.obj"])
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("--strict takes no value"));
}

/// The converter names the cheapest exact renderer: culling alone for a closed convex solid
/// (cube, icosphere — the STL's welded vertices close it), the scan-line renderer otherwise.
#[test]
fn the_cheapest_exact_renderer_follows_the_structure() {
    for (name, convex) in [
        ("cube.obj", true),
        ("icosphere.stl", true),
        ("torus.off", false),
    ] {
        let c = convert(&asset(name), &quick()).unwrap();
        assert_eq!(c.report.cull_only_ram.is_some(), convex, "{name}");
        let cull =
            "pub type Cheapest = zrow::cullonly::CullOnly<zrow::Q16_16, WIDTH, POLYGONS, EDGES>;";
        assert_eq!(c.rust.contains(cull), convex, "{name}");
        assert_eq!(
            c.rust.contains("pub type Cheapest = Renderer;"),
            !convex,
            "{name}"
        );
        assert!(c.report.to_string().contains("structure: "), "{name}");
    }
}
