//! What a mesh's structure allows: whether it is one closed convex solid, for which back-face
//! culling alone removes hidden surfaces ([`crate::cullonly`]).
//!
//! Checked in `f64` on the mesh's own vertices (exact for both formats' values, see
//! [`Scalar::to_f64`]), without allocating: `O(F²·k²)` for `F` faces of up to `k` vertices,
//! meant for start-up or the build host, not for every frame.

use crate::number::Scalar;
use crate::scene::{Mesh, MeshIndex};

/// Whether `mesh` is a closed convex solid with outward (counter-clockwise seen from outside)
/// faces:
///
/// - **closed and consistently oriented**: every directed edge `a → b` of a face is met once,
///   and exactly one face has the opposite edge `b → a` (so no edge is open, shared by more than
///   two faces, or shared by two faces in the same direction); every index is in range and
///   every face has three or more vertices;
/// - **convex**: no vertex of the mesh lies in front of any face's plane (Newell's normal,
///   outward) by more than `1e-9` of the mesh's extent — so the solid is its own convex hull
///   and its front faces never overlap on screen.
///
/// A mesh with no faces is not one.
pub fn closed_convex<N: Scalar, I: MeshIndex>(mesh: &Mesh<'_, N, I>) -> bool {
    let v = |i: usize| -> Option<[f64; 3]> {
        let p = mesh.vertices.get(i)?;
        let c = [p.x.to_f64(), p.y.to_f64(), p.z.to_f64()];
        c.iter().all(|x| x.is_finite()).then_some(c)
    };
    if mesh.faces.is_empty() {
        return false;
    }
    let mut extent: f64 = 0.0;
    for f in mesh.faces {
        if f.indices.len() < 3 || f.indices.iter().any(|&i| v(i.index()).is_none()) {
            return false;
        }
        for &i in f.indices {
            if let Some(c) = v(i.index()) {
                extent = c.iter().fold(extent, |m, x| m.max(x.abs()));
            }
        }
    }
    for (fi, f) in mesh.faces.iter().enumerate() {
        for (a, b) in face_edges(f.indices) {
            let (mut same, mut opposite) = (0, 0);
            for (gi, g) in mesh.faces.iter().enumerate() {
                for (c, d) in face_edges(g.indices) {
                    if (c, d) == (a, b) && gi != fi {
                        same += 1;
                    }
                    if (c, d) == (b, a) {
                        opposite += 1;
                    }
                }
            }
            if same != 0 || opposite != 1 || a == b {
                return false;
            }
        }
    }
    let tolerance = 1e-9 * extent.max(f64::MIN_POSITIVE);
    for f in mesh.faces {
        let Some(plane) = FacePlane::of(f.indices, v) else {
            return false;
        };
        let beyond = mesh
            .vertices
            .iter()
            .any(|p| plane.in_front([p.x.to_f64(), p.y.to_f64(), p.z.to_f64()], tolerance));
        if beyond {
            return false;
        }
    }
    true
}

/// A face's plane as [`closed_convex`] tests it: Newell's normal (outward for a face
/// counter-clockwise seen from outside; not unit, `norm2` is its squared length) through the
/// face's centroid, in `f64`. Public so that a host-side check with other data structures
/// (zrow-model's) keeps the same arithmetic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacePlane {
    /// Newell's normal.
    pub normal: [f64; 3],
    /// The centroid of the face's corners.
    pub centroid: [f64; 3],
    /// `|normal|²`.
    pub norm2: f64,
}

impl FacePlane {
    /// The plane of the face with vertex numbers `indices`, each corner from `vertex`; `None`
    /// if a corner is missing or the normal is zero or not finite.
    pub fn of<I: MeshIndex>(
        indices: &[I],
        vertex: impl Fn(usize) -> Option<[f64; 3]>,
    ) -> Option<Self> {
        let (mut n, mut c) = ([0.0f64; 3], [0.0f64; 3]);
        for (a, b) in face_edges(indices) {
            let (p, q) = (vertex(a)?, vertex(b)?);
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
            for (ck, pk) in c.iter_mut().zip(p) {
                *ck += pk / indices.len() as f64;
            }
        }
        let norm2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        (norm2 != 0.0 && norm2.is_finite()).then_some(FacePlane {
            normal: n,
            centroid: c,
            norm2,
        })
    }

    /// Whether `p` lies in front of the plane by more than `tolerance` (compared squared: no
    /// square root in the core).
    pub fn in_front(&self, p: [f64; 3], tolerance: f64) -> bool {
        let (n, c) = (self.normal, self.centroid);
        let dn = (p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1] + (p[2] - c[2]) * n[2];
        dn > 0.0 && dn * dn > tolerance * tolerance * self.norm2
    }
}

/// A face's directed edges `(a, b)` as vertex numbers, in order, the last closing the loop.
pub fn face_edges<I: MeshIndex>(f: &[I]) -> impl Iterator<Item = (usize, usize)> + '_ {
    f.iter()
        .zip(f.iter().cycle().skip(1))
        .map(|(&a, &b)| (a.index(), b.index()))
}
