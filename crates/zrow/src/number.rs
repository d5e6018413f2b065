//! Number formats: the [`Scalar`] trait and its two implementations, [`Q16_16`] and `f32`.
//!
//! A renderer is generic over its number format, so a Q16.16 renderer and an f32 renderer can
//! live side by side in one program. The format governs geometry (transform, clipping,
//! projection, lighting) and depth. Coverage never depends on it: vertices are snapped to a
//! sub-pixel grid of integers before any coverage decision (see [`crate::raster`]).
//!
//! Every operation a renderer uses is named here with its overflow behaviour, so nothing in the
//! pipeline relies on an operator that panics in debug builds and wraps in release:
//! geometry saturates, depth stepping wraps (and is exact modulo 2^32, see
//! [`Scalar::step`]), division and conversion are checked.

use crate::raster::RasterVertex;

/// Signed fixed point with 16 integer and 16 fractional bits (range ±32768, LSB 2^-16).
#[allow(non_camel_case_types)]
pub type Q16_16 = fixed::types::I16F16;

/// The depth plane of one polygon, ready for incremental stepping.
///
/// `z_ref` is the depth at the centre of pixel (`i_ref`, `j_ref`); moving one pixel right adds
/// `dzdx` (the seeds' −A/C), one row down adds `dzdy` (the seeds' −B/C).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthPlane<N> {
    /// Depth at the centre of the reference pixel.
    pub z_ref: N,
    /// Depth change per pixel to the right.
    pub dzdx: N,
    /// Depth change per row down.
    pub dzdy: N,
    /// Reference pixel column.
    pub i_ref: i32,
    /// Reference pixel row.
    pub j_ref: i32,
}

impl<N: Scalar> DepthPlane<N> {
    /// Depth at the centre of pixel (`i`, `j`), with the same bits incremental stepping gives.
    #[inline]
    pub fn at(&self, i: i32, j: i32) -> N {
        self.z_ref
            .step(self.dzdx, i.wrapping_sub(self.i_ref))
            .step(self.dzdy, j.wrapping_sub(self.j_ref))
    }

    /// Depth at the centre of pixel (`i`, `j`) without wrapping ([`Scalar::Unwrapped`]),
    /// extrapolated from pixel `anchor`, where [`Self::at`] must be in range (a sample the
    /// polygon covers): the plane's own value however far from the polygon, so the difference
    /// of two planes is linear everywhere on the screen. Where [`Self::at`] is in range, both
    /// agree.
    #[inline]
    pub fn at_unwrapped(&self, anchor: (i32, i32), i: i32, j: i32) -> N::Unwrapped {
        N::unwrapped(self, anchor, i, j)
    }
}

/// A number format the renderer can compute in.
///
/// Implemented for [`Q16_16`] and `f32`. All methods are total: none panics, whatever the input.
pub trait Scalar: Copy + PartialOrd + Default + core::fmt::Debug + 'static {
    /// Short name used in reports (`"q16.16"`, `"f32"`).
    const NAME: &'static str;
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// The largest value; a depth row is cleared to it (the seeds' "`depth[x]` = 1.0 (max value)").
    const MAX: Self;

    /// Converts from `f32`; `None` for NaN, infinity or a value outside the format's range.
    fn from_f32(v: f32) -> Option<Self>;
    /// Converts to `f32` (for reports and tests; rounding to nearest).
    fn to_f32(self) -> f32;
    /// Converts to `f64`, exactly (both formats fit an `f64`'s 53-bit mantissa).
    fn to_f64(self) -> f64;
    /// Whether the value is a number (always, for fixed point; not NaN or ±∞ for `f32`).
    fn is_finite(self) -> bool;
    /// Saturating addition.
    fn add(self, o: Self) -> Self;
    /// Saturating subtraction.
    fn sub(self, o: Self) -> Self;
    /// Saturating multiplication.
    fn mul(self, o: Self) -> Self;
    /// Division; `None` when dividing by zero or when the quotient is out of range.
    fn div(self, o: Self) -> Option<Self>;
    /// Saturating negation.
    fn neg(self) -> Self {
        Self::ZERO.sub(self)
    }
    /// Square root of a non-negative value (0 for negative input). Exact to the format's
    /// rounding: floor for Q16.16, within 1 ULP for f32.
    fn sqrt(self) -> Self;
    /// Clamps to 0..=1 and scales to 0..=255 (truncating).
    fn to_unit_u8(self) -> u8;

    /// Rounds to the nearest multiple of 2^-`bits` and returns it as an integer count of
    /// sub-pixels (ties round up). `None` if the result does not fit an `i32`.
    /// Monotone: `a <= b` implies `snap(a) <= snap(b)`, so snapping keeps convex polygons
    /// monotone in y.
    fn snap(self, bits: u32) -> Option<i32>;

    /// `self + step * n`, the incremental depth step over `n` pixels or rows.
    ///
    /// For Q16.16 this wraps, so it is exact modulo 2^32: however far a plane is extrapolated
    /// on the way, a depth that is in range at a sample inside the polygon comes out exact,
    /// and stepping one pixel at a time gives the same bits as stepping `n` at once.
    fn step(self, step: Self, n: i32) -> Self;

    /// A plane's depth as [`DepthPlane::at_unwrapped`] gives it, for comparisons only.
    type Unwrapped: PartialOrd + Copy;
    /// The plane's depth at pixel (`i`, `j`) without wrapping, extrapolated from `anchor`.
    /// Q16.16: the raw value in 64 bits, `at(anchor) + dzdx·(i − ai) + dzdy·(j − aj)`, exact
    /// for any two pixels of a screen (offsets below 2^16, steps below 2^31); `plane.z_ref`
    /// itself may have wrapped, its reference pixel lying off the polygon. f32:
    /// [`DepthPlane::at`] (it never wraps).
    fn unwrapped(plane: &DepthPlane<Self>, anchor: (i32, i32), i: i32, j: i32) -> Self::Unwrapped;

    /// `a0 + (a1 − a0) · (bound − c0) / (c1 − c0)`: the value of an attribute `a` where a
    /// coordinate `c` going from `c0` to `c1` crosses `bound` (a clip plane). Computed wide
    /// (Q16.16: 128-bit integers, rounded once), so no intermediate overflows.
    fn lerp_clip(a0: Self, a1: Self, c0: Self, c1: Self, bound: Self) -> Self;

    /// The depth plane through a polygon's snapped vertices (Newell's normal, so a polygon
    /// that snapping made slightly non-planar gets its best-fit plane). `None` for zero area.
    /// The caller passes the vertices in a canonical order ([`crate::raster::setup`] starts at
    /// the top-left vertex, clockwise), so the same polygon gives the same bits whatever order
    /// its vertices came in.
    ///
    /// - Q16.16: referenced at pixel (0, 0) and computed in 128-bit integers, each of `z_ref`,
    ///   `dzdx`, `dzdy` rounded once from the exact plane, so **coplanar polygons get identical
    ///   depth bits** and depth ties are exact ties. `z_ref` wraps (see [`Scalar::step`]).
    ///   Error at pixel (i, j): at most 0.5·(1 + i + j) LSB.
    /// - f32: referenced at the pixel of the first vertex (keeps values small, so little
    ///   cancellation); error a few ULP of the depths and gradients involved.
    fn depth_plane(v: &[RasterVertex<Self>], subpixel_bits: u32) -> Option<DepthPlane<Self>>;
}

/// Rounds `n / d` to nearest, ties away from zero. `d > 0`.
///
/// Divides in 64 bits when both fit (the common case): on a 32-bit core a 128-bit division
/// is a much longer library call. Same result either way.
fn div_round(n: i128, d: i128) -> i128 {
    if let (Ok(n), Ok(d)) = (i64::try_from(n), i64::try_from(d)) {
        if n > i64::MIN / 2 && n < i64::MAX / 2 {
            let q = if n >= 0 {
                (n + d / 2) / d
            } else {
                -((-n + d / 2) / d)
            };
            return q as i128;
        }
    }
    if n >= 0 {
        (n + d / 2) / d
    } else {
        -((-n + d / 2) / d)
    }
}

fn sat_i32(v: i128) -> i32 {
    v.clamp(i32::MIN as i128, i32::MAX as i128) as i32
}

/// Newell's normal of a polygon in (sub-pixel, sub-pixel, depth) units, as exact integers.
fn newell(v: &[(i128, i128, i128)]) -> (i128, i128, i128) {
    let (mut a, mut b, mut c) = (0i128, 0i128, 0i128);
    for (k, &(x0, y0, z0)) in v.iter().enumerate() {
        let (x1, y1, z1) = v[(k + 1) % v.len()];
        a += (y0 - y1) * (z0 + z1);
        b += (z0 - z1) * (x0 + x1);
        c += (x0 - x1) * (y0 + y1);
    }
    (a, b, c)
}

impl Scalar for Q16_16 {
    const NAME: &'static str = "q16.16";
    const ZERO: Self = Q16_16::ZERO;
    const ONE: Self = Q16_16::ONE;
    const MAX: Self = Q16_16::MAX;

    fn from_f32(v: f32) -> Option<Self> {
        Q16_16::checked_from_num(v)
    }
    fn to_f32(self) -> f32 {
        self.to_num::<f32>()
    }
    fn to_f64(self) -> f64 {
        self.to_num::<f64>()
    }
    fn is_finite(self) -> bool {
        true
    }
    fn add(self, o: Self) -> Self {
        self.saturating_add(o)
    }
    fn sub(self, o: Self) -> Self {
        self.saturating_sub(o)
    }
    fn mul(self, o: Self) -> Self {
        self.saturating_mul(o)
    }
    fn div(self, o: Self) -> Option<Self> {
        self.checked_div(o)
    }
    fn sqrt(self) -> Self {
        if self <= Self::ZERO {
            return Self::ZERO;
        }
        // 16.16 → value·2^16; sqrt(value)·2^16 = sqrt(bits·2^16).
        let root = ((self.to_bits() as u64) << 16).isqrt();
        Q16_16::from_bits(root as i32)
    }
    fn to_unit_u8(self) -> u8 {
        let b = self.to_bits().clamp(0, 1 << 16) as u32;
        ((b * 255) >> 16) as u8
    }
    fn snap(self, bits: u32) -> Option<i32> {
        let bits = bits.min(16);
        let shift = 16 - bits;
        if shift == 0 {
            return Some(self.to_bits());
        }
        let raw = self.to_bits() as i64;
        Some(((raw + (1 << (shift - 1))) >> shift) as i32)
    }
    #[inline]
    fn step(self, step: Self, n: i32) -> Self {
        self.wrapping_add(step.wrapping_mul_int(n))
    }
    type Unwrapped = i64;
    #[inline]
    fn unwrapped(p: &DepthPlane<Self>, (ai, aj): (i32, i32), i: i32, j: i32) -> i64 {
        // 32 × 32 → 64-bit products (one SMULL/SMLAL each on a Cortex-M4); the offsets fit
        // 32 bits for any two pixels of a screen.
        let (di, dj) = (i.wrapping_sub(ai) as i64, j.wrapping_sub(aj) as i64);
        let raw = |v: Self| v.to_bits() as i64;
        raw(p.at(ai, aj))
            .wrapping_add(raw(p.dzdx).wrapping_mul(di))
            .wrapping_add(raw(p.dzdy).wrapping_mul(dj))
    }
    fn lerp_clip(a0: Self, a1: Self, c0: Self, c1: Self, bound: Self) -> Self {
        let r = |v: Self| v.to_bits() as i128;
        let (mut num, mut den) = (r(bound) - r(c0), r(c1) - r(c0));
        if den == 0 {
            return a0;
        }
        if den < 0 {
            (num, den) = (-num, -den);
        }
        Q16_16::from_bits(sat_i32(r(a0) + div_round((r(a1) - r(a0)) * num, den)))
    }
    fn depth_plane(v: &[RasterVertex<Self>], subpixel_bits: u32) -> Option<DepthPlane<Self>> {
        let mut pts = [(0i128, 0i128, 0i128); crate::raster::MAX_POLYGON_VERTICES];
        let n = v.len().min(pts.len());
        if n < 3 {
            return None;
        }
        for (p, q) in pts.iter_mut().zip(v) {
            *p = (q.x as i128, q.y as i128, q.z.to_bits() as i128);
        }
        let (a, b, c) = newell(&pts[..n]);
        if c == 0 {
            return None;
        }
        // Normalise so the denominator is positive: the plane is the same.
        let (a, b, c) = if c < 0 { (-a, -b, -c) } else { (a, b, c) };
        let s = subpixel_bits;
        let (x0, y0, z0) = pts[0];
        // Pixel (0, 0)'s centre: z − z0 = −(A·(x − x0) + B·(y − y0)) / C, x and y in
        // sub-pixels, z in raw bits.
        let half = 1i128 << s >> 1;
        let z_ref = z0 + div_round(-(a * (half - x0) + b * (half - y0)), c);
        let dzdx = div_round(-(a << s), c);
        let dzdy = div_round(-(b << s), c);
        let (i_ref, j_ref) = (0, 0);
        Some(DepthPlane {
            // Wraps: exact modulo 2^32, like every later step.
            z_ref: Q16_16::from_bits(z_ref as i32),
            dzdx: Q16_16::from_bits(sat_i32(dzdx)),
            dzdy: Q16_16::from_bits(sat_i32(dzdy)),
            i_ref,
            j_ref,
        })
    }
}

/// Floor of a finite `f32` as `i64` (no `floor` in `core`).
fn floor_f32(t: f32) -> i64 {
    let i = t as i64;
    if (i as f32) > t {
        i - 1
    } else {
        i
    }
}

impl Scalar for f32 {
    const NAME: &'static str = "f32";
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const MAX: Self = f32::MAX;

    fn from_f32(v: f32) -> Option<Self> {
        v.is_finite().then_some(v)
    }
    fn to_f32(self) -> f32 {
        self
    }
    fn to_f64(self) -> f64 {
        self as f64
    }
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    fn add(self, o: Self) -> Self {
        self + o
    }
    fn sub(self, o: Self) -> Self {
        self - o
    }
    fn mul(self, o: Self) -> Self {
        self * o
    }
    fn div(self, o: Self) -> Option<Self> {
        let q = self / o;
        q.is_finite().then_some(q)
    }
    fn sqrt(self) -> Self {
        if self.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) || !self.is_finite() {
            return 0.0;
        }
        // micromath's estimate (up to ~6 % off) refined by three Newton steps (the error
        // squares each step: 6e-2, 2e-3, 2e-6, then rounding) to within 1 ULP.
        let mut r = micromath::F32Ext::sqrt(self);
        for _ in 0..3 {
            r = 0.5 * (r + self / r);
        }
        r
    }
    fn to_unit_u8(self) -> u8 {
        if self.is_nan() {
            return 0;
        }
        (self.clamp(0.0, 1.0) * 255.0) as u8
    }
    fn snap(self, bits: u32) -> Option<i32> {
        if !self.is_finite() {
            return None;
        }
        let t = self * (1u32 << bits.min(16)) as f32;
        if !(-2.0e9..=2.0e9).contains(&t) {
            return None;
        }
        // Above 2^23 every f32 is an integer; below it t + 0.5 is exact or rounds monotonely.
        let r = if t.abs() >= 8_388_608.0 {
            t as i64
        } else {
            floor_f32(t + 0.5)
        };
        Some(r as i32)
    }
    #[inline]
    fn step(self, step: Self, n: i32) -> Self {
        self + step * n as f32
    }
    type Unwrapped = f32;
    #[inline]
    fn unwrapped(p: &DepthPlane<Self>, _anchor: (i32, i32), i: i32, j: i32) -> f32 {
        p.at(i, j)
    }
    fn lerp_clip(a0: Self, a1: Self, c0: Self, c1: Self, bound: Self) -> Self {
        let den = c1 - c0;
        if den == 0.0 || !den.is_finite() {
            return a0;
        }
        a0 + (a1 - a0) * ((bound - c0) / den)
    }
    fn depth_plane(v: &[RasterVertex<Self>], subpixel_bits: u32) -> Option<DepthPlane<Self>> {
        if v.len() < 3 {
            return None;
        }
        let s = subpixel_bits;
        let scale = 1.0 / (1u32 << s) as f32;
        // Work in pixels relative to vertex 0, which keeps the products small.
        let (bx, by, bz) = (v[0].x, v[0].y, v[0].z);
        let rel = |q: &RasterVertex<f32>| {
            (
                (q.x - bx) as f32 * scale,
                (q.y - by) as f32 * scale,
                q.z - bz,
            )
        };
        let (mut a, mut b, mut c) = (0.0f32, 0.0f32, 0.0f32);
        for k in 0..v.len() {
            let (x0, y0, z0) = rel(&v[k]);
            let (x1, y1, z1) = rel(&v[(k + 1) % v.len()]);
            a += (y0 - y1) * (z0 + z1);
            b += (z0 - z1) * (x0 + x1);
        }
        // The area comes from the exact integers, so its sign always agrees with culling.
        let mut area = 0i64;
        for k in 0..v.len() {
            let (p, q) = (&v[k], &v[(k + 1) % v.len()]);
            area += (p.x as i64 - q.x as i64) * (p.y as i64 + q.y as i64);
        }
        if area == 0 {
            return None;
        }
        c += area as f32 * scale * scale;
        let i_ref = bx >> s;
        let j_ref = by >> s;
        let half = 0.5f32;
        let xs = (i_ref as f32 + half) - bx as f32 * scale;
        let ys = (j_ref as f32 + half) - by as f32 * scale;
        const LIMIT: f32 = 1.0e30;
        let dzdx = (-a / c).clamp(-LIMIT, LIMIT);
        let dzdy = (-b / c).clamp(-LIMIT, LIMIT);
        let z_ref = (bz + dzdx * xs + dzdy * ys).clamp(-LIMIT, LIMIT);
        Some(DepthPlane {
            z_ref,
            dzdx,
            dzdy,
            i_ref,
            j_ref,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q16_16_sqrt_is_floor_exact() {
        for bits in [0i32, 1, 2, 1 << 16, 2 << 16, 12345678, i32::MAX] {
            let v = Q16_16::from_bits(bits);
            let r = Scalar::sqrt(v).to_bits() as i64;
            let target = (bits as i64) << 16;
            assert!(
                r * r <= target && (r + 1) * (r + 1) > target,
                "sqrt({bits})"
            );
        }
    }

    #[test]
    fn f32_sqrt_within_one_ulp() {
        const MAX_ERROR_ULP: f32 = 1.0;
        for v in [1.0e-6f32, 0.5, 2.0, 3.0, 1000.0, 12345.678, 1.0e20] {
            let exact = (v as f64).sqrt();
            let got = Scalar::sqrt(v) as f64;
            let ulp = (exact as f32).to_bits();
            let ulp = f32::from_bits(ulp + 1) as f64 - exact as f32 as f64;
            assert!((got - exact).abs() <= MAX_ERROR_ULP as f64 * ulp, "{v}");
        }
    }

    #[test]
    fn snap_rounds_to_nearest_and_is_monotone() {
        let q = |v: f32| Q16_16::from_f32(v).unwrap();
        assert_eq!(q(1.5).snap(4), Some(24));
        assert_eq!(q(-0.03125).snap(4), Some(0)); // -0.5 sub-pixel rounds up
        assert_eq!(1.5f32.snap(4), Some(24));
        assert_eq!((-0.03125f32).snap(4), Some(0));
        assert_eq!(f32::NAN.snap(4), None);
        assert_eq!(1.0e12f32.snap(4), None);
        let mut last = i32::MIN;
        let mut v = -3.0f32;
        while v < 3.0 {
            let s = v.snap(4).unwrap();
            assert!(s >= last);
            last = s;
            v += 0.001;
        }
    }

    #[test]
    fn q16_16_step_is_exact_modulo_wrap() {
        // Extrapolate far outside the range and come back: the result is exact.
        let z = Q16_16::from_num(5);
        let dz = Q16_16::from_num(1000);
        let far = z.step(dz, 100); // 100_005 does not fit: wraps
        assert_eq!(far.step(dz, -100), z);
    }
}
