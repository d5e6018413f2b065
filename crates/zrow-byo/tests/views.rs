//! The included meshes under orientations the converter never sampled (a seed it does not
//! use): the renderer sized by the converter never runs out of room, and draws what a
//! generously sized one draws, and so does its display renderer (`Display`: no depth row,
//! 12-bit slots), in less RAM; the cube, a closed convex solid, is drawn exactly by culling
//! alone at the converter's capacities; the icosphere, emitted as a triangle list, draws what
//! the same triangles as a list of faces draw; converted with compact positions, it draws
//! what the same positions in Q16.16 draw, within 2^-15 of the Q16.16 conversion's.

use zrow::Rgb565;
use zrow::{
    Affine, Config, FrameBuffer, Mesh, MeshIndex, ModelScene, Object, Renderer, Scanline, Q16_16,
};
use zrow_byo::{cube, icosphere, icosphere_compact, torus};
use zrow_model::camera::{light, View};
use zrow_model::convert::random_rotations;

type Big = Scanline<Q16_16, 240, 8192, 2048, 512>;

// The display renderer the converter emits is the smaller one (checked as the test builds).
const _: () = assert!(torus::Display::RAM_BYTES < torus::Renderer::RAM_BYTES);

/// Renders `mesh` turned by `rot` with `R`, as the converter's views are set up.
fn draw<R: Renderer<Q16_16>, I: MeshIndex>(
    r: &mut R,
    mesh: &Mesh<'_, Q16_16, I>,
    rot: &[[f64; 3]; 3],
) -> Result<Vec<Rgb565>, zrow::RenderError<core::convert::Infallible>> {
    let m = rot.map(|row| row.map(|c| c as f32));
    let transform = Affine::from_f32([
        [m[0][0], m[0][1], m[0][2], 0.0],
        [m[1][0], m[1][1], m[1][2], 0.0],
        [m[2][0], m[2][1], m[2][2], 0.0],
    ])
    .unwrap();
    let objects = [Object { mesh, transform }];
    let scene = ModelScene {
        objects: &objects,
        camera: View::default().camera().unwrap(),
        light: light(),
    };
    let mut pixels = vec![Rgb565::new(0, 0, 0); 240 * 240];
    r.render(
        &scene,
        &Config::model(240, 240),
        &mut FrameBuffer::new(&mut pixels, 240),
    )?;
    Ok(pixels)
}

#[test]
fn the_converted_capacities_hold_under_unsampled_views() {
    let (mut small, mut big) = (Box::new(torus::Renderer::new()), Box::new(Big::new()));
    let mut display = Box::new(torus::Display::new());
    for rot in random_rotations(300, 0x05ee_db10) {
        let got = draw(&mut *small, &torus::MESH, &rot).expect("capacities hold");
        assert!(got == draw(&mut *big, &torus::MESH, &rot).unwrap());
        assert!(got == draw(&mut *display, &torus::MESH, &rot).expect("display capacities hold"));
    }
    println!(
        "torus: converter capacities P={} E={} A={}, renderer RAM {} B (a 240x240 frame + 16-bit z-buffer: {} B)",
        torus::POLYGONS,
        torus::EDGES,
        torus::ACTIVE,
        torus::Renderer::RAM_BYTES,
        240 * 240 * 4
    );
}

#[test]
fn the_cube_needs_culling_alone() {
    assert!(zrow::structure::closed_convex(&cube::MESH));
    assert!(!zrow::structure::closed_convex(&torus::MESH));
    // The converter found the cube closed and convex, so its `Cheapest` is culling alone.
    assert_eq!(<cube::Cheapest as Renderer<Q16_16>>::NAME, "cull-only");
    assert_eq!(<torus::Cheapest as Renderer<Q16_16>>::NAME, "scanline");
    let mut cull = Box::new(cube::Cheapest::new());
    let mut scan = Box::new(cube::Renderer::new());
    for rot in random_rotations(100, 0xc0be) {
        assert!(
            draw(&mut *cull, &cube::MESH, &rot).unwrap()
                == draw(&mut *scan, &cube::MESH, &rot).unwrap()
        );
    }
}

#[test]
fn a_model_of_triangles_is_emitted_as_a_triangle_list() {
    assert!(matches!(
        icosphere::MESH.faces,
        zrow::Faces::Triangles { .. }
    ));
    assert!(matches!(torus::MESH.faces, zrow::Faces::List(_)));
    assert_eq!(icosphere::MESH.faces.len(), icosphere::TRIANGLES.len());
    assert!(icosphere::COLORS.len() == 1 || icosphere::COLORS.len() == icosphere::TRIANGLES.len());
    // The same triangles as a list of faces draw the same frames.
    let faces: Vec<zrow::Face<'_, _>> = icosphere::MESH.faces.iter().collect();
    let listed = Mesh::with_normals(&icosphere::VERTICES, &faces, &icosphere::NORMALS);
    let (mut small, mut big) = (Box::new(icosphere::Renderer::new()), Box::new(Big::new()));
    for rot in random_rotations(100, 0x1c05) {
        let got = draw(&mut *small, &icosphere::MESH, &rot).expect("capacities hold");
        assert!(got.iter().any(|&p| p != Rgb565::new(0, 0, 0)));
        assert!(got == draw(&mut *big, &listed, &rot).unwrap());
    }
}

#[test]
fn compact_positions_draw_what_their_values_draw() {
    let compact = &icosphere_compact::MESH;
    assert!(matches!(
        compact.vertices,
        zrow::Vectors::Compact { shift: 14, .. }
    ));
    // Half the vertices' and the normals' flash, and every coordinate within 2^-15 (plus
    // the Q16.16 conversion's own 2^-17) of the Q16.16 conversion's.
    assert_eq!(
        core::mem::size_of_val(&icosphere_compact::VERTICES),
        icosphere_compact::VERTICES.len() * 6
    );
    assert_eq!(
        core::mem::size_of_val(&icosphere_compact::NORMALS),
        icosphere_compact::NORMALS.len() * 6
    );
    assert_eq!(compact.vertices.len(), icosphere::VERTICES.len());
    assert_eq!(compact.normals.len(), icosphere::NORMALS.len());
    let pairs = compact
        .vertices
        .iter()
        .zip(icosphere::VERTICES.iter().copied())
        .chain(
            compact
                .normals
                .iter()
                .zip(icosphere::NORMALS.iter().copied()),
        );
    for (c, q) in pairs {
        for (a, b) in [(c.x, q.x), (c.y, q.y), (c.z, q.z)] {
            let d = (a.to_bits() - b.to_bits()).abs();
            assert!(d <= 3, "{a} against {b}");
        }
    }
    // The same values as a Q16.16 position table draw the same frames, and the compact
    // conversion's own capacities hold.
    let values: Vec<zrow::Vec3<Q16_16>> = compact.vertices.iter().collect();
    let normals: Vec<zrow::Vec3<Q16_16>> = compact.normals.iter().collect();
    let faces: Vec<zrow::Face<'_, _>> = compact.faces.iter().collect();
    let plain = Mesh::with_normals(&values, &faces, &normals);
    let (mut small, mut big) = (
        Box::new(icosphere_compact::Renderer::new()),
        Box::new(Big::new()),
    );
    for rot in random_rotations(100, 0xc0_3ac7) {
        let got = draw(&mut *small, compact, &rot).expect("capacities hold");
        assert!(got.iter().any(|&p| p != Rgb565::new(0, 0, 0)));
        assert!(got == draw(&mut *big, &plain, &rot).unwrap());
    }
}
