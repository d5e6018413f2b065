//! Small vector and affine-matrix helpers in any [`Scalar`] format (saturating).

use crate::number::Scalar;

/// Which `f32` routines compute trigonometry (rotations, the field of view), the square
/// roots of lighting and geometry's vertex transforms: the speed–accuracy knob of the presets.
///
/// | routine | [`MathLib::Micromath`] (measured, tests/shading.rs) | [`MathLib::Libm`] |
/// |---|---|---|
/// | sin, cos | abs. error 1.09e-3 on ±2π | ≤ 1 ULP (musl; 3e-8 abs. measured) |
/// | tan | rel. error 1.3 % on \|x\| ≤ 1.4 | ≤ 1 ULP |
/// | sqrt | rel. error 6.1 % on 1e-6..1e6 | [`Scalar::sqrt`]: within 1 ULP |
/// | f32 vertex transform ([`Affine::apply_checked_with`]) | summed plainly: ≤ 3 units of the last place of the largest term | compensated: ≤ 0.5 unit plus about 2^-44 of the largest term |
///
/// Lighting uses reciprocal square roots: [`Scalar::rsqrt`] for [`MathLib::Libm`] (relative
/// error below 2^-18 in fixed point, a few ULP in f32), micromath's `invsqrt` (3.4 %) for
/// [`MathLib::Micromath`].
///
/// Micromath is smaller and, on a Cortex-M without a fast divider, faster; its errors move
/// vertices (trig) and change face intensities (sqrt). [`Scalar::sqrt`] itself is always exact
/// (Q16.16: floor-exact; f32: refined to 1 ULP); `MathLib` picks what lighting uses.
///
/// In the fixed-point formats [`MathLib::Libm`] does not call libm: rotations
/// ([`Affine::rotate_yx_translate_with`]) and the field of view
/// ([`crate::Projection::perspective_with`]) take their sines and cosines from
/// [`crate::number::sin_cos_q31`], integer arithmetic within 2^-30 of the exact values, and
/// round each matrix entry once to the format: at least as exact as libm's `f32` results
/// rounded to the format, and no floating-point library in a fixed-point program (libm's
/// `sinf` computes in `f64`, software on a Cortex-M4F, 6 KB of flash with its argument
/// reduction). Angles must then be below 2^23 radians in magnitude (`None` otherwise).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MathLib {
    /// `micromath` 2.1: fast approximations.
    Micromath,
    /// `libm` 0.2 (a port of musl's libm): exact to about one ULP. Fixed-point formats:
    /// exact integer sines instead (see above).
    #[default]
    Libm,
}

impl MathLib {
    /// Sine of `x` radians.
    pub fn sin(self, x: f32) -> f32 {
        match self {
            MathLib::Micromath => micromath::F32Ext::sin(x),
            MathLib::Libm => libm::sinf(x),
        }
    }
    /// Cosine of `x` radians.
    pub fn cos(self, x: f32) -> f32 {
        match self {
            MathLib::Micromath => micromath::F32Ext::cos(x),
            MathLib::Libm => libm::cosf(x),
        }
    }
    /// Tangent of `x` radians.
    pub fn tan(self, x: f32) -> f32 {
        match self {
            MathLib::Micromath => micromath::F32Ext::tan(x),
            MathLib::Libm => libm::tanf(x),
        }
    }
    /// Square root of `x` in any format, computed in `f32` for [`MathLib::Micromath`] and by
    /// [`Scalar::sqrt`] (exact) for [`MathLib::Libm`]. 0 for `x ≤ 0`.
    pub fn sqrt<N: Scalar>(self, x: N) -> N {
        match self {
            MathLib::Micromath => {
                let v = x.to_f32();
                if v.is_nan() || v <= 0.0 {
                    return N::ZERO;
                }
                N::from_f32(micromath::F32Ext::sqrt(v)).unwrap_or(N::ZERO)
            }
            MathLib::Libm => x.sqrt(),
        }
    }
    /// `1/√x` in any format: micromath's estimate in `f32` for [`MathLib::Micromath`],
    /// [`Scalar::rsqrt`] for [`MathLib::Libm`]. 0 for `x ≤ 0`.
    pub fn rsqrt<N: Scalar>(self, x: N) -> N {
        match self {
            MathLib::Micromath => {
                let v = x.to_f32();
                if v.is_nan() || v <= 0.0 {
                    return N::ZERO;
                }
                N::from_f32(micromath::F32Ext::invsqrt(v)).unwrap_or(N::ZERO)
            }
            MathLib::Libm => x.rsqrt(),
        }
    }
}

/// A 3-vector.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Vec3<N> {
    /// x
    pub x: N,
    /// y
    pub y: N,
    /// z
    pub z: N,
}

impl<N: Scalar> Vec3<N> {
    /// From components.
    pub const fn new(x: N, y: N, z: N) -> Self {
        Vec3 { x, y, z }
    }
    /// From `f32` components; `None` if any is not representable.
    pub fn from_f32(v: [f32; 3]) -> Option<Self> {
        Some(Vec3::new(
            N::from_f32(v[0])?,
            N::from_f32(v[1])?,
            N::from_f32(v[2])?,
        ))
    }
    /// Difference (saturating, like every operation here).
    pub fn minus(self, o: Self) -> Self {
        Vec3::new(self.x.sub(o.x), self.y.sub(o.y), self.z.sub(o.z))
    }
    /// Dot product.
    pub fn dot(self, o: Self) -> N {
        self.x.mul(o.x).add(self.y.mul(o.y)).add(self.z.mul(o.z))
    }
    /// Cross product.
    pub fn cross(self, o: Self) -> Self {
        Vec3::new(
            self.y.mul(o.z).sub(self.z.mul(o.y)),
            self.z.mul(o.x).sub(self.x.mul(o.z)),
            self.x.mul(o.y).sub(self.y.mul(o.x)),
        )
    }
    /// Divides by the largest component magnitude, so the result's components lie in
    /// [−1, 1] and its squared length in [1, 3] (no overflow in later dot products).
    /// `None` for the zero vector.
    pub fn unit_max(self) -> Option<Self> {
        let abs = |v: N| if v < N::ZERO { v.neg() } else { v };
        let mut m = abs(self.x);
        for c in [abs(self.y), abs(self.z)] {
            if c > m {
                m = c;
            }
        }
        if m <= N::ZERO {
            return None;
        }
        Some(Vec3::new(self.x.div(m)?, self.y.div(m)?, self.z.div(m)?))
    }
}

/// An affine transform: a 3×4 matrix (rotation/scale columns and a translation column).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine<N> {
    /// Rows of the matrix; `m[r][3]` is the translation.
    pub m: [[N; 4]; 3],
}

/// An [`Affine`] transform made ready to transform many points ([`Affine::prepare`]).
#[derive(Clone, Copy, Debug)]
pub struct Prepared<'a, N: Scalar> {
    affine: &'a Affine<N>,
    halves: [N::RowHalves; 3],
}

impl<N: Scalar> Prepared<'_, N> {
    /// [`Affine::apply_checked_with`], the same bits.
    #[inline(always)]
    pub fn apply_checked_with(&self, math: MathLib, p: Vec3<N>) -> Option<Vec3<N>> {
        let plain = math == MathLib::Micromath;
        let [x, y, z] = N::affine_halved(&self.affine.m, &self.halves, [p.x, p.y, p.z], plain)?;
        Some(Vec3::new(x, y, z))
    }
}

impl<N: Scalar> Affine<N> {
    /// The identity.
    pub fn identity() -> Self {
        let (o, z) = (N::ONE, N::ZERO);
        Affine {
            m: [[o, z, z, z], [z, o, z, z], [z, z, o, z]],
        }
    }
    /// From `f32` rows; `None` if an entry is not representable.
    pub fn from_f32(m: [[f32; 4]; 3]) -> Option<Self> {
        let mut out = Self::identity();
        for (dst, src) in out.m.iter_mut().zip(&m) {
            for (d, s) in dst.iter_mut().zip(src) {
                *d = N::from_f32(*s)?;
            }
        }
        Some(out)
    }
    /// Rotation about the y axis then the x axis (angles in radians) and a translation:
    /// in f32 with libm's sines and cosines, in fixed point with exact integer ones
    /// ([`MathLib::Libm`]; [`Affine::rotate_yx_translate_with`] picks the maths).
    pub fn rotate_yx_translate(yaw: f32, pitch: f32, t: [f32; 3]) -> Option<Self> {
        Self::rotate_yx_translate_with(MathLib::Libm, yaw, pitch, t)
    }
    /// [`Affine::rotate_yx_translate`] with the sines and cosines from `math`.
    pub fn rotate_yx_translate_with(
        math: MathLib,
        yaw: f32,
        pitch: f32,
        t: [f32; 3],
    ) -> Option<Self> {
        if N::EXACT_STEPS {
            if math == MathLib::Libm {
                return Self::rotate_yx_translate_exact(yaw, pitch, t);
            }
            // Fixed point with micromath: no libm linked into a fixed-point program.
            return Self::rotate_yx_translate_f32(MathLib::Micromath, yaw, pitch, t);
        }
        Self::rotate_yx_translate_f32(math, yaw, pitch, t)
    }
    /// The fixed-point formats' exact rotation: sines and cosines in integers
    /// ([`crate::number::sin_cos_q31`], within 2^-30), each entry (a product of two of them)
    /// formed exactly and rounded once to the format. No floating-point trigonometry: a
    /// fixed-point program that turns its objects this way links no float library.
    fn rotate_yx_translate_exact(yaw: f32, pitch: f32, t: [f32; 3]) -> Option<Self> {
        let (sy, cy) = crate::number::sin_cos_q31(yaw)?;
        let (sp, cp) = crate::number::sin_cos_q31(pitch)?;
        // Products of two 1.31 values: 2.62 fixed point.
        let e = |a: i64, b: i64| N::from_scaled(a * b, 62);
        let one = 1i64 << 31;
        Some(Affine {
            m: [
                [e(cy, one)?, N::ZERO, e(sy, one)?, N::from_f32(t[0])?],
                [e(sp, sy)?, e(cp, one)?, e(-sp, cy)?, N::from_f32(t[1])?],
                [e(-cp, sy)?, e(sp, one)?, e(cp, cy)?, N::from_f32(t[2])?],
            ],
        })
    }
    /// The rotation computed in `f32` with `math`'s sines and cosines, converted.
    fn rotate_yx_translate_f32(math: MathLib, yaw: f32, pitch: f32, t: [f32; 3]) -> Option<Self> {
        let (sy, cy) = (math.sin(yaw), math.cos(yaw));
        let (sp, cp) = (math.sin(pitch), math.cos(pitch));
        // R = Rx(pitch) · Ry(yaw)
        Self::from_f32([
            [cy, 0.0, sy, t[0]],
            [sp * sy, cp, -sp * cy, t[1]],
            [-cp * sy, sp, cp * cy, t[2]],
        ])
    }
    /// Applies to a point. Each coordinate is summed exactly and rounded once
    /// ([`Scalar::affine_row`]: within half a unit of the last place in fixed point, however
    /// large the partial sums; in f32 compensated, the same plus about 2^-44 of the largest
    /// term); a coordinate beyond the format saturates, with the exact
    /// result's sign. [`Affine::apply_checked`] says so instead.
    pub fn apply(&self, p: Vec3<N>) -> Vec3<N> {
        let row = |r: &[N; 4]| N::affine_row_saturating(r, [p.x, p.y, p.z]);
        Vec3::new(row(&self.m[0]), row(&self.m[1]), row(&self.m[2]))
    }
    /// [`Affine::apply`], or `None` if a coordinate of the result does not fit the format (or,
    /// in f32, is not finite).
    pub fn apply_checked(&self, p: Vec3<N>) -> Option<Vec3<N>> {
        self.apply_checked_with(MathLib::Libm, p)
    }
    /// [`Affine::apply_checked`] as accurate as `math` asks: [`MathLib::Libm`] exactly so,
    /// [`MathLib::Micromath`] with f32 rows summed plainly ([`Scalar::affine_row_as`]: within
    /// 3 units of the last place of the largest term, at about a fifth of the cost). Fixed
    /// point sums exactly either way. (Geometry transforms a mesh's vertices with
    /// [`Affine::prepare`], the same results.)
    #[inline]
    pub fn apply_checked_with(&self, math: MathLib, p: Vec3<N>) -> Option<Vec3<N>> {
        self.prepare().apply_checked_with(math, p)
    }
    /// The transform made ready for many points ([`Prepared::apply_checked_with`]: the same
    /// results as [`Affine::apply_checked_with`]; f32 splits its entries for the compensated
    /// sums once here instead of once per point).
    pub fn prepare(&self) -> Prepared<'_, N> {
        Prepared {
            affine: self,
            halves: [0, 1, 2].map(|k| N::row_halves(&self.m[k])),
        }
    }
    /// Applies the linear part only (to a direction).
    pub fn apply_dir(&self, p: Vec3<N>) -> Vec3<N> {
        let row = |r: &[N; 4]| r[0].mul(p.x).add(r[1].mul(p.y)).add(r[2].mul(p.z));
        Vec3::new(row(&self.m[0]), row(&self.m[1]), row(&self.m[2]))
    }
    /// The rotation nearest the linear part (its rows made orthonormal again, Gram–Schmidt in
    /// `f32`, the handedness kept), with the same translation; `None` if the linear part is
    /// degenerate (a zero or repeated row) or an entry does not fit the format.
    ///
    /// Composing rotations rounds every entry each time, so a transform accumulated frame by
    /// frame (`m = step.then_after(&m)`) drifts from a rotation: in Q16.16, 10^4 compositions
    /// stay within 0.01 of one (tested), but Q24.8 cannot hold a small rotation at all (its
    /// entries are multiples of 1/256) and drifts without bound. Call this on the accumulated
    /// transform now and then (every frame is cheap: a few dozen `f32` operations), or
    /// rebuild it from accumulated angles with [`Affine::rotate_yx_translate`].
    pub fn orthonormalized(&self) -> Option<Self> {
        let row = |r: usize| [0, 1, 2].map(|c| self.m[r][c].to_f32());
        let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let unit = |a: [f32; 3]| {
            let n = libm::sqrtf(dot(a, a));
            (n > 0.0 && n.is_finite()).then(|| a.map(|v| v / n))
        };
        let cross = |a: [f32; 3], b: [f32; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let r0 = unit(row(0))?;
        let r1 = row(1);
        let d = dot(r1, r0);
        let r1 = unit([r1[0] - d * r0[0], r1[1] - d * r0[1], r1[2] - d * r0[2]])?;
        let mut r2 = cross(r0, r1);
        if dot(r2, row(2)) < 0.0 {
            r2 = r2.map(|v| -v); // a mirror stays a mirror
        }
        let mut out = Self::from_f32([
            [r0[0], r0[1], r0[2], 0.0],
            [r1[0], r1[1], r1[2], 0.0],
            [r2[0], r2[1], r2[2], 0.0],
        ])?;
        // The translation as it was (not through f32, which could round it).
        for r in 0..3 {
            out.m[r][3] = self.m[r][3];
        }
        Some(out)
    }
    /// `self ∘ o`: applies `o` first. Each entry is summed exactly and rounded once, like
    /// [`Affine::apply`].
    pub fn then_after(&self, o: &Self) -> Self {
        let mut out = Self::identity();
        for r in 0..3 {
            for c in 0..4 {
                let t = if c == 3 { self.m[r][3] } else { N::ZERO };
                let row = [self.m[r][0], self.m[r][1], self.m[r][2], t];
                let col = [o.m[0][c], o.m[1][c], o.m[2][c]];
                out.m[r][c] = N::affine_row_saturating(&row, col);
            }
        }
        out
    }
}
