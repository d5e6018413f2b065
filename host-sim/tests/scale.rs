//! Models far beyond the host renderer's tables: generated here (no large file committed),
//! drawn band by band, the scan-line frame equal to the z-buffer's.

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use zrow_sim::model::{parse, LoadedModel, ModelFace, ModelFormat};
use zrow_sim::model_render::{render_model_image, View};
use zrow_sim::render::{Algo, Format};

/// A torus of `2·nu·nv` triangles, already normalised (inside the unit sphere).
fn torus(nu: u32, nv: u32) -> LoadedModel {
    let mut positions = Vec::with_capacity((nu * nv) as usize);
    for i in 0..nu {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(nu);
        for j in 0..nv {
            let b = std::f64::consts::TAU * f64::from(j) / f64::from(nv);
            let r = 0.7 + 0.25 * b.cos();
            positions.push([
                (r * a.cos()) as f32,
                (0.25 * b.sin()) as f32,
                (r * a.sin()) as f32,
            ]);
        }
    }
    let mut faces = Vec::with_capacity(2 * (nu * nv) as usize);
    for i in 0..nu {
        for j in 0..nv {
            let at = |di: u32, dj: u32| ((i + di) % nu) * nv + (j + dj) % nv;
            let color = if (i / 8 + j / 8) % 2 == 0 {
                Rgb565::WHITE
            } else {
                Rgb565::CYAN
            };
            for indices in [
                vec![at(0, 0), at(0, 1), at(1, 0)],
                vec![at(1, 0), at(0, 1), at(1, 1)],
            ] {
                faces.push(ModelFace {
                    indices,
                    color,
                    origin: None,
                    normals: Vec::new(),
                });
            }
        }
    }
    LoadedModel {
        file: format!("torus-{}.generated", 2 * nu * nv),
        vertex_origins: vec![None; positions.len()],
        positions,
        faces,
        normals: Vec::new(),
        vertex_normals: Vec::new(),
        centre: [0.0; 3],
        scale: 1.0,
        warnings: Vec::new(),
    }
}

fn scanline_equals_zbuffer(model: &LoadedModel, size: u16, format: Format) {
    let view = View::default();
    let draw = |algo| render_model_image(model, &view, size, size, algo, format).unwrap();
    let (scan, z) = (draw(Algo::Scanline), draw(Algo::ZBuffer));
    let differ = scan
        .pixels
        .iter()
        .zip(&z.pixels)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(differ, 0, "{}: {differ} pixels differ", model.file);
    // The torus is there: a good share of the frame is lit.
    let lit = scan.pixels.iter().filter(|&&p| p != Rgb565::BLACK).count();
    assert!(
        lit > usize::from(size) * usize::from(size) / 10,
        "{lit} lit"
    );
}

#[test]
fn a_200000_triangle_model_renders_and_the_methods_agree() {
    let model = torus(500, 200);
    assert_eq!(model.faces.len(), 200_000);
    scanline_equals_zbuffer(&model, 240, Format::Q16_16);
    scanline_equals_zbuffer(&model, 320, Format::F32);
}

#[test]
fn a_1000000_triangle_model_renders_and_the_methods_agree() {
    let model = torus(1000, 500);
    assert_eq!(model.faces.len(), 1_000_000);
    scanline_equals_zbuffer(&model, 240, Format::Q16_16);
}

#[test]
fn an_obj_with_more_than_65536_vertices_loads() {
    // A strip of 70,000 vertices: the loader used to stop at 65,536 and report "no faces".
    let n = 35_000;
    let mut obj = String::new();
    for i in 0..n {
        let x = i as f32 / n as f32;
        obj += &format!("v {x} 0 0\nv {x} 1 0\n");
    }
    for i in 0..n - 1 {
        let (a, b) = (2 * i + 1, 2 * i + 2);
        obj += &format!("f {a} {} {b}\nf {b} {} {}\n", a + 2, a + 2, b + 2);
    }
    let model = parse("strip.obj", ModelFormat::Obj, obj.as_bytes(), ".".as_ref()).unwrap();
    assert_eq!(model.positions.len(), 70_000);
    assert_eq!(model.faces.len(), 2 * (n - 1));
    assert_eq!(
        model.faces.last().unwrap().indices,
        vec![69_997, 69_998, 69_999]
    );
}
