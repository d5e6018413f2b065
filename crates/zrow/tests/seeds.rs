//! Small worked examples of the classic hidden-surface questions (which triangle is in front
//! at a point and at what depth; which polygon a depth sort paints first; which cube faces are
//! back faces), with the answers worked by hand, as tests.

mod common;
use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{backface::is_back_face, Camera, Config, Face, Projection, Scalar, Vec3, Q16_16};

/// Two triangles: s1 = (0,0,6),(6,0,0),(0,6,0), s2 = (2,0,6),(6,0,6),(4,4,0); at (3, 1) s1 is
/// visible with depth 2. Our samples are at pixel centres, so the scene moves by half a pixel
/// to put pixel (3, 1)'s centre on the example's point.
fn seed002<N: Scalar>() {
    let sh = |x: f32, y: f32, z: f32| [x + 0.5, y + 0.5, z];
    let p = Polys::new(vec![
        vec![sh(0., 0., 6.), sh(6., 0., 0.), sh(0., 6., 0.)],
        vec![sh(2., 0., 6.), sh(6., 0., 6.), sh(4., 4., 0.)],
    ]);
    let cfg = Config::screen(8, 8);
    let cap = p.render::<N>(&cfg).unwrap();
    assert_eq!(index_of(cap.at(3, 1)), Some(0), "s1 visible at (3,1)");
    assert_eq!(cap.z(3, 1).to_f32(), 2.0, "depth 2 at (3,1)");
    // The hand-worked walk: (0,6) is s1's apex, depth 0, but a bottom vertex owns no sample (top-left
    // rule); (0,5) has depth 1 and the row y = 1 starts at depth 5.
    assert_eq!(index_of(cap.at(0, 6)), None);
    assert_eq!(cap.z(0, 5).to_f32(), 1.0);
    assert_eq!(cap.z(0, 1).to_f32(), 5.0);
    // Where only s2 covers, s2 shows: (5, 1) is inside s2 only, depth 6 − 1.5·1 = 4.5.
    assert_eq!(index_of(cap.at(5, 1)), Some(1));
    assert_eq!(cap.z(5, 1).to_f32(), 4.5);
    // And the whole frame equals the exact reference.
    let refr = reference::<N>(&p, &cfg, tie_tolerance::<N>(16));
    assert!(mismatches(&cap, &refr).is_empty());
}

#[test]
fn seed002_s1_visible_at_3_1_with_depth_2_q16_16() {
    seed002::<Q16_16>();
}

#[test]
fn seed002_s1_visible_at_3_1_with_depth_2_f32() {
    seed002::<f32>();
}

/// A depth-sort example: P (100,100,50),(50,50,50),(150,50,50) and Q (40,80,60),(70,70,50),
/// (10,75,70): their boxes overlap in xy, their depths do not (P at 50, Q at 50..70), so "Q is
/// painted first, followed by P". The scan-line picture must equal exactly that painting.
/// (They only touch — Q's vertex (70,70) lies on P's edge — and where they touch, at depth 50
/// both, P wins the tie as first in the scene.)
fn example6<N: Scalar>() {
    let p = Polys::new(vec![
        vec![[100., 100., 50.], [50., 50., 50.], [150., 50., 50.]],
        vec![[40., 80., 60.], [70., 70., 50.], [10., 75., 70.]],
    ]);
    let (zp_max, zq_min) = (50.0, 50.0);
    assert!(zp_max <= zq_min, "no depth overlap: P is never behind Q");
    let cfg = Config::screen(160, 120);
    let both = p.render::<N>(&cfg).unwrap();
    let mut painted = Capture::<N>::new(160, 120);
    for k in [1, 0] {
        let alone = Polys::new(vec![p.polys[k].clone()])
            .render::<N>(&cfg)
            .unwrap();
        for (dst, src) in painted.color.iter_mut().zip(&alone.color) {
            if *src != Rgb565::BLACK {
                *dst = color_of(k);
            }
        }
    }
    assert_eq!(both.color, painted.color);
    assert!(both.color.contains(&color_of(0)) && both.color.contains(&color_of(1)));
}

#[test]
fn example6_p_painted_over_q() {
    example6::<Q16_16>();
    example6::<f32>();
}

/// The unit cube [0,1]^3 with outward counter-clockwise faces, one colour per face.
pub const CUBE_FACES: [(&[u16], &str); 6] = [
    (&[1, 3, 7, 5], "+x"),
    (&[0, 4, 6, 2], "-x"),
    (&[2, 6, 7, 3], "+y"),
    (&[0, 1, 5, 4], "-y"),
    (&[4, 5, 7, 6], "+z"),
    (&[0, 2, 3, 1], "-z"),
];

fn cube_vertices<N: Scalar>() -> Vec<Vec3<N>> {
    (0..8)
        .map(|i| {
            Vec3::from_f32([(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32]).unwrap()
        })
        .collect()
}

/// Renders the unit cube, each face in its own unshaded colour (full ambient), and returns the
/// pixel count of each face.
fn render_cube<N: Scalar>(camera: Camera<N>, size: u16) -> [usize; 6] {
    let verts = cube_vertices::<N>();
    let faces: Vec<Face> = CUBE_FACES
        .iter()
        .enumerate()
        .map(|(i, (idx, _))| Face {
            indices: idx,
            color: color_of(i),
            alpha: 255,
        })
        .collect();
    let cap = render_model(&verts, &faces, camera, &Config::model(size, size));
    let mut seen = [0usize; 6];
    for c in &cap.color {
        if let Some(i) = index_of(*c) {
            seen[i] += 1;
        }
    }
    assert_eq!(
        seen.iter().sum::<usize>(),
        cap.drawn(),
        "only face colours drawn"
    );
    seen
}

/// Back faces: the unit cube at the origin seen from (5, −1, 5): faces +x, −y and +z are
/// visible, the other three are back faces.
fn cube_from_5_m1_5<N: Scalar>() {
    // The hand-worked table: V = (−5, 1, −5) against each normal.
    let v = Vec3::<N>::from_f32([-5.0, 1.0, -5.0]).unwrap();
    let normals = [
        ([1., 0., 0.], false),
        ([-1., 0., 0.], true),
        ([0., 1., 0.], true),
        ([0., -1., 0.], false),
        ([0., 0., 1.], false),
        ([0., 0., -1.], true),
    ];
    for (n, back) in normals {
        assert_eq!(
            is_back_face(Vec3::<N>::from_f32(n).unwrap(), v),
            back,
            "{n:?}"
        );
    }
    // And rendered through the whole pipeline, each face in its own colour.
    let camera = Camera::look_at(
        [5.0, -1.0, 5.0],
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        Camera::<N>::perspective(0.6, 0.1, 50.0).unwrap(),
    )
    .unwrap();
    let seen = render_cube(camera, 96);
    let visible: Vec<&str> = (0..6)
        .filter(|&i| seen[i] > 0)
        .map(|i| CUBE_FACES[i].1)
        .collect();
    assert_eq!(visible, ["+x", "-y", "+z"], "pixels per face {seen:?}");
    assert!(seen.iter().all(|&n| n == 0 || n > 50));
}

#[test]
fn seed004_cube_from_5_m1_5_shows_px_my_pz() {
    cube_from_5_m1_5::<Q16_16>();
    cube_from_5_m1_5::<f32>();
}

/// The same cube from (20, 40, 20) the visible faces are +x, +y, +z.
#[test]
fn seed004_cube_from_20_40_20() {
    let v = Vec3::<f32>::new(-20.0, -40.0, -20.0);
    let vis = |n: [f32; 3]| !is_back_face(Vec3::new(n[0], n[1], n[2]), v);
    assert!(vis([1., 0., 0.]) && vis([0., 1., 0.]) && vis([0., 0., 1.]));
    assert!(!vis([-1., 0., 0.]) && !vis([0., -1., 0.]) && !vis([0., 0., -1.]));
}

/// Orthographic projection gives the textbook "back face if C < 0" along the view axis.
#[test]
fn orthographic_cube_shows_one_face_head_on() {
    let camera = Camera::look_at(
        [0.5, 0.5, 5.0],
        [0.5, 0.5, 0.0],
        [0.0, 1.0, 0.0],
        Projection::Orthographic {
            half_height: 1.0,
            near: 0.5,
            far: 10.0,
        },
    )
    .unwrap();
    let seen = render_cube::<f32>(camera, 64);
    // Only +z faces the viewer: a 32x32 square (half_height 1 → 32 px per unit).
    assert_eq!(seen, [0, 0, 0, 0, 32 * 32, 0]);
}
