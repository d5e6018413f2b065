//! Property tests: the scan-line renderer equals the exact reference on random scenes.
//!
//! Vertices lie on the 1/256 grid, so snapping at 8 bits is the identity and the reference's
//! coverage is exact: every pixel must match except where the reference itself calls a depth
//! tie (the two nearest polygons closer than the format's stated depth error). Visible depths
//! must be within that error too.

mod common;
use common::Rng as XorShift;
use common::*;
use proptest::prelude::*;
use zrow::{Config, Scalar, Q16_16};

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
    let tol = tie_tolerance::<N>((W + H) as usize + 4 * MARGIN as usize);
    let refr = reference::<N>(p, &cfg, 2.0 * tol);
    let bad = mismatches(&cap, &refr);
    prop_assert!(
        bad.is_empty(),
        "{} pixels differ, first {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    for y in 0..H as usize {
        for x in 0..W as usize {
            if let Verdict::Visible(_, z) = refr[y * W as usize + x] {
                let got = cap.z(x, y).to_f32() as f64;
                let err = (got - z).abs();
                let allowed = if N::NAME == "f32" {
                    1e-3 * (1.0 + z.abs())
                } else {
                    tol
                };
                prop_assert!(err <= allowed, "depth at ({x},{y}): got {got}, exact {z}");
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn scanline_equals_reference_q16_16(p in scene()) {
        check::<Q16_16>(&p)?;
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
        check::<f32>(&p).unwrap();
    }
}
