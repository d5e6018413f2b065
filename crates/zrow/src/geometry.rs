//! Geometry: transform, projection, back-face culling, clipping and snapping — the stage every
//! method shares.
//!
//! - **Model mode** ([`ModelScene`]): each vertex of an object's mesh goes model → view by one
//!   affine transform per object (summed exactly, rounded once: [`Affine::apply_checked`]),
//!   then to clip space and, when it lies inside the view volume and the guard band
//!   ([`GUARD_BAND`](crate::raster::GUARD_BAND) pixels round the viewport), straight to snapped
//!   sub-pixels — once per vertex per frame, into the renderer's [`VertexBuffer`](crate::scene::VertexBuffer), whatever
//!   number of faces share it. A face whose vertices all made it is then a few index loads:
//!   its **winding on the snapped vertices** decides back-facing (two multiplies, nothing
//!   normalised; zero area counts as back-facing), and only faces that survive are lit: flat
//!   Lambert from the directional light, with the face normal in model space — the cross
//!   product of its first two edges (exact in fixed point), or the mesh's precomputed
//!   [`normals`](crate::scene::Mesh::normals) — taken to view space by the cofactor matrix of
//!   the object's transform (right for any scale or mirror). A face with a vertex outside
//!   takes the clipping path: its corners are transformed again and the polygon is clipped in
//!   clip space against the near and far planes (so only w ≥ near > 0 is ever divided by) and
//!   the guard band, then projected and snapped like the rest. Depth is
//!   `DEPTH_RANGE · (1 − near/w) · far/(far − near)` under perspective (affine in 1/w, hence
//!   linear in screen space, 0 at the near plane and `DEPTH_RANGE` at the far plane) and linear
//!   in w under an orthographic camera.
//! - **Screen-space mode** ([`ScreenScene`]): vertices are already pixels: snapped once each,
//!   and polygons reaching beyond the guard band are clipped to it.
//!
//! Projection goes from clip space to sub-pixels in one exact, once-rounded step per
//! coordinate ([`Scalar::ratio`]): `x = c + round(c · x_clip / w)` with `c` half the viewport
//! in sub-pixels. Clipping happens before snapping and before any integer conversion, so
//! coordinates of any size (±32767 in Q16.16, ±1e30 in f32) neither overflow nor reach outside
//! the screen. A vertex pushed beyond the number format by its object's transform is
//! [`Error::NonFinite`] for the first face that uses it. A shared edge is always cut from its
//! inside end, so both neighbours get the same point.

use crate::error::Error;
use crate::math::{Affine, Prepared, Vec3};
use crate::number::{cross3, dot3, f32_from_small_int, sub3, Scalar};
use crate::raster::{
    canonical, signed_area2, Config, Cull, RasterVertex, GUARD_BAND, MAX_FACE_VERTICES,
    MAX_POLYGON_VERTICES,
};
use crate::scene::{
    Face, Faces, IntensityPlane, Mesh, MeshIndex, ModelScene, Polygon, Projection, Scene,
    ScreenScene, SnappedScene, Vectors, VertexBuffer, INDEXED_CORNERS,
};
use crate::shading::Shading;
use core::cell::Cell;
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::Rgb565;
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
    #[inline]
    pub fn w(&self, z: N) -> N {
        match *self {
            ViewDepth::InverseW { k, k_near } => k_near.div_inline(k.sub(z)).unwrap_or(N::MAX),
            ViewDepth::Linear { near, per_depth } => near.add(z.mul(per_depth)),
        }
    }
}

type Poly<V> = Vec<V, MAX_POLYGON_VERTICES>;

/// Sutherland–Hodgman against one plane. `cross(inside, outside)` makes the new vertex.
///
/// A convex polygon gains at most one vertex per plane, so a face within
/// [`MAX_FACE_VERTICES`] stays within [`MAX_POLYGON_VERTICES`] after the six planes; more can
/// only come from an outline that is not convex, which is [`Error::NotConvex`].
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
        let mut push = |v| out.push(v).map_err(|_| Error::NotConvex { face });
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

/// Gathers a face's vertices into `out` (the caller's, kept from face to face: nothing is
/// returned by value), checking its size and indices.
fn gather<N: Scalar, I: MeshIndex>(
    mesh: &Mesh<'_, N, I>,
    face: &Face<'_, I>,
    no: u32,
    out: &mut Poly<Vec3<N>>,
) -> Result<(), Error> {
    if face.indices.len() < 3 {
        return Err(Error::TooFewVertices { face: no });
    }
    if face.indices.len() > MAX_FACE_VERTICES {
        return Err(Error::TooManyVertices { face: no });
    }
    out.clear();
    for &i in face.indices {
        let v = mesh.vertices.get(i.index()).ok_or(Error::IndexOutOfRange {
            face: no,
            index: i.index() as u32,
        })?;
        if !(v.x.is_finite() && v.y.is_finite() && v.z.is_finite()) {
            return Err(Error::NonFinite { face: no });
        }
        let _ = out.push(v); // fits: checked against MAX_FACE_VERTICES above
    }
    Ok(())
}

/// What a vertex slot holds when its vertex could not be projected (outside the view volume
/// or the guard band, or not a number): faces using it take the clipping path.
const UNPROJECTED: i32 = i32::MIN;

fn unprojected<N: Scalar>() -> RasterVertex<N> {
    RasterVertex {
        x: UNPROJECTED,
        y: 0,
        z: N::ZERO,
    }
}

/// A screen-space point snapped to the sub-pixel grid.
fn snap<N: Scalar>(p: &Vec3<N>, s: u32, face: u32) -> Result<RasterVertex<N>, Error> {
    Ok(RasterVertex {
        x: p.x.snap(s).ok_or(Error::NonFinite { face })?,
        y: p.y.snap(s).ok_or(Error::NonFinite { face })?,
        z: p.z,
    })
}

/// Whether model mode lights vertices for smooth shading (the `gouraud` feature, on by
/// default: about 2 KB of flash on a Cortex-M4, which a firmware that draws flat leaves out).
const SMOOTH: bool = cfg!(feature = "gouraud");

/// The intensity plane of a smooth-shaded polygon: through its snapped corners `v` (clockwise
/// on the display if `clockwise`) at the levels `levels` their vertices were lit with, fitted
/// as a depth plane is ([`Scalar::depth_plane`], the corners in [`canonical`] order, so the
/// polygon gets the same bits whichever corner it was listed from).
fn intensity_plane<N: Scalar>(
    v: &[RasterVertex<N>],
    levels: &[N],
    clockwise: bool,
    cfg: &Config,
) -> Option<IntensityPlane<N>> {
    let mut lit = [RasterVertex::default(); MAX_POLYGON_VERTICES];
    for ((d, p), &z) in lit.iter_mut().zip(v).zip(levels) {
        *d = RasterVertex { x: p.x, y: p.y, z };
    }
    let mut ordered = [RasterVertex::default(); MAX_POLYGON_VERTICES];
    let n = canonical(&lit[..v.len().min(levels.len())], clockwise, &mut ordered);
    let levels = N::depth_plane(&ordered[..n], cfg.subpixel_bits as u32)?;
    let dither = matches!(cfg.shading, Shading::Gouraud { dither: true });
    Some(IntensityPlane { levels, dither })
}

/// How far back a facet is followed: faces listed one after the other in one plane merge into
/// one facet for at most this many steps (a polygon of [`MAX_FACE_VERTICES`] corners split into
/// triangles takes 8), so that finding a face's facet is bounded whatever the mesh.
const FACET_RUN: usize = 16;

/// Where [`facet_color`] is in one mesh's faces: the scene number of the mesh's face 0, and
/// the face asked last with its facet's first face (`usize::MAX`: none yet).
struct FacetWalk {
    first_no: u32,
    last: Cell<(usize, usize)>,
}

impl FacetWalk {
    fn new(first_no: u32) -> Self {
        FacetWalk {
            first_no,
            last: Cell::new((usize::MAX, 0)),
        }
    }
}

/// How one object's faces are coloured: lit ([`Lighting`]), or, drawn as facets, numbered
/// ([`facet_color`]).
struct FacePaint<N> {
    lighting: Lighting<N>,
    facets: FacetWalk,
}

/// The colour face `k` of `mesh` is drawn in under [`Shading::Facets`]: the raw value
/// `facet + 1`, where `facet` is the scene number of the first face of its facet: faces are
/// followed back while each continues the one before it ([`same_facet`]), at most
/// [`FACET_RUN`] steps. Out of line: the loops that call it draw shaded frames nearly always,
/// and only faces that survive culling ask.
///
/// Faces ask in order, so where the face before asked last (`walk`), the walk back from `k`
/// is its walk after one test: `k`'s facet is that facet (its start kept within
/// [`FACET_RUN`] of `k`) if `k` continues face `k − 1`, else `k` itself. One test instead of
/// the walk.
#[inline(never)]
fn facet_color<N: Scalar, I: MeshIndex>(
    mesh: &Mesh<'_, N, I>,
    k: usize,
    walk: &FacetWalk,
) -> Rgb565 {
    // Whether face `j` (above 0) continues face `j − 1`.
    let continues = |j: usize| match (mesh.faces.get(j - 1), mesh.faces.get(j)) {
        (Some(prev), Some(face)) => same_facet(mesh, &prev, &face),
        _ => false,
    };
    let first = match walk.last.get() {
        (before, its_first) if k > 0 && before == k - 1 => match continues(k) {
            true => its_first.max(k.saturating_sub(FACET_RUN)),
            false => k,
        },
        _ => {
            let mut first = k;
            while first > 0 && k - first < FACET_RUN && continues(first) {
                first -= 1;
            }
            first
        }
    };
    walk.last.set((k, first));
    // Below 2^16: the scene's face count was checked ([`facets_fit`]).
    Rgb565::from(RawU16::new((walk.first_no as usize + first + 1) as u16))
}

/// The most faces a scene drawn as facets may have: each facet's value `facet + 1` is 16 bits.
const MAX_FACETS: usize = 65_535;

/// Facets of a scene of more faces than 16 bits can name: refused before anything is drawn,
/// rather than drawn with two facets sharing a value.
fn facets_fit(facets: bool, faces: usize) -> Result<(), Error> {
    match facets && faces > MAX_FACETS {
        true => Err(Error::Unsupported {
            feature: "hidden lines of more than 65,535 faces",
        }),
        false => Ok(()),
    }
}

/// Whether `face` continues the facet of `prev`: they share an edge (two vertices), face the
/// same side, and `face`'s other corners lie in `prev`'s plane — within 4 LSB of the format
/// (so that a flat quad's corners, rounded to it, do not split it) plus 10⁻³ of their distance
/// from its first corner (0.06°; the bound is met up to a factor √2). In f32 on purpose: it
/// decides which edges are drawn, not where.
fn same_facet<N: Scalar, I: MeshIndex>(
    mesh: &Mesh<'_, N, I>,
    prev: &Face<'_, I>,
    face: &Face<'_, I>,
) -> bool {
    let shared = |i: &I| prev.indices.iter().any(|j| j.index() == i.index());
    if face.indices.iter().filter(|i| shared(i)).count() < 2 {
        return false;
    }
    // Compact positions whose conversion to the format is exact are taken as their integers,
    // every length then 2^shift times the model's (and the LSB tolerance with them): f32
    // rounds a product or sum scaled by a power of two to the same bits scaled, so every test
    // below decides the same. Their differences (below 2^17, exact in f32) are then taken in
    // integers and converted once: no f32 subtraction, no multiply to convert (each a library
    // call on a core without an FPU).
    let raw = match mesh.vertices {
        // Exact: f32 always, fixed point for `shift` at most its fractional bits (its LSB is
        // 2^-F, read from the constant's exponent).
        Vectors::Compact { raw, shift }
            if N::LSB == 0.0 || shift as u32 + (N::LSB.to_bits() >> 23) <= 127 =>
        {
            Some((raw, f32::from_bits((127 + shift as u32) << 23))) // 2^shift
        }
        _ => None,
    };
    // `q − p`, vertices by index.
    let diff = |p: &I, q: &I| -> Option<[f32; 3]> {
        match raw {
            Some((raw, _)) => {
                let (p, q) = (raw.get(p.index())?, raw.get(q.index())?);
                let d = |k: usize| f32_from_small_int(q[k] as i32 - p[k] as i32);
                Some([d(0), d(1), d(2)])
            }
            None => {
                let point = |i: &I| {
                    let v = mesh.vertices.get(i.index())?;
                    Some([v.x.to_f32(), v.y.to_f32(), v.z.to_f32()])
                };
                Some(sub3(point(q)?, point(p)?))
            }
        }
    };
    // A face's first corner and its normal, scaled to a largest component of 1 so that no
    // product below overflows.
    let plane = |f: &Face<'_, I>| -> Option<(I, [f32; 3])> {
        let a = *f.indices.first()?;
        let n = cross3(diff(&a, f.indices.get(1)?)?, diff(&a, f.indices.get(2)?)?);
        // The largest magnitude, compared as bits (the same order for numbers; a NaN, which
        // `f32::max` passes over, counts as 0), in integer instructions.
        let bits = |e: f32| match e.to_bits() & 0x7fff_ffff {
            b if b > 0x7f80_0000 => 0,
            b => b,
        };
        let big = f32::from_bits(n.iter().fold(0, |m, &e| m.max(bits(e))));
        // Scaled by a power of two (exact, and three multiplies rather than three divisions
        // where f32 is soft-float): the tests below do not depend on the normal's length.
        let exp = (big.to_bits() >> 23) & 0xff;
        let scale = match exp {
            1..=253 => f32::from_bits((254 - exp) << 23), // 2^(127 − exp), its largest to [1, 2)
            _ => 1.0 / big,
        };
        (big > 0.0 && big.is_finite()).then(|| (a, n.map(|e| e * scale)))
    };
    let (Some((a, n)), Some((_, m))) = (plane(prev), plane(face)) else {
        return false;
    };
    if dot3(n, m) <= 0.0 {
        return false;
    }
    let unit = raw.map_or(1.0, |(_, unit)| unit);
    let (nn, lsb) = (dot3(n, n), 4.0 * N::LSB * unit);
    face.indices.iter().filter(|i| !shared(i)).all(|i| {
        diff(&a, i).is_some_and(|d| {
            let h = dot3(n, d);
            h * h <= 2.0 * nn * (lsb * lsb + 1e-6 * dot3(d, d))
        })
    })
}

/// 0, 1, 2, …: the corners of a polygon whose vertices are listed in order.
const IN_ORDER: [u32; MAX_POLYGON_VERTICES] = {
    let mut a = [0u32; MAX_POLYGON_VERTICES];
    let mut k = 0;
    while k < MAX_POLYGON_VERTICES {
        a[k] = k as u32;
        k += 1;
    }
    a
};

/// A polygon as geometry hands it to the renderer.
struct Out<N> {
    color: Rgb565,
    intensity: Option<IntensityPlane<N>>,
    alpha: u8,
    face: u32,
    area2: i64,
}

/// Hands over a polygon whose corners are slots of the buffer already (a face whose vertices
/// all projected). One with more than [`INDEXED_CORNERS`] corners is first copied into a run
/// of consecutive slots (or, without room, into scratch).
fn emit_indexed<N: Scalar>(
    buf: &mut VertexBuffer<'_, N>,
    corners: &mut [u32],
    out: Out<N>,
    f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
) -> Result<(), Error> {
    if corners.len() > INDEXED_CORNERS {
        return emit_run(buf, corners, out, f);
    }
    f(&Polygon {
        vertices: buf.as_slice(),
        corners,
        cached: true,
        color: out.color,
        intensity: out.intensity,
        alpha: out.alpha,
        face: out.face,
        area2: out.area2,
    })
}

/// [`emit_indexed`] of a polygon of more than [`INDEXED_CORNERS`] corners: its vertices
/// copied into a run of consecutive slots. Out of line: the copy (216 bytes in a 32-bit
/// format, and `emit_new`'s corners) stays off the stack of every face's path.
#[cold]
#[inline(never)]
fn emit_run<N: Scalar>(
    buf: &mut VertexBuffer<'_, N>,
    corners: &[u32],
    out: Out<N>,
    f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
) -> Result<(), Error> {
    let mut v = [RasterVertex::default(); MAX_POLYGON_VERTICES];
    for (d, &c) in v.iter_mut().zip(corners.iter()) {
        *d = buf.as_slice()[c as usize];
    }
    emit_new(buf, &v[..corners.len()], out, f)
}

/// Hands over a polygon of new vertices (clipped, or copied for a run): as a run of
/// consecutive slots of the buffer, or, without room, in scratch.
fn emit_new<N: Scalar>(
    buf: &mut VertexBuffer<'_, N>,
    v: &[RasterVertex<N>],
    out: Out<N>,
    f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
) -> Result<(), Error> {
    let n = v.len();
    let mut corners = [0u32; MAX_POLYGON_VERTICES];
    let (vertices, cached) = match buf.claim(n) {
        Some(start) => {
            buf.slots_from(start)[..n].copy_from_slice(v);
            for (k, c) in corners[..n].iter_mut().enumerate() {
                *c = (start + k) as u32;
            }
            (buf.as_slice(), true)
        }
        None => {
            corners[..n].copy_from_slice(&IN_ORDER[..n]);
            (v, false)
        }
    };
    f(&Polygon {
        vertices,
        corners: &corners[..n],
        cached,
        color: out.color,
        intensity: out.intensity,
        alpha: out.alpha,
        face: out.face,
        area2: out.area2,
    })
}

/// Hands over, in scratch, a polygon the buffer had no room for although all its vertices
/// projected: counted as [`emit_indexed`] would have claimed it (a run only past
/// [`INDEXED_CORNERS`] corners), so [`VertexBuffer::needed`] is what a buffer with room uses.
fn emit_unclaimed<N: Scalar>(
    buf: &mut VertexBuffer<'_, N>,
    v: &[RasterVertex<N>],
    out: Out<N>,
    f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
) -> Result<(), Error> {
    if v.len() > INDEXED_CORNERS {
        buf.claim_none(v.len());
    }
    f(&Polygon {
        vertices: v,
        corners: &IN_ORDER[..v.len()],
        cached: false,
        color: out.color,
        intensity: out.intensity,
        alpha: out.alpha,
        face: out.face,
        area2: out.area2,
    })
}

/// Checks a face's size and indices and writes its corners (`base` + index) into `corners`;
/// returns the corner count and whether every corner's slot holds a projected vertex.
fn corners_of<N: Scalar, I: MeshIndex>(
    face: &Face<'_, I>,
    vertex_count: usize,
    base: Option<usize>,
    buf: &VertexBuffer<'_, N>,
    corners: &mut [u32; MAX_POLYGON_VERTICES],
    no: u32,
) -> Result<(usize, bool), Error> {
    let slots = buf.as_slice();
    let b = base.unwrap_or(0);
    let mut projected = base.is_some();
    let n = face_corners(face, vertex_count, b, corners, no, |slot| {
        projected &= slots.get(slot).is_some_and(|v| v.x != UNPROJECTED);
        Ok(())
    })?;
    Ok((n, projected))
}

/// Checks a face's size and indices and writes its corners (`base` + index) into `corners`,
/// handing each to `corner` once its index is checked; returns the corner count.
#[inline(always)]
fn face_corners<I: MeshIndex>(
    face: &Face<'_, I>,
    vertex_count: usize,
    base: usize,
    corners: &mut [u32; MAX_POLYGON_VERTICES],
    no: u32,
    mut corner: impl FnMut(usize) -> Result<(), Error>,
) -> Result<usize, Error> {
    let n = face.indices.len();
    if n < 3 {
        return Err(Error::TooFewVertices { face: no });
    }
    if n > MAX_FACE_VERTICES {
        return Err(Error::TooManyVertices { face: no });
    }
    for (c, &i) in corners.iter_mut().zip(face.indices) {
        let i = i.index();
        if i >= vertex_count {
            return Err(Error::IndexOutOfRange {
                face: no,
                index: i as u32,
            });
        }
        *c = (base + i) as u32;
        corner(base + i)?;
    }
    Ok(n)
}

/// Twice the signed area of the polygon with these corners in the buffer (positive =
/// clockwise on the display), exact.
#[inline]
fn area_of<N: Copy>(slots: &[RasterVertex<N>], corners: &[u32]) -> i64 {
    let p = |k: usize| &slots[corners[k] as usize];
    if let [a, b, c] = corners {
        let (a, b, c) = (
            &slots[*a as usize],
            &slots[*b as usize],
            &slots[*c as usize],
        );
        // Shoelace of a triangle, as two products of edge vectors.
        return (b.x as i64 - a.x as i64) * (c.y as i64 - a.y as i64)
            - (c.x as i64 - a.x as i64) * (b.y as i64 - a.y as i64);
    }
    let mut area = 0i64;
    for k in 0..corners.len() {
        let (u, v) = (p(k), p((k + 1) % corners.len()));
        area += u.x as i64 * v.y as i64 - v.x as i64 * u.y as i64;
    }
    area
}

/// Whether the culling rule drops a polygon of this doubled signed area (the rule of
/// [`crate::raster::outline`]: zero area always, clockwise when back faces are culled).
#[inline]
fn dropped(area: i64, cfg: &Config) -> bool {
    area == 0 || (cfg.cull == Cull::Back && area > 0)
}

/// Every vertex of `vertices` transformed by `mv` into its slot: inside the view volume and
/// the guard band, projected and snapped; else marked unprojected. Out of line: the loop keeps
/// its registers for itself.
#[inline(never)]
fn project_all<N: Scalar>(
    slots: &mut [RasterVertex<N>],
    vertices: Vectors<'_, N>,
    mv: &Prepared<'_, N>,
    proj: &Projector<N>,
    cfg: &Config,
) {
    for (slot, v) in slots.iter_mut().zip(vertices.iter()) {
        let c = mv.apply_checked_with(cfg.math, v).map(|v| proj.clip(v));
        *slot = c
            .filter(|c| proj.inside(c))
            .and_then(|c| proj.screen(&c))
            .unwrap_or_else(unprojected);
    }
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

/// A screen-space scene's [`ViewDepth`]: depth is the view distance itself.
fn screen_depth<N: Scalar>() -> ViewDepth<N> {
    ViewDepth::Linear {
        near: N::ZERO,
        per_depth: N::ONE,
    }
}

impl<N: Scalar, I: MeshIndex> Scene<N> for ScreenScene<'_, N, I> {
    fn polygons(
        &self,
        cfg: &Config,
        buf: &mut VertexBuffer<'_, N>,
        f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
    ) -> Result<(), Error> {
        let mesh = &self.mesh;
        mesh.check()?;
        let s = cfg.subpixel_bits as u32;
        let (lo, hx, hy): (N, N, N) = (
            num(-GUARD_BAND),
            num(cfg.width as i32 + GUARD_BAND),
            num(cfg.height as i32 + GUARD_BAND),
        );
        // Every vertex snapped once; those outside the guard band (or not numbers) are left
        // to the faces' clipping.
        let base = buf.claim(mesh.vertices.len());
        if let Some(b) = base {
            for (slot, p) in buf.slots_from(b).iter_mut().zip(mesh.vertices.iter()) {
                let inside = p.x >= lo && p.x <= hx && p.y >= lo && p.y <= hy;
                *slot = match inside && p.z.is_finite() {
                    true => snap(&p, s, 0).unwrap_or_else(|_| unprojected()),
                    false => unprojected(),
                };
            }
        }
        let mut corners = [0u32; MAX_POLYGON_VERTICES];
        // A face's vertices and their snapped corners, kept from face to face (no copy or
        // clearing of either per face).
        let mut poly: Poly<Vec3<N>> = Vec::new();
        let mut v = [RasterVertex::default(); MAX_POLYGON_VERTICES];
        // `cfg!` first: a constant the compiler drops the facet code on, in a build without
        // the feature (the call alone left 1.4 KB of it in the Cortex-M4 firmware's flash).
        let facets = cfg!(feature = "lines") && cfg.shading.is_facets();
        facets_fit(facets, mesh.faces.len())?;
        let walk = FacetWalk::new(0);
        for (no, face) in mesh.faces.iter().enumerate() {
            let facet;
            let face = match facets {
                true => {
                    let color = facet_color(mesh, no, &walk);
                    facet = Face {
                        color,
                        alpha: 255,
                        ..face
                    };
                    &facet
                }
                false => &face,
            };
            let no = no as u32;
            let (n, projected) =
                corners_of(face, mesh.vertices.len(), base, buf, &mut corners, no)?;
            let mut out = Out {
                color: face.color,
                intensity: None,
                alpha: face.alpha,
                face: no,
                area2: 0,
            };
            if projected {
                out.area2 = area_of(buf.as_slice(), &corners[..n]);
                emit_indexed(buf, &mut corners[..n], out, f)?;
                continue;
            }
            gather(mesh, face, no, &mut poly)?;
            if base.is_none()
                && poly
                    .iter()
                    .all(|p| p.x >= lo && p.x <= hx && p.y >= lo && p.y <= hy)
            {
                // No room in the buffer, but nothing to clip either.
                for (d, p) in v.iter_mut().zip(&poly) {
                    *d = snap(p, s, no)?;
                }
                out.area2 = signed_area2(&v[..n]);
                emit_unclaimed(buf, &v[..n], out, f)?;
                continue;
            }
            clip_guard_band(&mut poly, cfg, no)?;
            if poly.len() >= 3 {
                for (d, p) in v.iter_mut().zip(&poly) {
                    *d = snap(p, s, no)?;
                }
                out.area2 = signed_area2(&v[..poly.len()]);
                emit_new(buf, &v[..poly.len()], out, f)?;
            }
        }
        Ok(())
    }

    fn view_depth(&self, _cfg: &Config) -> Option<ViewDepth<N>> {
        Some(screen_depth())
    }
}

impl<N: Scalar, I: MeshIndex> Scene<N> for SnappedScene<'_, N, I> {
    /// Each face as it is, over the scene's own vertices (checked, not copied).
    fn polygons(
        &self,
        cfg: &Config,
        _: &mut VertexBuffer<'_, N>,
        f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
    ) -> Result<(), Error> {
        cfg.validate(usize::MAX)?;
        if self.subpixel_bits != cfg.subpixel_bits {
            return Err(Error::BadConfig);
        }
        if cfg.shading.is_facets() {
            return Err(Error::Unsupported {
                feature: "hidden lines of a snapped scene: draw its ScreenScene",
            });
        }
        let s = cfg.subpixel_bits as u32;
        let lo = -GUARD_BAND << s;
        let (hx, hy) = (
            (cfg.width as i32 + GUARD_BAND) << s,
            (cfg.height as i32 + GUARD_BAND) << s,
        );
        let vertices = self.vertices;
        let mut corners = [0u32; MAX_POLYGON_VERTICES];
        for (no, face) in self.faces.iter().enumerate() {
            let no = no as u32;
            let n = face_corners(&face, vertices.len(), 0, &mut corners, no, |i| {
                // (In range: `face_corners` checked the index.)
                match vertices.get(i) {
                    Some(v) if !(v.x >= lo && v.x <= hx && v.y >= lo && v.y <= hy) => {
                        Err(Error::OutsideGuardBand { face: no })
                    }
                    Some(v) if !v.z.is_finite() => Err(Error::NonFinite { face: no }),
                    _ => Ok(()),
                }
            })?;
            let corners = &corners[..n];
            if n > INDEXED_CORNERS && !(1..n).all(|k| corners[k] == corners[0] + k as u32) {
                return Err(Error::Unsupported {
                    feature: "a snapped scene's face of more than 4 corners on vertices that \
                              are not consecutive",
                });
            }
            f(&Polygon {
                vertices,
                corners,
                cached: true,
                area2: area_of(vertices, corners),
                color: face.color,
                intensity: None,
                alpha: face.alpha,
                face: no,
            })?;
        }
        Ok(())
    }

    fn lent_vertices(&self) -> Option<&[RasterVertex<N>]> {
        Some(self.vertices)
    }

    fn view_depth(&self, _cfg: &Config) -> Option<ViewDepth<N>> {
        Some(screen_depth())
    }
}

/// Scales a colour by an intensity in 0..=1.
pub fn shade<N: Scalar>(c: Rgb565, intensity: N) -> Rgb565 {
    crate::raster::shade_level(c, intensity.to_unit_u8())
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

/// A clip-space vertex: `x`, `y` scaled by the projection, `w` the distance in front of the eye.
#[derive(Clone, Copy)]
struct ClipV<N> {
    x: N,
    y: N,
    w: N,
    /// Smooth shading's intensity level at this point (0 when flat), interpolated by
    /// clipping like the coordinates.
    level: N,
}

/// Everything model mode needs to take a view-space point to snapped sub-pixels.
struct Projector<N> {
    perspective: bool,
    /// Focal lengths (perspective) or reciprocal half sizes (orthographic), x and y.
    sx: N,
    sy: N,
    near: N,
    far: N,
    /// The guard band in normalised units, x and y: `|x| ≤ gx·d` keeps x within
    /// [`GUARD_BAND`] pixels of the viewport.
    gx: N,
    gy: N,
    /// Half the viewport, in sub-pixels: the projection's centre and scale.
    kx: i32,
    ky: i32,
    /// `DEPTH_RANGE · far / (far − near)` and it times `near` (depth affine in 1/w).
    depth_k: N,
    k_near: N,
    /// `DEPTH_RANGE / (far − near)` (depth linear in w).
    depth_lin: N,
    linear_w: bool,
}

impl<N: Scalar> Projector<N> {
    fn new<I>(scene: &ModelScene<'_, N, I>, cfg: &Config) -> Result<Self, Error> {
        let (w_px, h_px) = (cfg.width as f32, cfg.height as f32);
        let aspect = N::from_f32(h_px / w_px).unwrap_or(N::ONE);
        let (perspective, sx, sy, near, far) = match scene.camera.projection {
            Projection::Perspective { focal, near, far } => {
                (true, focal.mul(aspect), focal, near, far)
            }
            Projection::Orthographic {
                half_height,
                near,
                far,
            } => {
                let inv = N::ONE.div(half_height).ok_or(Error::BadConfig)?;
                (false, inv.mul(aspect), inv, near, far)
            }
        };
        if !(near > N::ZERO && far > near) {
            return Err(Error::BadConfig);
        }
        // Guard band in normalised units: |x/w| <= gx keeps x within GUARD_BAND pixels.
        let gx = N::from_f32(1.0 + 2.0 * GUARD_BAND as f32 / w_px).ok_or(Error::BadConfig)?;
        let gy = N::from_f32(1.0 + 2.0 * GUARD_BAND as f32 / h_px).ok_or(Error::BadConfig)?;
        let range = N::from_f32(DEPTH_RANGE).ok_or(Error::BadConfig)?;
        let depth_k = range.mul(far.div(far.sub(near)).ok_or(Error::BadConfig)?);
        let s = cfg.subpixel_bits as u32;
        Ok(Projector {
            perspective,
            sx,
            sy,
            near,
            far,
            gx,
            gy,
            kx: (cfg.width as i32) << (s - 1),
            ky: (cfg.height as i32) << (s - 1),
            depth_k,
            k_near: depth_k.mul(near),
            depth_lin: range.div(far.sub(near)).ok_or(Error::BadConfig)?,
            linear_w: perspective && cfg.depth == DepthMapping::LinearW,
        })
    }

    /// A view-space point in clip space.
    #[inline]
    fn clip(&self, v: Vec3<N>) -> ClipV<N> {
        ClipV {
            x: v.x.mul(self.sx),
            y: v.y.mul(self.sy),
            w: v.z.neg(),
            level: N::ZERO,
        }
    }

    /// What x and y are divided by: w under perspective.
    #[inline]
    fn d(&self, v: &ClipV<N>) -> N {
        if self.perspective {
            v.w
        } else {
            N::ONE
        }
    }

    /// Guard plane `i`'s signed distance (0, 1: x ≤ gx·d, x ≥ −gx·d; 2, 3: the same in y),
    /// written `coord ∓ g·d` so that both planes of an axis use the one product `g·d`.
    #[inline]
    fn guard_c(&self, i: usize, v: &ClipV<N>) -> N {
        let (coord, g) = if i < 2 {
            (v.x, self.gx)
        } else {
            (v.y, self.gy)
        };
        let gd = g.mul(self.d(v));
        if i % 2 == 0 {
            coord.sub(gd)
        } else {
            coord.add(gd)
        }
    }

    /// Whether `v` is inside guard plane `i` (`c ≤ 0` for the planes on the positive side).
    #[inline]
    fn inside_guard(&self, i: usize, v: &ClipV<N>) -> bool {
        let c = self.guard_c(i, v);
        if i % 2 == 0 {
            c <= N::ZERO
        } else {
            c >= N::ZERO
        }
    }

    /// Whether clipping would leave `v` where it is: inside the near and far planes and the
    /// guard band (the same tests the clipping path makes, one product per axis).
    #[inline]
    fn inside(&self, v: &ClipV<N>) -> bool {
        let d = self.d(v);
        v.w >= self.near && v.w <= self.far && v.x.within(self.gx, d) && v.y.within(self.gy, d)
    }

    /// Clips a polygon in clip space: near, far, then the four guard-band planes.
    fn clip_polygon(&self, clip: &mut Poly<ClipV<N>>, face: u32) -> Result<(), Error> {
        let lerp = |i: &ClipV<N>, o: &ClipV<N>, ci: N, co: N, b: N| ClipV {
            x: N::lerp_clip(i.x, o.x, ci, co, b),
            y: N::lerp_clip(i.y, o.y, ci, co, b),
            w: N::lerp_clip(i.w, o.w, ci, co, b),
            level: match SMOOTH {
                true => N::lerp_clip(i.level, o.level, ci, co, b),
                false => N::ZERO,
            },
        };
        let (near, far) = (self.near, self.far);
        clip_plane(
            clip,
            |v| v.w >= near,
            |i, o| lerp(i, o, i.w, o.w, near),
            face,
        )?;
        clip_plane(clip, |v| v.w <= far, |i, o| lerp(i, o, i.w, o.w, far), face)?;
        for g in 0..4 {
            clip_plane(
                clip,
                |v| self.inside_guard(g, v),
                |i, o| lerp(i, o, self.guard_c(g, i), self.guard_c(g, o), N::ZERO),
                face,
            )?;
        }
        Ok(())
    }

    /// A clip-space point inside the view volume and the guard band, projected and snapped:
    /// `x = kx + round(kx · x / d)`, `y = ky − round(ky · y / d)`, and its depth.
    #[inline(always)]
    fn screen(&self, v: &ClipV<N>) -> Option<RasterVertex<N>> {
        let inverse_w = self.perspective && !self.linear_w;
        let k = inverse_w.then_some(self.k_near);
        let (x, y, k_over_w) = v.x.project(v.y, self.d(v), self.kx, self.ky, k)?;
        let z = if inverse_w {
            self.depth_k.sub(k_over_w)
        } else {
            v.w.sub(self.near).mul(self.depth_lin)
        };
        Some(RasterVertex {
            x: self.kx.checked_add(x)?,
            y: self.ky.checked_sub(y)?,
            z,
        })
    }
}

/// Flat Lambert shading of one object's faces: `ambient + (1 − ambient)·max(0, n̂·l̂)` with the
/// face normal taken to view space by the cofactor matrix C of the object's model-view
/// transform (right for any scale or mirror).
///
/// When C is a scaled rotation — CᵀC = g·I within 2^-10 relative, as for any rigid motion or
/// uniform scale — the light is taken to model space once per object instead (`l_m = Cᵀl/√g`),
/// so a face costs two dot products and a reciprocal square root: `n·l_m / √(n·n)`.
/// Otherwise each normal is transformed: `Cn·l / √(Cn·Cn)`.
struct Lighting<N> {
    /// Light in view space, unit length.
    light: Option<Vec3<N>>,
    to_view: Option<Affine<N>>,
    /// Light in model space, scaled by `1/√g`, when C is a scaled rotation.
    model_light: Option<Vec3<N>>,
    ambient: N,
    /// `1 − ambient`, what the Lambert term is scaled by.
    diffuse: N,
    math: crate::math::MathLib,
    /// 255 in the format: an intensity's level.
    levels: N,
}

impl<N: Scalar> Lighting<N> {
    fn for_object(
        mv: &Affine<N>,
        light: Option<Vec3<N>>,
        ambient: N,
        math: crate::math::MathLib,
    ) -> Self {
        let to_view = normal_matrix(mv);
        let model_light = match (to_view, light) {
            (Some(c), Some(l)) => scaled_rotation(&c, math).map(|k| {
                // Cᵀl / √g.
                let col = |j: usize| {
                    c.m[0][j]
                        .mul(l.x)
                        .add(c.m[1][j].mul(l.y))
                        .add(c.m[2][j].mul(l.z))
                        .mul(k)
                };
                Vec3::new(col(0), col(1), col(2))
            }),
            _ => None,
        };
        Lighting {
            light,
            to_view,
            model_light,
            ambient,
            diffuse: N::ONE.sub(ambient),
            math,
            levels: N::from_f32(255.0).unwrap_or(N::ONE),
        }
    }

    /// The colour of a face with model-space normal `normal` (any length; `None`: unlit).
    fn color(&self, base: Rgb565, normal: Option<[N; 3]>) -> Rgb565 {
        shade(base, self.intensity(normal))
    }

    /// A smooth-shaded vertex's level: its intensity times 255.
    fn level(&self, normal: Option<[N; 3]>) -> N {
        self.intensity(normal).mul(self.levels)
    }

    /// `ambient + (1 − ambient)·max(0, n̂·l̂)` for model-space normal `normal`. Inlined into
    /// its callers (a face's colour, a smooth vertex's level): one call a face fewer, and no
    /// firmware flash more (the Cortex-M4 firmware's size unchanged).
    #[inline(always)]
    fn intensity(&self, normal: Option<[N; 3]>) -> N {
        let lambert = match (normal, self.model_light, self.light, self.to_view) {
            (Some(n), Some(lm), _, _) => self.lambert(n, lm),
            (Some([x, y, z]), None, Some(l), Some(m)) => {
                let n = m.apply_dir(Vec3::new(x, y, z));
                self.lambert([n.x, n.y, n.z], l)
            }
            _ => N::ZERO,
        };
        self.ambient.add(self.diffuse.mul(lambert))
    }
}

impl<N: Scalar> Lighting<N> {
    /// `max(0, n·l) / |n|` ([`Scalar::affine_row_as`], plain: in fixed point the dot products
    /// are summed exactly and rounded once; f32 sums plainly, far within an intensity step).
    #[inline]
    fn lambert(&self, n: [N; 3], l: Vec3<N>) -> N {
        let dot = |a: [N; 3], b: [N; 3]| N::affine_row_as(&[a[0], a[1], a[2], N::ZERO], b, true);
        match dot(n, [l.x, l.y, l.z]) {
            Some(d) if d > N::ZERO => d.mul(self.math.rsqrt(dot(n, n).unwrap_or(N::MAX))),
            _ => N::ZERO,
        }
    }
}

/// `1/√g` if CᵀC = g·I within 2^-10 relative (C a scaled rotation, possibly mirrored).
fn scaled_rotation<N: Scalar>(c: &Affine<N>, math: crate::math::MathLib) -> Option<N> {
    let g = |i: usize, j: usize| {
        c.m[0][i]
            .mul(c.m[0][j])
            .add(c.m[1][i].mul(c.m[1][j]))
            .add(c.m[2][i].mul(c.m[2][j]))
    };
    let d = g(0, 0).add(g(1, 1)).add(g(2, 2));
    let mean = d.div(N::from_f32(3.0)?)?;
    let tol = mean.div(N::from_f32(1024.0)?)?;
    let abs = |v: N| if v < N::ZERO { v.neg() } else { v };
    let close = |v: N, want: N| abs(v.sub(want)) <= tol;
    let ok = (0..3).all(|i| (0..3).all(|j| close(g(i, j), if i == j { mean } else { N::ZERO })));
    (ok && mean > N::ZERO).then(|| math.rsqrt(mean))
}

/// A model face some of whose corners did not project (outside the view volume or the guard
/// band): its corners again, clipped in clip space if they need it (or, with no room in the
/// vertex buffer, projected here if they do not), then emitted with the flat colour `color`
/// gives, or smooth shaded if `levels` has its corners' levels (clipping interpolates them).
/// Out of line: its clipping buffers (about a kilobyte on a 32-bit core) stay off the stack of
/// the common path, where every corner projected.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn emit_clipped<N: Scalar, I: MeshIndex>(
    mesh: &Mesh<'_, N, I>,
    face: &Face<'_, I>,
    this: u32,
    mv: &Prepared<'_, N>,
    proj: &Projector<N>,
    cfg: &Config,
    color: impl FnOnce() -> Rgb565,
    levels: Option<&[N]>,
    buf: &mut VertexBuffer<'_, N>,
    f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
) -> Result<(), Error> {
    let mut clip: Poly<ClipV<N>> = Vec::new();
    for (k, &i) in face.indices.iter().enumerate() {
        let p = mesh.vertices.get(i.index()).ok_or(Error::IndexOutOfRange {
            face: this,
            index: i.index() as u32,
        })?;
        let v = mv
            .apply_checked_with(cfg.math, p)
            .filter(|v| v.x.is_finite() && v.y.is_finite() && v.z.is_finite())
            .ok_or(Error::NonFinite { face: this })?;
        let mut c = proj.clip(v);
        if SMOOTH {
            c.level = levels.and_then(|l| l.get(k).copied()).unwrap_or(N::ZERO);
        }
        let _ = clip.push(c); // fits: checked against MAX_FACE_VERTICES
    }
    let unclipped = clip.iter().all(|c| proj.inside(c));
    if !unclipped {
        proj.clip_polygon(&mut clip, this)?;
    }
    if clip.len() < 3 {
        return Ok(());
    }
    let mut v = [RasterVertex::default(); MAX_POLYGON_VERTICES];
    for (d, c) in v.iter_mut().zip(&clip) {
        *d = proj.screen(c).ok_or(Error::NonFinite { face: this })?;
    }
    let v = &v[..clip.len()];
    let area2 = signed_area2(v);
    if dropped(area2, cfg) {
        return Ok(());
    }
    let mut intensity = None;
    if SMOOTH && levels.is_some() {
        let mut lit = [N::ZERO; MAX_POLYGON_VERTICES];
        for (d, c) in lit.iter_mut().zip(&clip) {
            *d = c.level;
        }
        intensity = intensity_plane(v, &lit[..v.len()], area2 > 0, cfg);
    }
    let out = Out {
        color: match intensity {
            Some(_) => face.color,
            None => color(),
        },
        intensity,
        alpha: face.alpha,
        face: this,
        area2,
    };
    if unclipped {
        emit_unclaimed(buf, v, out, f)
    } else {
        emit_new(buf, v, out, f)
    }
}

impl<N: Scalar, I: MeshIndex> Scene<N> for ModelScene<'_, N, I> {
    fn polygons(
        &self,
        cfg: &Config,
        buf: &mut VertexBuffer<'_, N>,
        f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
    ) -> Result<(), Error> {
        if !SMOOTH && cfg.shading.is_smooth() {
            return Err(Error::Unsupported {
                feature: "smooth shading (zrow built without `gouraud`)",
            });
        }
        let proj = Projector::new(self, cfg)?;
        let light = self.camera.view.apply_dir(self.light.direction).unit_max();
        let light = light.and_then(|l| {
            let len = cfg.math.sqrt(l.dot(l));
            Some(Vec3::new(l.x.div(len)?, l.y.div(len)?, l.z.div(len)?))
        });
        for obj in self.objects {
            obj.mesh.check()?;
        }
        let mut no = 0u32;
        let facets = cfg!(feature = "lines") && cfg.shading.is_facets(); // as in ScreenScene
        facets_fit(
            facets,
            self.objects.iter().map(|o| o.mesh.faces.len()).sum(),
        )?;
        for obj in self.objects {
            let mv = self.camera.view.then_after(&obj.transform);
            let lighting = Lighting::for_object(&mv, light, self.light.ambient, cfg.math);
            // Lit, or as facets numbered from this object's first face (one capture for the
            // colour closure: a second one cost the shaded frames' faces a spill).
            let paint = FacePaint {
                lighting,
                facets: FacetWalk::new(no),
            };
            let mesh = obj.mesh;
            // Every vertex once: transformed, and, inside the view volume and the guard band,
            // projected and snapped.
            let base = buf.claim(mesh.vertices.len());
            let prepared = mv.prepare();
            if let Some(b) = base {
                project_all(buf.slots_from(b), mesh.vertices, &prepared, &proj, cfg);
            }
            let normal = |k: usize, face: &Face<'_, I>| -> Option<[N; 3]> {
                if let Some(n) = mesh.normals.get(k) {
                    return Some([n.x, n.y, n.z]);
                }
                if let Vectors::Compact { raw, shift } = mesh.vertices {
                    let v = |j: usize| raw.get(face.indices.get(j)?.index()).copied();
                    return N::face_normal_compact(v(0)?, v(1)?, v(2)?, shift as u32);
                }
                let v = |j: usize| {
                    let p = mesh.vertices.get(face.indices[j].index())?;
                    Some([p.x, p.y, p.z])
                };
                N::face_normal(v(0)?, v(1)?, v(2)?)
            };
            let count = mesh.vertices.len();
            // Smooth: each corner lit with its vertex's normal, the face's own colour scaled
            // per pixel (a plane that cannot be fitted leaves the face flat).
            let smooth = SMOOTH && cfg.shading.is_smooth() && !mesh.vertex_normals.is_empty();
            let level = |i: usize| {
                let n = mesh.vertex_normals.get(i);
                paint.lighting.level(n.map(|n| [n.x, n.y, n.z]))
            };
            let levels_of = |face: &Face<'_, I>| {
                let mut levels = [N::ZERO; MAX_POLYGON_VERTICES];
                for (d, i) in levels.iter_mut().zip(face.indices) {
                    *d = level(i.index());
                }
                levels
            };
            // A smooth face's intensity plane through its snapped corners `v`.
            let plane = |face: &Face<'_, I>, v: &[RasterVertex<N>], area2: i64| {
                let n = v.len().min(face.indices.len());
                intensity_plane(v, &levels_of(face)[..n], area2 > 0, cfg)
            };
            // Its colour: its facet's, or its own under an intensity plane, else lit flat;
            // opaque as a facet.
            let first_no = no;
            // (`cfg!` again inside the closures: they read `facets` through a reference, and
            // a build without the feature must see a constant to drop the facet code.)
            let color = |k: usize, face: &Face<'_, I>, smooth: bool| match (
                cfg!(feature = "lines") && facets,
                smooth,
            ) {
                (true, _) => facet_color(mesh, k, &paint.facets),
                (false, true) => face.color,
                (false, false) => paint.lighting.color(face.color, normal(k, face)),
            };
            let alpha = |face: &Face<'_, I>| match cfg!(feature = "lines") && facets {
                true => 255,
                false => face.alpha,
            };
            // A front triangle whose corners all projected (nearly every face of a mesh in
            // view): lit, and handed on by slot.
            let front =
                |k: usize,
                 face: &Face<'_, I>,
                 mut c: [u32; 3],
                 area2: i64,
                 buf: &mut VertexBuffer<'_, N>,
                 f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>| {
                    let intensity = match smooth {
                        true => {
                            let v = |j: usize| buf.as_slice().get(c[j] as usize).copied();
                            let v = [v(0), v(1), v(2)].map(|v| v.unwrap_or_default());
                            plane(face, &v, area2)
                        }
                        false => None,
                    };
                    let out = Out {
                        color: color(k, face, intensity.is_some()),
                        intensity,
                        alpha: alpha(face),
                        face: first_no + k as u32,
                        area2,
                    };
                    emit_indexed(buf, &mut c, out, f)
                };
            // The doubled signed area of the triangle on slots `b + i` (`None` unless all
            // three are in the buffer and projected). Projected corners lie within the guard
            // band (below 2^25 sub-pixels at any screen size): differences fit 32 bits, each
            // product is one 32 × 32 → 64-bit multiply.
            let winding = |slots: &[RasterVertex<N>], b: usize, [i0, i1, i2]: [usize; 3]| {
                let own = slots.get(b..b.checked_add(count)?)?;
                let v = |i: usize| own.get(i).filter(|v| v.x != UNPROJECTED);
                let (v0, v1, v2) = (v(i0)?, v(i1)?, v(i2)?);
                let d = |a: i32, b: i32| a.wrapping_sub(b) as i64;
                Some(d(v1.x, v0.x) * d(v2.y, v0.y) - d(v2.x, v0.x) * d(v1.y, v0.y))
            };
            // Any other face: a polygon whose corners all projected, by slot; else clipped.
            let any = |k: usize,
                       face: &Face<'_, I>,
                       buf: &mut VertexBuffer<'_, N>,
                       f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>|
             -> Result<(), Error> {
                let this = first_no + k as u32;
                let mut corners = [0u32; MAX_POLYGON_VERTICES];
                let (n, projected) = corners_of(face, count, base, buf, &mut corners, this)?;
                if projected {
                    let area2 = area_of(buf.as_slice(), &corners[..n]);
                    if dropped(area2, cfg) {
                        return Ok(());
                    }
                    let mut intensity = None;
                    if smooth {
                        let mut v = [RasterVertex::default(); MAX_POLYGON_VERTICES];
                        for (d, &c) in v.iter_mut().zip(&corners[..n]) {
                            *d = buf.as_slice().get(c as usize).copied().unwrap_or_default();
                        }
                        intensity = plane(face, &v[..n], area2);
                    }
                    let out = Out {
                        color: color(k, face, intensity.is_some()),
                        intensity,
                        alpha: alpha(face),
                        face: this,
                        area2,
                    };
                    return emit_indexed(buf, &mut corners[..n], out, f);
                }
                let levels = smooth.then(|| levels_of(face));
                let n = face.indices.len().min(MAX_POLYGON_VERTICES);
                let levels = levels.as_ref().map(|l| &l[..n]);
                let color = || color(k, face, false);
                let opaque;
                let face = match facets {
                    true => {
                        opaque = Face {
                            alpha: 255,
                            ..*face
                        };
                        &opaque
                    }
                    false => face,
                };
                emit_clipped(
                    mesh, face, this, &prepared, &proj, cfg, color, levels, buf, f,
                )
            };
            // Face `k`'s corners if it is a triangle.
            let triangle = |k: usize| {
                let t = match mesh.faces {
                    Faces::Triangles { indices, .. } => *indices.get(k)?,
                    Faces::List(l) => <[I; 3]>::try_from(l.get(k)?.indices).ok()?,
                };
                Some(t.map(|i| i.index()))
            };
            for k in 0..mesh.faces.len() {
                // A triangle whose corners all projected is culled here by its winding
                // alone: a face the culling drops costs no more.
                let mut fast = None;
                if let (Some(b), Some(i)) = (base, triangle(k)) {
                    match winding(buf.as_slice(), b, i) {
                        Some(area2) if dropped(area2, cfg) => continue,
                        Some(area2) => fast = Some((i.map(|i| (b + i) as u32), area2)),
                        None => {}
                    }
                }
                let Some(face) = mesh.faces.get(k) else { break };
                match fast {
                    Some((c, area2)) => front(k, &face, c, area2, buf, f)?,
                    None => any(k, &face, buf, f)?,
                }
            }
            no = first_no + mesh.faces.len() as u32;
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
