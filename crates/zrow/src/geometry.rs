//! Geometry: transform, back-face culling, clipping, projection and snapping.
//!
//! - **Model mode** ([`ModelScene`]): vertices go model → view by one affine transform per
//!   object; the seeds' normal-versus-view test drops back faces ([`crate::backface`]); the face
//!   is flat (Lambert) shaded from the directional light. The face normal is the cross product
//!   of the face's first two view-space edges, or, for a mesh with precomputed
//!   [`normals`](crate::scene::Mesh::normals), the given normal taken to view space by the
//!   cofactor matrix of the object's transform (right for any scale or mirror). Depth and
//!   coverage come from the vertices either way; only shading, and the cull decision for a
//!   face seen within rounding of edge-on, can differ; the polygon is clipped in clip space
//!   against the near and far planes (so only w ≥ near > 0 is ever divided by) and a guard band
//!   ([`GUARD_BAND`](crate::raster::GUARD_BAND) pixels round the viewport), then divided and snapped. Depth is
//!   `DEPTH_RANGE · (1 − near/w) · far/(far − near)` under perspective (affine in 1/w, hence
//!   linear in screen space, 0 at the near plane and `DEPTH_RANGE` at the far plane) and linear
//!   in w under an orthographic camera.
//! - **Screen-space mode** ([`ScreenScene`]): vertices are already pixels; polygons are clipped
//!   to the guard band and snapped.
//!
//! Clipping happens before snapping and before any integer conversion, so coordinates of any
//! size (±32767 in Q16.16, ±1e30 in f32) neither overflow nor reach outside the screen.
//! A shared edge is always cut from its inside end, so both neighbours get the same point.

use crate::backface::is_back_face;
use crate::error::Error;
use crate::math::{Affine, Vec3};
use crate::number::Scalar;
use crate::raster::{
    Config, Cull, RasterPolygon, RasterVertex, GUARD_BAND, MAX_FACE_VERTICES, MAX_POLYGON_VERTICES,
};
use crate::scene::{Face, Mesh, MeshIndex, ModelScene, Projection, Scene, ScreenScene};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use heapless::Vec;

/// Depth of the far plane in model mode (the near plane is at 0).
pub const DEPTH_RANGE: f32 = 256.0;

/// How a perspective camera's depth is stored ([`crate::Config::depth`]). Orthographic cameras
/// and screen-space scenes store depth linear in w either way (it is then screen-linear).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DepthMapping {
    /// `DEPTH_RANGE · (1 − near/w) · far/(far − near)`: affine in 1/w, so linear in screen
    /// space along any plane — what the edge walk's linear interpolation assumes. Exact; its
    /// resolution is fine near the eye and coarse far away (Δw ≈ w²·LSB / (`DEPTH_RANGE`·near)).
    #[default]
    InverseW,
    /// `DEPTH_RANGE · (w − near) / (far − near)` at the vertices, interpolated linearly in
    /// screen space ("z-buffering w"): uniform resolution, but w is not linear in screen space,
    /// so depth between the vertices is wrong (too far in the middle of a receding polygon)
    /// and interpenetrating or nearly touching surfaces can swap. Kept to measure that trade.
    LinearW,
}

/// How a frame's stored depth maps back to view distance w: the camera's depth mapping, for
/// stages after visibility ([`crate::shading`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewDepth<N> {
    /// `w = k_near / (k − z)` (perspective, [`DepthMapping::InverseW`]).
    InverseW {
        /// `DEPTH_RANGE · far / (far − near)`.
        k: N,
        /// `k · near`.
        k_near: N,
    },
    /// `w = near + z · per_depth` (orthographic, [`DepthMapping::LinearW`], screen space).
    Linear {
        /// w at depth 0.
        near: N,
        /// Change of w per unit of stored depth.
        per_depth: N,
    },
}

impl<N: Scalar> ViewDepth<N> {
    /// View distance at stored depth `z` (saturating; the far limit where `z` reaches `k`).
    pub fn w(&self, z: N) -> N {
        match *self {
            ViewDepth::InverseW { k, k_near } => k_near.div(k.sub(z)).unwrap_or(N::MAX),
            ViewDepth::Linear { near, per_depth } => near.add(z.mul(per_depth)),
        }
    }
}

type Poly<V> = Vec<V, MAX_POLYGON_VERTICES>;

/// Sutherland–Hodgman against one plane. `cross(inside, outside)` makes the new vertex.
fn clip_plane<V: Copy>(
    poly: &mut Poly<V>,
    inside: impl Fn(&V) -> bool,
    cross: impl Fn(&V, &V) -> V,
    face: u32,
) -> Result<(), Error> {
    if poly.iter().all(&inside) {
        return Ok(());
    }
    let mut out: Poly<V> = Vec::new();
    let n = poly.len();
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        let (ia, ib) = (inside(&a), inside(&b));
        let mut push = |v| out.push(v).map_err(|_| Error::TooManyVertices { face });
        if ia {
            push(a)?;
        }
        if ia && !ib {
            push(cross(&a, &b))?;
        } else if !ia && ib {
            push(cross(&b, &a))?;
        }
    }
    *poly = out;
    Ok(())
}

/// Gathers a face's vertices, checking its size and indices.
fn gather<N: Scalar, I: MeshIndex>(
    mesh: &Mesh<'_, N, I>,
    face: &Face<'_, I>,
    no: u32,
) -> Result<Poly<Vec3<N>>, Error> {
    if face.indices.len() < 3 {
        return Err(Error::TooFewVertices { face: no });
    }
    if face.indices.len() > MAX_FACE_VERTICES {
        return Err(Error::TooManyVertices { face: no });
    }
    let mut out = Vec::new();
    for &i in face.indices {
        let v = *mesh.vertices.get(i.index()).ok_or(Error::IndexOutOfRange {
            face: no,
            index: i.index() as u32,
        })?;
        if !(v.x.is_finite() && v.y.is_finite() && v.z.is_finite()) {
            return Err(Error::NonFinite { face: no });
        }
        let _ = out.push(v); // fits: checked against MAX_FACE_VERTICES above
    }
    Ok(out)
}

fn snap_all<N: Scalar>(
    poly: &Poly<Vec3<N>>,
    cfg: &Config,
    color: Rgb565,
    alpha: u8,
    face: u32,
) -> Result<RasterPolygon<N>, Error> {
    let s = cfg.subpixel_bits as u32;
    let mut vertices = Vec::new();
    for p in poly {
        let x = p.x.snap(s).ok_or(Error::NonFinite { face })?;
        let y = p.y.snap(s).ok_or(Error::NonFinite { face })?;
        let _ = vertices.push(RasterVertex { x, y, z: p.z });
    }
    Ok(RasterPolygon {
        vertices,
        color,
        alpha,
        face,
    })
}

fn num<N: Scalar>(v: i32) -> N {
    // Viewport sizes and guard band are far inside every format's range.
    N::from_f32(v as f32).unwrap_or(N::ZERO)
}

/// Clips a screen-space polygon (x, y in pixels) to the guard band.
fn clip_guard_band<N: Scalar>(
    poly: &mut Poly<Vec3<N>>,
    cfg: &Config,
    face: u32,
) -> Result<(), Error> {
    let lo: N = num(-GUARD_BAND);
    let hx: N = num(cfg.width as i32 + GUARD_BAND);
    let hy: N = num(cfg.height as i32 + GUARD_BAND);
    let at_x = |b: N| {
        move |i: &Vec3<N>, o: &Vec3<N>| {
            Vec3::new(
                b,
                N::lerp_clip(i.y, o.y, i.x, o.x, b),
                N::lerp_clip(i.z, o.z, i.x, o.x, b),
            )
        }
    };
    let at_y = |b: N| {
        move |i: &Vec3<N>, o: &Vec3<N>| {
            Vec3::new(
                N::lerp_clip(i.x, o.x, i.y, o.y, b),
                b,
                N::lerp_clip(i.z, o.z, i.y, o.y, b),
            )
        }
    };
    clip_plane(poly, |v| v.x >= lo, at_x(lo), face)?;
    clip_plane(poly, |v| v.x <= hx, at_x(hx), face)?;
    clip_plane(poly, |v| v.y >= lo, at_y(lo), face)?;
    clip_plane(poly, |v| v.y <= hy, at_y(hy), face)
}

impl<N: Scalar, I: MeshIndex> Scene<N> for ScreenScene<'_, N, I> {
    fn polygons(
        &self,
        cfg: &Config,
        f: &mut dyn FnMut(&RasterPolygon<N>) -> Result<(), Error>,
    ) -> Result<(), Error> {
        self.mesh.check_normals()?;
        for (no, face) in self.mesh.faces.iter().enumerate() {
            let no = no as u32;
            let mut poly = gather(&self.mesh, face, no)?;
            clip_guard_band(&mut poly, cfg, no)?;
            if poly.len() >= 3 {
                f(&snap_all(&poly, cfg, face.color, face.alpha, no)?)?;
            }
        }
        Ok(())
    }

    /// Screen-space depth is the view distance itself.
    fn view_depth(&self, _cfg: &Config) -> Option<ViewDepth<N>> {
        Some(ViewDepth::Linear {
            near: N::ZERO,
            per_depth: N::ONE,
        })
    }
}

/// Scales a colour by an intensity in 0..=1.
pub fn shade<N: Scalar>(c: Rgb565, intensity: N) -> Rgb565 {
    let i = intensity.to_unit_u8() as u16;
    let s = |ch: u8| ((ch as u16 * i + 127) / 255) as u8;
    Rgb565::new(s(c.r()), s(c.g()), s(c.b()))
}

/// The matrix that takes a model-space normal to view space for the transform `mv`: the
/// cofactor matrix of `mv`'s linear part M (`cof(M)·(a × b) = Ma × Mb`, so the normal stays
/// perpendicular to the face and keeps its side under any scale or mirror), computed from M
/// divided by its largest entry magnitude so no product overflows (a positive scale changes no
/// direction). `None` if M is singular.
fn normal_matrix<N: Scalar>(mv: &Affine<N>) -> Option<Affine<N>> {
    let abs = |v: N| if v < N::ZERO { v.neg() } else { v };
    let mut big = N::ZERO;
    for row in &mv.m {
        for &e in &row[..3] {
            if abs(e) > big {
                big = abs(e);
            }
        }
    }
    let mut m = [[N::ZERO; 3]; 3];
    for (dst, src) in m.iter_mut().zip(&mv.m) {
        for (d, &e) in dst.iter_mut().zip(&src[..3]) {
            *d = e.div(big)?;
        }
    }
    let mut out = Affine::identity();
    for (r, row) in out.m.iter_mut().enumerate() {
        for (c, e) in row.iter_mut().take(3).enumerate() {
            // Cofactor (r, c): the 2×2 minor of the rows and columns other than r and c,
            // taken cyclically so the sign comes out right. Every index is `% 3`, inside `m`.
            let (r1, r2, c1, c2) = ((r + 1) % 3, (r + 2) % 3, (c + 1) % 3, (c + 2) % 3);
            *e = m[r1][c1].mul(m[r2][c2]).sub(m[r1][c2].mul(m[r2][c1]));
        }
    }
    Some(out)
}

/// Picks one coordinate of a clip-space vertex.
type Coord<N> = fn(&ClipV<N>) -> N;

/// A clip-space vertex: `x`, `y` scaled by the projection, `w` the distance in front of the eye.
#[derive(Clone, Copy)]
struct ClipV<N> {
    x: N,
    y: N,
    w: N,
}

impl<N: Scalar, I: MeshIndex> Scene<N> for ModelScene<'_, N, I> {
    fn polygons(
        &self,
        cfg: &Config,
        f: &mut dyn FnMut(&RasterPolygon<N>) -> Result<(), Error>,
    ) -> Result<(), Error> {
        let (w_px, h_px) = (cfg.width as f32, cfg.height as f32);
        let (perspective, sx, sy, near, far) = match self.camera.projection {
            Projection::Perspective { focal, near, far } => {
                let aspect = N::from_f32(h_px / w_px).unwrap_or(N::ONE);
                (true, focal.mul(aspect), focal, near, far)
            }
            Projection::Orthographic {
                half_height,
                near,
                far,
            } => {
                let inv = N::ONE.div(half_height).ok_or(Error::BadConfig)?;
                let aspect = N::from_f32(h_px / w_px).unwrap_or(N::ONE);
                (false, inv.mul(aspect), inv, near, far)
            }
        };
        if !(near > N::ZERO && far > near) {
            return Err(Error::BadConfig);
        }
        // Guard band in normalised units: |x/w| <= gx keeps x within GUARD_BAND pixels.
        let gx = N::from_f32(1.0 + 2.0 * GUARD_BAND as f32 / w_px).ok_or(Error::BadConfig)?;
        let gy = N::from_f32(1.0 + 2.0 * GUARD_BAND as f32 / h_px).ok_or(Error::BadConfig)?;
        let (cx, cy): (N, N) = (
            N::from_f32(w_px * 0.5).ok_or(Error::BadConfig)?,
            N::from_f32(h_px * 0.5).ok_or(Error::BadConfig)?,
        );
        let range = N::from_f32(DEPTH_RANGE).ok_or(Error::BadConfig)?;
        let depth_k = range.mul(far.div(far.sub(near)).ok_or(Error::BadConfig)?);
        let depth_lin = range.div(far.sub(near)).ok_or(Error::BadConfig)?;
        let k_near = depth_k.mul(near);
        let light = self.camera.view.apply_dir(self.light.direction).unit_max();
        let linear_w = perspective && cfg.depth == DepthMapping::LinearW;
        let light = light.and_then(|l| {
            let len = cfg.math.sqrt(l.dot(l));
            Some(Vec3::new(l.x.div(len)?, l.y.div(len)?, l.z.div(len)?))
        });
        let minus_one = N::ONE.neg();
        for obj in self.objects {
            obj.mesh.check_normals()?;
        }
        let mut no = 0u32;
        for obj in self.objects {
            let mv = self.camera.view.then_after(&obj.transform);
            let to_view = if obj.mesh.normals.is_empty() {
                None // not needed: every normal comes from the cross product
            } else {
                normal_matrix(&mv)
            };
            for (k, face) in obj.mesh.faces.iter().enumerate() {
                let this = no;
                no += 1;
                let mut poly = gather(obj.mesh, face, this)?;
                for v in poly.iter_mut() {
                    *v = mv.apply(*v);
                }
                let normal = match obj.mesh.normals.get(k) {
                    // Checked above: `normals` is empty or has one entry per face.
                    Some(&n) => to_view.and_then(|m| m.apply_dir(n).unit_max()),
                    None => poly[1]
                        .minus(poly[0])
                        .cross(poly[2].minus(poly[0]))
                        .unit_max(),
                };
                let Some(normal) = normal else {
                    continue; // degenerate face: zero area (or a zero normal)
                };
                if cfg.cull == Cull::Back {
                    let view = if perspective {
                        poly[0]
                    } else {
                        Vec3::new(N::ZERO, N::ZERO, minus_one)
                    };
                    if is_back_face(normal, view) {
                        continue;
                    }
                }
                let lambert = match light {
                    Some(l) => {
                        let d = normal.dot(l);
                        let len = cfg.math.sqrt(normal.dot(normal));
                        if d > N::ZERO {
                            d.div(len).unwrap_or(N::ZERO)
                        } else {
                            N::ZERO
                        }
                    }
                    None => N::ZERO,
                };
                let a = self.light.ambient;
                let color = shade(face.color, a.add(N::ONE.sub(a).mul(lambert)));
                let mut clip: Poly<ClipV<N>> = Vec::new();
                for v in &poly {
                    let _ = clip.push(ClipV {
                        x: v.x.mul(sx),
                        y: v.y.mul(sy),
                        w: v.z.neg(),
                    });
                }
                let lerp = |i: &ClipV<N>, o: &ClipV<N>, ci: N, co: N, b: N| ClipV {
                    x: N::lerp_clip(i.x, o.x, ci, co, b),
                    y: N::lerp_clip(i.y, o.y, ci, co, b),
                    w: N::lerp_clip(i.w, o.w, ci, co, b),
                };
                let d = |v: &ClipV<N>| if perspective { v.w } else { N::ONE };
                clip_plane(
                    &mut clip,
                    |v| v.w >= near,
                    |i, o| lerp(i, o, i.w, o.w, near),
                    this,
                )?;
                clip_plane(
                    &mut clip,
                    |v| v.w <= far,
                    |i, o| lerp(i, o, i.w, o.w, far),
                    this,
                )?;
                // Guard-band planes x = ±g·d, written as c = x ∓ g·d crossing 0.
                let planes: [(Coord<N>, N); 4] = [
                    (|v| v.x, gx),
                    (|v| v.x, gx.neg()),
                    (|v| v.y, gy),
                    (|v| v.y, gy.neg()),
                ];
                for (coord, g) in planes {
                    let c = |v: &ClipV<N>| coord(v).sub(g.mul(d(v)));
                    let inside = |v: &ClipV<N>| {
                        if g > N::ZERO {
                            c(v) <= N::ZERO
                        } else {
                            c(v) >= N::ZERO
                        }
                    };
                    clip_plane(
                        &mut clip,
                        inside,
                        |i, o| lerp(i, o, c(i), c(o), N::ZERO),
                        this,
                    )?;
                }
                if clip.len() < 3 {
                    continue;
                }
                let mut screen: Poly<Vec3<N>> = Vec::new();
                for v in &clip {
                    let (nx, ny, z) = if perspective {
                        let nx = v.x.div(v.w).ok_or(Error::NonFinite { face: this })?;
                        let ny = v.y.div(v.w).ok_or(Error::NonFinite { face: this })?;
                        let z = if linear_w {
                            v.w.sub(near).mul(depth_lin)
                        } else {
                            depth_k.sub(k_near.div(v.w).ok_or(Error::NonFinite { face: this })?)
                        };
                        (nx, ny, z)
                    } else {
                        (v.x, v.y, v.w.sub(near).mul(depth_lin))
                    };
                    let _ = screen.push(Vec3::new(cx.add(nx.mul(cx)), cy.sub(ny.mul(cy)), z));
                }
                f(&snap_all(&screen, cfg, color, face.alpha, this)?)?;
            }
        }
        Ok(())
    }

    /// The inverse of the depth mapping `polygons` applies (same constants, same operations).
    fn view_depth(&self, cfg: &Config) -> Option<ViewDepth<N>> {
        let range = N::from_f32(DEPTH_RANGE)?;
        let (perspective, near, far) = match self.camera.projection {
            Projection::Perspective { near, far, .. } => (true, near, far),
            Projection::Orthographic { near, far, .. } => (false, near, far),
        };
        if !(near > N::ZERO && far > near) {
            return None;
        }
        if perspective && cfg.depth == DepthMapping::InverseW {
            let k = range.mul(far.div(far.sub(near))?);
            Some(ViewDepth::InverseW {
                k,
                k_near: k.mul(near),
            })
        } else {
            Some(ViewDepth::Linear {
                near,
                per_depth: far.sub(near).div(range)?,
            })
        }
    }
}
