//! Exact integer division for 32-bit cores.
//!
//! A Cortex-M3/M4 divides 32 by 32 bits in one instruction (`udiv`), but a 64-bit division is a
//! library call of about 90 instructions. Geometry divides 64-bit numerators by 32-bit
//! divisors thousands of times a frame (projection, depth planes, lighting), so this does it
//! in two hardware divisions per 32-bit digit pair (Knuth's algorithm D with 16-bit digits,
//! Hacker's Delight §9.4 `divlu`), with the same, exact, result. A 64-bit host divides in
//! hardware instead (same result; the digit method stays tested on every target).

/// `(floor(n / d), n mod d)` for `d > 0`.
#[inline]
pub(crate) fn divmod_u64_u32(n: u64, d: u32) -> (u64, u32) {
    if cfg!(target_pointer_width = "64") {
        return (n / d as u64, (n % d as u64) as u32);
    }
    divmod_digits(n, d)
}

/// [`divmod_u64_u32`] in 32-bit hardware divisions.
#[inline]
fn divmod_digits(n: u64, d: u32) -> (u64, u32) {
    let (hi, lo) = ((n >> 32) as u32, n as u32);
    if hi == 0 {
        return ((lo / d) as u64, lo % d);
    }
    let (qh, rh) = (hi / d, hi % d);
    let (ql, r) = divlu(rh, lo, d);
    (((qh as u64) << 32) | ql as u64, r)
}

/// `(u1·2^32 + u0) / v` and its remainder, for `u1 < v` (so the quotient fits 32 bits):
/// normalise `v`, then two steps each dividing by its top 16 bits and correcting the digit
/// estimate (at most twice). Every intermediate fits 32 bits (the product in the correction
/// test is formed only once the digit is below 2^16).
#[inline]
fn divlu(u1: u32, u0: u32, v: u32) -> (u32, u32) {
    const B: u32 = 1 << 16;
    let s = v.leading_zeros();
    let v = v << s;
    let (vn1, vn0) = (v >> 16, v & 0xffff);
    let un32 = if s == 0 {
        u1
    } else {
        (u1 << s) | (u0 >> (32 - s))
    };
    let un10 = u0 << s;
    let (un1, un0) = (un10 >> 16, un10 & 0xffff);
    let digit = |un: u32, next: u32| {
        let mut q = un / vn1;
        let mut rhat = un - q * vn1;
        while q >= B || q * vn0 > (rhat << 16) + next {
            q -= 1;
            rhat += vn1;
            if rhat >= B {
                break;
            }
        }
        q
    };
    let q1 = digit(un32, un1);
    // The partial remainder is below v; the wrapping arithmetic is exact modulo 2^32.
    let un21 = (un32 << 16)
        .wrapping_add(un1)
        .wrapping_sub(q1.wrapping_mul(v));
    let q0 = digit(un21, un0);
    let r = (un21 << 16)
        .wrapping_add(un0)
        .wrapping_sub(q0.wrapping_mul(v))
        >> s;
    ((q1 << 16) | q0, r)
}

/// The high 64 bits of `a·b`, from four 32 × 32-bit products.
#[inline]
fn mulhi(a: u64, b: u64) -> u64 {
    let (a0, a1) = (a & 0xffff_ffff, a >> 32);
    let (b0, b1) = (b & 0xffff_ffff, b >> 32);
    let (p00, p01, p10, p11) = (a0 * b0, a0 * b1, a1 * b0, a1 * b1);
    let mid = (p00 >> 32) + (p01 & 0xffff_ffff) + (p10 & 0xffff_ffff);
    p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32)
}

/// Division by one positive divisor many times, exactly: the divisor's reciprocal once
/// (`floor((2^64 − 1)/d)`, two hardware divisions), then per quotient a high multiply, which
/// is at most two below the quotient, and a correction by the remainder. A divisor beyond 32
/// bits divides the plain way.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Recip {
    d: u64,
    /// 0 when `d` does not fit 32 bits.
    inv: u64,
}

impl Recip {
    /// The reciprocal of `d ≥ 1`.
    #[inline]
    pub(crate) fn new(d: u64) -> Self {
        let inv = match u32::try_from(d) {
            Ok(d32) if d32 > 0 => divmod_u64_u32(u64::MAX, d32).0,
            _ => 0,
        };
        Recip { d, inv }
    }

    /// `(floor(n / d), n mod d)`.
    #[inline]
    pub(crate) fn divmod(&self, n: u64) -> (u64, u64) {
        if self.inv == 0 {
            return (n / self.d, n % self.d);
        }
        let mut q = mulhi(n, self.inv);
        let mut r = n - q * self.d;
        while r >= self.d {
            q += 1;
            r -= self.d;
        }
        (q, r)
    }

    /// `n / d` rounded to nearest, ties away from zero: [`div_round`] by this divisor.
    #[inline]
    pub(crate) fn div_round(&self, n: i64) -> i64 {
        let (q, r) = self.divmod(n.unsigned_abs());
        let q = q + (r >= self.d - r) as u64;
        if n < 0 {
            (q as i64).wrapping_neg()
        } else {
            q as i64
        }
    }
}

/// `n / d` rounded to nearest, ties away from zero, for `d ≠ 0`. Two hardware divisions when
/// `|d|` fits 32 bits, a library division otherwise. Wraps only where the quotient itself does
/// not fit (`i64::MIN / ±1`), which callers never ask for.
#[inline]
pub(crate) fn div_round(n: i64, d: i64) -> i64 {
    let (un, ud) = (n.unsigned_abs(), d.unsigned_abs());
    let q = if ud <= u32::MAX as u64 {
        let (q, r) = divmod_u64_u32(un, ud as u32);
        q + (2 * r as u64 >= ud) as u64
    } else {
        let (q, r) = (un / ud, un % ud);
        q + (r >= ud - r) as u64
    };
    if (n < 0) != (d < 0) {
        (q as i64).wrapping_neg()
    } else {
        q as i64
    }
}

/// `n / d` rounded to nearest, ties away from zero, for `0 < d < 2^24` and a quotient that fits
/// an `i32`: long division whose first digit is the numerator's top 32 bits and each further
/// digit 8 bits (a hardware division each: one for a numerator below 2^32, two for a
/// projection's typical 2^33), the quotient in one register. The result of
/// [`div_round`]`(n, d)` where that fits an `i32`; `None` where it does not, or `d` is out of
/// range.
#[inline]
pub(crate) fn div_round_small_divisor(n: i64, d: u32) -> Option<i32> {
    if d == 0 || d >= 1 << 24 {
        return None;
    }
    let un = n.unsigned_abs();
    // Most numerators (a projection's x and y) fit 32 bits: one hardware division.
    let (q, r) = if un >> 32 == 0 {
        (un as u32 / d, un as u32 % d)
    } else {
        // Bits below the first digit: a multiple of 8, so that the first digit has at most 32.
        let extra = (32 - ((un >> 32) as u32).leading_zeros() + 7) & !7;
        let top = (un >> extra) as u32;
        let (mut q, mut r) = (top / d, top % d);
        let mut left = extra;
        while left > 0 {
            if q > 1 << 23 {
                return None; // the quotient passes 2^31
            }
            left -= 8;
            let t = r << 8 | (un >> left) as u32 & 0xff; // r < d < 2^24
            (q, r) = ((q << 8) | (t / d), t % d);
        }
        (q, r)
    };
    rounded(q, r, d, n < 0)
}

/// [`div_round`] of two numerators by one divisor `d > 0`, where both fit 32 bits and both
/// quotients' magnitudes stay below 2^31: one hardware division each and a single test for
/// both (`q + 1` cannot wrap: a quotient of 2^32 − 1 means `d = 1` and no remainder). `None`
/// otherwise, for the caller to take each the general way (which also decides a quotient of
/// exactly −2^31).
#[inline(always)]
pub(crate) fn div_round_pair(a: i64, b: i64, d: u32) -> Option<(i32, i32)> {
    let (ua, ub) = (a.unsigned_abs(), b.unsigned_abs());
    if (ua | ub) >> 32 != 0 || d == 0 {
        return None;
    }
    let round = |n: u32| {
        let (q, r) = (n / d, n % d);
        q + (r >= d - r) as u32
    };
    let (qa, qb) = (round(ua as u32), round(ub as u32));
    if (qa | qb) >> 31 != 0 {
        return None;
    }
    Some((signed(qa, a < 0), signed(qb, b < 0)))
}

/// `n · 2^shift / d` rounded to nearest, ties away from zero: [`div_round_small_divisor`] of
/// that numerator, for `shift` a multiple of 8 (a fixed-point format's fractional bits), its
/// digits taken from `n` and then zeros with no 64-bit shift: one hardware division for `n`
/// and one per 8 bits of `shift`. The same result; `None` where that is.
#[inline]
pub(crate) fn div_round_shifted(n: i32, shift: u32, d: u32) -> Option<i32> {
    if d == 0 || d >= 1 << 24 || shift % 8 != 0 {
        return div_round_small_divisor((n as i64) << shift.min(32), d);
    }
    let un = n.unsigned_abs();
    let (mut q, mut r) = (un / d, un % d);
    for _ in 0..shift / 8 {
        if q > 1 << 23 {
            return None; // the quotient passes 2^31
        }
        let t = r << 8; // r < d < 2^24
        (q, r) = ((q << 8) | (t / d), t % d);
    }
    rounded(q, r, d, n < 0)
}

/// A fixed-point division: `n · 2^shift / d` rounded to nearest, ties away from zero (`n`, `d`
/// a format's bits, `shift` its fractional bits); `None` for `d = 0` or a quotient that does
/// not fit an `i32`. On a 32-bit core a divisor below 2^24 (nearly every one) takes a hardware
/// division per 8 bits of the quotient ([`div_round_shifted_signed`]) instead of a 64-bit
/// division; the same result. Out of line: most callers divide a few times a frame, and
/// their loops keep their registers ([`div_fixed_inline`] is for a loop that divides once a
/// pixel).
#[inline(never)]
pub(crate) fn div_fixed(n: i32, shift: u32, d: i32) -> Option<i32> {
    div_fixed_inline(n, shift, d)
}

/// [`div_fixed`], its common path inlined into the caller.
#[inline(always)]
pub(crate) fn div_fixed_inline(n: i32, shift: u32, d: i32) -> Option<i32> {
    if cfg!(target_pointer_width = "32") {
        if let Some(q) = div_round_shifted_signed(n, shift, d) {
            return Some(q);
        }
    }
    div_fixed_wide(n, shift, d)
}

/// [`div_fixed`] the general way (a 64-bit numerator). Out of line: rare, and its callers'
/// loops keep their registers.
#[inline(never)]
fn div_fixed_wide(n: i32, shift: u32, d: i32) -> Option<i32> {
    if d == 0 {
        return None;
    }
    i32::try_from(div_round((n as i64) << shift, d as i64)).ok()
}

/// `n · 2^shift / d` rounded to nearest, ties away from zero, for a divisor of either sign:
/// [`div_round_shifted`] by `|d|`, negated for a negative `d` (the rounding is symmetric). The
/// result of [`div_round`]`((n as i64) << shift, d as i64)` where this gives one; `None` where
/// `d` is 0 or `|d|` not below 2^24, `shift` not a multiple of 8, or the quotient does not
/// fit an `i32` (then the caller divides the general way, which decides).
#[inline]
pub(crate) fn div_round_shifted_signed(n: i32, shift: u32, d: i32) -> Option<i32> {
    let ud = d.unsigned_abs();
    if ud == 0 || ud >= 1 << 24 || shift % 8 != 0 {
        return None;
    }
    let q = div_round_shifted(n, shift, ud)?;
    match d < 0 {
        true => q.checked_neg(),
        false => Some(q),
    }
}

/// Quotient `q` and remainder `r` of a magnitude by `d`, rounded to nearest (ties away from
/// zero) and signed: `None` if that does not fit an `i32`.
#[inline]
fn rounded(q: u32, r: u32, d: u32, negative: bool) -> Option<i32> {
    let q = q.checked_add((r >= d - r) as u32)?;
    // Up to 2^31 − 1, or 2^31 for a negative quotient.
    let most = (1u32 << 31) - !negative as u32;
    (q <= most).then(|| signed(q, negative))
}

/// A magnitude of at most 2^31 (2^31 only if `negative`) with its sign.
#[inline(always)]
fn signed(q: u32, negative: bool) -> i32 {
    match negative {
        true => (q as i32).wrapping_neg(),
        false => q as i32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::xorshift64;

    #[test]
    fn divmod_equals_the_native_division() {
        // The digit method itself (a 64-bit host divides natively in divmod_u64_u32).
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let edges = [
            1u32,
            2,
            3,
            0xffff,
            0x1_0000,
            0x1_0001,
            0x7fff_ffff,
            0x8000_0000,
            u32::MAX,
        ];
        for _ in 0..200_000 {
            let r = xorshift64(&mut seed);
            // Numerators and divisors of every width, and the boundary values.
            let n = r >> (xorshift64(&mut seed) % 64);
            let d = match xorshift64(&mut seed) % 4 {
                0 => edges[(r % edges.len() as u64) as usize],
                _ => ((xorshift64(&mut seed) as u32) >> (xorshift64(&mut seed) % 32)).max(1),
            };
            assert_eq!(
                divmod_digits(n, d),
                (n / d as u64, (n % d as u64) as u32),
                "{n} / {d}"
            );
        }
        for &d in &edges {
            for n in [
                0u64,
                1,
                d as u64 - 1,
                d as u64,
                u64::MAX,
                u64::MAX - 1,
                1 << 63,
            ] {
                assert_eq!(divmod_digits(n, d), (n / d as u64, (n % d as u64) as u32));
            }
        }
    }

    #[test]
    fn reciprocal_division_equals_the_native_one() {
        let mut seed = 0x7f4a_7c15_9e37_79b9u64;
        for _ in 0..100_000 {
            let d = match xorshift64(&mut seed) % 4 {
                0 => 1 + xorshift64(&mut seed) % 7,
                1 => u32::MAX as u64 - xorshift64(&mut seed) % 3,
                2 => xorshift64(&mut seed) >> (xorshift64(&mut seed) % 64) | 1,
                _ => (xorshift64(&mut seed) as u32 >> (xorshift64(&mut seed) % 32)).max(1) as u64,
            };
            let r = Recip::new(d);
            for n in [
                xorshift64(&mut seed) >> (xorshift64(&mut seed) % 64),
                u64::MAX,
                d - 1,
                d,
                d.wrapping_mul(3),
                0,
            ] {
                assert_eq!(r.divmod(n), (n / d, n % d), "{n} / {d}");
                let s = (n >> 1) as i64;
                for v in [s, -s].into_iter().filter(|_| d <= i64::MAX as u64) {
                    assert_eq!(r.div_round(v), div_round(v, d as i64), "{v} / {d}");
                }
            }
        }
    }

    #[test]
    fn div_round_is_nearest_ties_away_from_zero() {
        let exact = |n: i64, d: i64| {
            let (n, d) = (n as i128, d as i128);
            let q = (2 * n.abs() + d.abs()) / (2 * d.abs());
            (if (n < 0) != (d < 0) { -q } else { q }) as i64
        };
        assert_eq!(div_round(5, 2), 3);
        assert_eq!(div_round(-5, 2), -3);
        assert_eq!(div_round(7, -2), -4);
        assert_eq!(div_round(-7, 3), -2);
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200_000 {
            let n = (xorshift64(&mut seed) as i64) >> (xorshift64(&mut seed) % 63);
            let d = ((xorshift64(&mut seed) as i64) >> (xorshift64(&mut seed) % 63)).max(1);
            let d = if xorshift64(&mut seed) % 2 == 0 {
                d
            } else {
                -d
            };
            assert_eq!(div_round(n, d), exact(n, d), "{n} / {d}");
        }
    }

    #[test]
    fn pair_path_equals_div_round() {
        // Numerators around 2^32 and quotients around 2^31 (both sides), divisors from 1 to
        // 2^31 − 1: where the pair answers, each is `div_round`'s, and it answers whenever
        // both numerators fit 32 bits and both quotients stay below 2^31.
        let mut seed = 0x51_7cc1_b727_220au64;
        let mut answered = 0;
        for i in 0..300_000u32 {
            let mut r = || xorshift64(&mut seed);
            let d = match i % 3 {
                0 => 1 + r() % 5,
                1 => (r() as u32 >> (r() % 31)).max(1) as u64,
                _ => (1u64 << 31) - 1 - r() % 3,
            } as i64;
            let mut n = || -> i64 {
                let v = match r() % 4 {
                    0 => (1i64 << 32) - 1 - (r() % 3) as i64,
                    1 => (d << 31) - d / 2 - 1 + (r() % 3) as i64,
                    _ => (r() >> (r() % 64)) as i64 >> 1,
                };
                if r() % 2 == 0 {
                    v
                } else {
                    -v
                }
            };
            let (a, b) = (n(), n());
            let fits =
                |v: i64| v.unsigned_abs() < 1 << 32 && div_round(v, d).unsigned_abs() < 1 << 31;
            match div_round_pair(a, b, d as u32) {
                Some((qa, qb)) => {
                    answered += 1;
                    assert_eq!(
                        (qa as i64, qb as i64),
                        (div_round(a, d), div_round(b, d)),
                        "{a}, {b} / {d}"
                    );
                }
                None => assert!(!(fits(a) && fits(b)), "{a}, {b} / {d}: not answered"),
            }
        }
        assert!(answered > 50_000, "{answered}");
    }

    #[test]
    fn small_divisor_path_equals_div_round() {
        // Numerators of every size (both ends included), divisors on both sides of 2^24:
        // where the path answers, the answer is `div_round`'s.
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut taken = 0;
        for k in 0..400_000u32 {
            let n = match k % 7 {
                0 => i64::MAX,
                1 => i64::MIN + 1,
                _ => (xorshift64(&mut seed) as i64) >> (xorshift64(&mut seed) % 64),
            };
            let d = ((xorshift64(&mut seed) as u32) >> (xorshift64(&mut seed) % 32)).max(1);
            let want = div_round(n, d as i64);
            match div_round_small_divisor(n, d) {
                Some(q) => {
                    assert_eq!(q as i64, want, "{n} / {d}");
                    taken += 1;
                }
                None => assert!(d >= 1 << 24 || i32::try_from(want).is_err(), "{n} / {d}"),
            }
        }
        assert!(taken > 100_000, "{taken}");
        // A numerator shifted by a format's fractional bits: the same as unshifted.
        for k in 0..200_000u32 {
            let n = (xorshift64(&mut seed) as i32) >> (xorshift64(&mut seed) % 32);
            let d = ((xorshift64(&mut seed) as u32) >> (xorshift64(&mut seed) % 32)).max(1);
            let shift = [8, 16, 0, 24][(k % 4) as usize];
            let want = div_round_small_divisor((n as i64) << shift, d);
            assert_eq!(div_round_shifted(n, shift, d), want, "{n} << {shift} / {d}");
        }
        assert_eq!(div_round_shifted(i32::MIN, 16, 1 << 16), Some(i32::MIN));
        assert_eq!(div_round_shifted(i32::MAX, 16, 1 << 16), Some(i32::MAX));
        assert_eq!(div_round_shifted(1 << 15, 16, 1), None);
        assert_eq!(div_round_small_divisor(5, 2), Some(3));
        assert_eq!(div_round_small_divisor(-5, 2), Some(-3));
        assert_eq!(div_round_small_divisor(1, 0), None);
        // The ends of `i32`, reached through further digits.
        assert_eq!(div_round_small_divisor(-(1 << 39), 256), Some(i32::MIN));
        assert_eq!(div_round_small_divisor(1 << 39, 256), None);
        assert_eq!(
            div_round_small_divisor(((1 << 31) - 1) * 3, 3),
            Some(i32::MAX)
        );
    }

    /// The fixed-point division the long way: `div_round` of the shifted numerator, `None`
    /// past `i32` or for a zero divisor.
    fn fixed_wide(n: i32, shift: u32, d: i32) -> Option<i32> {
        (d != 0)
            .then(|| i32::try_from(div_round((n as i64) << shift, d as i64)).ok())
            .flatten()
    }

    #[test]
    fn fixed_point_division_equals_the_wide_one() {
        // Both signs of numerator and divisor, divisors on both sides of 2^24 and 0, the
        // formats' shifts (and one the fast path declines): the signed fast path, where it
        // answers, and `div_fixed` (both paths on a 32-bit core, the wide one on a 64-bit
        // host), always, give the wide division's answer.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut taken = 0;
        let mut check = |n: i32, shift: u32, d: i32| {
            let want = fixed_wide(n, shift, d);
            assert_eq!(div_fixed(n, shift, d), want, "{n} << {shift} / {d}");
            assert_eq!(div_fixed_inline(n, shift, d), want, "{n} << {shift} / {d}");
            match div_round_shifted_signed(n, shift, d) {
                Some(q) => {
                    assert_eq!(Some(q), want, "{n} << {shift} / {d}");
                    taken += 1;
                }
                // Declined: out of its range, or a quotient past `i32` (of either sign).
                None => assert!(
                    d == 0
                        || d.unsigned_abs() >= 1 << 24
                        || shift % 8 != 0
                        || i64::from(want.unwrap_or(i32::MIN)).abs() >= (1 << 31) - 1,
                    "{n} << {shift} / {d}"
                ),
            }
        };
        for k in 0..400_000u32 {
            let n = (xorshift64(&mut seed) as i32) >> (xorshift64(&mut seed) % 32);
            let d = (xorshift64(&mut seed) as i32) >> (xorshift64(&mut seed) % 32);
            check(n, [16, 8, 16, 12][(k % 4) as usize], d);
        }
        for n in [0, 1, -1, i32::MAX, i32::MIN, 1 << 15, -(1 << 15), 3 << 14] {
            for d in [
                1,
                -1,
                2,
                -2,
                3,
                -3,
                (1 << 24) - 1,
                -(1 << 24) + 1,
                1 << 24,
                0,
            ] {
                for shift in [8, 16] {
                    check(n, shift, d);
                }
            }
        }
        assert!(taken > 200_000, "{taken}");
    }
}
