//! Converts `assets/models/torus.off`, `assets/models/cube.obj` and
//! `assets/models/icosphere.stl` into `$OUT_DIR/torus.rs`, `$OUT_DIR/cube.rs` and
//! `$OUT_DIR/icosphere.rs` (const data for flash: Q16.16 positions, u8 indices, per-face normals,
//! scan-line capacities for every orientation at 240×240, distance 3), the icosphere once more
//! with compact positions into `$OUT_DIR/icosphere_compact.rs`, the torus once more with one
//! normal per vertex for smooth shading (crease angle 60°) into `$OUT_DIR/torus_smooth.rs`, and
//! keeps each
//! converter report next to it (`$OUT_DIR/NAME.txt`). A bad model fails the build with the
//! converter's one-line error naming file and line.

use std::path::{Path, PathBuf};
use zrow_model::convert::{write_for_build, ConvertOptions};

fn main() {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/models");
    let compact = ConvertOptions {
        compact: true,
        ..ConvertOptions::default()
    };
    let smooth = ConvertOptions {
        smooth: Some(60.0),
        ..ConvertOptions::default()
    };
    for (file, name, opts) in [
        ("torus.off", "torus", &ConvertOptions::default()),
        ("cube.obj", "cube", &ConvertOptions::default()),
        ("icosphere.stl", "icosphere", &ConvertOptions::default()),
        ("icosphere.stl", "icosphere_compact", &compact),
        ("torus.off", "torus_smooth", &smooth),
    ] {
        match write_for_build(&models.join(file), opts, &out, name) {
            Ok(report) => {
                std::fs::write(out.join(format!("{name}.txt")), report.to_string())
                    .expect("write the report");
            }
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(1);
            }
        }
    }
}
