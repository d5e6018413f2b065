//! Per-vertex normals for smooth shading: one unit normal per vertex, the mesh's vertices split
//! where a vertex needs more than one.
//!
//! Smooth (Gouraud) shading lights each vertex with its own normal and interpolates between
//! them (Gouraud 1971; Foley & van Dam §16.2.4). A mesh's vertices have no normal of their own
//! unless the file gives them, so they come from one of two places:
//!
//! - **The file's normals** ([`from_corners`]): an OBJ's `vn`, one per face corner. A vertex
//!   whose corners carry different normals is split into one vertex per normal.
//! - **The faces around the vertex** ([`from_faces`]), with a **crease angle**: two faces that
//!   share an edge are smooth across it when their normals are at most the crease angle apart,
//!   else the edge is a crease and stays sharp (as is an edge three or more faces share). Around each vertex, the faces joined through
//!   smooth edges form a fan that shares one normal: the sum of the fan's unit face normals,
//!   each weighted by the face's angle at the vertex (Thürmer & Wüthrich 1998: the result does
//!   not depend on how a surface is cut into triangles), made unit length. A vertex with k
//!   fans is split into k vertices. A cube at a 45° crease has 24 vertices, each with its
//!   face's normal; at 100° its 8 corners point along the diagonals; a finely divided sphere
//!   or torus keeps every vertex, each normal close to the surface's.
//!
//! Face normals are Newell's (exact for planar polygons, a least-squares fit otherwise), in
//! `f64`. A face of zero area has no normal: it joins no fan, and its corners take their
//! vertex's first fan's normal (the zero vector if the vertex has no other face). The result
//! depends only on the input, in face order (vertices are numbered in order of first use), so
//! converting a model twice emits the same data.

use std::collections::HashMap;

/// A crease angle that keeps a cube's edges sharp (90°) and smooths a sphere or torus cut into
/// a few hundred faces (neighbouring normals 10° to 20° apart), degrees.
pub const DEFAULT_CREASE_DEGREES: f64 = 45.0;

/// A mesh with one normal per vertex: vertices split where one needed several normals.
#[derive(Clone, Debug, PartialEq)]
pub struct VertexNormals {
    /// For each vertex, the input vertex it is a copy of.
    pub source: Vec<u32>,
    /// For each vertex, its unit normal (the zero vector where no face around it has an area).
    pub normals: Vec<[f64; 3]>,
    /// The faces, in input order, their corners renumbered to these vertices.
    pub faces: Vec<Vec<u32>>,
}

type P3 = [f64; 3];

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(v: P3) -> Option<P3> {
    let len = dot(v, v).sqrt();
    (len > 0.0 && len.is_finite()).then(|| v.map(|c| c / len))
}

/// Newell's normal of a polygon, not normalised (twice the area long for a planar one).
pub(crate) fn newell(points: &[P3]) -> P3 {
    let mut n = [0.0; 3];
    for (k, p) in points.iter().enumerate() {
        let q = points[(k + 1) % points.len()];
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    n
}

/// Newell's normal of a polygon, unit length (`None`: zero area).
fn face_normal(points: &[P3]) -> Option<P3> {
    unit(newell(points))
}

/// The angle of a polygon at `at` between its neighbours `prev` and `next`, radians (0 when
/// an edge has zero length).
fn corner_angle(prev: P3, at: P3, next: P3) -> f64 {
    match (unit(sub(prev, at)), unit(sub(next, at))) {
        (Some(a), Some(b)) => dot(a, b).clamp(-1.0, 1.0).acos(),
        _ => 0.0,
    }
}

/// Union-find over a vertex's corners (a few each), with path halving.
fn root(parent: &mut [usize], mut k: usize) -> usize {
    while parent[k] != k {
        parent[k] = parent[parent[k]];
        k = parent[k];
    }
    k
}

/// Vertex normals from the faces, smooth across edges where the faces' normals are at most
/// `crease_degrees` apart (see the module doc). Corners that index no position are left out
/// of every fan (the face keeps them, with a zero normal).
///
/// ```
/// use zrow_model::vertex_normals::from_faces;
/// // A unit cube: 8 corners, 6 quads counter-clockwise from outside.
/// let p = |i: u32| [(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64];
/// let positions: Vec<[f64; 3]> = (0..8).map(p).collect();
/// let faces: Vec<&[u32]> = vec![
///     &[0, 2, 3, 1], &[4, 5, 7, 6], &[0, 1, 5, 4], &[2, 6, 7, 3], &[0, 4, 6, 2], &[1, 3, 7, 5],
/// ];
/// let sharp = from_faces(&positions, &faces, 45.0);
/// assert_eq!(sharp.normals.len(), 24); // every corner its face's normal
/// let round = from_faces(&positions, &faces, 100.0);
/// assert_eq!(round.normals.len(), 8); // every corner along its diagonal
/// let d = 1.0 / 3f64.sqrt();
/// assert!(round.normals[0].iter().all(|&c| (c + d).abs() < 1e-12));
/// ```
pub fn from_faces(positions: &[[f64; 3]], faces: &[&[u32]], crease_degrees: f64) -> VertexNormals {
    let at = |i: u32| positions.get(i as usize).copied();
    let normals: Vec<Option<P3>> = faces
        .iter()
        .map(|f| {
            let points: Option<Vec<P3>> = f.iter().map(|&i| at(i)).collect();
            points.and_then(|p| face_normal(&p))
        })
        .collect();
    let cos_crease = crease_degrees.to_radians().cos();
    // Every corner, by vertex: (face, position in the face).
    let mut corners: Vec<Vec<(u32, u32)>> = vec![Vec::new(); positions.len()];
    for (f, face) in faces.iter().enumerate() {
        for (k, &v) in face.iter().enumerate() {
            if let Some(list) = corners.get_mut(v as usize) {
                list.push((f as u32, k as u32));
            }
        }
    }
    // Each corner's fan, by (face, position in the face).
    let mut corner_fan: HashMap<(u32, u32), u32> = HashMap::new();
    let mut fan_sum: Vec<P3> = Vec::new();
    for (v, list) in corners.iter().enumerate() {
        // Neighbours across the two edges at each corner; corners whose faces share an edge
        // through `v` (the same neighbour) and whose normals are within the crease join.
        let neighbours = |&(f, k): &(u32, u32)| {
            let face = faces[f as usize];
            let n = face.len();
            let k = k as usize;
            [face[(k + n - 1) % n], face[(k + 1) % n]]
        };
        let mut parent: Vec<usize> = (0..list.len()).collect();
        let mut by_neighbour: HashMap<u32, Vec<usize>> = HashMap::new();
        for (c, corner) in list.iter().enumerate() {
            for w in neighbours(corner) {
                if w as usize != v {
                    by_neighbour.entry(w).or_default().push(c);
                }
            }
        }
        // An edge is smooth only between exactly two faces (a manifold edge): an edge that
        // more faces share is a crease, which also keeps this linear in the corners whatever
        // the file (the partition does not depend on the order the edges are visited in).
        for sharing in by_neighbour.values() {
            if let [a, b] = sharing[..] {
                let (na, nb) = (normals[list[a].0 as usize], normals[list[b].0 as usize]);
                if let (Some(na), Some(nb)) = (na, nb) {
                    if dot(na, nb) >= cos_crease {
                        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                        parent[ra.max(rb)] = ra.min(rb);
                    }
                }
            }
        }
        // One fan per root, numbered in corner order; sums weighted by the corner angles.
        let mut fan_of_root: HashMap<usize, u32> = HashMap::new();
        let mut first_fan = None;
        for (c, &(f, k)) in list.iter().enumerate() {
            let Some(n) = normals[f as usize] else {
                continue;
            };
            let r = root(&mut parent, c);
            let fan = *fan_of_root.entry(r).or_insert_with(|| {
                fan_sum.push([0.0; 3]);
                fan_sum.len() as u32 - 1
            });
            first_fan.get_or_insert(fan);
            let face = faces[f as usize];
            let [prev, next] = neighbours(&(f, k));
            let w = match (at(prev), at(face[k as usize]), at(next)) {
                (Some(a), Some(b), Some(c)) => corner_angle(a, b, c),
                _ => 0.0,
            };
            let s = &mut fan_sum[fan as usize];
            for a in 0..3 {
                s[a] += w * n[a];
            }
            corner_fan.insert((f, k), fan);
        }
        // Zero-area faces take the vertex's first fan, or none.
        for &(f, k) in list {
            if normals[f as usize].is_none() {
                let fan = first_fan.unwrap_or_else(|| {
                    fan_sum.push([0.0; 3]);
                    fan_sum.len() as u32 - 1
                });
                first_fan = Some(fan);
                corner_fan.insert((f, k), fan);
            }
        }
    }
    let fan_normal: Vec<P3> = fan_sum
        .iter()
        .map(|&s| unit(s).unwrap_or([0.0; 3]))
        .collect();
    // Vertices in order of first use: one per fan met.
    let mut out = VertexNormals {
        source: Vec::new(),
        normals: Vec::new(),
        faces: Vec::with_capacity(faces.len()),
    };
    let mut vertex_of_fan: HashMap<u32, u32> = HashMap::new();
    let mut vertex_of_stray: HashMap<u32, u32> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        let mut renumbered = Vec::with_capacity(face.len());
        for (k, &v) in face.iter().enumerate() {
            let key = corner_fan.get(&(f as u32, k as u32)).copied();
            let (map, id) = match key {
                Some(fan) => (&mut vertex_of_fan, fan),
                None => (&mut vertex_of_stray, v), // a corner indexing no position
            };
            let next = out.source.len() as u32;
            let new = *map.entry(id).or_insert_with(|| {
                out.source.push(v);
                out.normals
                    .push(key.map_or([0.0; 3], |fan| fan_normal[fan as usize]));
                next
            });
            renumbered.push(new);
        }
        out.faces.push(renumbered);
    }
    out
}

/// Vertex normals given per face corner (an OBJ's `vn`): `corner_normals[f][k]` is the normal
/// of corner `k` of face `f`, made unit length here (a zero or non-finite one becomes the zero
/// vector). A vertex is split into one vertex per distinct normal among its corners.
///
/// ```
/// use zrow_model::vertex_normals::from_corners;
/// let faces: Vec<&[u32]> = vec![&[0, 1, 2], &[0, 2, 3]];
/// let up = [0.0, 0.0, 2.0];
/// let tilted = [0.0, 1.0, 1.0];
/// let (first, second) = ([up, up, up], [tilted, up, up]);
/// let v = from_corners(&faces, &[&first, &second]);
/// assert_eq!(v.source, [0, 1, 2, 0, 3]); // vertex 0 has two normals
/// assert_eq!(v.normals[0], [0.0, 0.0, 1.0]);
/// assert_eq!(v.faces[1], [3, 2, 4]);
/// ```
pub fn from_corners(faces: &[&[u32]], corner_normals: &[&[[f64; 3]]]) -> VertexNormals {
    let mut out = VertexNormals {
        source: Vec::new(),
        normals: Vec::new(),
        faces: Vec::with_capacity(faces.len()),
    };
    let mut vertex_of: HashMap<(u32, [u64; 3]), u32> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        let given = corner_normals.get(f).copied().unwrap_or(&[]);
        let mut renumbered = Vec::with_capacity(face.len());
        for (k, &v) in face.iter().enumerate() {
            let n = given.get(k).and_then(|&n| unit(n)).unwrap_or([0.0; 3]);
            let next = out.source.len() as u32;
            let new = *vertex_of
                .entry((v, n.map(f64::to_bits)))
                .or_insert_with(|| {
                    out.source.push(v);
                    out.normals.push(n);
                    next
                });
            renumbered.push(new);
        }
        out.faces.push(renumbered);
    }
    out
}

/// A model's vertex normals: the file's own ([`from_corners`]) when every face corner has one
/// (`corners[f][k]` indexes `normals`), else [`from_faces`] with `crease_degrees`; and whether
/// they are the file's.
pub fn from_file_or_faces(
    positions: &[[f64; 3]],
    faces: &[&[u32]],
    normals: &[[f32; 3]],
    corners: &[&[u32]],
    crease_degrees: f64,
) -> (VertexNormals, bool) {
    let given = !normals.is_empty()
        && faces.len() == corners.len()
        && faces.iter().zip(corners).all(|(f, c)| f.len() == c.len());
    if !given {
        return (from_faces(positions, faces, crease_degrees), false);
    }
    let at = |n: u32| {
        normals
            .get(n as usize)
            .map_or([0.0; 3], |n| n.map(f64::from))
    };
    let corners: Vec<Vec<P3>> = corners
        .iter()
        .map(|c| c.iter().map(|&n| at(n)).collect())
        .collect();
    let corners: Vec<&[P3]> = corners.iter().map(|c| &c[..]).collect();
    (from_corners(faces, &corners), true)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A torus of `n × m` quads (major radius 1, minor 0.4), counter-clockwise from outside,
    /// with each vertex's exact surface normal.
    fn torus(n: u32, m: u32) -> (Vec<P3>, Vec<[u32; 4]>, Vec<P3>) {
        let (mut p, mut normal, mut faces) = (Vec::new(), Vec::new(), Vec::new());
        for i in 0..n {
            for j in 0..m {
                let (u, w) = (
                    i as f64 * std::f64::consts::TAU / n as f64,
                    j as f64 * std::f64::consts::TAU / m as f64,
                );
                let r = 1.0 + 0.4 * w.cos();
                p.push([r * u.cos(), r * u.sin(), 0.4 * w.sin()]);
                normal.push([w.cos() * u.cos(), w.cos() * u.sin(), w.sin()]);
                let at = |a: u32, b: u32| (a % n) * m + b % m;
                faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        (p, faces, normal)
    }

    #[test]
    fn a_smooth_torus_keeps_its_vertices_and_the_surface_normals() {
        let (p, quads, exact) = torus(25, 20);
        // As quads and as triangles (each quad cut along a diagonal): the angle weights give
        // the same normals either way.
        let tris: Vec<[u32; 3]> = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        let as_quads: Vec<&[u32]> = quads.iter().map(|q| &q[..]).collect();
        let as_tris: Vec<&[u32]> = tris.iter().map(|t| &t[..]).collect();
        for faces in [as_quads, as_tris] {
            let v = from_faces(&p, &faces, DEFAULT_CREASE_DEGREES);
            assert_eq!(v.normals.len(), p.len());
            let mut worst: f64 = 0.0;
            for (k, n) in v.normals.iter().enumerate() {
                let e = exact[v.source[k] as usize];
                worst = worst.max(dot(*n, e).clamp(-1.0, 1.0).acos().to_degrees());
                assert!((dot(*n, *n) - 1.0).abs() < 1e-12);
            }
            // Faces 14.4° x 18° apart: the averaged normals within a degree of the surface's.
            assert!(worst < 1.0, "{worst}°");
            // Renumbered faces point at copies of the same positions.
            for (f, face) in v.faces.iter().enumerate() {
                let src: Vec<u32> = face.iter().map(|&i| v.source[i as usize]).collect();
                assert_eq!(src, faces[f]);
            }
        }
        // A crease below every pair of neighbours' angle (at least 2.2°, near the top and
        // bottom circles) makes every face flat: one vertex per corner.
        let flat = from_faces(&p, &quads.iter().map(|q| &q[..]).collect::<Vec<_>>(), 1.0);
        assert_eq!(flat.normals.len(), 4 * quads.len());
    }

    #[test]
    fn a_cylinder_keeps_its_rim_sharp_and_its_side_smooth() {
        // 16 side quads and two 16-gon caps.
        let n = 16u32;
        let mut p = Vec::new();
        for z in [0.0, 1.0] {
            for i in 0..n {
                let a = i as f64 * std::f64::consts::TAU / n as f64;
                p.push([a.cos(), a.sin(), z]);
            }
        }
        let side: Vec<[u32; 4]> = (0..n)
            .map(|i| [i, (i + 1) % n, n + (i + 1) % n, n + i])
            .collect();
        let bottom: Vec<u32> = (0..n).rev().collect();
        let top: Vec<u32> = (n..2 * n).collect();
        let mut faces: Vec<&[u32]> = side.iter().map(|q| &q[..]).collect();
        faces.push(&bottom);
        faces.push(&top);
        let v = from_faces(&p, &faces, DEFAULT_CREASE_DEGREES);
        // Each rim vertex: one side copy (radial normal) and one cap copy (axial).
        assert_eq!(v.normals.len(), 4 * n as usize);
        for (k, nrm) in v.normals.iter().enumerate() {
            let q = p[v.source[k] as usize];
            let radial = [q[0], q[1], 0.0];
            let axial = [0.0, 0.0, if q[2] > 0.5 { 1.0 } else { -1.0 }];
            let close = |a: P3, b: P3| (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12);
            assert!(close(*nrm, radial) || close(*nrm, axial), "{k}: {nrm:?}");
        }
    }

    /// Many faces on one edge (a non-manifold fan of flaps, all nearly coplanar): the edge is
    /// a crease, so each flap keeps its own normal, and the work stays linear in the faces.
    #[test]
    fn an_edge_of_many_faces_is_a_crease() {
        let n = 20_000u32;
        let mut p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let mut tris = Vec::new();
        for k in 0..n {
            let a = k as f64 * 1e-6;
            p.push([0.5, a.cos(), a.sin()]);
            tris.push([0, 1, k + 2]);
        }
        let faces: Vec<&[u32]> = tris.iter().map(|t| &t[..]).collect();
        let v = from_faces(&p, &faces, DEFAULT_CREASE_DEGREES);
        assert_eq!(v.normals.len(), 3 * n as usize);
        // Two flaps alone on the edge are smooth across it.
        let v = from_faces(&p, &faces[..2], DEFAULT_CREASE_DEGREES);
        assert_eq!(v.normals.len(), 4);
    }

    #[test]
    fn degenerate_and_stray_corners_never_panic() {
        let p = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
        ];
        // A real triangle, a zero-area one sharing vertex 0, an isolated zero-area one on 1,3,
        // and one corner beyond the positions.
        let faces: Vec<&[u32]> = vec![&[0, 1, 2], &[0, 1, 3], &[1, 3, 3], &[0, 2, 9]];
        let v = from_faces(&p, &faces, 45.0);
        assert_eq!(v.faces.len(), 4);
        // The zero-area face's corner at 0 shares the triangle's normal.
        assert_eq!(v.faces[1][0], v.faces[0][0]);
        assert_eq!(v.normals[v.faces[0][0] as usize], [0.0, 0.0, 1.0]);
        // The stray corner is kept, with a zero normal.
        assert_eq!(v.source[v.faces[3][2] as usize], 9);
        assert_eq!(v.normals[v.faces[3][2] as usize], [0.0; 3]);
        assert!(v.normals.iter().all(|n| n.iter().all(|c| c.is_finite())));
        // Nothing at all.
        assert_eq!(from_faces(&[], &[], 45.0).normals.len(), 0);
    }
}
