//! `docs/extremes.md` item 23 for every method, and property tests in the fuzzer's spirit
//! (see tests/extremes.rs for where the other items are; the format list is
//! [`for_formats!`]).
//!
//! Scenes with extreme, degenerate and non-finite input — NaN, ±∞, ±huge, ±f32::MAX,
//! subnormal and signed-zero coordinates, coordinates either side of ±32767, collinear and
//! zero-area faces, repeated and out-of-range indices, faces of 0..12 vertices, more polygons
//! than the capacity — and extreme configurations (1×1, 2048 wide, 1 and 8 sub-pixel bits,
//! and invalid ones) go to every method, cull-only and ordered included, in every format, in
//! screen space (also snapped: [`zrow::SnappedScene`]) and in model mode. f32 coordinates reach a fixed-point format through its
//! checked conversion: the conversion must refuse exactly the values the format cannot hold
//! (the typed refusal a loader reports), and the test then feeds the format's nearest value
//! (a saturating loader). The property: no panic (debug build: no overflow either), rows top
//! to bottom each once (the [`Capture`] asserts it) and all of them, or an error that is one of
//! the typed scene errors, true of the input, before any row.

mod common;
use common::*;
use embedded_graphics_core::pixelcolor::Rgb565;
use proptest::prelude::*;
use zrow::abuffer::ABuffer;
use zrow::bsp::Bsp;
use zrow::cullonly::CullOnly;
use zrow::depthsort::DepthSort;
use zrow::ordered::Ordered;
use zrow::raster::RasterVertex;
use zrow::raster::MAX_FACE_VERTICES;
use zrow::warnock::Warnock;
use zrow::{Affine, Camera, Config, Error, Face, Light, Mesh, ModelScene, Object, Projection};
use zrow::{Faces, RenderError, Scalar, Scanline, ScreenScene, SnappedScene, Vec3, ZBuffer};
use zrow::{Q16_16, Q24_8};

/// Runs a generic item for every number format (adding a format is one line here).
macro_rules! for_formats {
    ($f:ident $(, $a:expr)*) => {{
        $f::<Q16_16>($($a),*);
        $f::<Q24_8>($($a),*);
        $f::<f32>($($a),*);
    }};
}

/// Every method at small capacities (16 polygons, so scenes overflow them), rows of `W`,
/// frames up to `H` rows for the z-buffer.
fn methods<N: Scalar, const W: usize, const H: usize>() -> Vec<Method<N>> {
    vec![
        Method::new::<Scanline<N, W, 64, 16, 8>>(),
        Method::new::<ZBuffer<N, W, H>>(),
        Method::tiled::<W, 2, 16, 64>(),
        Method::new::<DepthSort<N, W, 16, 64, 64>>(),
        Method::new::<Warnock<N, W, 4, 16, 64, 64>>(),
        Method::new::<Bsp<N, W, 16, 64, 64, 32>>(),
        Method::new::<ABuffer<N, W, 16, 64, 16>>(),
        Method::new::<CullOnly<N, W, 16, 64>>(),
        Method::new::<Ordered<N, W, 16, 64>>(),
    ]
}

/// One generated input: f32 vertices, faces, configuration, mode.
#[derive(Clone, Debug)]
struct Input {
    verts: Vec<[f32; 3]>,
    faces: Vec<Vec<u16>>,
    width: u16,
    height: u16,
    subpixel_bits: u8,
    model: bool,
}

impl Input {
    fn config_ok(&self) -> bool {
        (1..=2048).contains(&self.width)
            && (1..=2048).contains(&self.height)
            && (1..=8).contains(&self.subpixel_bits)
    }
}

/// The error must be true of the input.
///
/// A scene of snapped vertices (`snapped`) also refuses a vertex past the guard band (or not
/// snappable) and a face of more than four corners that are not consecutive vertices.
fn check_error(e: Error, input: &Input, what: &str, snapped: bool) {
    let face = |f: u32| {
        input
            .faces
            .get(f as usize)
            .unwrap_or_else(|| panic!("{what}: {e:?} names no face"))
    };
    match e {
        Error::BadConfig => assert!(!input.config_ok(), "{what}: {e:?}"),
        Error::Capacity {
            needed, capacity, ..
        } => assert!(needed > capacity, "{what}: {e:?}"),
        Error::IndexOutOfRange { face: f, index } => {
            assert!(face(f).contains(&(index as u16)), "{what}: {e:?}");
            assert!(index as usize >= input.verts.len(), "{what}: {e:?}");
        }
        Error::TooFewVertices { face: f } => assert!(face(f).len() < 3, "{what}: {e:?}"),
        Error::TooManyVertices { face: f } => {
            assert!(face(f).len() > MAX_FACE_VERTICES, "{what}: {e:?}")
        }
        Error::NonFinite { face: f } => {
            face(f);
        }
        Error::NotConvex { face: f } => assert!(face(f).len() >= 4, "{what}: {e:?}"),
        Error::OutsideGuardBand { face: f } if snapped => {
            face(f);
        }
        Error::Unsupported { .. } if snapped => {
            assert!(input.faces.iter().any(|f| f.len() > 4), "{what}: {e:?}")
        }
        other => panic!("{what}: {other:?} from a mesh without normals"),
    }
    if !input.config_ok() {
        assert_eq!(
            e,
            Error::BadConfig,
            "{what}: a bad configuration is reported first"
        );
    }
}

/// The format's value for an f32: its checked conversion, which must refuse exactly what the
/// format cannot hold; refused values become the nearest the format has — for NaN and ±∞ its
/// own (f32: NaN and ±∞; fixed point, saturating: 0 and ±MAX).
fn convert<N: Scalar>(v: f32) -> N {
    let max = max_f32::<N>();
    match N::from_f32(v) {
        Some(n) => {
            assert!(v.is_finite(), "{} accepted {v}", N::NAME);
            n
        }
        None => {
            assert!(
                !v.is_finite() || v.abs() > max,
                "{} refused {v}, which it holds",
                N::NAME
            );
            // MAX·MAX is +∞ in f32, MAX in fixed point; ∞ − ∞ is NaN, or 0.
            let inf = N::MAX.mul(N::MAX);
            match v {
                _ if v.is_nan() => inf.sub(inf),
                f32::INFINITY => inf,
                f32::NEG_INFINITY => inf.neg(),
                _ if v > 0.0 => N::MAX,
                _ => N::MAX.neg(),
            }
        }
    }
}

fn run<N: Scalar>(input: &Input) {
    let verts: Vec<Vec3<N>> = input
        .verts
        .iter()
        .map(|v| Vec3::new(convert(v[0]), convert(v[1]), convert(v[2])))
        .collect();
    let faces: Vec<Face> = input
        .faces
        .iter()
        .enumerate()
        .map(|(k, f)| Face::new(f, color_of(k)))
        .collect();
    let mut cfg = if input.model {
        Config::model(input.width, input.height)
    } else {
        Config::screen(input.width, input.height)
    };
    cfg.subpixel_bits = input.subpixel_bits;
    let mesh = Mesh::new(&verts, &faces);
    let objects = [Object {
        mesh: &mesh,
        transform: Affine::identity(),
    }];
    let model = ModelScene {
        objects: &objects,
        camera: Camera::look_at(
            [0.3, 0.2, 4.0],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            Projection::Perspective {
                focal: N::from_f32(1.5).unwrap(),
                near: N::from_f32(0.1).unwrap(),
                far: N::from_f32(50.0).unwrap(),
            },
        )
        .unwrap(),
        light: Light {
            direction: verts.first().copied().unwrap_or_default(),
            ambient: N::ZERO,
        },
    };
    let screen = ScreenScene { mesh };
    // In screen mode, the same vertices snapped as well (a vertex that does not snap is put
    // past the guard band), lent to the renderer.
    let s = cfg.subpixel_bits as u32;
    let snapped_vertices: Vec<RasterVertex<N>> = verts
        .iter()
        .map(|v| RasterVertex {
            x: v.x.snap(s).unwrap_or(i32::MAX),
            y: v.y.snap(s).unwrap_or(i32::MIN),
            z: v.z,
        })
        .collect();
    let snapped = SnappedScene {
        vertices: &snapped_vertices,
        faces: Faces::List(&faces),
        subpixel_bits: cfg.subpixel_bits,
    };
    let scenes: Vec<(&dyn zrow::Scene<N>, bool)> = match input.model {
        true => vec![(&model, false)],
        false => vec![(&screen, false), (&snapped, true)],
    };
    let mut ms = if input.width > 64 {
        methods::<N, 2048, 3>()
    } else {
        methods::<N, 64, 48>()
    };
    for (scene, lent) in scenes {
        for m in &mut ms {
            let what = format!("{} {} (snapped: {lent})", N::NAME, m.name);
            let (result, cap) = m.outcome(scene, &cfg);
            match result {
                Ok(_) => assert_eq!(cap.rows_received, input.height as usize, "{what}"),
                Err(RenderError::Scene(e)) => {
                    assert_eq!(cap.rows_received, 0, "{what}: {e:?} after rows");
                    check_error(e, input, &what, lent);
                }
                Err(RenderError::Sink(())) => panic!("{what}: the capture never fails"),
            }
        }
    }
}

/// Coordinates: mostly ordinary; at Q16.16's edge, huge, non-finite, subnormal, signed zero.
fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![
        24 => -40.0f32..120.0,
        1 => prop_oneof![Just(32767.0f32), Just(32767.998), Just(32768.0), Just(-32768.0),
                         Just(-32768.01), Just(32769.0), Just(-32767.0)],
        1 => prop_oneof![(1.0e4f32..1.0e7), (-1.0e7f32..-1.0e4), (1.0e30f32..3.0e38)],
        1 => prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY),
                         Just(f32::MAX), Just(f32::MIN), Just(f32::MIN_POSITIVE),
                         (1u32..0x7f_ffff).prop_map(f32::from_bits), Just(-0.0f32)],
    ]
}

/// A face: mostly a triangle, sometimes a quad or pentagon (of any vertices: often not
/// convex); indices taken modulo the vertex count (repeats allowed).
fn face() -> impl Strategy<Value = Vec<u16>> {
    prop_oneof![
        10 => prop::collection::vec(any::<u16>(), 3..=3),
        1 => prop::collection::vec(any::<u16>(), 4..=5),
    ]
}

fn input() -> impl Strategy<Value = Input> {
    let vertex = (coord(), coord(), coord()).prop_map(|(x, y, z)| [x, y, z]);
    let verts = prop::collection::vec(vertex, 0..10);
    // Up to 40 faces (beyond the capacity of 16), and maybe one wild face: 0..12 indices,
    // some beyond the vertices.
    let faces = prop::collection::vec(face(), 0..40);
    let wild = prop_oneof![
        3 => Just(None),
        1 => (prop::collection::vec(any::<u16>(), 0..12), any::<prop::sample::Index>()).prop_map(Some),
    ];
    let config = prop_oneof![
        12 => (1u16..=64, 1u16..=48),
        2 => Just((1u16, 1u16)),
        2 => (Just(2048u16), 1u16..=3),
        1 => prop_oneof![Just((0u16, 8u16)), Just((64, 0)), Just((2049, 2))],
    ];
    let bits =
        prop_oneof![8 => Just(8u8), 2 => Just(1u8), 4 => 1u8..=8, 1 => Just(0u8), 1 => Just(9u8)];
    // Degenerate faces: a collinear vertex (midpoint of the first two) and zero-area faces.
    let collinear = any::<bool>();
    (verts, faces, wild, config, bits, any::<bool>(), collinear).prop_map(
        |(mut verts, faces, wild, (width, height), subpixel_bits, model, collinear)| {
            let n = verts.len() as u16;
            let mut faces: Vec<Vec<u16>> = faces
                .into_iter()
                .map(|f| f.into_iter().map(|i| i % n.max(1)).collect())
                .collect();
            if let Some((f, at)) = wild {
                let f = f.into_iter().map(|i| i % (n + 2)).collect();
                faces.insert(at.index(faces.len() + 1), f);
            }
            if model {
                // Ordinary coordinates to the camera's scale (it looks at the origin from 4).
                for c in verts.iter_mut().flatten() {
                    if c.abs() < 200.0 {
                        *c /= 40.0;
                    }
                }
            }
            if collinear && verts.len() >= 2 {
                let (a, b) = (verts[0], verts[1]);
                verts.push([
                    (a[0] + b[0]) / 2.0,
                    (a[1] + b[1]) / 2.0,
                    (a[2] + b[2]) / 2.0,
                ]);
                let n = verts.len() as u16;
                faces.push(vec![0, 1, n - 1]);
                faces.push(vec![0, 0, 1]);
            }
            Input {
                verts,
                faces,
                width,
                height,
                subpixel_bits,
                model,
            }
        },
    )
}

proptest! {
    #![proptest_config(crate::common::proptest_config(600))]

    #[test]
    fn every_method_every_format_survives_extreme_input(input in input()) {
        for_formats!(run, &input);
    }
}

/// Ordinary vertices of a 16×16 screen.
fn tri<N: Scalar>() -> Vec<Vec3<N>> {
    [
        [1.0, 1.0, 1.0],
        [9.0, 1.0, 2.0],
        [1.0, 9.0, 3.0],
        [14.0, 14.0, 1.0],
    ]
    .iter()
    .map(|v| Vec3::from_f32(*v).unwrap())
    .collect()
}

/// Renders screen-space faces with each of `ms`: for each, its error (or None) and the rows
/// it sent.
fn each<N: Scalar>(
    ms: &mut [Method<N>],
    verts: &[Vec3<N>],
    faces: &[Vec<u16>],
    cfg: &Config,
) -> Vec<(String, Option<Error>, usize)> {
    let f: Vec<Face> = faces
        .iter()
        .map(|i| Face::new(i, Rgb565::new(31, 0, 0)))
        .collect();
    let scene = ScreenScene {
        mesh: Mesh::new(verts, &f),
    };
    ms.iter_mut()
        .map(|m| {
            let (r, cap) = m.outcome(&scene, cfg);
            let e = match r {
                Ok(_) => None,
                Err(RenderError::Scene(e)) => Some(e),
                Err(RenderError::Sink(())) => panic!("sink"),
            };
            (m.name.to_string(), e, cap.rows_received)
        })
        .collect()
}

// 23 for every method: each bad input is its typed error, and no row has been sent.
fn bad_input_every_method<N: Scalar>() {
    let cfg = Config::screen(16, 16);
    let v = tri::<N>();
    let ok = vec![0u16, 1, 2];
    // One set of renderers throughout: errors must leave nothing behind.
    let mut ms = methods::<N, 64, 48>();
    let mut expect = |faces: Vec<Vec<u16>>, verts: &[Vec3<N>], cfg: &Config, want: Error| {
        for (name, e, rows) in each(&mut ms, verts, &faces, cfg) {
            assert_eq!(e, Some(want), "{} {name}", N::NAME);
            assert_eq!(rows, 0, "{} {name}", N::NAME);
        }
    };
    expect(
        vec![ok.clone(), vec![0, 1, 7]],
        &v,
        &cfg,
        Error::IndexOutOfRange { face: 1, index: 7 },
    );
    expect(
        vec![ok.clone(), vec![0, 1]],
        &v,
        &cfg,
        Error::TooFewVertices { face: 1 },
    );
    expect(vec![vec![]], &v, &cfg, Error::TooFewVertices { face: 0 });
    expect(
        vec![ok.clone(), vec![0; MAX_FACE_VERTICES + 1]],
        &v,
        &cfg,
        Error::TooManyVertices { face: 1 },
    );
    expect(
        vec![vec![0, 3, 1, 2]],
        &v,
        &cfg,
        Error::NotConvex { face: 0 },
    );
    let mut bad = Config::screen(16, 16);
    bad.subpixel_bits = 0;
    expect(vec![ok.clone()], &v, &bad, Error::BadConfig);
    expect(
        vec![ok.clone()],
        &v,
        &Config::screen(0, 16),
        Error::BadConfig,
    );
    // Non-finite coordinates, where the format has them (f32: MAX·MAX is +inf).
    let inf = N::MAX.mul(N::MAX);
    if !inf.is_finite() {
        let mut w = v.clone();
        w[2].y = inf;
        expect(vec![ok.clone()], &w, &cfg, Error::NonFinite { face: 0 });
        w[2].y = inf.sub(inf); // NaN
        expect(
            vec![vec![3, 1, 0], ok.clone()],
            &w,
            &cfg,
            Error::NonFinite { face: 1 },
        );
    }
    // More polygons than the capacity (16): a capacity error naming more than it holds
    // (the z-buffer keeps no polygons: it draws them all).
    for (name, e, rows) in each(&mut ms, &v, &vec![ok.clone(); 40], &cfg) {
        if name == "zbuffer" {
            assert_eq!((e, rows), (None, 16));
            continue;
        }
        assert!(
            matches!(e, Some(Error::Capacity { needed, capacity, .. }) if needed > capacity),
            "{} {name}: {e:?}",
            N::NAME
        );
        assert_eq!(rows, 0, "{} {name}", N::NAME);
    }
    // Wider than the rows: a capacity error too.
    for (name, e, rows) in each(
        &mut ms,
        &v,
        std::slice::from_ref(&ok),
        &Config::screen(65, 4),
    ) {
        assert!(
            matches!(e, Some(Error::Capacity { .. })),
            "{} {name}: {e:?}",
            N::NAME
        );
        assert_eq!(rows, 0);
    }
    // And the same methods draw a good scene afterwards (no state left by the errors).
    for (name, e, rows) in each(&mut ms, &v, &[ok], &cfg) {
        assert_eq!((e, rows), (None, 16), "{} {name}", N::NAME);
    }
}

#[test]
fn e23_every_method_reports_bad_input_before_any_row() {
    for_formats!(bad_input_every_method);
}

/// A scene of one's own that hands over, already projected, two overlapping convex polygons
/// of `corners` corners each (regular, on a 16×16 screen, the second nearer), so that the
/// methods that keep polygons for the frame and those that compare planes all meet them;
/// `past` is added to each polygon's second corner index (beyond the vertices when nonzero);
/// `lie`: the polygons say they are in the frame's buffer (`cached`) but are not.
struct Gons {
    corners: usize,
    past: u32,
    lie: bool,
}

impl Gons {
    fn new(corners: usize) -> Self {
        Gons {
            corners,
            past: 0,
            lie: false,
        }
    }
}

impl<N: Scalar> zrow::Scene<N> for Gons {
    fn polygons(
        &self,
        cfg: &Config,
        vertices: &mut zrow::scene::VertexBuffer<'_, N>,
        f: &mut dyn FnMut(&zrow::scene::Polygon<'_, N>) -> Result<(), Error>,
    ) -> Result<(), Error> {
        let s = cfg.subpixel_bits as u32;
        for (k, z) in [(0usize, 5.0f32), (1, 2.0)] {
            let ring: Vec<zrow::raster::RasterVertex<N>> = (0..self.corners)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / self.corners as f64;
                    let (x, y) = (8.0 + k as f64 + 7.0 * a.cos(), 8.0 + 7.0 * a.sin());
                    zrow::raster::RasterVertex {
                        x: (x * (1 << s) as f64).round() as i32,
                        y: (y * (1 << s) as f64).round() as i32,
                        z: N::from_f32(z).unwrap(),
                    }
                })
                .collect();
            let start = if self.lie { None } else { vertices.push(&ring) };
            let mut corners: Vec<u32> = (0..self.corners as u32)
                .map(|i| start.unwrap_or(0) + i)
                .collect();
            corners[1] += self.past;
            let area2 = zrow::raster::signed_area2(&ring);
            let (cached, scratch);
            let polygon = zrow::scene::Polygon {
                vertices: if start.is_some() {
                    cached = vertices.as_slice();
                    cached
                } else {
                    scratch = &ring[..];
                    scratch
                },
                corners: &corners,
                cached: start.is_some() || self.lie,
                area2,
                color: color_of(k),
                intensity: None,
                alpha: 255,
                face: k as u32,
            };
            f(&polygon)?;
        }
        Ok(())
    }
}

// A polygon of more corners than clipping makes (17, from a scene of one's own): a typed
// error before any row from every method, never a panic, never the polygon cut to its first
// 16 corners; the largest one clipping makes (16) drawn, as the z-buffer draws it.
fn too_many_corners<N: Scalar>() {
    let cfg = Config::screen(16, 16);
    let mut ms = methods::<N, 16, 16>();
    let most = zrow::raster::MAX_POLYGON_VERTICES;
    let (reference, _) = ms[1].outcome(&Gons::new(most), &cfg);
    let reference = reference.map(|_| ());
    assert_eq!(reference, Ok(()));
    let (_, expected) = ms[1].outcome(&Gons::new(most), &cfg);
    for m in &mut ms {
        let (r, cap) = m.outcome(&Gons::new(most), &cfg);
        assert!(r.is_ok(), "{} {}: {r:?}", N::NAME, m.name);
        assert_eq!(cap.color, expected.color, "{} {}", N::NAME, m.name);
        let (r, cap) = m.outcome(&Gons::new(most + 1), &cfg);
        assert_eq!(
            r.map(|_| ()),
            Err(RenderError::Scene(Error::TooManyVertices { face: 0 })),
            "{} {}",
            N::NAME,
            m.name
        );
        assert_eq!(cap.rows_received, 0, "{} {}", N::NAME, m.name);
    }
}

#[test]
fn a_polygon_of_too_many_corners_is_a_typed_error() {
    for_formats!(too_many_corners);
}

// A scene of one's own whose corner lies beyond its vertices: a typed error before any row
// from every method, never a panic; one that says its polygons are in the frame's buffer
// when they are not: never a panic either (the scan-line method, which keeps polygons by
// slot, refuses it, naming the first such face; the others copy the corners and draw it as
// the honest scene).
fn bad_corners<N: Scalar>() {
    let cfg = Config::screen(16, 16);
    let mut ms = methods::<N, 16, 16>();
    for corners in [3, 4, 5, 9] {
        let (_, honest) = ms[1].outcome(&Gons::new(corners), &cfg);
        for m in &mut ms {
            let past = Gons {
                past: 1000,
                ..Gons::new(corners)
            };
            let (r, cap) = m.outcome(&past, &cfg);
            // Corner 1 of the first polygon: slot 1 + 1000.
            assert_eq!(
                r.map(|_| ()),
                Err(RenderError::Scene(Error::IndexOutOfRange {
                    face: 0,
                    index: 1001
                })),
                "{} {} {corners}",
                N::NAME,
                m.name
            );
            assert_eq!(cap.rows_received, 0, "{} {}", N::NAME, m.name);
            let lie = Gons {
                lie: true,
                ..Gons::new(corners)
            };
            let (r, cap) = m.outcome(&lie, &cfg);
            if m.name == "scanline" {
                assert_eq!(
                    r.map(|_| ()),
                    Err(RenderError::Scene(Error::NotInFrame { face: 0 })),
                    "{} {corners}",
                    N::NAME
                );
                assert_eq!(cap.rows_received, 0);
            } else {
                assert!(r.is_ok(), "{} {} {corners}: {r:?}", N::NAME, m.name);
                assert_eq!(cap.color, honest.color, "{} {} {corners}", N::NAME, m.name);
            }
        }
    }
}

#[test]
fn a_scene_of_its_own_with_bad_corners_is_a_typed_error() {
    for_formats!(bad_corners);
}
