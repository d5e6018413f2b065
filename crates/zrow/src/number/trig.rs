//! Sines and cosines of an `f32` angle in integer arithmetic, for the fixed-point formats.
//!
//! libm's `sinf` computes in `f64`: on a Cortex-M4F that is software floating point, and
//! with its argument reduction for huge angles it is about 6 KB of flash, a fifth of a small
//! board's demo. A fixed-point rotation needs its entries to 2^-16 (Q16.16), so this
//! computes them in 64-bit integers, more exactly than the format holds them: the angle is
//! taken exactly from its bits, reduced by π/2 in two parts (Cody and Waite, "Software Manual
//! for the Elementary Functions", 1980, §8), and sine and cosine of the remainder (at most
//! π/4) summed as their Taylor series to the 12th power in 1.31 fixed point. Measured error
//! (`tests` below, against f64): 1.5 units of 2^-31, within 2^-30 for every angle below 2^23 radians in
//! magnitude; larger angles (and NaN, infinities) are refused. The fixed-point crates'
//! own sines (`fixed_math`, `fixed_trigonometry`) are accurate to a few decimal places, not
//! to the format's last place, hence this.

/// π/2 rounded to 2^-30, in units of 2^-30.
const HALF_PI_Q30: i64 = 1_686_629_713;
/// π/2 less [`HALF_PI_Q30`], in units of 2^-60.
const HALF_PI_REST_Q60: i64 = 70_064_199;
/// One in 1.31 fixed point.
const ONE: i64 = 1 << 31;
/// 1/3!, 1/5!, …, 1/11! in 1.31 fixed point, highest power first.
const SIN: [i64; 5] = [54, 5_918, 426_088, 17_895_697, 357_913_941];
/// 1/2!, 1/4!, …, 1/12! in 1.31 fixed point, highest power first.
const COS: [i64; 6] = [4, 592, 53_261, 2_982_616, 89_478_485, 1_073_741_824];

/// The largest angle magnitude (radians, exclusive) [`sin_cos_q31`] takes: 2^23.
pub const TRIG_LIMIT: f32 = 8_388_608.0;

/// `a·b` in 1.31 fixed point, rounded (`|a|, |b| ≤ 2^31`).
#[inline]
fn mul(a: i64, b: i64) -> i64 {
    (a * b + (1 << 30)) >> 31
}

/// `(sin x, cos x)` in 1.31 fixed point (units of 2^-31), within 2^-30 of the exact values;
/// `None` if `x` is not finite or its magnitude is [`TRIG_LIMIT`] or more.
pub fn sin_cos_q31(x: f32) -> Option<(i64, i64)> {
    if x.is_nan() || x.abs() >= TRIG_LIMIT {
        return None;
    }
    let bits = x.to_bits();
    let exp = ((bits >> 23) & 0xff) as i32;
    let fraction = (bits & 0x7f_ffff) as i64;
    // |x| = m · 2^e exactly.
    let (m, e) = if exp == 0 {
        (fraction, -149)
    } else {
        (fraction | 0x80_0000, exp - 150)
    };
    // The remainder r = |x| − k·π/2 in units of 2^-60, and k.
    let (r60, k) = if e >= -30 {
        // |x| < 2^23 and m < 2^24: |x| in units of 2^-30 fits 53 bits, k fits 23.
        let x30 = m << (e + 30);
        let k = (x30 + HALF_PI_Q30 / 2) / HALF_PI_Q30;
        (((x30 - k * HALF_PI_Q30) << 30) - k * HALF_PI_REST_Q60, k)
    } else if e >= -60 {
        // |x| < 2^-6: no reduction.
        (m << (e + 60), 0)
    } else {
        ((m >> (-60 - e).min(63)), 0)
    };
    let r = (r60 + (1 << 28)) >> 29;
    let r2 = mul(r, r);
    let s = mul(
        ONE - mul(SIN.iter().skip(1).fold(SIN[0], |p, &c| c - mul(p, r2)), r2),
        r,
    );
    let c = ONE - mul(COS.iter().skip(1).fold(COS[0], |p, &c| c - mul(p, r2)), r2);
    let (s, c) = match k & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    };
    Some((if x < 0.0 { -s } else { s }, c))
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::{eprintln, vec::Vec};

    /// Largest error in units of 2^-31 against f64 over `angles`.
    fn worst(angles: impl Iterator<Item = f32>) -> f64 {
        let mut worst = 0f64;
        for x in angles {
            let (s, c) = sin_cos_q31(x).unwrap();
            let unit = |v: i64| v as f64 / ONE as f64;
            let xs = x as f64;
            let err = (unit(s) - xs.sin()).abs().max((unit(c) - xs.cos()).abs());
            worst = worst.max(err * ONE as f64);
        }
        worst
    }

    #[test]
    fn within_2_pow_minus_30() {
        // Every f32 step over ±2π near the quadrant boundaries, a dense sweep, tiny and
        // subnormal angles, and large ones up to the limit (a fixed xorshift sequence).
        let mut s = 0x9e37_79b9u32;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s
        };
        let sweep = (-20_000..=20_000).map(|i| i as f32 * (core::f32::consts::TAU / 20_000.0));
        let boundaries = (-8..=8).flat_map(|q| {
            let b = q as f32 * core::f32::consts::FRAC_PI_4;
            let mut v = b;
            (0..64).map(move |_| {
                v = f32::from_bits(v.to_bits() + 1);
                v
            })
        });
        let tiny = [
            0.0, -0.0, 1e-45, 1e-38, 1e-20, 1e-9, 3e-7, 0.015625, -0.0078125,
        ];
        let large: Vec<f32> = (0..20_000)
            .map(|_| {
                let v = f32::from_bits(next() & 0x4aff_ffff);
                if next() & 1 == 0 {
                    v
                } else {
                    -v
                }
            })
            .filter(|v| v.abs() < TRIG_LIMIT)
            .collect();
        let w = worst(sweep.chain(boundaries).chain(tiny).chain(large));
        eprintln!("sin_cos_q31: worst error {w:.3} units of 2^-31");
        assert!(w <= 2.0, "{w}");
    }

    #[test]
    fn refuses_what_it_cannot_reduce() {
        for x in [TRIG_LIMIT, -TRIG_LIMIT, 1e30, f32::INFINITY, f32::NAN] {
            assert_eq!(sin_cos_q31(x), None, "{x}");
        }
        assert!(sin_cos_q31(f32::from_bits(TRIG_LIMIT.to_bits() - 1)).is_some());
    }
}
