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
        for (a, b) in edges(f.indices) {
            let (mut same, mut opposite) = (0, 0);
            for (gi, g) in mesh.faces.iter().enumerate() {
                for (c, d) in edges(g.indices) {
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
        // Newell's normal and the face's centroid.
        let (mut n, mut c) = ([0.0f64; 3], [0.0f64; 3]);
        for (a, b) in edges(f.indices) {
            let (Some(p), Some(q)) = (v(a), v(b)) else {
                return false;
            };
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
            for (ck, pk) in c.iter_mut().zip(p) {
                *ck += pk / f.indices.len() as f64;
            }
        }
        // No square root in core: compare d·|n| with tolerance·|n|, squared.
        let norm2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        if norm2 == 0.0 || !norm2.is_finite() {
            return false;
        }
        for p in mesh.vertices {
            let dn = (p.x.to_f64() - c[0]) * n[0]
                + (p.y.to_f64() - c[1]) * n[1]
                + (p.z.to_f64() - c[2]) * n[2];
            if dn > 0.0 && dn * dn > tolerance * tolerance * norm2 {
                return false;
            }
        }
    }
    true
}

/// A face's directed edges `(a, b)` as vertex numbers, in order, the last closing the loop.
fn edges<I: MeshIndex>(f: &[I]) -> impl Iterator<Item = (usize, usize)> + '_ {
    f.iter()
        .zip(f.iter().cycle().skip(1))
        .map(|(&a, &b)| (a.index(), b.index()))
}
