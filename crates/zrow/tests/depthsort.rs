//! Depth-sort equals the exact reference (`docs/extremes.md` item 20).

mod common;
use common::*;
use zrow::depthsort::DepthSort;
use zrow::{Config, Scalar, Q16_16};

type Ds<N> = DepthSort<N, 64, 256, 1024, 4096>;

fn check<N: Scalar>(p: &Polys, w: u16, h: u16) -> zrow::FrameStats {
    let cfg = Config::screen(w, h);
    let mut r = Box::new(Ds::<N>::new());
    let (cap, stats) = p.render_stats(&mut *r, &cfg).unwrap();
    let tol = tie_tolerance::<N>(4 * (w + h) as usize);
    let refr = reference::<N>(p, &cfg, 2.0 * tol);
    let bad = mismatches(&cap, &refr);
    assert!(
        bad.is_empty(),
        "{} pixels differ, first {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    stats
}

#[test]
fn cyclic_overlap_is_split_and_exact() {
    for shift in [0.0, 0.25, 1.0] {
        println!("shift {shift}");
        let s = check::<Q16_16>(&scenes::cyclic(shift), 48, 48);
        assert!(s.splits > 0, "a cyclic overlap needs a split");
        check::<f32>(&scenes::cyclic(shift), 48, 48);
    }
}

#[test]
fn random_and_dense_scenes_equal_the_reference() {
    let mut rng = Rng(0x5eed_0001);
    for _ in 0..40 {
        let n = 1 + rng.below(30) as usize;
        check::<Q16_16>(&scenes::random(&mut rng, n, 48.0, 40.0), 48, 40);
        check::<f32>(&scenes::random(&mut rng, n, 48.0, 40.0), 48, 40);
    }
    for _ in 0..10 {
        let n = 2 + rng.below(8) as usize;
        let s = check::<Q16_16>(&scenes::dense(&mut rng, n, 48.0, 40.0), 48, 40);
        println!("dense {n}: {} splits", s.splits);
        check::<f32>(&scenes::dense(&mut rng, n, 48.0, 40.0), 48, 40);
    }
}

#[test]
fn too_few_pieces_is_a_typed_error_before_any_row() {
    use zrow::{Error, RenderError, Table};
    let p = scenes::cyclic(0.0);
    let cfg = Config::screen(48, 48);
    let err = p
        .render_with(
            &mut *Box::new(DepthSort::<Q16_16, 48, 8, 64, 3>::new()),
            &cfg,
        )
        .unwrap_err();
    // `render_with`'s capture asserts on any row received, so none was sent.
    assert!(
        matches!(
            err,
            RenderError::Scene(Error::Capacity {
                table: Table::Pieces,
                ..
            })
        ),
        "{err:?}"
    );
}
