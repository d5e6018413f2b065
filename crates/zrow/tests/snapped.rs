//! A scene of snapped vertices ([`SnappedScene`]) lends them to the renderer: every method
//! draws it as it draws the [`ScreenScene`] of the same positions unsnapped, the scan-line
//! method with no vertex buffer at all, and what such a scene cannot be (unclipped, one grid)
//! is a typed error before any row is sent.

mod common;

use common::{every_method, painters, scenes, Capture, Polys, Rng};
use embedded_graphics_core::pixelcolor::Rgb565;
use zrow::raster::RasterVertex;
use zrow::{
    Config, Error, Face, Faces, RenderError, Scalar, Scanline, SnappedScene, Q16_16, Q24_8,
};

/// Scenes whose vertices all lie within the guard band (a snapped scene is not clipped).
fn scenes_for(rng: &mut Rng, rounds: usize) -> Vec<Polys> {
    let mut out = Vec::new();
    for _ in 0..rounds {
        out.push(scenes::random(rng, 40, 64.0, 48.0));
        out.push(scenes::dense(rng, 12, 64.0, 48.0));
        out.push(scenes::steep(rng, 20, 64.0, 48.0));
    }
    out
}

fn same_as_screen<N: Scalar>(rounds: usize, bits: &[u8]) {
    let mut rng = Rng(0x5eed_0017);
    let mut methods = every_method::<N>();
    methods.extend(painters::<N>());
    for (k, p) in scenes_for(&mut rng, rounds).iter().enumerate() {
        for &s in bits {
            let cfg = Config {
                subpixel_bits: s,
                ..Config::screen(64, 48)
            };
            for m in &mut methods {
                // The snapped scene first: a renderer's buffer then holds the scene before,
                // not these vertices.
                let snapped =
                    p.with_snapped::<N, _>(cfg.subpixel_bits, |scene| m.outcome(scene, &cfg));
                let screen = p.with_scene(|scene| m.outcome(scene, &cfg));
                assert_eq!(
                    screen.0.as_ref().map(|r| r.0.polygons).ok(),
                    snapped.0.as_ref().map(|r| r.0.polygons).ok(),
                    "{}: scene {k}, {s} sub-pixel bits: outcome",
                    m.name
                );
                assert!(
                    screen.1 == snapped.1,
                    "{}: scene {k}, {s} sub-pixel bits: frames differ",
                    m.name
                );
            }
        }
    }
}

/// Every method, the painters included, draws a snapped scene bit for bit as the screen
/// scene it was snapped from (colours and depths): in Q16.16 at 8 and 3 sub-pixel bits, in
/// f32 and Q24.8 at 8 (fewer scenes: a debug build's frames of every method take a while).
#[test]
fn every_method_draws_a_snapped_scene_as_its_screen_scene() {
    same_as_screen::<Q16_16>(2, &[8, 3]);
    same_as_screen::<f32>(1, &[8]);
    same_as_screen::<Q24_8>(1, &[8]);
}

/// The scan-line method keeps no copy of a snapped scene's vertices: a renderer without a
/// vertex buffer (V = 0) draws it as one with room does, and the requirements say 0 slots;
/// the same renderer refuses the screen scene, which needs its buffer.
#[test]
fn the_scan_line_method_reads_lent_vertices_without_a_buffer() {
    let mut rng = Rng(0x1e47);
    let cfg = Config::screen(64, 48);
    let mut lent = Box::new(Scanline::<Q16_16, 64, 0, 256, 256>::new());
    let mut buffered = Box::new(Scanline::<Q16_16, 64, 1024, 256, 256>::new());
    for p in scenes_for(&mut rng, 2) {
        let (a, b, req) = p.with_snapped::<Q16_16, _>(cfg.subpixel_bits, |scene| {
            let mut a = Capture::new(64, 48);
            let mut b = Capture::new(64, 48);
            lent.render(scene, &cfg, &mut a).unwrap();
            buffered.render(scene, &cfg, &mut b).unwrap();
            (a, b, zrow::requirements(scene, &cfg).unwrap())
        });
        assert!(a == b);
        assert!(a.drawn() > 0);
        assert_eq!(req.vertices, 0);
        let screen = p.with_scene::<Q16_16, _>(|scene| zrow::requirements(scene, &cfg).unwrap());
        assert_eq!(
            (screen.polygons, screen.active_polygons),
            (req.polygons, req.active_polygons)
        );
        assert!(screen.vertices > 0);
        let refused =
            p.with_scene::<Q16_16, _>(|scene| lent.render(scene, &cfg, &mut Capture::new(64, 48)));
        assert!(matches!(
            refused,
            Err(RenderError::Scene(Error::Capacity {
                table: zrow::Table::Vertices,
                capacity: 0,
                ..
            }))
        ));
    }
}

/// What a snapped scene cannot be is refused before any row, by every method: a grid other
/// than the frame's, a vertex beyond the guard band, a vertex that is not a number, a face
/// of more than four corners on vertices that are not consecutive, an index past the
/// vertices, hidden lines.
#[test]
fn a_snapped_scene_out_of_its_bounds_is_a_typed_error() {
    let cfg = Config::screen(64, 48);
    let s = cfg.subpixel_bits as u32;
    let v = |x: i32, y: i32, z: f32| RasterVertex {
        x: x << s,
        y: y << s,
        z,
    };
    let far = zrow::raster::GUARD_BAND + 64 + 1;
    let ok = [v(1, 1, 1.0), v(30, 2, 1.0), v(3, 30, 1.0)];
    let outside = [v(1, 1, 1.0), v(far, 2, 1.0), v(3, 30, 1.0)];
    let nan = [v(1, 1, 1.0), v(30, 2, f32::NAN), v(3, 30, 1.0)];
    let ring = [
        v(10, 1, 1.0),
        v(20, 5, 1.0),
        v(20, 15, 1.0),
        v(10, 20, 1.0),
        v(1, 10, 1.0),
    ];
    let tri = [Face::new(&[0u16, 1, 2], Rgb565::new(31, 0, 0))];
    let scrambled = [Face::new(&[0u16, 1, 2, 4, 3], Rgb565::new(31, 0, 0))];
    let in_order = [Face::new(&[0u16, 1, 2, 3, 4], Rgb565::new(31, 0, 0))];
    let past = [Face::new(&[0u16, 1, 3], Rgb565::new(31, 0, 0))];
    let scene =
        |vertices: &'static [RasterVertex<f32>], faces: &'static [Face<'static>]| SnappedScene {
            vertices,
            faces: Faces::List(faces),
            subpixel_bits: cfg.subpixel_bits,
        };
    let leak = |v: &[RasterVertex<f32>]| -> &'static [RasterVertex<f32>] { v.to_vec().leak() };
    let leak_f = |f: &[Face<'static>]| -> &'static [Face<'static>] { f.to_vec().leak() };
    let coarse = SnappedScene {
        subpixel_bits: 4,
        ..scene(leak(&ok), leak_f(&tri))
    };
    let facets = Config {
        shading: zrow::shading::Shading::Facets,
        ..cfg
    };
    let cases: [(SnappedScene<'static, f32>, Config, Error); 6] = [
        (coarse, cfg, Error::BadConfig),
        (
            scene(leak(&outside), leak_f(&tri)),
            cfg,
            Error::OutsideGuardBand { face: 0 },
        ),
        (
            scene(leak(&nan), leak_f(&tri)),
            cfg,
            Error::NonFinite { face: 0 },
        ),
        (
            scene(leak(&ring), leak_f(&scrambled)),
            cfg,
            Error::Unsupported {
                feature: "a snapped scene's face of more than 4 corners on vertices that are \
                          not consecutive",
            },
        ),
        (
            scene(leak(&ok), leak_f(&past)),
            cfg,
            Error::IndexOutOfRange { face: 0, index: 3 },
        ),
        (
            scene(leak(&ok), leak_f(&tri)),
            facets,
            Error::Unsupported {
                feature: "hidden lines of a snapped scene: draw its ScreenScene",
            },
        ),
    ];
    let mut methods = every_method::<f32>();
    methods.extend(painters::<f32>());
    for (scene, cfg, want) in &cases {
        for m in &mut methods {
            let (result, cap) = m.outcome(scene, cfg);
            match result {
                Err(RenderError::Scene(e)) if e == *want => {}
                // A method may refuse a hidden-line frame for a reason of its own first.
                Err(RenderError::Scene(Error::Unsupported { .. }))
                    if matches!(cfg.shading, zrow::shading::Shading::Facets) => {}
                other => panic!("{}: {want:?} expected, got {other:?}", m.name),
            }
            assert_eq!(
                cap.rows_received, 0,
                "{}: rows sent before {want:?}",
                m.name
            );
        }
    }
    // The same faces in order are drawn (a run of consecutive vertices), by every method.
    let good = scene(leak(&ring), leak_f(&in_order));
    for m in &mut methods {
        let (result, cap) = m.outcome(&good, &cfg);
        assert!(result.is_ok(), "{}: {result:?}", m.name);
        assert!(cap.drawn() > 100, "{}", m.name);
    }
}

/// A scene of one's own that lends its vertices but hands a polygon over on others (here its
/// second, pushed into the frame's buffer instead): the scan-line method, which keeps
/// polygons by slot of the one slice it reads, refuses the frame before any row, naming that
/// face (not a capacity: the buffer has room).
#[test]
fn a_lending_scene_that_hands_a_polygon_over_elsewhere_is_refused() {
    struct Lends {
        vertices: Vec<RasterVertex<Q16_16>>,
    }
    impl zrow::Scene<Q16_16> for Lends {
        fn polygons(
            &self,
            _: &Config,
            buffer: &mut zrow::scene::VertexBuffer<'_, Q16_16>,
            f: &mut dyn FnMut(&zrow::scene::Polygon<'_, Q16_16>) -> Result<(), Error>,
        ) -> Result<(), Error> {
            let area2 = zrow::raster::signed_area2(&self.vertices);
            let polygon = |vertices, corners, face| zrow::scene::Polygon {
                vertices,
                corners,
                cached: true,
                area2,
                color: Rgb565::new(31, 0, 0),
                intensity: None,
                alpha: 255,
                face,
            };
            f(&polygon(&self.vertices, &[0, 1, 2], 0))?;
            let start = buffer.push(&self.vertices).ok_or(Error::BadConfig)?;
            let corners = [start, start + 1, start + 2];
            f(&polygon(buffer.as_slice(), &corners, 1))
        }
        fn lent_vertices(&self) -> Option<&[RasterVertex<Q16_16>]> {
            Some(&self.vertices)
        }
    }
    let cfg = Config::screen(64, 48);
    let s = cfg.subpixel_bits as u32;
    let v = |x: i32, y: i32| RasterVertex {
        x: x << s,
        y: y << s,
        z: Q16_16::from_num(1),
    };
    let scene = Lends {
        vertices: vec![v(1, 1), v(30, 2), v(3, 30)],
    };
    let mut r = Box::new(Scanline::<Q16_16, 64, 16, 16, 16>::new());
    let mut cap = Capture::new(64, 48);
    assert_eq!(
        r.render(&scene, &cfg, &mut cap),
        Err(RenderError::Scene(Error::NotInFrame { face: 1 }))
    );
    assert_eq!(cap.rows_received, 0);
}
