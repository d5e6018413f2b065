//! Number formats: the [`Scalar`] trait and its three implementations, [`Q16_16`], [`Q24_8`]
//! and `f32`.
//!
//! A renderer is generic over its number format, so a Q16.16 renderer and an f32 renderer can
//! live side by side in one program. The format governs geometry (transform, clipping,
//! projection, lighting) and depth. Coverage never depends on it: vertices are snapped to a
//! sub-pixel grid of integers before any coverage decision (see [`crate::raster`]).
//!
//! The two fixed-point formats are one implementation (`impl_fixed!`) that works on the raw
//! 32-bit value and the type's own fractional bits F:
//!
//! | format | range | LSB | depth 0..256 (model mode) |
//! |---|---|---|---|
//! | [`Q16_16`] | ±32,768 | 2^-16 | 2^24 steps |
//! | [`Q24_8`] | ±8,388,608 | 2^-8 | 2^16 steps |
//!
//! Q24.8 trades precision for range, in geometry as in depth: a depth plane's gradients are
//! rounded to 1/256 per pixel as well, so its error grows 256 times faster across the screen
//! than in Q16.16 (see [`Scalar::depth_plane`]).
//!
//! Every operation a renderer uses is named here with its overflow behaviour, so nothing in the
//! pipeline relies on an operator that panics in debug builds and wraps in release:
//! geometry saturates, depth stepping wraps (and is exact modulo 2^32, see
//! [`Scalar::step`]), division and conversion are checked.

use crate::raster::RasterVertex;

mod div;
pub(crate) use div::divmod_u64_u32;
mod dot2;
mod trig;

pub use trig::{sin_cos_q31, TRIG_LIMIT};

/// Signed fixed point with 16 integer and 16 fractional bits (range ±32768, LSB 2^-16).
#[allow(non_camel_case_types)]
pub type Q16_16 = fixed::types::I16F16;

/// Signed fixed point with 24 integer and 8 fractional bits (range ±8,388,608, LSB 2^-8):
/// a 16-bit-class depth (0..256 in model mode is 65,536 steps) in a 32-bit word, with
/// coordinates to ±8,388,607. Build one as `Q24_8::from_bits(384) // 24.8 fixed point: 1.5`.
#[allow(non_camel_case_types)]
pub type Q24_8 = fixed::types::I24F8;

/// The depth plane of one polygon, ready for incremental stepping.
///
/// `z_ref` is the depth at the centre of pixel (`i_ref`, `j_ref`); moving one pixel right adds
/// `dzdx` (−A/C for the plane Ax + By + Cz + D = 0), one row down adds `dzdy` (−B/C).
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

    /// Its depth at the centre of pixel (0, `j_ref`), the first step of [`Self::at`]: with the
    /// gradients and `j_ref`, all that evaluating the plane needs. Stepped from there by rows
    /// and then by columns it gives the bits of [`Self::at`] in the exact formats at every
    /// pixel, in f32 its value at column 0 (elsewhere one more rounded step: within a few
    /// units of the last place of the terms). The scan-line method's active entries keep only this.
    #[inline]
    pub fn column_0(&self) -> N {
        self.z_ref.step(self.dzdx, 0i32.wrapping_sub(self.i_ref))
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
/// Implemented for [`Q16_16`], [`Q24_8`] and `f32`. All methods are total: none panics,
/// whatever the input.
pub trait Scalar: Copy + PartialOrd + Default + core::fmt::Debug + 'static {
    /// Short name used in reports (`"q16.16"`, `"q24.8"`, `"f32"`).
    const NAME: &'static str;
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// The largest value; a depth row is cleared to it (the farthest depth: nothing drawn).
    const MAX: Self;
    /// Whether [`Scalar::step`] is exact (fixed point: wrapping integer steps equal the plane
    /// bit for bit), so a renderer may step a depth instead of evaluating the plane again.
    const EXACT_STEPS: bool;
    /// The format's resolution (its least significant bit) as an `f32`: 2⁻¹⁶ in Q16.16, 2⁻⁸
    /// in Q24.8, 0 in floating point (whose rounding is relative).
    const LSB: f32;

    /// Converts from `f32`; `None` for NaN, infinity or a value outside the format's range.
    fn from_f32(v: f32) -> Option<Self>;
    /// The format's value nearest `v · 2^-frac` (`frac ≤ 62`; a tie rounds up), or `None` if
    /// it does not fit: how values computed in integers (the sines of [`sin_cos_q31`]) reach
    /// the format.
    fn from_scaled(v: i64, frac: u32) -> Option<Self>;
    /// `v · 2^-shift` for a compact 16-bit position ([`crate::Vectors::Compact`]), in
    /// 32-bit arithmetic: exact when the format has `shift` or more fractional bits, else
    /// rounded to nearest (a tie up). Always fits: a 16-bit integer is below 2^15.
    fn from_compact(v: i16, shift: u32) -> Self;
    /// `v` in the format, saturated at its ends (f32: `v as f32`, exact below 2^24).
    fn from_int(v: i32) -> Self;
    /// The format's value nearest `n / d` for `d > 0`, zero otherwise. Fixed point: rounded
    /// once from the exact quotient, ties away from zero, in integers (a Cortex-M3 links no
    /// floating point for it); f32: the quotient of the two converted to f32.
    fn from_ratio(n: i32, d: i32) -> Self;
    /// Converts to `f32` (for reports and tests; rounding to nearest).
    fn to_f32(self) -> f32;
    /// Converts to `f64`, exactly (every format fits an `f64`'s 53-bit mantissa).
    fn to_f64(self) -> f64;
    /// `self · 2^e` as an integer, where it is one and below 2^62 in magnitude: fixed point
    /// with `e` at least its fractional bits, in integer arithmetic. `None` otherwise (always
    /// in floating point), for the caller to take `f64`'s way: where this answers,
    /// `self.to_f64() · 2^e` is the same integer.
    #[doc(hidden)]
    fn scaled_exact(self, e: i32) -> Option<i64> {
        let _ = e;
        None
    }
    /// Whether the value is a number (always, for fixed point; not NaN or ±∞ for `f32`).
    fn is_finite(self) -> bool;
    /// Saturating addition.
    fn add(self, o: Self) -> Self;
    /// Saturating subtraction.
    fn sub(self, o: Self) -> Self;
    /// Multiplication, rounded to nearest (fixed point: within half a unit of the last place;
    /// ties round up) and saturating.
    fn mul(self, o: Self) -> Self;
    /// Whether `self` lies within `±g·d`: `self.sub(g.mul(d)) <= 0 && self.add(g.mul(d)) >= 0`,
    /// the guard band's test of a clip-space coordinate. Fixed point gives the same answer
    /// without rounding or saturating anything (one product and one comparison).
    #[inline]
    fn within(self, g: Self, d: Self) -> bool {
        let gd = g.mul(d);
        self.sub(gd) <= Self::ZERO && self.add(gd) >= Self::ZERO
    }
    /// Division, rounded to nearest (fixed point: ties away from zero); `None` when dividing by
    /// zero or when the quotient is out of range.
    fn div(self, o: Self) -> Option<Self>;
    /// [`Scalar::div`] inlined into the caller (the same result): for a loop that divides
    /// once a pixel, such as the depth cue's distance (fixed point on a 32-bit core: its
    /// common path, a few hardware divisions, without a call).
    #[inline(always)]
    fn div_inline(self, o: Self) -> Option<Self> {
        self.div(o)
    }
    /// `round(self · k / d)` as an integer: a ratio of two values of the format scaled by an
    /// integer, exact and rounded once (ties away from zero; f32: in f32, then to nearest).
    /// Projection uses it to go from clip space straight to sub-pixels. `None` if `d ≤ 0`, the
    /// result does not fit an `i32`, or an input is not finite.
    fn ratio(self, k: i32, d: Self) -> Option<i32>;
    /// The three quotients of a perspective projection by one divisor `d > 0`:
    /// `(self.ratio(kx, d), y.ratio(ky, d), k.div(d))`, the last only when `k` is given.
    /// Fixed point: `d`'s reciprocal once, then a multiply and a correction each (exact,
    /// the same results). `None` where one of them would be.
    fn project(
        self,
        y: Self,
        d: Self,
        kx: i32,
        ky: i32,
        k: Option<Self>,
    ) -> Option<(i32, i32, Self)> {
        let z = match k {
            Some(k) => k.div(d)?,
            None => Self::ZERO,
        };
        Some((self.ratio(kx, d)?, y.ratio(ky, d)?, z))
    }
    /// `row[0]·p[0] + row[1]·p[1] + row[2]·p[2] + row[3]`: one row of an affine transform.
    /// Fixed point: the products are summed exactly (64-bit and wider) and rounded once, to
    /// nearest, so the result is within half a unit of the last place whatever the partial
    /// sums do. f32: compensated (Ogita, Rump & Oishi's `Dot2`), as if summed in twice the
    /// precision and rounded once: within half a unit of the last place plus about 2^-44 of
    /// the largest term. `None` if the result does not fit the format (or, in f32, is not
    /// finite).
    fn affine_row(row: &[Self; 4], p: [Self; 3]) -> Option<Self>;
    /// [`Scalar::affine_row`], or where the result does not fit, the format's end with the
    /// exact result's sign (±[`Scalar::MAX`]; zero for NaN input). Fixed point decides the
    /// sign in integers, so a fixed-point program links no floating point for it.
    fn affine_row_saturating(row: &[Self; 4], p: [Self; 3]) -> Self;
    /// [`Scalar::affine_row`], or, when `plain`, summed plainly where a few units of the last
    /// place do not matter (lighting, whose result is an 8-bit intensity; transforms under
    /// [`crate::MathLib::Micromath`]). Fixed point ignores `plain` (exact, and as cheap); f32
    /// then takes three products and three sums, each rounded (within 3 units of the last
    /// place of the largest term, 1.96 measured near the format's limits, at about a fifth of
    /// the compensated sum's cost).
    #[inline]
    fn affine_row_as(row: &[Self; 4], p: [Self; 3], plain: bool) -> Option<Self> {
        let _ = plain;
        Self::affine_row(row, p)
    }
    /// What a transform row keeps ready for many points ([`crate::math::Affine::prepare`]):
    /// in f32 the Veltkamp halves of its three linear entries, split once per transform
    /// instead of once per point; fixed point, where its linear entries are small enough to sum
    /// without an overflow check, the sum's start (the translation and the rounding half).
    type RowHalves: Copy + core::fmt::Debug;
    /// [`Scalar::RowHalves`] of `row`.
    fn row_halves(row: &[Self; 4]) -> Self::RowHalves;
    /// [`Scalar::affine_row_as`] with `row`'s [`Scalar::row_halves`] given: the same result.
    fn affine_row_halved(
        row: &[Self; 4],
        halves: &Self::RowHalves,
        p: [Self; 3],
        plain: bool,
    ) -> Option<Self>;
    /// [`Scalar::affine_row_halved`] of the three rows of a transform at one point: the same
    /// results. Fixed point tests once a point whether every row is small, and then sums all
    /// three inline with the point in registers.
    #[inline(always)]
    fn affine_halved(
        m: &[[Self; 4]; 3],
        halves: &[Self::RowHalves; 3],
        p: [Self; 3],
        plain: bool,
    ) -> Option<[Self; 3]> {
        let row = |k: usize| Self::affine_row_halved(&m[k], &halves[k], p, plain);
        Some([row(0)?, row(1)?, row(2)?])
    }
    /// The direction of the face normal `(b − a) × (c − a)`, scaled by a power of two (f32: by
    /// the reciprocal of its largest component) so that its largest component lies in
    /// [1/2, 1]: a direction with the format's full precision, for lighting, without a
    /// division per component. Fixed point: the cross product is exact (64-bit integers).
    /// `None` for a zero normal.
    fn face_normal(a: [Self; 3], b: [Self; 3], c: [Self; 3]) -> Option<[Self; 3]>;
    /// [`Scalar::face_normal`] of three compact positions ([`Scalar::from_compact`] with
    /// `shift`): the same result. Fixed point takes it from the 16-bit integers themselves
    /// where that is exact — the cross product of the converted positions is theirs times a
    /// power of two, which the normalisation takes out — without converting them.
    #[inline]
    fn face_normal_compact(a: [i16; 3], b: [i16; 3], c: [i16; 3], shift: u32) -> Option<[Self; 3]> {
        let f = |p: [i16; 3]| p.map(|v| Self::from_compact(v, shift));
        Self::face_normal(f(a), f(b), f(c))
    }
    /// Saturating negation.
    fn neg(self) -> Self {
        Self::ZERO.sub(self)
    }
    /// Square root of a non-negative value (0 for negative input). Exact to the format's
    /// rounding: floor for fixed point (the root's bits are `isqrt(bits·2^F)`, F the
    /// fractional bits), within 1 ULP for f32.
    fn sqrt(self) -> Self;
    /// `1/√self` for a positive value (0 otherwise). Fixed point: normalised by an even shift,
    /// a 24-entry table guess and two Newton steps (no division), relative error below
    /// 2^-18 before the final rounding; f32: micromath's estimate and two Newton steps, within
    /// a few ULP.
    fn rsqrt(self) -> Self;
    /// Clamps to 0..=1 and scales to 0..=255 (truncating).
    fn to_unit_u8(self) -> u8;
    /// Rounds to the nearest integer (halves up) and clamps to 0..=255: a Gouraud intensity
    /// level ([`crate::scene::IntensityPlane`]); not a number gives 0.
    fn to_level(self) -> u8;

    /// Rounds to the nearest multiple of 2^-`bits` and returns it as an integer count of
    /// sub-pixels (ties round up). `None` if the result does not fit an `i32`.
    /// `bits` is at most the format's fractional bits (8 in Q24.8, 16 otherwise; a larger
    /// value is taken as that many, so the count is then in units of 2^-F); the
    /// configuration allows 1..=8 ([`crate::raster::MAX_SUBPIXEL_BITS`]), exact in every format.
    /// Monotone: `a <= b` implies `snap(a) <= snap(b)`, so snapping keeps convex polygons
    /// monotone in y.
    fn snap(self, bits: u32) -> Option<i32>;

    /// `self + step * n`, the incremental depth step over `n` pixels or rows.
    ///
    /// In fixed point this wraps, so it is exact modulo 2^32 LSB: however far a plane is extrapolated
    /// on the way, a depth that is in range at a sample inside the polygon comes out exact,
    /// and stepping one pixel at a time gives the same bits as stepping `n` at once.
    fn step(self, step: Self, n: i32) -> Self;

    /// A plane's depth as [`DepthPlane::at_unwrapped`] gives it, for comparisons only.
    type Unwrapped: PartialOrd + Copy;
    /// The plane's depth at pixel (`i`, `j`) without wrapping, extrapolated from `anchor`.
    /// Fixed point: the raw value in 64 bits, `at(anchor) + dzdx·(i − ai) + dzdy·(j − aj)`, exact
    /// for any two pixels of a screen (offsets below 2^16, steps below 2^31); `plane.z_ref`
    /// itself may have wrapped, its reference pixel lying off the polygon. f32:
    /// [`DepthPlane::at`] (it never wraps).
    fn unwrapped(plane: &DepthPlane<Self>, anchor: (i32, i32), i: i32, j: i32) -> Self::Unwrapped;

    /// `a0 + (a1 − a0) · (bound − c0) / (c1 − c0)`: the value of an attribute `a` where a
    /// coordinate `c` going from `c0` to `c1` crosses `bound` (a clip plane). Computed wide
    /// (fixed point: 128-bit integers, rounded once), so no intermediate overflows.
    fn lerp_clip(a0: Self, a1: Self, c0: Self, c1: Self, bound: Self) -> Self;

    /// The depth plane through a polygon's snapped vertices (Newell's normal, so a polygon
    /// that snapping made slightly non-planar gets its best-fit plane). `None` for zero area.
    /// The caller passes the vertices in a canonical order ([`crate::raster::setup`] starts at
    /// the top-left vertex, clockwise), so the same polygon gives the same bits whatever order
    /// its vertices came in.
    ///
    /// - Fixed point (Q16.16, Q24.8): referenced at pixel (0, 0) and computed in 128-bit
    ///   integers, each of `z_ref`, `dzdx`, `dzdy` rounded once from the exact plane, so
    ///   **coplanar polygons get identical depth bits** and depth ties are exact ties. `z_ref`
    ///   wraps (see [`Scalar::step`]). Error at pixel (i, j): at most 0.5·(1 + i + j) LSB —
    ///   in Q24.8 (LSB 1/256) up to 0.94 depth units at the far corner of 240 × 240.
    /// - f32: referenced at the pixel of the first vertex (keeps values small, so little
    ///   cancellation); error a few ULP of the depths and gradients involved.
    ///
    /// Every method decides visibility on this plane; the depth a sink that reads depth is
    /// told comes from [`Scalar::exact_plane`] (within 0.5 LSB).
    fn depth_plane(v: &[RasterVertex<Self>], subpixel_bits: u32) -> Option<DepthPlane<Self>>;

    /// A polygon's plane as exactly as a sink is told its depth ([`Scalar::exact_plane`]).
    type ExactPlane: Copy + core::fmt::Debug;
    /// The plane of [`Scalar::depth_plane`] (the same vertices, in the same canonical order)
    /// held finely enough that [`Scalar::exact_run`] gives each pixel's depth within one unit
    /// of the last place of the exact value: in fixed point 32 more fractional bits, stepped
    /// exactly modulo 2^64 and rounded once (within 0.5 LSB + 2^-20 LSB on any screen); in f32
    /// the plane in f64, rounded once to f32 (within 0.5 ulp and a few 2^-50 of the terms).
    /// Visibility is still decided on [`Scalar::depth_plane`]'s bits, the same in every
    /// method; this is what the depth handed to a sink that reads depth
    /// ([`crate::RowSink::WANTS_DEPTH`]) is evaluated from. `None` for zero area, or (fixed
    /// point) coordinates far beyond the guard band.
    fn exact_plane(v: &[RasterVertex<Self>], subpixel_bits: u32) -> Option<Self::ExactPlane>;
    /// The depths of `plane` at the centres of pixels `x0..` of row `y`, one per element of
    /// `out`.
    fn exact_run(plane: &Self::ExactPlane, x0: i32, y: i32, out: &mut [Self]);
    /// The depth of `plane` at the centre of pixel (`i`, `j`): [`Scalar::exact_run`]'s.
    fn exact_at(plane: &Self::ExactPlane, i: i32, j: i32) -> Self {
        let mut out = [Self::ZERO];
        Self::exact_run(plane, i, j, &mut out);
        out[0]
    }
}

/// A fixed-point [`Scalar::ExactPlane`]: depth in units of 2^-32 of the format's LSB at the
/// centre of pixel (0, 0), and its steps per pixel right and per row down, all exact modulo
/// 2^64 (a depth in range at a covered pixel comes out exact, as in [`Scalar::step`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WidePlane {
    z00: i64,
    dx: i64,
    dy: i64,
}

/// [`WidePlane`] of the polygon `v` (raw depth bits `bits`): Newell's normal in 128-bit
/// integers, as [`plane_i128`], each value rounded once at 2^-32 LSB. `None` for zero area or
/// if a product would not fit 128 bits (coordinates far beyond any guard band).
fn wide_plane<N: Copy>(
    v: &[RasterVertex<N>],
    s: u32,
    bits: impl Fn(N) -> i32,
) -> Option<WidePlane> {
    if v.len() < 3 {
        return None;
    }
    let ((a, b, c), (x0, y0, z0)) = normal_i128(v, bits)?;
    let half = 1i128 << s >> 1;
    let wide = |v: i128| v.checked_mul(1 << 32);
    let num = a
        .checked_mul(half - x0)?
        .checked_add(b.checked_mul(half - y0)?)?;
    let z00 = wide(z0)?.checked_add(div_round(wide(num)?.checked_neg()?, c))?;
    let dx = div_round(wide(a.checked_mul(1 << s)?)?.checked_neg()?, c);
    let dy = div_round(wide(b.checked_mul(1 << s)?)?.checked_neg()?, c);
    // Kept modulo 2^64: every later step wraps the same way.
    Some(WidePlane {
        z00: z00 as i64,
        dx: dx as i64,
        dy: dy as i64,
    })
}

/// [`Scalar::exact_run`] in fixed point: raw bits rounded once from a [`WidePlane`].
#[inline]
fn wide_run(p: &WidePlane, x0: i32, y: i32, mut put: impl FnMut(usize, i32), n: usize) {
    let mut z = p
        .z00
        .wrapping_add(p.dx.wrapping_mul(x0 as i64))
        .wrapping_add(p.dy.wrapping_mul(y as i64));
    for k in 0..n {
        put(k, (z.wrapping_add(1 << 31) >> 32) as i32);
        z = z.wrapping_add(p.dx);
    }
}

/// An f32 [`Scalar::ExactPlane`]: the plane in f64, from its first vertex (in pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneF64 {
    z0: f64,
    x0: f64,
    y0: f64,
    gx: f64,
    gy: f64,
}

/// Rounds `n / d` to nearest, ties away from zero. `d > 0`.
///
/// Divides in 64 bits when both fit (the common case; two hardware divisions when `d` fits 32
/// bits, see `div`): on a 32-bit core a 128-bit division is a much longer library call. Same
/// result either way. Out of line: only cold paths call it (the 128-bit depth plane three times,
/// fixed-point clipping's interpolation once), so flash holds one copy instead of four.
#[inline(never)]
fn div_round(n: i128, d: i128) -> i128 {
    if let (Ok(n), Ok(d)) = (i64::try_from(n), i64::try_from(d)) {
        if n > i64::MIN / 2 && n < i64::MAX / 2 {
            return div::div_round(n, d) as i128;
        }
    }
    let q = udiv_u128(n.unsigned_abs().saturating_add(d as u128 >> 1), d as u128) as i128;
    if n >= 0 {
        q
    } else {
        -q
    }
}

/// `n / d` (floor) for `d > 0`, one quotient bit a step. Only the cold 128-bit paths divide
/// in 128 bits (degenerate or off-screen polygons, far beyond the screen): the library's
/// 128-bit division is about 2 KB of flash on a 32-bit core, this is a tenth of it, at up to
/// 128 short steps a division.
#[inline(never)]
#[cold]
fn udiv_u128(n: u128, d: u128) -> u128 {
    // (A zero divisor never comes here; answered with 0 rather than a panic.)
    if n < d || d == 0 {
        return 0;
    }
    let shift = d.leading_zeros() - n.leading_zeros();
    let (mut r, mut q) = (n, 0u128);
    let mut sub = d << shift;
    for _ in 0..=shift {
        q <<= 1;
        if r >= sub {
            r -= sub;
            q |= 1;
        }
        sub >>= 1;
    }
    q
}

/// `v · 2^-shift` as an `f32` built from its bits in integer instructions, for cores without
/// an FPU: exact for `|v| < 2^24` (24 significant bits at most) and `shift ≤ 126`.
#[inline]
fn f32_from_int_bits(v: i32, shift: u32) -> f32 {
    if v == 0 {
        return 0.0;
    }
    let m = v.unsigned_abs();
    let top = 31 - m.leading_zeros(); // 0..=23
                                      // shift ≤ 126: the exponent stays at least 1 (normal).
    let exp = 127 + top - shift.min(126);
    let sign = if v < 0 { 1 << 31 } else { 0 };
    f32::from_bits(sign | exp << 23 | ((m << (23 - top)) & 0x7f_ffff))
}

/// `a · b` in f32, each product and sum rounded in order.
#[inline]
pub(crate) fn dot3(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a − b` in f32.
#[inline]
pub(crate) fn sub3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a × b` in f32.
#[inline]
pub(crate) fn cross3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `v` as an `f32` for `|v| < 2^24` (exact): the conversion where there is an FPU, else
/// [`f32_from_int_bits`] (on a core without one, `as f32` is a library call; larger values,
/// which no caller passes, are converted).
#[inline]
pub(crate) fn f32_from_small_int(v: i32) -> f32 {
    if cfg!(all(target_arch = "arm", not(target_abi = "eabihf"))) && v.unsigned_abs() < 1 << 24 {
        f32_from_int_bits(v, 0)
    } else {
        v as f32
    }
}

fn sat_i32(v: i128) -> i32 {
    v.clamp(i32::MIN as i128, i32::MAX as i128) as i32
}

/// [`Scalar::affine_row_as`] out of line: a fixed-point transform row with a linear entry of
/// 2^30 or more, rare, kept off the inlined path of [`Scalar::affine_row_halved`].
#[inline(never)]
fn affine_row_general<N: Scalar>(row: &[N; 4], p: [N; 3], plain: bool) -> Option<N> {
    N::affine_row_as(row, p, plain)
}

/// A fixed-point transform row whose linear entries are below 2^30 ([`Scalar::row_halves`]):
/// the three products summed in `i64` from `start` (the translation in product units, plus
/// the rounding half) with no overflow check (each product below 2^61, the translation below
/// 2^47), then shifted — rounded to nearest with the half added first, `(v + 2^(f−1)) >> f`,
/// as `affine_row`'s wider sums round with `((v >> (f − 1)) + 1) >> 1`. `None` if it does
/// not fit.
#[inline(always)]
fn small_row<Frac: fixed::types::extra::LeEqU32>(
    row: &[fixed::FixedI32<Frac>; 4],
    p: [fixed::FixedI32<Frac>; 3],
    start: i64,
) -> Option<fixed::FixedI32<Frac>> {
    let prod = |a: fixed::FixedI32<Frac>, b: fixed::FixedI32<Frac>| {
        a.to_bits() as i64 * b.to_bits() as i64
    };
    let v = start + prod(row[0], p[0]) + prod(row[1], p[1]) + prod(row[2], p[2]);
    let f = fixed::FixedI32::<Frac>::FRAC_NBITS;
    i32::try_from(v >> f).ok().map(fixed::FixedI32::from_bits)
}

/// `v` as an `i32`, saturated: one comparison of the high word in the common case.
#[inline]
fn sat_i64(v: i64) -> i32 {
    let low = v as i32;
    if low as i64 == v {
        low
    } else if v < 0 {
        i32::MIN
    } else {
        i32::MAX
    }
}

/// `1/√t` at the middle of each sixteenth of t ∈ [1/2, 2), in 2.30 fixed point: the first
/// guess of [`rsqrt_bits`] (within 3 %).
const RSQRT_GUESS: [u32; 24] = [
    1473161629, 1393471397, 1325455684, 1266516759, 1214800200, 1168942037, 1127913670, 1090922784,
    1057347856, 1026693558, 998559613, 972618566, 948599586, 926276469, 905458609, 885984104,
    867714429, 850530263, 834328203, 819018128, 804521086, 790767575, 777696137, 765252196,
];

/// `2^45/√m` (`2^30/√t`, `t = m/2^30`) for `m ∈ [2^29, 2^31)`: [`RSQRT_GUESS`] and two Newton
/// steps (see [`rsqrt_bits`]), in the machine's word: [`rsqrt_steps_32`] on a 32-bit core,
/// the same steps in 64-bit words on a 64-bit host (the same bits: tested).
#[inline]
fn rsqrt_steps(m: u32) -> u32 {
    if cfg!(target_pointer_width = "64") {
        rsqrt_steps_64(m)
    } else {
        rsqrt_steps_32(m)
    }
}

/// [`rsqrt_steps`] with every value in 32 bits, so that each product is one 32 × 32 → 64-bit
/// multiply: `r` stays within 3 % of `2^30/√t < 2^30.5`, so `r² / 2^30 < 2^32`, and
/// `tr2 = t·r²/2^30` within 7 % of 2^30, so `3·2^30 − tr2` is positive and below 2^32.
#[inline]
fn rsqrt_steps_32(m: u32) -> u32 {
    let mut r = RSQRT_GUESS[(m >> 26) as usize - 8];
    let mul = |a: u32, b: u32, s: u32| ((a as u64 * b as u64) >> s) as u32;
    for _ in 0..2 {
        let r2 = mul(r, r, 30);
        let tr2 = mul(m, r2, 30);
        r = mul(r, (3u32 << 30).wrapping_sub(tr2), 31);
    }
    r
}

/// [`rsqrt_steps`] in 64-bit words, where nothing can overflow.
#[inline]
fn rsqrt_steps_64(m: u32) -> u32 {
    let mut r = RSQRT_GUESS[(m >> 26) as usize - 8] as u64;
    for _ in 0..2 {
        let tr2 = (m as u64 * ((r * r) >> 30)) >> 30;
        r = (r * ((3u64 << 30).wrapping_sub(tr2))) >> 31;
    }
    r as u32
}

/// The raw bits of `1/√x` for the fixed-point value with raw bits `raw` and `f` (even)
/// fractional bits; 0 for `raw ≤ 0`. `raw` is shifted left by an even amount into
/// `m ∈ [2^29, 2^31)`, so `x = t·2^(30 − f − sh)` with `t = m/2^30 ∈ [1/2, 2)`; `1/√t` starts
/// from [`RSQRT_GUESS`] and takes two Newton steps `r ← r·(3 − t·r²)/2` (3 % → 1.4e-3 →
/// 3e-6), then the power of two is shifted back in, rounded to nearest.
fn rsqrt_bits(raw: i32, f: u32) -> i32 {
    if raw <= 0 {
        return 0;
    }
    let sh = (raw.leading_zeros() - 1) & !1;
    let m = (raw as u32) << sh;
    let r = rsqrt_steps(m);
    // 1/√x = (r/2^30)·2^((f + sh − 30)/2), as raw bits: r·2^((f + sh − 30)/2 + f − 30).
    let shift = (f + sh) as i32 / 2 - 15 + f as i32 - 30;
    if shift >= 0 {
        sat_i64(((r as i64) << shift.min(32)).min(i32::MAX as i64))
    } else {
        // Rounded to nearest in 32 bits (`r < 2^31`): 0 from a shift of 32 on.
        let s = (-shift) as u32;
        match s {
            1..=31 => ((r + (1 << (s - 1))) >> s) as i32,
            _ => 0,
        }
    }
}

/// The fixed-point [`Scalar::face_normal`] of three 16-bit integer positions, as raw bits with
/// `f` fractional bits: the cross product of two edges, exact (edges below 2^16, products
/// below 2^32, components below 2^33), its largest component shifted to `[2^(f−1), 2^f)`.
/// `None` for a zero normal.
#[inline]
fn face_normal_i16(a: [i16; 3], b: [i16; 3], c: [i16; 3], f: u32) -> Option<[i32; 3]> {
    // (Written out, not `array::map`: the Cortex-M4 firmware's build left that a call.)
    let d = |p: &[i16; 3], i: usize| p[i] as i32 - a[i] as i32;
    let e1 = [d(&b, 0), d(&b, 1), d(&b, 2)];
    let e2 = [d(&c, 0), d(&c, 1), d(&c, 2)];
    // Edges in −2^15..2^15 (nearly every model's): each product within 2^30, each component
    // within 2^31 − 2^15, all in 32 bits; the same bits as the 64-bit products below.
    // (All six tested at once: the biased edges OR-ed together stay below 2^16 only if each
    // does.)
    let biased = |v: i32| v.wrapping_add(1 << 15) as u32;
    let any = biased(e1[0]) | biased(e1[1]) | biased(e1[2]);
    if (any | biased(e2[0]) | biased(e2[1]) | biased(e2[2])) < 1 << 16 {
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let m = n[0].unsigned_abs() | n[1].unsigned_abs() | n[2].unsigned_abs();
        if m == 0 {
            return None;
        }
        let shift = (32 - m.leading_zeros()) as i32 - f as i32;
        let out = |v: i32| if shift >= 0 { v >> shift } else { v << -shift };
        return Some([out(n[0]), out(n[1]), out(n[2])]);
    }
    let p = |u: i32, v: i32| u as i64 * v as i64;
    let n = [
        p(e1[1], e2[2]) - p(e1[2], e2[1]),
        p(e1[2], e2[0]) - p(e1[0], e2[2]),
        p(e1[0], e2[1]) - p(e1[1], e2[0]),
    ];
    // The highest bit of any component is the largest one's.
    let m = n[0].unsigned_abs() | n[1].unsigned_abs() | n[2].unsigned_abs();
    if m == 0 {
        return None;
    }
    let shift = (64 - m.leading_zeros()) as i32 - f as i32;
    let out = |v: i64| (if shift >= 0 { v >> shift } else { v << -shift }) as i32;
    Some([out(n[0]), out(n[1]), out(n[2])])
}

/// [`plane_i64`]'s three quotients for a divisor `c` below 2^24, as
/// [`div::div_round_small_divisor`] gives them: `round(num / c)`, `round(−sa / c)`,
/// `round(−sb / c)`; `None` if `c` is larger or a quotient does not fit an `i32` (then the
/// reciprocal's, which are the same where these are). Out of line: its callers keep their
/// registers.
#[inline(never)]
fn small_area_plane(num: i64, sa: i64, sb: i64, c: u64) -> Option<(i32, i32, i32)> {
    let c = u32::try_from(c).ok().filter(|&c| c < 1 << 24)?;
    let q = |n: i64| div::div_round_small_divisor(n, c);
    Some((q(num)?, q(-sa)?, q(-sb)?))
}

/// The fixed-point depth plane of [`Scalar::depth_plane`] in 64-bit integers: `Some(None)` for
/// zero area, `Some(Some((z_ref, dzdx, dzdy)))` as raw bits, or `None` when an intermediate does
/// not fit 64 bits (then the 128-bit computation, which gives the same bits, is used). Every
/// polygon of an ordinary screen fits; the divisions are two hardware ones each when the
/// polygon's doubled area in sub-pixels fits 32 bits.
#[allow(clippy::type_complexity)]
fn plane_i64<N: Copy>(
    v: &[RasterVertex<N>],
    s: u32,
    bits: impl Fn(N) -> i32,
) -> Option<Option<(i32, i32, i32)>> {
    let half = 1i64 << s >> 1;
    let small = |p: &RasterVertex<N>| p.x.unsigned_abs() < 1 << 22 && p.y.unsigned_abs() < 1 << 22;
    if let [p0, p1, p2] = v {
        if small(p0) && small(p1) && small(p2) {
            // A triangle on screen: Newell's normal is the cross product of two edges, and
            // with coordinates below 2^22 and depths below 2^32 every product fits 64 bits.
            let d = |p: &RasterVertex<N>| {
                (
                    p.x as i64 - p0.x as i64,
                    p.y as i64 - p0.y as i64,
                    bits(p.z) as i64 - bits(p0.z) as i64,
                )
            };
            let ((x1, y1, z1), (x2, y2, z2)) = (d(p1), d(p2));
            let (a, b, c) = (y1 * z2 - z1 * y2, z1 * x2 - x1 * z2, x1 * y2 - y1 * x2);
            if c == 0 {
                return Some(None);
            }
            let (a, b, c) = if c < 0 { (-a, -b, -c) } else { (a, b, c) };
            if a.unsigned_abs() < 1 << 39 && b.unsigned_abs() < 1 << 39 {
                let num = -(a * (half - p0.x as i64) + b * (half - p0.y as i64));
                // A small triangle (a doubled area below 2^24 sub-pixels², nearly every one of
                // a mesh): three quotients in 8-bit hardware digits, where they fit `i32`.
                if let Some(p) = small_area_plane(num, a << s, b << s, c as u64) {
                    return Some(Some((bits(p0.z).wrapping_add(p.0), p.1, p.2)));
                }
                // Else three quotients by one divisor: its reciprocal once.
                let c = div::Recip::new(c as u64);
                let z_ref = (bits(p0.z) as i64).wrapping_add(c.div_round(num));
                return Some(Some((
                    z_ref as i32,
                    sat_i64(c.div_round(-(a << s))),
                    sat_i64(c.div_round(-(b << s))),
                )));
            }
        }
    }
    let (mut a, mut b, mut c) = (0i64, 0i64, 0i64);
    for (k, p) in v.iter().enumerate() {
        let q = &v[(k + 1) % v.len()];
        let (x0, y0, z0) = (p.x as i64, p.y as i64, bits(p.z) as i64);
        let (x1, y1, z1) = (q.x as i64, q.y as i64, bits(q.z) as i64);
        a = a.checked_add((y0 - y1).checked_mul(z0 + z1)?)?;
        b = b.checked_add((z0 - z1).checked_mul(x0 + x1)?)?;
        c = c.checked_add((x0 - x1).checked_mul(y0 + y1)?)?;
    }
    if c == 0 {
        return Some(None);
    }
    let (a, b, c) = if c < 0 { (-a, -b, -c) } else { (a, b, c) };
    let (x0, y0, z0) = (v[0].x as i64, v[0].y as i64, bits(v[0].z) as i64);
    let num = a
        .checked_mul(half - x0)?
        .checked_add(b.checked_mul(half - y0)?)?
        .checked_neg()?;
    let (ax, by) = (a.checked_mul(1 << s)?, b.checked_mul(1 << s)?);
    // Halved bounds keep div_round's rounding step from overflowing.
    let fits = |v: i64| v > i64::MIN / 2 && v < i64::MAX / 2;
    if !(fits(num) && fits(ax) && fits(by)) {
        return None;
    }
    let c = div::Recip::new(c as u64);
    let z_ref = z0.wrapping_add(c.div_round(num));
    Some(Some((
        z_ref as i32, // wraps: exact modulo 2^32, like every later step
        sat_i64(c.div_round(-ax)),
        sat_i64(c.div_round(-by)),
    )))
}

/// The fixed-point depth plane of [`Scalar::depth_plane`] in 128-bit integers (any input):
/// `(z_ref, dzdx, dzdy)` as raw bits, or `None` for zero area. Out of line and cold: it runs
/// only when [`plane_i64`] does not fit, and its 128-bit temporaries (244 bytes of stack on the
/// Cortex-M3 firmware, 324 on the Cortex-M4's) then stay out of every caller's frame.
#[inline(never)]
#[cold]
fn plane_i128<N: Copy>(
    v: &[RasterVertex<N>],
    s: u32,
    bits: impl Fn(N) -> i32,
) -> Option<(i32, i32, i32)> {
    let ((a, b, c), (x0, y0, z0)) = normal_i128(v, bits)?;
    // Pixel (0, 0)'s centre: z − z0 = −(A·(x − x0) + B·(y − y0)) / C, x and y in sub-pixels,
    // z in raw bits (the format's LSB).
    let half = 1i128 << s >> 1;
    let z_ref = z0 + div_round(-(a * (half - x0) + b * (half - y0)), c);
    Some((
        z_ref as i32, // wraps: exact modulo 2^32, like every later step
        sat_i32(div_round(-(a << s), c)),
        sat_i32(div_round(-(b << s), c)),
    ))
}

/// Three 128-bit integers: a normal or a point.
type I128x3 = (i128, i128, i128);

/// Newell's normal `(A, B, C)` of the polygon `v` (raw depth bits `bits`) with `C > 0` (the
/// same plane), and its first vertex, in 128-bit integers; `None` for zero area. Each corner is
/// widened where it is read, not gathered first: a gathered copy of the largest polygon's
/// corners is 864 bytes of stack, on the path of every frame that needs a 128-bit plane.
fn normal_i128<N: Copy>(
    v: &[RasterVertex<N>],
    bits: impl Fn(N) -> i32,
) -> Option<(I128x3, I128x3)> {
    let v = &v[..v.len().min(crate::raster::MAX_POLYGON_VERTICES)];
    let wide = |q: &RasterVertex<N>| (q.x as i128, q.y as i128, bits(q.z) as i128);
    let (a, b, c) = newell(v.len(), |k| wide(&v[k]));
    if c == 0 {
        return None;
    }
    let normal = if c < 0 { (-a, -b, -c) } else { (a, b, c) };
    Some((normal, wide(v.first()?)))
}

/// Newell's normal of the polygon of `n` corners `corner(0..n)` in (sub-pixel, sub-pixel,
/// depth) units, as exact integers.
fn newell(n: usize, corner: impl Fn(usize) -> I128x3) -> I128x3 {
    let (mut a, mut b, mut c) = (0i128, 0i128, 0i128);
    for k in 0..n {
        let ((x0, y0, z0), (x1, y1, z1)) = (corner(k), corner((k + 1) % n));
        a += (y0 - y1) * (z0 + z1);
        b += (z0 - z1) * (x0 + x1);
        c += (x0 - x1) * (y0 + y1);
    }
    (a, b, c)
}

/// One implementation for every signed 32-bit fixed-point format: `$t` is the type (a
/// `fixed::FixedI32`), `$name` its report name. Everything works on the raw bits, scaled by
/// the type's own fractional bits (`F = $t::FRAC_NBITS`), so Q16.16 and Q24.8 share each line.
macro_rules! impl_fixed {
    ($t:ident, $name:literal) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const ZERO: Self = $t::ZERO;
            const ONE: Self = $t::ONE;
            const MAX: Self = $t::MAX;
            const EXACT_STEPS: bool = true;
            const LSB: f32 = 1.0 / (1u32 << $t::FRAC_NBITS) as f32;

            fn from_f32(v: f32) -> Option<Self> {
                $t::checked_from_num(v)
            }
            #[inline]
            fn from_int(v: i32) -> Self {
                $t::from_bits(sat_i64((v as i64) << $t::FRAC_NBITS))
            }
            #[inline]
            fn from_ratio(n: i32, d: i32) -> Self {
                if d <= 0 {
                    return $t::ZERO;
                }
                // (A 32-bit core, a denominator below 2^24: in hardware digits, the same bits.)
                if cfg!(target_pointer_width = "32") {
                    if let Some(q) = div::div_round_shifted_signed(n, $t::FRAC_NBITS, d) {
                        return $t::from_bits(q);
                    }
                }
                $t::from_bits(sat_i64(div::div_round(
                    (n as i64) << $t::FRAC_NBITS,
                    d as i64,
                )))
            }
            #[inline]
            fn from_compact(v: i16, shift: u32) -> Self {
                let f = $t::FRAC_NBITS;
                $t::from_bits(if shift <= f {
                    // |v| ≤ 2^15 and f − shift ≤ 16: fits 32 bits (−2^31 included).
                    (v as i32) << (f - shift)
                } else {
                    ((v as i32 >> (shift - f - 1).min(16)) + 1) >> 1
                })
            }
            fn from_scaled(v: i64, frac: u32) -> Option<Self> {
                let f = $t::FRAC_NBITS;
                let raw = if frac > f {
                    (v >> (frac - f - 1).min(63)).checked_add(1)? >> 1
                } else {
                    v.checked_mul(1 << (f - frac))?
                };
                i32::try_from(raw).ok().map($t::from_bits)
            }
            fn to_f32(self) -> f32 {
                self.to_num::<f32>()
            }
            fn to_f64(self) -> f64 {
                self.to_num::<f64>()
            }
            #[inline]
            fn scaled_exact(self, e: i32) -> Option<i64> {
                let k = e.checked_sub($t::FRAC_NBITS as i32)?;
                if !(0..=62).contains(&k) {
                    return None;
                }
                let v = (self.to_bits() as i64).checked_mul(1 << k)?;
                (v.unsigned_abs() < 1 << 62).then_some(v)
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
            #[inline]
            fn mul(self, o: Self) -> Self {
                let f = $t::FRAC_NBITS;
                let p = self.to_bits() as i64 * o.to_bits() as i64;
                $t::from_bits(sat_i64((p + (1 << (f - 1))) >> f))
            }
            #[inline]
            fn within(self, g: Self, d: Self) -> bool {
                // With q = ⌊Q/2^f⌋, Q = g·d + 2^(f−1) (`mul` before it saturates): saturating
                // keeps signs, so the default's test is −sat(q) ≤ x ≤ sat(q); for x ≠ MIN that
                // is |x| ≤ q, that is |x|·2^f ≤ Q, and for x = MIN it fails (−x > MAX).
                let f = $t::FRAC_NBITS;
                let q = g.to_bits() as i64 * d.to_bits() as i64 + (1 << (f - 1));
                let x = self.to_bits();
                x != i32::MIN && ((x.unsigned_abs() as i64) << f) <= q
            }
            #[inline]
            fn div(self, o: Self) -> Option<Self> {
                div::div_fixed(self.to_bits(), $t::FRAC_NBITS, o.to_bits()).map($t::from_bits)
            }
            #[inline(always)]
            fn div_inline(self, o: Self) -> Option<Self> {
                div::div_fixed_inline(self.to_bits(), $t::FRAC_NBITS, o.to_bits())
                    .map($t::from_bits)
            }
            #[inline]
            fn ratio(self, k: i32, d: Self) -> Option<i32> {
                let d = d.to_bits();
                if d <= 0 {
                    return None;
                }
                i32::try_from(div::div_round(self.to_bits() as i64 * k as i64, d as i64)).ok()
            }
            // Inlined into the vertex loop: its call took a fifth of its cost in arguments on
            // the stack and saved registers (the torus frame −8.4 k on the Cortex-M4F, for
            // 432 bytes of the F411 firmware's flash).
            #[inline(always)]
            fn project(
                self,
                y: Self,
                d: Self,
                kx: i32,
                ky: i32,
                k: Option<Self>,
            ) -> Option<(i32, i32, Self)> {
                let d = d.to_bits();
                if d <= 0 {
                    return None;
                }
                // A divisor below 2^24 (most vertices): each quotient in one or two
                // hardware divisions; a larger one, the general division.
                let q = |n: i64| match d < 1 << 24 {
                    true => div::div_round_small_divisor(n, d as u32),
                    false => i32::try_from(div::div_round(n, d as i64)).ok(),
                };
                let (nx, ny) = (
                    self.to_bits() as i64 * kx as i64,
                    y.to_bits() as i64 * ky as i64,
                );
                // Both numerators below 2^32 and both quotients below 2^31 (a vertex in the
                // guard band): one hardware division each and one test for both, the same
                // quotients; else each the way above.
                let (x, y) = match div::div_round_pair(nx, ny, d as u32) {
                    Some(xy) => xy,
                    None => (q(nx)?, q(ny)?),
                };
                let z = match k {
                    // (Below 2^24, the same quotient without 64-bit shifts: the numerator's
                    // low bits are zeros.)
                    Some(k) if d < 1 << 24 => $t::from_bits(div::div_round_shifted(
                        k.to_bits(),
                        $t::FRAC_NBITS,
                        d as u32,
                    )?),
                    Some(k) => $t::from_bits(q((k.to_bits() as i64) << $t::FRAC_NBITS)?),
                    None => Self::ZERO,
                };
                Some((x, y, z))
            }
            /// Where the row's linear entries are all below 2^30 in magnitude, so that the
            /// three products and the translation sum in `i64` with no overflow check (each
            /// product below 2^61, the translation below 2^47), the sum's start: the
            /// translation in product units with the rounding half added. Decided once per
            /// transform instead of once per point.
            type RowHalves = Option<i64>;
            #[inline]
            fn row_halves(row: &[Self; 4]) -> Option<i64> {
                let small = |v: Self| (v.to_bits().wrapping_add(1 << 30) as u32) < 1 << 31;
                let f = $t::FRAC_NBITS;
                (small(row[0]) && small(row[1]) && small(row[2]))
                    .then(|| ((row[3].to_bits() as i64) << f) + (1 << (f - 1)))
            }
            // Inline where the row is small (three multiply-accumulates, a rounding shift);
            // the general sum out of line: inlined whole three times a vertex, it cost a
            // Q16.16 firmware 1.2 KB of flash for 1 % fewer instructions.
            #[inline]
            fn affine_row_halved(
                row: &[Self; 4],
                start: &Option<i64>,
                p: [Self; 3],
                plain: bool,
            ) -> Option<Self> {
                if let Some(t) = *start {
                    return small_row(row, p, t);
                }
                affine_row_general(row, p, plain)
            }
            // One test a point instead of one a row, and the point kept in registers (the
            // general path takes it in memory).
            #[inline(always)]
            fn affine_halved(
                m: &[[Self; 4]; 3],
                start: &[Option<i64>; 3],
                p: [Self; 3],
                plain: bool,
            ) -> Option<[Self; 3]> {
                if let [Some(a), Some(b), Some(c)] = *start {
                    let row = |r: &[Self; 4], t: i64| small_row(r, p, t);
                    return Some([row(&m[0], a)?, row(&m[1], b)?, row(&m[2], c)?]);
                }
                let row = |k: usize| affine_row_general(&m[k], p, plain);
                Some([row(0)?, row(1)?, row(2)?])
            }
            #[inline]
            fn affine_row(row: &[Self; 4], p: [Self; 3]) -> Option<Self> {
                if let Some(t) = Self::row_halves(row) {
                    return small_row(row, p, t);
                }
                let f = $t::FRAC_NBITS;
                let prod = |a: Self, b: Self| a.to_bits() as i64 * b.to_bits() as i64;
                // Each product is below 2^62, so three of them and the translation fit 2^64
                // only just: add in i64 with an overflow check, in i128 when it trips.
                let t = (row[3].to_bits() as i64) << f;
                let sum = prod(row[0], p[0])
                    .checked_add(prod(row[1], p[1]))
                    .and_then(|v| v.checked_add(prod(row[2], p[2])))
                    .and_then(|v| v.checked_add(t));
                let rounded = match sum {
                    Some(v) => (v >> (f - 1)).checked_add(1)? >> 1,
                    None => {
                        let wide = prod(row[0], p[0]) as i128
                            + prod(row[1], p[1]) as i128
                            + prod(row[2], p[2]) as i128
                            + t as i128;
                        i64::try_from(((wide >> (f - 1)) + 1) >> 1).ok()?
                    }
                };
                i32::try_from(rounded).ok().map($t::from_bits)
            }
            fn affine_row_saturating(row: &[Self; 4], p: [Self; 3]) -> Self {
                Self::affine_row(row, p).unwrap_or_else(|| {
                    let wide = |a: Self, b: Self| a.to_bits() as i128 * b.to_bits() as i128;
                    let v = wide(row[0], p[0])
                        + wide(row[1], p[1])
                        + wide(row[2], p[2])
                        + ((row[3].to_bits() as i128) << $t::FRAC_NBITS);
                    match v.signum() {
                        1 => $t::MAX,
                        -1 => -$t::MAX,
                        _ => $t::ZERO,
                    }
                })
            }
            #[inline]
            fn face_normal_compact(
                a: [i16; 3],
                b: [i16; 3],
                c: [i16; 3],
                shift: u32,
            ) -> Option<[Self; 3]> {
                // Converted exactly (`shift` at most F), the positions are these integers
                // times 2^(F − shift), and with F − shift below 14 their edges (below 2^16)
                // stay below 2^30 converted, where `face_normal` is exact (no pre-shift): its
                // result is then the same from the integers themselves.
                let f = $t::FRAC_NBITS;
                if shift <= f && f - shift < 14 {
                    let [x, y, z] = face_normal_i16(a, b, c, f)?;
                    return Some([$t::from_bits(x), $t::from_bits(y), $t::from_bits(z)]);
                }
                let f = |p: [i16; 3]| p.map(|v| Self::from_compact(v, shift));
                Self::face_normal(f(a), f(b), f(c))
            }
            fn face_normal(a: [Self; 3], b: [Self; 3], c: [Self; 3]) -> Option<[Self; 3]> {
                // Edges below 2^15 (a model's edges, nearly always): the cross product fits
                // 32 bits, and so does everything else.
                let d = |p: Self, q: Self| p.to_bits().checked_sub(q.to_bits());
                let small = |v: i32| (v.wrapping_add(1 << 15) as u32) < 1 << 16;
                if let (Some(x1), Some(y1), Some(z1), Some(x2), Some(y2), Some(z2)) = (
                    d(b[0], a[0]),
                    d(b[1], a[1]),
                    d(b[2], a[2]),
                    d(c[0], a[0]),
                    d(c[1], a[1]),
                    d(c[2], a[2]),
                ) {
                    if small(x1) && small(y1) && small(z1) && small(x2) && small(y2) && small(z2) {
                        let n = [y1 * z2 - z1 * y2, z1 * x2 - x1 * z2, x1 * y2 - y1 * x2];
                        let m = n[0].unsigned_abs() | n[1].unsigned_abs() | n[2].unsigned_abs();
                        if m == 0 {
                            return None;
                        }
                        // The largest component to [2^(F−1), 2^F): the highest bit of any
                        // component is the largest one's.
                        let shift = (32 - m.leading_zeros()) as i32 - $t::FRAC_NBITS as i32;
                        return Some(n.map(|v| {
                            $t::from_bits(if shift >= 0 { v >> shift } else { v << -shift })
                        }));
                    }
                }
                let e = |p: [Self; 3]| p.map(|v| v.to_bits() as i64);
                let (a, b, c) = (e(a), e(b), e(c));
                let mut e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                let mut e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
                // Edges below 2^30 keep every product below 2^60 and the cross product exact.
                let big = e1
                    .iter()
                    .chain(&e2)
                    .map(|v| v.unsigned_abs())
                    .max()
                    .unwrap_or(0);
                let pre = (64 - big.leading_zeros()).saturating_sub(30);
                for v in e1.iter_mut().chain(e2.iter_mut()) {
                    *v >>= pre;
                }
                // Below 2^30: 32-bit factors, 64-bit products (one SMULL each).
                let (e1, e2) = (e1.map(|v| v as i32), e2.map(|v| v as i32));
                let p = |a: i32, b: i32| a as i64 * b as i64;
                let n = [
                    p(e1[1], e2[2]) - p(e1[2], e2[1]),
                    p(e1[2], e2[0]) - p(e1[0], e2[2]),
                    p(e1[0], e2[1]) - p(e1[1], e2[0]),
                ];
                let m = n.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0);
                if m == 0 {
                    return None;
                }
                // Largest component to [2^(F−1), 2^F): a shift either way.
                let bits = 64 - m.leading_zeros() as i32;
                let shift = bits - $t::FRAC_NBITS as i32;
                Some(n.map(|v| {
                    let v = if shift >= 0 { v >> shift } else { v << -shift };
                    $t::from_bits(v as i32)
                }))
            }
            fn sqrt(self) -> Self {
                if self <= Self::ZERO {
                    return Self::ZERO;
                }
                // bits = value·2^F; sqrt(value)·2^F = sqrt(bits·2^F). bits < 2^31 and F ≤ 16,
                // so the product fits 47 bits and the root 24: it fits the format.
                let root = ((self.to_bits() as u64) << $t::FRAC_NBITS).isqrt();
                $t::from_bits(root as i32)
            }
            fn rsqrt(self) -> Self {
                $t::from_bits(rsqrt_bits(self.to_bits(), $t::FRAC_NBITS))
            }
            fn to_unit_u8(self) -> u8 {
                let f = $t::FRAC_NBITS;
                let b = self.to_bits().clamp(0, 1 << f) as u32;
                ((b * 255) >> f) as u8
            }
            #[inline]
            fn to_level(self) -> u8 {
                let f = $t::FRAC_NBITS;
                let r = (self.to_bits() as i64 + (1 << (f - 1))) >> f;
                r.clamp(0, 255) as u8
            }
            fn snap(self, bits: u32) -> Option<i32> {
                let bits = bits.min($t::FRAC_NBITS);
                let shift = $t::FRAC_NBITS - bits;
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
                // 32 × 32 → 64-bit products (one SMULL/SMLAL each on a Cortex-M4); the
                // offsets fit 32 bits for any two pixels of a screen.
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
                $t::from_bits(sat_i32(r(a0) + div_round((r(a1) - r(a0)) * num, den)))
            }
            fn depth_plane(
                v: &[RasterVertex<Self>],
                subpixel_bits: u32,
            ) -> Option<DepthPlane<Self>> {
                let n = v.len().min(crate::raster::MAX_POLYGON_VERTICES);
                if n < 3 {
                    return None;
                }
                let bits = |z: Self| z.to_bits();
                let (z_ref, dzdx, dzdy) = match plane_i64(&v[..n], subpixel_bits, bits) {
                    Some(plane) => plane?,
                    None => plane_i128(&v[..n], subpixel_bits, bits)?,
                };
                Some(DepthPlane {
                    z_ref: $t::from_bits(z_ref),
                    dzdx: $t::from_bits(dzdx),
                    dzdy: $t::from_bits(dzdy),
                    i_ref: 0,
                    j_ref: 0,
                })
            }
            type ExactPlane = WidePlane;
            fn exact_plane(v: &[RasterVertex<Self>], subpixel_bits: u32) -> Option<WidePlane> {
                wide_plane(v, subpixel_bits, |z: Self| z.to_bits())
            }
            fn exact_run(p: &WidePlane, x0: i32, y: i32, out: &mut [Self]) {
                let n = out.len();
                wide_run(p, x0, y, |k, b| out[k] = $t::from_bits(b), n);
            }
        }
    };
}

impl_fixed!(Q16_16, "q16.16");
impl_fixed!(Q24_8, "q24.8");

/// Floor of a finite `f32` as `i64` (no `floor` in `core`).
fn floor_f32(t: f32) -> i64 {
    if t.abs() < 2_147_483_648.0 {
        // Within an i32 (every caller's case): the same truncation and rounding as the i64
        // conversions, one FPU instruction each where the 64-bit ones are library calls.
        let i = t as i32;
        return if (i as f32) > t {
            i as i64 - 1
        } else {
            i as i64
        };
    }
    let i = t as i64;
    if (i as f32) > t {
        i - 1
    } else {
        i
    }
}

/// `v` rounded to the nearest `f32`, as `v as f32` does, through the FPU's 32-bit conversion
/// when `v` fits an `i32` (the 64-bit one is a library call).
fn i64_to_f32(v: i64) -> f32 {
    match i32::try_from(v) {
        Ok(v) => v as f32,
        Err(_) => v as f32,
    }
}

impl Scalar for f32 {
    const NAME: &'static str = "f32";
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const MAX: Self = f32::MAX;
    const EXACT_STEPS: bool = false;
    const LSB: f32 = 0.0;

    fn from_f32(v: f32) -> Option<Self> {
        v.is_finite().then_some(v)
    }
    #[inline]
    fn from_int(v: i32) -> Self {
        v as f32
    }
    #[inline]
    fn from_ratio(n: i32, d: i32) -> Self {
        if d > 0 {
            n as f32 / d as f32
        } else {
            0.0
        }
    }
    #[inline]
    fn from_compact(v: i16, shift: u32) -> Self {
        if cfg!(all(target_arch = "arm", not(target_abi = "eabihf"))) {
            // No FPU (a Cortex-M3, say): conversion and multiply would be library calls.
            f32_from_int_bits(v as i32, shift)
        } else {
            v as f32 * f32::from_bits((127 - shift.min(126)) << 23)
        }
    }
    fn from_scaled(v: i64, frac: u32) -> Option<Self> {
        // 2^-frac is a normal f32 for frac ≤ 126: the scaling is exact.
        Some(v as f32 * f32::from_bits((127 - frac.min(126)) << 23))
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
    // Inlined into the projection (twice a vertex): out of line, each call saved and restored
    // an FPU register around 30 instructions of work (Cortex-M4F mesh1k −12.7 k).
    #[inline(always)]
    fn ratio(self, k: i32, d: Self) -> Option<i32> {
        if d.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) {
            return None; // also NaN
        }
        let t = self * k as f32 / d;
        if !(-2.0e9..=2.0e9).contains(&t) {
            return None; // also NaN
        }
        // Above 2^23 every f32 is an integer; below it t + 0.5 is exact or rounds monotonely.
        Some(if t.abs() >= 8_388_608.0 {
            t as i32
        } else {
            floor_f32(t + 0.5) as i32
        })
    }
    fn affine_row(row: &[Self; 4], p: [Self; 3]) -> Option<Self> {
        let v = dot2::affine_row_f32(row, p);
        v.is_finite().then_some(v)
    }
    #[inline]
    fn affine_row_as(row: &[Self; 4], p: [Self; 3], plain: bool) -> Option<Self> {
        if !plain {
            return Self::affine_row(row, p);
        }
        let v = dot2::plain_row_f32(row, p);
        v.is_finite().then_some(v)
    }
    type RowHalves = [(f32, f32); 3];
    #[inline]
    fn row_halves(row: &[Self; 4]) -> Self::RowHalves {
        [0, 1, 2].map(|k| dot2::split(row[k]))
    }
    // Inlined whole into the vertex loop (three rows a point): the point's Veltkamp splits,
    // the same for every row, are then computed once, and no call saves the FPU registers
    // (Cortex-M4F mesh1k −37 k; fixed-point builds keep their own out-of-line path).
    #[inline(always)]
    fn affine_row_halved(
        row: &[Self; 4],
        halves: &Self::RowHalves,
        p: [Self; 3],
        plain: bool,
    ) -> Option<Self> {
        let v = if plain {
            dot2::plain_row_f32(row, p)
        } else {
            dot2::affine_row_halved_f32(row, halves, p)
        };
        v.is_finite().then_some(v)
    }
    fn affine_row_saturating(row: &[Self; 4], p: [Self; 3]) -> Self {
        Self::affine_row(row, p).unwrap_or_else(|| {
            // The sign of the sum in f64 (each product exact, the sum nearly so).
            let w = |a: f32, b: f32| a as f64 * b as f64;
            let v = w(row[0], p[0]) + w(row[1], p[1]) + w(row[2], p[2]) + row[3] as f64;
            if v > 0.0 {
                f32::MAX
            } else if v < 0.0 {
                -f32::MAX
            } else {
                0.0
            }
        })
    }
    #[inline]
    fn face_normal(a: [Self; 3], b: [Self; 3], c: [Self; 3]) -> Option<[Self; 3]> {
        let n = cross3(sub3(b, a), sub3(c, a));
        // `f32::max`'s result (a NaN passed over) by comparisons: on a Cortex-M4F it is a
        // library call (`fmaxf`).
        let max = |a: f32, b: f32| if a.is_nan() || b > a { b } else { a };
        let m = max(max(n[0].abs(), n[1].abs()), n[2].abs());
        if m.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) || !m.is_finite() {
            return None;
        }
        let inv = 1.0 / m;
        Some(n.map(|v| v * inv))
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
    fn rsqrt(self) -> Self {
        if self.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) || !self.is_finite() {
            return 0.0;
        }
        let mut y = micromath::F32Ext::invsqrt(self);
        for _ in 0..2 {
            y *= 1.5 - 0.5 * self * y * y;
        }
        y
    }
    fn to_unit_u8(self) -> u8 {
        if self.is_nan() {
            return 0;
        }
        (self.clamp(0.0, 1.0) * 255.0) as u8
    }
    #[inline]
    fn to_level(self) -> u8 {
        if self.is_nan() {
            return 0;
        }
        // Truncation of a value in 0.5..=255.5 is the floor: round half up.
        (self + 0.5).clamp(0.0, 255.0) as u8
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
        c += i64_to_f32(area) * scale * scale;
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
    type ExactPlane = PlaneF64;
    fn exact_plane(v: &[RasterVertex<Self>], subpixel_bits: u32) -> Option<PlaneF64> {
        if v.len() < 3 {
            return None;
        }
        let scale = 1.0 / (1u32 << subpixel_bits) as f64;
        // In pixels relative to vertex 0: every difference and product is exact in f64 but
        // for depths of very different magnitudes.
        let (bx, by, bz) = (v[0].x, v[0].y, v[0].z as f64);
        let rel = |q: &RasterVertex<f32>| {
            (
                (q.x as i64 - bx as i64) as f64 * scale,
                (q.y as i64 - by as i64) as f64 * scale,
                q.z as f64 - bz,
            )
        };
        let (mut a, mut b, mut c) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..v.len() {
            let (x0, y0, z0) = rel(&v[k]);
            let (x1, y1, z1) = rel(&v[(k + 1) % v.len()]);
            a += (y0 - y1) * (z0 + z1);
            b += (z0 - z1) * (x0 + x1);
            c += (x0 - x1) * (y0 + y1);
        }
        if c == 0.0 || !(a.is_finite() && b.is_finite() && c.is_finite()) {
            return None;
        }
        Some(PlaneF64 {
            z0: bz,
            x0: bx as f64 * scale,
            y0: by as f64 * scale,
            gx: -a / c,
            gy: -b / c,
        })
    }
    fn exact_run(p: &PlaneF64, x0: i32, y: i32, out: &mut [Self]) {
        let v = (y as f64 + 0.5 - p.y0) * p.gy + p.z0;
        for (k, d) in out.iter_mut().enumerate() {
            let u = (x0 as f64 + k as f64 + 0.5 - p.x0) * p.gx;
            *d = (v + u).clamp(-1.0e30, 1.0e30) as f32;
        }
    }
}

/// The tests' fixed-seed generator: Marsaglia's xorshift (13, 7, 17), the new state.
#[cfg(test)]
pub(crate) fn xorshift64(seed: &mut u64) -> u64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    *seed
}

/// [`xorshift64`]'s 32-bit form (13, 17, 5).
#[cfg(test)]
pub(crate) fn xorshift32(seed: &mut u32) -> u32 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 17;
    *seed ^= *seed << 5;
    *seed
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The integer construction of a small integer's f32 against the conversion: every value
    /// below 2^17 in magnitude (differences of 16-bit positions), and around 2^24.
    #[test]
    fn f32_int_bits_equal_the_conversion() {
        let near_end = (1 << 24) - 3..(1 << 24) + 3;
        for v in (-(1 << 17)..=1 << 17)
            .chain(near_end.clone())
            .chain(near_end.map(|v: i32| -v))
        {
            if v.unsigned_abs() < 1 << 24 {
                assert_eq!(
                    f32_from_int_bits(v, 0).to_bits(),
                    (v as f32).to_bits(),
                    "{v}"
                );
            }
            assert_eq!(f32_from_small_int(v).to_bits(), (v as f32).to_bits(), "{v}");
        }
    }

    /// The integer construction of a compact f32 position against the FPU's, every input.
    #[test]
    fn f32_compact_bits_equal_the_conversion() {
        for v in i16::MIN..=i16::MAX {
            for shift in [0, 1, 8, 14, 16, 30, 100, 126, 127, 200] {
                let want = v as f32 * f32::from_bits((127 - shift.min(126)) << 23);
                assert_eq!(
                    f32_from_int_bits(v as i32, shift).to_bits(),
                    want.to_bits(),
                    "{v} {shift}"
                );
            }
        }
    }

    /// The 32-bit shortcuts of `floor_f32` and `i64_to_f32` give the 64-bit conversions'
    /// results: around the i32 limits, the integers and halves, and a fixed xorshift sample.
    #[test]
    fn f32_conversions_through_i32_equal_the_64_bit_ones() {
        let floor_ref = |t: f32| {
            let i = t as i64;
            if (i as f32) > t {
                i - 1
            } else {
                i
            }
        };
        let check = |t: f32| assert_eq!(floor_f32(t), floor_ref(t), "{t}");
        for e in [
            0.0f32,
            0.5,
            1.0,
            8_388_607.5,
            8_388_608.0,
            16_777_217.0,
            2_147_483_520.0,
        ] {
            for t in [
                e,
                -e,
                2_147_483_648.0,
                -2_147_483_648.0,
                3.0e9,
                -3.0e9,
                1.0e-30,
            ] {
                check(t);
                check(f32::from_bits(t.to_bits() + 1));
                check(-f32::from_bits(t.to_bits() + 1));
            }
        }
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..100_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let t = f32::from_bits(s as u32);
            if t.is_finite() && t.abs() < 1.0e12 {
                check(t);
            }
            let v = (s as i64) >> (s >> 58);
            assert_eq!(i64_to_f32(v).to_bits(), (v as f32).to_bits(), "{v}");
        }
        for v in [
            i32::MIN as i64,
            i32::MAX as i64,
            i32::MAX as i64 + 1,
            i32::MIN as i64 - 1,
        ] {
            assert_eq!(i64_to_f32(v).to_bits(), (v as f32).to_bits(), "{v}");
        }
    }

    /// The compact 128-bit division against the library's, on wide operands (a fixed
    /// xorshift sequence) and on the edges.
    #[test]
    fn udiv_u128_matches_the_library() {
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        for _ in 0..20_000 {
            let wide = |a: u64, b: u64, k: u64| ((a as u128) << 64 | b as u128) >> (k % 128);
            let n = wide(next(), next(), next());
            let d = wide(next(), next(), next()).max(1);
            assert_eq!(udiv_u128(n, d), n / d, "{n} / {d}");
            let r = |v: u128| v as i128 >> 2;
            let sign = if next() & 1 == 0 { 1 } else { -1 };
            let (n, d) = (r(n) * sign, r(d).max(1));
            let want = if n >= 0 {
                (n + d / 2) / d
            } else {
                -((-n + d / 2) / d)
            };
            assert_eq!(div_round(n, d), want, "{n} / {d}");
        }
        for (n, d) in [
            (0, 1),
            (1, 1),
            (u128::MAX, 1),
            (u128::MAX, u128::MAX),
            (5, 7),
            (7, 5),
        ] {
            assert_eq!(udiv_u128(n, d), n / d);
        }
        assert_eq!(udiv_u128(u128::MAX, 0), 0);
    }

    /// The same unit tests for every fixed-point format: `$t` and its fractional bits `$f`
    /// (written out, not read from the type, so a wrong shift in `impl_fixed!` shows).
    macro_rules! fixed_tests {
        ($m:ident, $t:ident, $f:literal, $name:literal) => {
            mod $m {
                use super::super::*;

                #[test]
                fn name_and_fraction() {
                    assert_eq!(<$t as Scalar>::NAME, $name);
                    assert_eq!(<$t as Scalar>::ONE.to_bits(), 1 << $f);
                    assert_eq!(
                        <$t as Scalar>::from_f32(0.5).map($t::to_bits),
                        Some(1 << ($f - 1))
                    );
                    // Range: 2^(31 − F); just past it is refused, not wrapped.
                    let top = (1u64 << (31 - $f)) as f32;
                    assert_eq!(<$t as Scalar>::from_f32(top), None);
                    assert_eq!(
                        <$t as Scalar>::from_f32(-top).map($t::to_bits),
                        Some(i32::MIN)
                    );
                    assert_eq!(<$t as Scalar>::from_f32(f32::NAN), None);
                }

                #[test]
                fn from_scaled_rounds_to_nearest() {
                    let s =
                        |v: i64, frac: u32| <$t as Scalar>::from_scaled(v, frac).map($t::to_bits);
                    // 2^-(F+1) is half a unit: rounds up; a hair less rounds down.
                    assert_eq!(s(1, $f + 1), Some(1));
                    assert_eq!(s((1 << 20) - 1, $f + 21), Some(0));
                    assert_eq!(s(-(1 << 20) - 1, $f + 21), Some(-1));
                    assert_eq!(s(-(3 << 40), $f + 41), Some(-1));
                    assert_eq!(s(5, $f), Some(5));
                    assert_eq!(s(5, $f - 1), Some(10));
                    assert_eq!(s(i64::MAX, 62), Some(2 << $f));
                    assert_eq!(s(1 << 31, 0), None);
                    assert_eq!(s(i64::MAX, 0), None);
                    assert_eq!(s(i64::MAX, $f + 1), None);
                    // Compact positions: the same values as from_scaled, every shift.
                    for shift in 0..=40u32 {
                        for v in [0i16, 1, -1, 3, -3, 255, -256, 12345, i16::MAX, i16::MIN] {
                            let want = s(v as i64, shift).unwrap();
                            let got = <$t as Scalar>::from_compact(v, shift).to_bits();
                            assert_eq!(got, want, "{v} at 2^-{shift}");
                        }
                    }
                }

                #[test]
                fn face_normal_compact_equals_the_converted_positions() {
                    // Random triangles of every size (edges up to the whole i16 range, and
                    // degenerate ones), every shift: the same normal as `face_normal` of the
                    // positions `from_compact` gives.
                    let mut seed = 0x2545_f491u32;
                    let mut next = || crate::number::xorshift32(&mut seed);
                    let (mut fast, mut none) = (0, 0);
                    for k in 0..30_000u32 {
                        let bits = 1 + k % 16;
                        let mut p = || {
                            let mut v = [0i16; 3];
                            for c in &mut v {
                                *c = (next() as i16) >> (16 - bits);
                            }
                            v
                        };
                        let (a, b) = (p(), p());
                        let c = match k % 9 {
                            0 => a, // degenerate
                            _ => p(),
                        };
                        let shift = k % 24;
                        let f = |p: [i16; 3]| p.map(|v| <$t as Scalar>::from_compact(v, shift));
                        let want = <$t as Scalar>::face_normal(f(a), f(b), f(c));
                        let got = <$t as Scalar>::face_normal_compact(a, b, c, shift);
                        assert_eq!(got, want, "{a:?} {b:?} {c:?} at 2^-{shift}");
                        fast += (shift <= $f && $f - shift < 14) as u32;
                        none += got.is_none() as u32;
                    }
                    assert!(fast > 5_000 && none > 3_000, "{fast} {none}");
                }

                #[test]
                fn sqrt_is_floor_exact() {
                    for bits in [0i32, 1, 2, 3, 1 << $f, 2 << $f, 4 << $f, 12345678, i32::MAX] {
                        let r = Scalar::sqrt($t::from_bits(bits)).to_bits() as i64;
                        let target = (bits as i64) << $f;
                        assert!(
                            r * r <= target && (r + 1) * (r + 1) > target,
                            "sqrt({bits})"
                        );
                    }
                    assert_eq!(Scalar::sqrt($t::from_num(9)), $t::from_num(3));
                    assert_eq!(Scalar::sqrt($t::from_num(-4)), $t::ZERO);
                }

                #[test]
                fn to_unit_u8_scales_and_clamps() {
                    let u = |v: f32| <$t as Scalar>::from_f32(v).unwrap().to_unit_u8();
                    assert_eq!(u(1.0), 255);
                    assert_eq!(u(0.5), 127);
                    assert_eq!(u(0.0), 0);
                    assert_eq!(u(-3.0), 0);
                    assert_eq!(u(7.0), 255);
                    // One LSB below 1: 255·(1 − 2^-F), truncated.
                    assert_eq!($t::from_bits((1 << $f) - 1).to_unit_u8(), 254);
                }

                #[test]
                fn snap_rounds_to_nearest_ties_up_and_is_monotone() {
                    let q = |v: f32| <$t as Scalar>::from_f32(v).unwrap();
                    assert_eq!(q(1.5).snap(4), Some(24));
                    assert_eq!(q(-0.03125).snap(4), Some(0)); // -0.5 sub-pixel rounds up
                    assert_eq!(q(0.03125).snap(4), Some(1)); // +0.5 sub-pixel rounds up
                    assert_eq!(q(-0.09375).snap(4), Some(-1)); // -1.5 sub-pixels rounds up
                                                               // One LSB under a half sub-pixel rounds down; at 8 bits snapping is exact
                                                               // (the 1/256 grid), in both formats.
                    let lsb = $t::from_bits(1);
                    assert_eq!(q(0.03125).sub(lsb).snap(4), Some(0));
                    assert_eq!(q(-2.75).snap(8), Some(-704));
                    assert_eq!(q(1.0 / 256.0).snap(8), Some(1));
                    // More bits than the format has: the raw value (the `bits.min(F)` rule).
                    assert_eq!(q(1.5).snap($f + 4), Some(3 << ($f - 1)));
                    // The extremes fit an i32 at every grid.
                    for bits in 1..=$f {
                        assert!($t::MIN.snap(bits).is_some() && $t::MAX.snap(bits).is_some());
                    }
                    for bits in [1, 4, 8] {
                        let mut last = i32::MIN;
                        for raw in (-3 << $f)..(3 << $f) {
                            let s = $t::from_bits(raw).snap(bits).unwrap();
                            assert!(s >= last, "snap not monotone at {raw} ({bits} bits)");
                            let exact = raw as f64 / (1u64 << $f) as f64 * (1u64 << bits) as f64;
                            assert!((s as f64 - exact).abs() <= 0.5, "{raw} at {bits} bits");
                            last = s;
                        }
                    }
                }

                #[test]
                fn step_is_exact_modulo_wrap() {
                    // Extrapolate far outside the range and come back: the result is exact.
                    let z = $t::from_num(5);
                    let dz = $t::from_bits(1 << 27); // 2^(27 − F) per step
                    let far = z.step(dz, 100); // 100 · 2^27 does not fit 32 bits: wraps
                    assert_eq!(far.step(dz, -100), z);
                    let mut walked = z;
                    for _ in 0..100 {
                        walked = walked.step(dz, 1);
                    }
                    assert_eq!(walked, far);
                }

                #[test]
                fn depth_plane_is_exact_on_the_grid() {
                    // z = 2 + x/4 − y/8 (x, y in pixels): exact in both formats. Vertices in
                    // 8-bit sub-pixels, listed clockwise on the display.
                    let v = |x: i32, y: i32| RasterVertex {
                        x: x << 8,
                        y: y << 8,
                        z: <$t as Scalar>::from_f32(2.0 + x as f32 / 4.0 - y as f32 / 8.0).unwrap(),
                    };
                    let p = <$t as Scalar>::depth_plane(&[v(0, 0), v(16, 0), v(0, 16)], 8).unwrap();
                    assert_eq!(p.dzdx.to_bits(), 1 << ($f - 2));
                    assert_eq!(p.dzdy.to_bits(), -(1 << ($f - 3)));
                    // At pixel (3, 5)'s centre (3.5, 5.5): 2 + 0.875 − 0.6875.
                    assert_eq!(p.at(3, 5), <$t as Scalar>::from_f32(2.1875).unwrap());
                    assert_eq!(p.at_unwrapped((3, 5), 3, 5), p.at(3, 5).to_bits() as i64);
                }

                #[test]
                fn lerp_clip_rounds_once() {
                    let q = |v: f32| <$t as Scalar>::from_f32(v).unwrap();
                    // a from 0 to 10 while c goes 0 → 4: at c = 1, a = 2.5.
                    assert_eq!(
                        $t::lerp_clip(q(0.0), q(10.0), q(0.0), q(4.0), q(1.0)),
                        q(2.5)
                    );
                    // Descending: a = 10 at c = 4 down to 0 at c = 0; at c = 1, a = 2.5.
                    assert_eq!(
                        $t::lerp_clip(q(10.0), q(0.0), q(4.0), q(0.0), q(1.0)),
                        q(2.5)
                    );
                    assert_eq!(
                        $t::lerp_clip(q(7.0), q(1.0), q(2.0), q(2.0), q(2.0)),
                        q(7.0)
                    );
                }
            }
        };
    }

    fixed_tests!(q16_16, Q16_16, 16, "q16.16");

    #[test]
    fn rsqrt_is_within_its_bound() {
        // Relative error 2^-18 before rounding, plus half a unit of the last place.
        for f in [8u32, 16] {
            let mut raw = 1i64;
            while raw < i32::MAX as i64 / 2 {
                for r in [raw, raw + raw / 3, raw + raw / 7 + 1].map(|r| r as i32) {
                    let x = r as f64 / (1u64 << f) as f64;
                    let want = 1.0 / x.sqrt() * (1u64 << f) as f64;
                    let got = rsqrt_bits(r, f) as f64;
                    assert!(
                        (got - want).abs() <= want * 2f64.powi(-18) + 0.5,
                        "f {f} raw {r}: {got} vs {want}"
                    );
                }
                raw = raw * 5 / 4 + 1;
            }
        }
        assert_eq!(rsqrt_bits(0, 16), 0);
        assert_eq!(rsqrt_bits(-5, 16), 0);
        assert_eq!(rsqrt_bits(4 << 16, 16), 1 << 15); // 1/√4 = 0.5
        let f = Scalar::rsqrt(2.0f32);
        assert!((f - core::f32::consts::FRAC_1_SQRT_2).abs() < 2e-7, "{f}");
    }

    #[test]
    fn rsqrt_steps_in_32_bits_equal_them_in_64() {
        // Every `m` of the range was compared once (2^31 − 2^29 values); here each guess
        // interval's ends and a stride between.
        let ends = (8u32..32).flat_map(|k| [k << 26, (k << 26) + 1, ((k + 1) << 26) - 1]);
        for m in ((1u32 << 29)..(1 << 31)).step_by(997).chain(ends) {
            assert_eq!(rsqrt_steps_32(m), rsqrt_steps_64(m), "m {m}");
        }
    }

    #[test]
    fn scaled_exact_is_the_f64_product_where_it_answers() {
        // Both fixed formats, values of every size and sign, exponents around and beyond
        // their fractional bits: where the integer way answers it is `to_f64() · 2^e`
        // (exact in f64: at most 32 significant bits), and it answers for every exponent
        // from the fractional bits up while the product stays below 2^62.
        fn check<N: Scalar>(bits: i32, frac: i32, e: i32, v: N) {
            let want = v.to_f64() * 2f64.powi(e);
            match v.scaled_exact(e) {
                Some(got) => assert_eq!(got as f64, want, "{bits} · 2^{e}"),
                None => assert!(
                    e < frac || want.abs() >= 2f64.powi(62),
                    "{bits} · 2^{e} declined"
                ),
            }
        }
        let mut seed = 0x5851_f42d_4c95_7f2du64;
        for k in 0..100_000 {
            let bits = (xorshift64(&mut seed) as i32) >> (k % 32);
            let e = k % 70 - 4;
            check(bits, 16, e, Q16_16::from_bits(bits));
            check(bits, 8, e, crate::Q24_8::from_bits(bits));
        }
        assert_eq!(0.5f32.scaled_exact(8), None);
    }

    #[test]
    fn plane_in_64_bits_equals_the_128_bit_one() {
        let mut seed = 0x853c_49e6_748f_ea9bu64;
        let mut next = |m: i64| {
            let seed = crate::number::xorshift64(&mut seed);
            (seed % (2 * m as u64 + 1)) as i64 - m
        };
        let (mut fast, mut planes, mut tiny) = (0, 0, 0);
        for k in 0..60_000 {
            // A mesh's tiny triangles (their quotients in 8-bit digits), small polygons near
            // the screen, large ones across the guard band, and extreme coordinates that push
            // the 64-bit path out.
            let (reach, z) = match k % 4 {
                0 => (1 << 12, 1 << 20),
                1 => (1 << 17, 1 << 24),
                2 => (1 << 9, 1 << 24),
                _ => (1 << 30, 1 << 31),
            };
            let (cx, cy) = (next(1 << 21), next(1 << 21));
            let n = 3 + (next(2).unsigned_abs() as usize);
            let mut v = [RasterVertex::<i32>::default(); 5];
            let c = |v: i64| v.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
            for p in &mut v[..n] {
                *p = RasterVertex {
                    x: c(cx + next(reach)),
                    y: c(cy + next(reach)),
                    z: c(next(z)),
                };
            }
            let v = &v[..n];
            let s = 1 + (next(3) + 3) as u32 % 8;
            let wide = plane_i128(v, s, |z| z);
            if let Some(p) = plane_i64(v, s, |z| z) {
                assert_eq!(p, wide, "{v:?} s {s}");
                fast += 1;
                let area = crate::raster::signed_area2(v).unsigned_abs();
                tiny += (n == 3 && area > 0 && area < 1 << 24) as u32;
            }
            planes += wide.is_some() as u32;
        }
        assert!(
            fast > 30_000 && planes > 40_000 && tiny > 5_000,
            "{fast} fast of {planes}, {tiny} tiny"
        );
    }
    /// [`DepthPlane::column_0`] stepped to row `j`, then to column `i`, equals
    /// [`DepthPlane::at`] bit for bit (f32: in value at column 0, and within 4 units of the
    /// last place elsewhere), for planes of every size, far from their reference pixel too (the
    /// scan-line keeps only the gradients, `column_0` and `j_ref` of a plane).
    fn column_0_steps_to_the_plane<N: Scalar>() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = |m: i32| {
            let seed = crate::number::xorshift64(&mut seed);
            (seed % (2 * m as u64 + 1)) as i32 - m
        };
        let mut planes = 0;
        for k in 0..20_000 {
            let reach = [1 << 8, 1 << 12, 1 << 16][k % 3];
            let (cx, cy) = (next(1 << 14), next(1 << 14));
            let v: [RasterVertex<N>; 3] = core::array::from_fn(|_| RasterVertex {
                x: cx + next(reach),
                y: cy + next(reach),
                z: N::from_f32(next(1 << 14) as f32 / 64.0).unwrap_or(N::ZERO),
            });
            let Some(p) = N::depth_plane(&v, 4) else {
                continue;
            };
            planes += 1;
            let z_col = p.column_0();
            for _ in 0..8 {
                let (i, j) = (next(1 << 11), next(1 << 11));
                for i in [0, i] {
                    let row = z_col.step(p.dzdy, j.wrapping_sub(p.j_ref));
                    let got = row.step(p.dzdx, i);
                    let want = p.at(i, j);
                    // Bit for bit, but in f32 off column 0: there within 4 units of the last
                    // place of the largest term.
                    let tolerance = if N::EXACT_STEPS || i == 0 {
                        0.0
                    } else {
                        let terms = [
                            p.z_ref.to_f64(),
                            p.dzdx.to_f64() * i as f64,
                            p.dzdx.to_f64() * p.i_ref as f64,
                            p.dzdy.to_f64() * (j - p.j_ref) as f64,
                            want.to_f64(),
                        ];
                        4.0 * terms.iter().fold(0.0f64, |m, t| m.max(t.abs())) * f32::EPSILON as f64
                    };
                    let (g, w) = (got.to_f64(), want.to_f64());
                    assert!(
                        g.to_bits() == w.to_bits() || (g - w).abs() <= tolerance,
                        "{} {p:?} at ({i}, {j}): {got:?} != {want:?}",
                        N::NAME
                    );
                }
            }
        }
        assert!(planes > 19_000, "{planes}");
    }

    /// [`Scalar::from_ratio`] in fixed point is `n/d` rounded once to nearest (ties away from
    /// zero), in f32 the f32 quotient; [`Scalar::from_int`] is exact in range and saturates.
    #[test]
    fn from_ratio_and_from_int() {
        fn fixed<N: Scalar>(frac: u32) {
            let mut seed = 0x9e37_79b9_7f4a_7c15u64;
            let mut next = |m: u64| {
                let seed = crate::number::xorshift64(&mut seed);
                seed % m
            };
            for k in 0..100_000 {
                let d = 1 + next([1 << 8, 1 << 22, (1 << 31) - 1][k % 3]) as i64;
                // |n/d| ≤ 1, as a crossing's fraction; both fit an i32.
                let n = (next(2 * d as u64 + 1) as i64 - d) as i32;
                let d = d as i32;
                let exact = (n as f64) * (1u64 << frac) as f64 / d as f64;
                let want = exact.abs().floor() + ((exact.abs().fract() >= 0.5) as u8 as f64);
                let want = want.copysign(exact);
                let got = N::from_ratio(n, d).to_f64() * (1u64 << frac) as f64;
                assert_eq!(got, want, "{} {n}/{d}", N::NAME);
            }
            assert_eq!(N::from_ratio(1, 0), N::ZERO);
            assert_eq!(N::from_ratio(1, -3), N::ZERO);
            assert_eq!(N::from_int(-7).to_f64(), -7.0);
            assert_eq!(N::from_int(i32::MAX), N::MAX);
            assert_eq!(
                N::from_int(i32::MIN).to_f64(),
                -(2f64.powi(31 - frac as i32))
            );
        }
        fixed::<Q16_16>(16);
        fixed::<Q24_8>(8);
        for (n, d) in [(1, 3), (-5, 7), (0, 9), (2_000_001, 3_000_017)] {
            assert_eq!(f32::from_ratio(n, d), n as f32 / d as f32);
        }
        assert_eq!(f32::from_ratio(1, 0), 0.0);
        assert_eq!(f32::from_int(-12), -12.0);
    }

    /// [`Scalar::within`] answers as its definition does (`x − g·d ≤ 0` and `x + g·d ≥ 0`,
    /// each rounded and saturated), at the ends of the range and at random, in every format.
    #[test]
    fn within_is_its_definition() {
        fn check<N: Scalar>(bits: impl Fn(i32) -> N) {
            let mut seed = 0x1234_5678_9abc_def1u64;
            let mut next = || crate::number::xorshift64(&mut seed);
            let edges = [
                i32::MIN,
                i32::MIN + 1,
                -65_537,
                -65_536,
                -1,
                0,
                1,
                2,
                127,
                128,
                65_535,
                65_536,
                65_537,
                i32::MAX - 1,
                i32::MAX,
            ];
            let mut values = [0i32; 75];
            values[..edges.len()].copy_from_slice(&edges);
            for v in &mut values[edges.len()..] {
                let r = next();
                // Every magnitude: shifted down by 0..=31 bits.
                *v = (r as i32) >> ((r >> 32) % 32);
            }
            let mut inside = 0;
            for &x in &values {
                for &g in &values {
                    for &d in &values {
                        let (x, g, d) = (bits(x), bits(g), bits(d));
                        let gd = g.mul(d);
                        let want = x.sub(gd) <= N::ZERO && x.add(gd) >= N::ZERO;
                        assert_eq!(x.within(g, d), want, "{} {x:?} {g:?} {d:?}", N::NAME);
                        inside += want as u32;
                    }
                }
            }
            assert!(inside > 10_000, "{} {inside}", N::NAME);
        }
        check(Q16_16::from_bits);
        check(Q24_8::from_bits);
        check(|v: i32| v as f32 / 65_536.0);
    }

    #[test]
    fn column_0_steps_to_the_plane_in_every_format() {
        column_0_steps_to_the_plane::<Q16_16>();
        column_0_steps_to_the_plane::<Q24_8>();
        column_0_steps_to_the_plane::<f32>();
    }

    fixed_tests!(q24_8, Q24_8, 8, "q24.8");

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

    /// The f32 face normal is the cross product over its largest magnitude, that magnitude
    /// taken as `f32::max` takes it (a NaN passed over), on ordinary, infinite, NaN and zero
    /// corners.
    #[test]
    fn f32_face_normal_scales_by_f32_max() {
        let reference = |a: [f32; 3], b: [f32; 3], c: [f32; 3]| {
            let n = cross3(sub3(b, a), sub3(c, a));
            let m = n[0].abs().max(n[1].abs()).max(n[2].abs());
            (m > 0.0 && m.is_finite()).then(|| n.map(|v| v * (1.0 / m)))
        };
        let values = [
            0.0,
            -0.0,
            1.0,
            -2.5,
            3.0e-20,
            7.0e18,
            f32::INFINITY,
            f32::NAN,
        ];
        let bits = |n: Option<[f32; 3]>| n.map(|n| n.map(f32::to_bits));
        let mut seen_nan = false;
        for (i, &p) in values.iter().enumerate() {
            for &q in &values[i..] {
                let (a, b, c) = ([p, 0.5, 1.0], [1.0, q, -1.0], [2.0, -3.0, 4.0]);
                let got = Scalar::face_normal(a, b, c);
                seen_nan |= got.is_some_and(|n| n.iter().any(|v| v.is_nan()));
                assert_eq!(bits(got), bits(reference(a, b, c)), "{a:?} {b:?} {c:?}");
            }
        }
        assert!(seen_nan, "no case had a NaN component beside a number");
    }

    #[test]
    fn f32_snap_rounds_to_nearest_and_is_monotone() {
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
}
