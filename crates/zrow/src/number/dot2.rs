//! One row of an affine transform in `f32`, as accurate as if computed in twice the precision
//! and rounded once.
//!
//! Summed plainly in `f32`, `a·x + b·y + c·z + t` rounds each of its three products and three
//! sums: up to 3 units of the last place of its largest term (1.96 measured near the format's
//! limits). Fixed point sums exactly and rounds once. For `f32` this is the compensated dot
//! product `Dot2` of Ogita, Rump & Oishi ("Accurate sum and dot product", SIAM J. Sci. Comput.
//! 26(6), 2005): each product split exactly into its rounded value and its error (Dekker's
//! `TwoProduct`, Veltkamp's splitting: no fused multiply-add, which `core` does not offer), the
//! rounded values summed with their rounding errors kept (Knuth's `TwoSum`), the errors added
//! back once at the end. The result is within half a unit of the last place of the exact
//! value plus `γ₄²·Σ|terms|` (`γ₄ = 4u/(1 − 4u)`, `u = 2^-24`: about 2^-44 of the largest term),
//! with the same bits on every IEEE 754 target (each operation is one correctly rounded `f32`
//! addition or multiplication).
//!
//! Valid while the products do not underflow and the entries stay below 2^115
//! (the splitting multiplies by 4097); beyond, the compensated terms are not numbers and the
//! plain sum is returned (still the format's rounding of each step).

/// Veltkamp's splitting: `a = hi + lo` exactly, each half with at most 12 significant bits.
#[inline(always)]
pub(crate) fn split(a: f32) -> (f32, f32) {
    let c = 4097.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a·b` as `(p, e)` with `p = fl(a·b)` and `p + e = a·b` exactly (Dekker's `TwoProduct`).
#[inline(always)]
fn two_product(a: (f32, (f32, f32)), b: (f32, (f32, f32))) -> (f32, f32) {
    let (a, (ah, al)) = a;
    let (b, (bh, bl)) = b;
    let p = a * b;
    (p, al * bl - (((p - ah * bh) - al * bh) - ah * bl))
}

/// `a + b` as `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly (Knuth's `TwoSum`).
#[inline(always)]
fn two_sum(a: f32, b: f32) -> (f32, f32) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `row[0]·p[0] + row[1]·p[1] + row[2]·p[2] + row[3]`, compensated (see the module).
#[inline]
pub(crate) fn affine_row_f32(row: &[f32; 4], p: [f32; 3]) -> f32 {
    affine_row_halved_f32(row, &[split(row[0]), split(row[1]), split(row[2])], p)
}

/// [`affine_row_f32`] with the row's first three entries already split ([`split`], once per
/// transform rather than once per point): the same bits.
#[inline]
pub(crate) fn affine_row_halved_f32(row: &[f32; 4], halves: &[(f32, f32); 3], p: [f32; 3]) -> f32 {
    let with_split = |v: f32| (v, split(v));
    let (s0, e0) = two_product((row[0], halves[0]), with_split(p[0]));
    let (h1, r1) = two_product((row[1], halves[1]), with_split(p[1]));
    let (h2, r2) = two_product((row[2], halves[2]), with_split(p[2]));
    let (s1, q1) = two_sum(s0, h1);
    let (s2, q2) = two_sum(s1, h2);
    let (s3, q3) = two_sum(s2, row[3]);
    let v = s3 + (((e0 + (q1 + r1)) + (q2 + r2)) + q3);
    if v.is_finite() {
        v
    } else {
        // The splitting overflowed (or the result is beyond the format): the plain sum.
        plain_row_f32(row, p)
    }
}

/// The same row summed plainly: three products and three sums, each rounded.
#[inline]
pub(crate) fn plain_row_f32(row: &[f32; 4], p: [f32; 3]) -> f32 {
    row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + row[3]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact value, to f64's rounding (products of f32s are exact in f64; the sum rounds
    /// within 2^-51 of the largest term, far below an f32 unit).
    fn exact(row: &[f32; 4], p: [f32; 3]) -> f64 {
        (0..3).map(|k| row[k] as f64 * p[k] as f64).sum::<f64>() + row[3] as f64
    }

    #[test]
    fn cancellation_keeps_every_bit() {
        // 30000·1 + 30000·1 − 30000·1 + 0, and a case plain f32 gets wrong by a whole term.
        assert_eq!(
            affine_row_f32(&[30000.0, 30000.0, -30000.0, 0.0], [1.0; 3]),
            30000.0
        );
        let (a, b) = (1.0 + f32::EPSILON, 1.0 - f32::EPSILON);
        // a·a = 1 + 2ε + ε², its ε² lost by a plain product; minus 1 + 2ε leaves ε² exactly.
        let row = [a, -(1.0 + 2.0 * f32::EPSILON), 0.0, 0.0];
        let want = exact(&row, [a, 1.0, b]);
        assert_eq!(affine_row_f32(&row, [a, 1.0, b]) as f64, want);
        assert_eq!(want, (f32::EPSILON as f64).powi(2));
    }

    #[test]
    fn within_half_an_ulp_of_the_result_on_random_rows() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut f = || {
            let seed = crate::number::xorshift64(&mut seed);
            // Mantissa and a modest exponent spread, random sign.
            let m = (seed >> 40) as f32 / (1u64 << 24) as f32 + 0.5;
            let e = ((seed >> 8) & 15) as i32 - 8;
            let s = if seed & 1 == 0 { 1.0 } else { -1.0 };
            s * m * 2f32.powi(e)
        };
        for _ in 0..100_000 {
            let row = [f(), f(), f(), f()];
            let p = [f(), f(), f()];
            let want = exact(&row, p);
            let got = affine_row_f32(&row, p) as f64;
            // Half an ulp of the result, plus the bound's second-order term.
            let w = (want.abs() as f32).max(f32::MIN_POSITIVE);
            let ulp = f32::from_bits(w.to_bits() & 0xff80_0000) as f64 * f32::EPSILON as f64;
            let terms: f64 = (0..3)
                .map(|k| (row[k] as f64 * p[k] as f64).abs())
                .sum::<f64>()
                + (row[3] as f64).abs();
            assert!(
                (got - want).abs() <= 0.5 * ulp + 1e-12 * terms,
                "{row:?} {p:?}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn beyond_the_splitting_range_the_plain_sum() {
        let big = 1.0e36f32;
        let row = [big, 1.0, 0.0, 0.0];
        assert_eq!(affine_row_f32(&row, [2.0, 3.0, 0.0]), big * 2.0 + 3.0);
        assert!(!affine_row_f32(&[f32::MAX, f32::MAX, 0.0, 0.0], [2.0, 2.0, 0.0]).is_finite());
    }
}
