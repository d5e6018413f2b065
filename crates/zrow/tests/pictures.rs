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

/// `docs/extremes.md` item 1, the golden vector: the 5x5 square from (0.5, 0.5) to (5.5, 5.5) split on its
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

/// A frame bigger than the display (128x128 into MockDisplay's 64x64, which panics on any
/// pixel drawn outside it or twice) is clipped to the display: each of its pixels drawn once,
/// as the frame has it; and a display in another colour type gets embedded-graphics'
/// conversion of the same frame.
#[test]
fn the_draw_target_sink_clips_and_converts() {
    use embedded_graphics::pixelcolor::{BinaryColor, Gray8, Rgb888};
    use embedded_graphics::prelude::*;
    use zrow::FrameBuffer;
    let v: Vec<Vec3<Q16_16>> = [
        [-10.0, -10.0, 1.0],
        [140.0, 20.0, 2.0],
        [30.0, 140.0, 3.0],
        [100.0, 0.0, 0.5],
        [128.0, 128.0, 0.5],
        [60.0, 120.0, 0.5],
    ]
    .iter()
    .map(|p| Vec3::from_f32(*p).unwrap())
    .collect();
    let f = [
        Face::new(&[0, 1, 2], Rgb565::RED),
        Face::new(&[3, 4, 5], Rgb565::new(3, 40, 28)),
    ];
    let scene = ScreenScene {
        mesh: Mesh::new(&v, &f),
    };
    let cfg = Config::screen(128, 128);
    let mut r = Box::new(Scanline::<Q16_16, 128, 32, 8, 8>::new());
    let mut frame = vec![Rgb565::BLACK; 128 * 128];
    r.render(&scene, &cfg, &mut FrameBuffer::new(&mut frame, 128))
        .unwrap();
    let at = |x: i32, y: i32| frame[y as usize * 128 + x as usize];
    assert!(frame.iter().any(|&c| c != Rgb565::BLACK) && frame[..64].contains(&Rgb565::RED));

    let mut display = MockDisplay::<Rgb565>::new();
    r.render(&scene, &cfg, &mut DrawTargetSink(&mut display))
        .unwrap();
    for p in display.bounding_box().points() {
        assert_eq!(display.get_pixel(p), Some(at(p.x, p.y)), "{p:?}");
    }

    fn converted<C>(
        r: &mut Scanline<Q16_16, 128, 32, 8, 8>,
        scene: &ScreenScene<'_, Q16_16>,
        cfg: &Config,
        at: impl Fn(i32, i32) -> Rgb565,
    ) where
        C: PixelColor + From<Rgb565> + std::fmt::Debug,
    {
        let mut display = MockDisplay::<C>::new();
        r.render(scene, cfg, &mut DrawTargetSink(&mut display))
            .unwrap();
        for p in display.bounding_box().points() {
            assert_eq!(display.get_pixel(p), Some(C::from(at(p.x, p.y))), "{p:?}");
        }
    }
    converted::<Rgb888>(&mut r, &scene, &cfg, at);
    converted::<Gray8>(&mut r, &scene, &cfg, at);
    converted::<BinaryColor>(&mut r, &scene, &cfg, at);
}

/// `Drawing` is an embedded-graphics `Drawable`: the same picture as the sink gives; a scene
/// the renderer rejects is `Ok(Err(..))` with nothing drawn; a failing display is `Err`.
#[test]
fn a_drawing_is_a_drawable() {
    use embedded_graphics::prelude::*;
    use zrow::{Drawing, Error};
    let q = |x: f32, y: f32| Vec3::<Q16_16>::from_f32([x, y, 1.0]).unwrap();
    let v = [q(0.5, 0.5), q(5.5, 0.5), q(5.5, 5.5), q(0.5, 5.5)];
    let (a, b) = ([0u16, 1, 3], [1u16, 2, 3]);
    let f = [Face::new(&a, Rgb565::RED), Face::new(&b, Rgb565::GREEN)];
    let scene = ScreenScene {
        mesh: Mesh::new(&v, &f),
    };
    let mut r = Scanline::<Q16_16, 16, 32, 8, 8>::new();
    let mut display = MockDisplay::new();
    let stats = Drawing::new(&mut r, &scene, Config::screen(7, 7))
        .draw(&mut display)
        .unwrap()
        .unwrap();
    assert_eq!(stats.polygons, 2);
    display.assert_pattern(&[
        "RRRRRKK", "RRRRGKK", "RRRGGKK", "RRGGGKK", "RGGGGKK", "KKKKKKK", "KKKKKKK",
    ]);

    // Room for one vertex only: the scene is rejected before any pixel.
    let mut small = Scanline::<Q16_16, 16, 1, 8, 8>::new();
    let mut untouched = MockDisplay::<Rgb565>::new();
    let got = Drawing::new(&mut small, &scene, Config::screen(7, 7))
        .draw(&mut untouched)
        .unwrap();
    assert!(
        matches!(
            got,
            Err(Error::Capacity {
                needed: 4,
                capacity: 1,
                ..
            })
        ),
        "{got:?}"
    );
    assert!(untouched
        .bounding_box()
        .points()
        .all(|p| untouched.get_pixel(p).is_none()));

    /// A display whose bus fails.
    struct Broken;
    impl OriginDimensions for Broken {
        fn size(&self) -> Size {
            Size::new(7, 7)
        }
    }
    impl DrawTarget for Broken {
        type Color = Rgb565;
        type Error = &'static str;
        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
            &mut self,
            _: I,
        ) -> Result<(), Self::Error> {
            Err("bus")
        }
    }
    let err = Drawing::new(&mut r, &scene, Config::screen(7, 7)).draw(&mut Broken);
    assert_eq!(err, Err("bus"));
}
