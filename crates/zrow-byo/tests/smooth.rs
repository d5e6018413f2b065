//! The torus converted with per-vertex normals (`torus_smooth`, crease angle 60°): the same
//! vertices and faces as the flat conversion, and at each vertex a unit normal close to the
//! torus's own surface normal there; its `MESH` draws smooth within the converter's capacities.

use zrow::Scalar;
use zrow_byo::{torus, torus_smooth};

#[test]
fn the_smooth_torus_has_the_surface_normals() {
    assert_eq!(torus_smooth::VERTICES, torus::VERTICES);
    assert_eq!(torus_smooth::FACES.len(), torus::FACES.len());
    for (a, b) in torus_smooth::FACES.iter().zip(&torus::FACES) {
        assert_eq!(a.indices, b.indices);
    }
    assert_eq!(torus_smooth::VERTEX_NORMALS.len(), torus::VERTICES.len());
    // The file's torus: major radius 1 about the y axis, minor 0.4; normalised into the unit
    // sphere by the loader (centre 0, one scale), so the core circle's radius is 1 / 1.4 of
    // the largest distance of a vertex from the axis, whatever the scale.
    let f = |v: zrow::Vec3<zrow::Q16_16>| [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()];
    let core_radius = torus::VERTICES
        .iter()
        .map(|&v| {
            let p = f(v);
            (p[0] * p[0] + p[2] * p[2]).sqrt()
        })
        .fold(0.0, f64::max)
        / 1.4;
    let mut worst: f64 = 0.0;
    for (&v, &n) in torus::VERTICES.iter().zip(&torus_smooth::VERTEX_NORMALS) {
        let (p, n) = (f(v), f(n));
        let r = (p[0] * p[0] + p[2] * p[2]).sqrt();
        let core = [p[0] / r * core_radius, 0.0, p[2] / r * core_radius];
        let d = [p[0] - core[0], p[1], p[2] - core[2]];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let cos = (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / len;
        let norm = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((norm - 1.0).abs() < 4.0 / 65536.0, "{norm}");
        worst = worst.max((cos / norm).clamp(-1.0, 1.0).acos().to_degrees());
    }
    eprintln!("torus_smooth: worst vertex normal {worst:.3}° from the surface's");
    // 16 x 8 quads: the faces on either side of a vertex along the tube differ in shape, so
    // their average leans a little (measured 2.74°), well under the 22.5° between faces.
    assert!(worst < 3.0, "{worst}°");
}

/// The converted mesh carries its vertex normals, and the renderer sized by the converter's
/// capacities with intensity planes draws it smooth: the z-buffer's frame, and not the flat one.
#[test]
fn the_smooth_torus_draws_smooth_within_its_capacities() {
    use zrow::shading::Shading;
    use zrow::{Affine, Config, FrameBuffer, ModelScene, Object, Rgb565, Scanline};
    use zrow_model::camera::{light, View};
    assert_eq!(
        torus_smooth::MESH.vertex_normals.len(),
        torus::VERTICES.len()
    );
    type Smooth = Scanline<
        zrow::Q16_16,
        { torus_smooth::WIDTH },
        { torus_smooth::VERTEX_SLOTS },
        { torus_smooth::POLYGONS },
        { torus_smooth::ACTIVE },
        u16,
        zrow::scanline::Uncued,
        [zrow::IntensityPlane<zrow::Q16_16>; torus_smooth::POLYGONS],
    >;
    let objects = [Object {
        mesh: &torus_smooth::MESH,
        transform: Affine::rotate_yx_translate(0.4, 0.3, [0.0; 3]).unwrap(),
    }];
    let scene = ModelScene {
        objects: &objects,
        camera: View::default().camera().unwrap(),
        light: light(),
    };
    let draw = |r: &mut dyn FnMut(&Config, &mut FrameBuffer<'_>), shading| {
        let mut cfg = Config::model(240, 240);
        cfg.shading = shading;
        let mut pixels = vec![Rgb565::new(0, 0, 0); 240 * 240];
        r(&cfg, &mut FrameBuffer::new(&mut pixels, 240));
        pixels
    };
    let mut scan = Box::new(Smooth::new());
    let mut zbuf = Box::new(zrow::ZBuffer::<zrow::Q16_16, 240, 240>::new());
    let smooth = draw(
        &mut |c, f| {
            scan.render(&scene, c, f).unwrap();
        },
        Shading::Gouraud { dither: false },
    );
    let flat = draw(
        &mut |c, f| {
            scan.render(&scene, c, f).unwrap();
        },
        Shading::Flat,
    );
    let by_z = draw(
        &mut |c, f| {
            zbuf.render(&scene, c, f).unwrap();
        },
        Shading::Gouraud { dither: false },
    );
    assert_eq!(smooth, by_z);
    let changed = smooth.iter().zip(&flat).filter(|(a, b)| a != b).count();
    assert!(changed > 1000, "smooth shading changed {changed} pixels");
}
