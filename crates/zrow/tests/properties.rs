//! Property tests: the scan-line renderer equals the exact reference on random scenes, for a
//! sink that reads depth and, in the same colours, for one that takes colours only.
//!
//! Vertices lie on the 1/256 grid, so snapping at 8 bits is the identity and the reference's
//! coverage is exact in every format: every pixel must match except where the reference
//! itself calls a depth tie (the two nearest polygons closer than the format's stated depth
//! error). Visible depths must be within that error too: in fixed point (Q16.16, Q24.8) the
//! stated bound of `Scalar::depth_plane` itself, 0.5·(1 + i + j) LSB at pixel (i, j).

mod common;
use common::Rng as XorShift;
use common::*;
use proptest::prelude::*;
use zrow::{Config, Scalar, Q16_16, Q24_8};

const W: u16 = 48;
const H: u16 = 40;
const MARGIN: f32 = 24.0;

/// A triangle or a planar parallelogram (4th vertex p0 + p2 − p1), on the 1/256 grid.
fn polygon() -> impl Strategy<Value = Vec<[f32; 3]>> {
    let coord = |lo: f32, hi: f32| {
        ((lo * 256.0) as i32..(hi * 256.0) as i32).prop_map(|v| v as f32 / 256.0)
    };
    let vertex = (
        coord(-MARGIN, W as f32 + MARGIN),
        coord(-MARGIN, H as f32 + MARGIN),
        (0i32..64 * 64).prop_map(|z| z as f32 / 64.0),
    )
        .prop_map(|(x, y, z)| [x, y, z]);
    (vertex.clone(), vertex.clone(), vertex, any::<bool>()).prop_map(|(a, b, c, quad)| {
        let mut v = vec![a, b, c];
        if quad {
            let d = [a[0] + c[0] - b[0], a[1] + c[1] - b[1], a[2] + c[2] - b[2]];
            if d.iter().all(|x| x.abs() < 3000.0) {
                // a, b, c, d in order round the parallelogram.
                v = vec![a, b, c, d];
            }
        }
        v
    })
}

fn scene() -> impl Strategy<Value = Polys> {
    prop::collection::vec(polygon(), 1..24).prop_map(Polys::new)
}

fn check<N: Scalar>(p: &Polys) -> Result<(), TestCaseError> {
    let cfg = Config::screen(W, H);
    let cap = p.render::<N>(&cfg).unwrap();
    // Fixed point: each plane is within 0.5·(1 + i + j) LSB at pixel (i, j), and i + j < W + H
    // on screen, so planes further apart than tie_tolerance(W + H) are in the right order.
    let (tie, lsb) = match lsb::<N>() {
        Some(lsb) => (tie_tolerance::<N>((W + H) as usize), lsb),
        None => (
            2.0 * tie_tolerance::<N>((W + H) as usize + 4 * MARGIN as usize),
            0.0,
        ),
    };
    let refr = reference::<N>(p, &cfg, tie);
    let bad = mismatches(&cap, &refr);
    prop_assert!(
        bad.is_empty(),
        "{} pixels differ, first {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    // A sink that takes colours only gets the same colours (its rows' spans that meet no
    // other are painted as they come, the rest swept from the last of those).
    let colours = p.render_colours::<N>(&cfg).unwrap();
    let differ = (colours.iter().zip(&cap.color))
        .filter(|(a, b)| a != b)
        .count();
    prop_assert!(
        differ == 0,
        "{differ} pixels differ for a sink of colours only"
    );
    for y in 0..H as usize {
        for x in 0..W as usize {
            if let Verdict::Visible(_, z) = refr[y * W as usize + x] {
                let got = cap.z(x, y).to_f32() as f64;
                let err = (got - z).abs();
                let allowed = if lsb > 0.0 {
                    // The stated bound; 1e-9 for the reference's own f64 rounding.
                    0.5 * (1.0 + (x + y) as f64) * lsb + 1e-9
                } else {
                    1e-3 * (1.0 + z.abs())
                };
                prop_assert!(err <= allowed, "depth at ({x},{y}): got {got}, exact {z}");
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(crate::common::proptest_config(96))]

    #[test]
    fn scanline_equals_reference_q16_16(p in scene()) {
        check::<Q16_16>(&p)?;
    }

    #[test]
    fn scanline_equals_reference_q24_8(p in scene()) {
        check::<Q24_8>(&p)?;
    }

    #[test]
    fn scanline_equals_reference_f32(p in scene()) {
        check::<f32>(&p)?;
    }
}

/// Dense interpenetrating stacks: many polygons crossing the same rows at nearly the same
/// depth, where span coherence must fall back to per-pixel resolution.
#[test]
fn dense_interpenetration_equals_reference() {
    let mut rng = XorShift(0x5EED);
    for _ in 0..20 {
        let mut polys = Vec::new();
        for _ in 0..40 {
            let z = |r: &mut XorShift| (r.below(64 * 64) as f32) / 64.0;
            let y0 = rng.f(-5.0, H as f32 + 5.0);
            let y1 = rng.f(-5.0, H as f32 + 5.0);
            let q = |v: f32| (v * 256.0).round() / 256.0;
            polys.push(vec![
                [q(-10.0), q(y0), z(&mut rng)],
                [q(W as f32 + 10.0), q(y1), z(&mut rng)],
                [
                    q(rng.f(0.0, W as f32)),
                    q(rng.f(0.0, H as f32)),
                    z(&mut rng),
                ],
            ]);
        }
        let p = Polys::new(polys);
        check::<Q16_16>(&p).unwrap();
        check::<Q24_8>(&p).unwrap();
        check::<f32>(&p).unwrap();
    }
}

/// Any input at all: every Q16.16 and Q24.8 bit pattern, every f32 (NaN, ±inf, subnormals, ±3e38),
/// indices in and out of range, faces of 0..12 vertices, model or screen mode. The renderer
/// returns a frame or a typed error; it never panics (these run in debug, where overflow
/// would) and never sends a row after an error.
mod no_panic {
    use super::*;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use zrow::{Affine, Camera, Face, Light, Mesh, ModelScene, Object, Projection, Vec3};

    fn run<N: Scalar>(verts: Vec<Vec3<N>>, faces: Vec<Vec<u16>>, model: bool) {
        let f: Vec<Face> = faces
            .iter()
            .map(|i| Face {
                indices: i,
                color: Rgb565::new(31, 0, 0),
                alpha: 255,
            })
            .collect();
        let mesh = Mesh::new(&verts, &f);
        let mut r = Box::new(zrow::Scanline::<N, 32, 256, 64, 64>::new());
        let mut cap = Capture::<N>::new(32, 24);
        let result = if model {
            let objects = [Object {
                mesh: &mesh,
                transform: Affine::identity(),
            }];
            let cam = Camera::look_at(
                [0.3, 0.2, 4.0],
                [0.0; 3],
                [0.0, 1.0, 0.0],
                Projection::Perspective {
                    focal: N::from_f32(1.5).unwrap(),
                    near: N::from_f32(0.1).unwrap(),
                    far: N::from_f32(50.0).unwrap(),
                },
            )
            .unwrap();
            let light = Light {
                direction: verts.first().copied().unwrap_or_default(),
                ambient: N::ZERO,
            };
            let scene = ModelScene {
                objects: &objects,
                camera: cam,
                light,
            };
            r.render(&scene, &Config::model(32, 24), &mut cap)
        } else {
            let scene = zrow::ScreenScene { mesh };
            r.render(&scene, &Config::screen(32, 24), &mut cap)
        };
        match result {
            Ok(_) => assert_eq!(cap.rows_received, 24),
            Err(_) => assert_eq!(cap.rows_received, 0),
        }
    }

    fn faces() -> impl Strategy<Value = Vec<Vec<u16>>> {
        prop::collection::vec(prop::collection::vec(0u16..10, 0..12), 0..10)
    }

    proptest! {
        #![proptest_config(crate::common::proptest_config(400))]

        #[test]
        fn any_q16_16_input(bits in prop::collection::vec(any::<[i32; 3]>(), 0..9), faces in faces(), model in any::<bool>()) {
            let v = bits.iter().map(|b| Vec3::new(Q16_16::from_bits(b[0]), Q16_16::from_bits(b[1]), Q16_16::from_bits(b[2]))).collect();
            run::<Q16_16>(v, faces, model);
        }

        #[test]
        fn any_q24_8_input(bits in prop::collection::vec(any::<[i32; 3]>(), 0..9), faces in faces(), model in any::<bool>()) {
            let v = bits.iter().map(|b| Vec3::new(Q24_8::from_bits(b[0]), Q24_8::from_bits(b[1]), Q24_8::from_bits(b[2]))).collect();
            run::<Q24_8>(v, faces, model);
        }

        #[test]
        fn any_f32_input(bits in prop::collection::vec(any::<[u32; 3]>(), 0..9), faces in faces(), model in any::<bool>()) {
            let v = bits.iter().map(|b| Vec3::new(f32::from_bits(b[0]), f32::from_bits(b[1]), f32::from_bits(b[2]))).collect();
            run::<f32>(v, faces, model);
        }

        #[test]
        fn small_coordinates_any_order(pts in prop::collection::vec(any::<[i16; 3]>(), 3..9), faces in faces(), model in any::<bool>()) {
            // Plausible magnitudes (±128 px / units) so most faces reach the raster stage.
            let v: Vec<Vec3<f32>> = pts.iter().map(|p| Vec3::new(p[0] as f32 / 256.0, p[1] as f32 / 256.0, p[2] as f32 / 256.0)).collect();
            let q: Vec<Vec3<Q16_16>> = v.iter().map(|p| Vec3::from_f32([p.x, p.y, p.z]).unwrap()).collect();
            let q24: Vec<Vec3<Q24_8>> = v.iter().map(|p| Vec3::from_f32([p.x, p.y, p.z]).unwrap()).collect();
            run::<f32>(v, faces.clone(), model);
            run::<Q16_16>(q, faces.clone(), model);
            run::<Q24_8>(q24, faces, model);
        }
    }
}
