//! Pictures as tests: small renders through the embedded-graphics `DrawTarget` adapter into
//! `MockDisplay`, which fails on a pixel drawn twice or off-screen, compared with ASCII grids.
//! (R red, G green, B blue, K black background.)

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use zrow::{Config, DrawTargetSink, Face, Mesh, Scalar, Scanline, ScreenScene, Vec3, Q16_16};

fn draw<N: Scalar>(
    verts: &[[f32; 3]],
    faces: &[(&[u16], Rgb565)],
    w: u16,
    h: u16,
) -> MockDisplay<Rgb565> {
    let v: Vec<Vec3<N>> = verts.iter().map(|p| Vec3::from_f32(*p).unwrap()).collect();
    let f: Vec<Face> = faces
        .iter()
        .map(|(i, c)| Face {
            indices: i,
            color: *c,
            alpha: 255,
        })
        .collect();
    let scene = ScreenScene {
        mesh: Mesh::new(&v, &f),
    };
    let mut display = MockDisplay::new();
    let mut r = Scanline::<N, 16, 32, 8, 8>::new();
    r.render(
        &scene,
        &Config::screen(w, h),
        &mut DrawTargetSink(&mut display),
    )
    .unwrap();
    display
}

/// EXTREMES 1's golden vector: the 5x5 square from (0.5, 0.5) to (5.5, 5.5) split on its
/// diagonal: pixel centres 0.5..4.5 lie inside or on its top and left edges, so pixels 0..=4:
/// 15 red, 10 green, none twice (MockDisplay would panic on overdraw).
fn split_square<N: Scalar>() {
    let v = [
        [0.5, 0.5, 1.0],
        [5.5, 0.5, 1.0],
        [5.5, 5.5, 1.0],
        [0.5, 5.5, 1.0],
    ];
    let d = draw::<N>(
        &v,
        &[(&[0, 1, 3], Rgb565::RED), (&[1, 2, 3], Rgb565::GREEN)],
        7,
        7,
    );
    d.assert_pattern(&[
        "RRRRRKK", "RRRRGKK", "RRRGGKK", "RRGGGKK", "RGGGGKK", "KKKKKKK", "KKKKKKK",
    ]);
}

#[test]
fn golden_split_square_picture() {
    split_square::<Q16_16>();
    split_square::<f32>();
}

/// Two triangles piercing each other: red is nearer on the left, green on the right; they
/// cross at x = 4 (depth red = x, green = 8 − x; at the tie column red, first, wins).
fn piercing<N: Scalar>() {
    let v = [
        [0.0, 0.0, 0.5],
        [8.0, 0.0, 8.5],
        [0.0, 4.0, 0.5],
        [0.0, 0.0, 7.5],
        [8.0, 0.0, -0.5],
        [8.0, 4.0, -0.5],
    ];
    let d = draw::<N>(
        &v,
        &[(&[0, 1, 2], Rgb565::RED), (&[3, 4, 5], Rgb565::GREEN)],
        8,
        4,
    );
    d.assert_pattern(&["RRRRGGGG", "RRRRGGGG", "RRRKKGGG", "RKKKKKKG"]);
}

#[test]
fn piercing_triangles_picture() {
    piercing::<Q16_16>();
    piercing::<f32>();
}
