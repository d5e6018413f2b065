//! Whether a mesh is one closed convex solid, for meshes of any size.
//!
//! [`zrow::structure::closed_convex`] answers without allocating, for a microcontroller at
//! start-up: it compares every edge with every other and every vertex with every face, which
//! takes minutes from about 50,000 faces. [`closed_convex`] here gives the same answer with
//! memory: the directed edges in a hash map (`O(E)`), each edge's neighbour tested for a reflex
//! angle (`O(E)`, which rejects almost every mesh that is not convex), and then each face's
//! plane tested against a bounding-volume tree of the vertices, which visits only the boxes
//! that reach in front of the plane: about `O(F log V)` for a convex mesh.

use std::collections::HashMap;
use zrow::scene::{Mesh, MeshIndex};
use zrow::structure::{face_edges, FacePlane};
use zrow::Scalar;

/// Whether `mesh` is a closed convex solid with outward faces: the rule, the tolerance and the
/// arithmetic of [`zrow::structure::closed_convex`], in about `O(E + F log V)`.
pub fn closed_convex<N: Scalar, I: MeshIndex>(mesh: &Mesh<'_, N, I>) -> bool {
    let points: Vec<Option<[f64; 3]>> = mesh
        .vertices
        .iter()
        .map(|p| {
            let c = [p.x.to_f64(), p.y.to_f64(), p.z.to_f64()];
            c.iter().all(|x| x.is_finite()).then_some(c)
        })
        .collect();
    let v = |i: usize| points.get(i).copied().flatten();
    if mesh.faces.is_empty() {
        return false;
    }
    let mut extent: f64 = 0.0;
    for f in mesh.faces {
        if f.indices.len() < 3 {
            return false;
        }
        for &i in f.indices {
            let Some(c) = v(i.index()) else {
                return false;
            };
            extent = c.iter().fold(extent, |m, x| m.max(x.abs()));
        }
    }
    // Closed and consistently oriented: every directed edge once, its opposite once.
    let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        for (a, b) in face_edges(f.indices) {
            if a == b || edges.insert((a, b), fi as u32).is_some() {
                return false;
            }
        }
    }
    if edges.keys().any(|&(a, b)| !edges.contains_key(&(b, a))) {
        return false;
    }
    let tolerance = 1e-9 * extent.max(f64::MIN_POSITIVE);
    let planes: Option<Vec<FacePlane>> = mesh
        .faces
        .iter()
        .map(|f| FacePlane::of(f.indices, v))
        .collect();
    let Some(planes) = planes else {
        return false;
    };
    let in_front = |plane: &FacePlane, p: [f64; 3]| plane.in_front(p, tolerance);
    // A reflex edge: the neighbour's corners in front of the face's plane.
    for (&(a, b), &fi) in &edges {
        let g = edges[&(b, a)] as usize;
        let plane = &planes[fi as usize];
        if mesh.faces.get(g).is_some_and(|f| {
            f.indices
                .iter()
                .any(|&k| v(k.index()).is_some_and(|p| in_front(plane, p)))
        }) {
            return false;
        }
    }
    // Every vertex behind every face's plane.
    let tree = Tree::new(points.iter().flatten().copied().collect());
    planes.iter().all(|plane| {
        let threshold = 0.5 * tolerance * plane.norm2.sqrt();
        !tree.any_beyond(plane, threshold, |p| in_front(plane, p))
    })
}

/// Points in a bounding-box tree: each node a box and a range of `points`, split at the median
/// of its longest side down to [`LEAF`] points.
struct Tree {
    points: Vec<[f64; 3]>,
    nodes: Vec<Node>,
}

struct Node {
    lo: [f64; 3],
    hi: [f64; 3],
    range: (usize, usize),
    /// The two children's indices, if split.
    children: Option<(usize, usize)>,
}

const LEAF: usize = 8;

impl Tree {
    fn new(mut points: Vec<[f64; 3]>) -> Self {
        let mut nodes = Vec::new();
        if !points.is_empty() {
            let n = points.len();
            Self::build(&mut points, 0, n, &mut nodes);
        }
        Tree { points, nodes }
    }

    fn build(points: &mut [[f64; 3]], start: usize, end: usize, nodes: &mut Vec<Node>) -> usize {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in &points[start..end] {
            for k in 0..3 {
                (lo[k], hi[k]) = (lo[k].min(p[k]), hi[k].max(p[k]));
            }
        }
        let me = nodes.len();
        nodes.push(Node {
            lo,
            hi,
            range: (start, end),
            children: None,
        });
        if end - start > LEAF {
            let axis = (0..3)
                .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
                .unwrap_or(0);
            let mid = (start + end) / 2;
            points[start..end]
                .select_nth_unstable_by(mid - start, |p, q| p[axis].total_cmp(&q[axis]));
            let left = Self::build(points, start, mid, nodes);
            let right = Self::build(points, mid, end, nodes);
            nodes[me].children = Some((left, right));
        }
        me
    }

    /// Whether a point for which `test` holds lies in a box reaching farther than `threshold`
    /// in front of `plane` (boxes that do not are skipped: their points cannot pass a test
    /// asking for more than that).
    fn any_beyond(
        &self,
        plane: &FacePlane,
        threshold: f64,
        test: impl Fn([f64; 3]) -> bool,
    ) -> bool {
        let mut stack = Vec::with_capacity(64);
        if !self.nodes.is_empty() {
            stack.push(0);
        }
        while let Some(i) = stack.pop() {
            let node = &self.nodes[i];
            let reach: f64 = (0..3)
                .map(|k| {
                    let (a, b) = (
                        node.lo[k] - plane.centroid[k],
                        node.hi[k] - plane.centroid[k],
                    );
                    (a * plane.normal[k]).max(b * plane.normal[k])
                })
                .sum();
            if reach <= threshold {
                continue;
            }
            match node.children {
                Some((l, r)) => stack.extend([l, r]),
                None => {
                    if self.points[node.range.0..node.range.1]
                        .iter()
                        .any(|&p| test(p))
                    {
                        return true;
                    }
                }
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use zrow::pixelcolor::Rgb565;
    use zrow::{Face, Vec3};

    fn mesh_check(points: &[[f32; 3]], faces: &[&[u32]]) -> (bool, bool) {
        let v: Vec<Vec3<f32>> = points.iter().map(|&p| Vec3::from_f32(p).unwrap()).collect();
        let f: Vec<Face<'_, u32>> = faces
            .iter()
            .map(|&indices| Face {
                indices,
                color: Rgb565::new(1, 2, 3),
                alpha: 255,
            })
            .collect();
        let mesh = Mesh::new(&v, &f);
        (closed_convex(&mesh), zrow::structure::closed_convex(&mesh))
    }

    const CUBE: [[f32; 3]; 8] = [
        [-1., -1., -1.],
        [1., -1., -1.],
        [1., 1., -1.],
        [-1., 1., -1.],
        [-1., -1., 1.],
        [1., -1., 1.],
        [1., 1., 1.],
        [-1., 1., 1.],
    ];
    const CUBE_FACES: [&[u32]; 6] = [
        &[0, 3, 2, 1],
        &[4, 5, 6, 7],
        &[0, 1, 5, 4],
        &[2, 3, 7, 6],
        &[1, 2, 6, 5],
        &[0, 4, 7, 3],
    ];

    #[test]
    fn agrees_with_the_core_on_small_meshes() {
        // A cube: closed and convex.
        assert_eq!(mesh_check(&CUBE, &CUBE_FACES), (true, true));
        // Open: one face gone.
        assert_eq!(mesh_check(&CUBE, &CUBE_FACES[1..]), (false, false));
        // One face turned inside out.
        let mut flipped = CUBE_FACES;
        flipped[0] = &[0, 1, 2, 3];
        assert_eq!(mesh_check(&CUBE, &flipped), (false, false));
        // A corner pushed in: closed, no longer convex (split the faces at it into triangles).
        let mut dented = CUBE;
        dented[6] = [0.2, 0.2, 0.2];
        let tri: [&[u32]; 12] = [
            &[0, 3, 2],
            &[0, 2, 1],
            &[4, 5, 6],
            &[4, 6, 7],
            &[0, 1, 5],
            &[0, 5, 4],
            &[2, 3, 7],
            &[2, 7, 6],
            &[1, 2, 6],
            &[1, 6, 5],
            &[0, 4, 7],
            &[0, 7, 3],
        ];
        assert_eq!(mesh_check(&dented, &tri), (false, false));
        assert_eq!(mesh_check(&CUBE, &tri), (true, true));
        // A face used twice.
        let twice = [CUBE_FACES[0], CUBE_FACES[0]];
        assert_eq!(mesh_check(&CUBE, &twice), (false, false));
    }

    /// A UV sphere of `n` bands; `bump` moves one vertex off it by that fraction of the
    /// radius. (In `f32` the sphere's vertices are rounded, so whether it passes the check's
    /// tolerance is a matter of rounding: what matters is that both checks say the same.)
    fn sphere(n: usize, bump: f32) -> (Vec<[f32; 3]>, Vec<Vec<u32>>) {
        let m = 2 * n;
        let mut points = vec![[0.0, 1.0, 0.0]];
        for i in 1..n {
            let t = std::f32::consts::PI * i as f32 / n as f32;
            for j in 0..m {
                let p = 2.0 * std::f32::consts::PI * j as f32 / m as f32;
                points.push([t.sin() * p.cos(), t.cos(), -t.sin() * p.sin()]);
            }
        }
        points.push([0.0, -1.0, 0.0]);
        let ring = |i: usize, j: usize| (1 + (i - 1) * m + j % m) as u32;
        let bottom = points.len() as u32 - 1;
        let mut faces = Vec::new();
        for j in 0..m {
            faces.push(vec![0, ring(1, j), ring(1, j + 1)]);
            faces.push(vec![bottom, ring(n - 1, j + 1), ring(n - 1, j)]);
        }
        for i in 1..n - 1 {
            for j in 0..m {
                faces.push(vec![ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)]);
                faces.push(vec![ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
            }
        }
        let k = points.len() / 2;
        points[k] = points[k].map(|c| c * (1.0 + bump));
        (points, faces)
    }

    /// A cube `[0, k]³` whose sides are `k × k` grids of triangles: integer corners, so it is
    /// exactly convex in `f32`. `dent` moves the middle vertex of the top side by that much
    /// along y (up: a bump, down: a dent).
    fn grid_cube(k: u32, dent: f32) -> (Vec<[f32; 3]>, Vec<Vec<u32>>) {
        let mut index: HashMap<[u32; 3], u32> = HashMap::new();
        let (mut points, mut faces) = (Vec::new(), Vec::new());
        let mut at = |p: [u32; 3]| {
            *index.entry(p).or_insert_with(|| {
                points.push(p.map(|c| c as f32));
                points.len() as u32 - 1
            })
        };
        // Each side: a fixed axis and value, two running axes in counter-clockwise order seen
        // from outside.
        for (axis, value, u, v) in [
            (0, 0, 2, 1),
            (0, k, 1, 2),
            (1, 0, 0, 2),
            (1, k, 2, 0),
            (2, 0, 1, 0),
            (2, k, 0, 1),
        ] {
            for i in 0..k {
                for j in 0..k {
                    let p = |di: u32, dj: u32| {
                        let mut c = [0; 3];
                        (c[axis], c[u], c[v]) = (value, i + di, j + dj);
                        c
                    };
                    let (a, b, c, d) = (at(p(0, 0)), at(p(1, 0)), at(p(1, 1)), at(p(0, 1)));
                    faces.push(vec![a, b, c]);
                    faces.push(vec![a, c, d]);
                }
            }
        }
        let middle = index[&[k / 2, k, k / 2]] as usize;
        points[middle][1] += dent;
        (points, faces)
    }

    #[test]
    fn agrees_with_the_core_on_spheres_and_grid_cubes() {
        for (n, bump) in [(6, 0.0), (12, 0.0), (12, 0.02), (12, -0.02)] {
            let (points, faces) = sphere(n, bump);
            let faces: Vec<&[u32]> = faces.iter().map(|f| &f[..]).collect();
            let (host, core) = mesh_check(&points, &faces);
            assert_eq!(host, core, "sphere n {n} bump {bump}");
        }
        for (dent, want) in [(0.0, true), (0.5, false), (-0.5, false)] {
            let (points, faces) = grid_cube(4, dent);
            let faces: Vec<&[u32]> = faces.iter().map(|f| &f[..]).collect();
            assert_eq!(mesh_check(&points, &faces), (want, want), "dent {dent}");
        }
    }

    #[test]
    fn the_box_tree_finds_what_a_scan_of_every_point_finds() {
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let points: Vec<[f64; 3]> = (0..2000).map(|_| [next(), next(), next()]).collect();
        let tree = Tree::new(points.clone());
        let mut found = 0;
        for _ in 0..500 {
            let n = [next(), next(), next()];
            let c = [next(), next(), next()].map(|x| x * 1.5);
            let plane = FacePlane {
                normal: n,
                centroid: c,
                norm2: n.iter().map(|x| x * x).sum(),
            };
            let threshold = 0.3 * plane.norm2.sqrt();
            let test =
                |p: [f64; 3]| (0..3).map(|k| (p[k] - c[k]) * n[k]).sum::<f64>() > 2.0 * threshold;
            let want = points.iter().any(|&p| test(p));
            assert_eq!(tree.any_beyond(&plane, threshold, test), want);
            found += usize::from(want);
        }
        // Both answers occur.
        assert!(found > 50 && found < 450, "{found}");
    }

    #[test]
    fn answers_for_a_large_mesh() {
        // 120,000 triangles: the core's pairwise check would compare 360,000 edges with each
        // other; this is the same answer from a hash map and a box tree.
        for (dent, want) in [(0.0, true), (-0.5, false)] {
            let (points, faces) = grid_cube(100, dent);
            assert_eq!(faces.len(), 120_000);
            let v: Vec<Vec3<f32>> = points.iter().map(|&p| Vec3::from_f32(p).unwrap()).collect();
            let f: Vec<Face<'_, u32>> = faces
                .iter()
                .map(|i| Face {
                    indices: i,
                    color: Rgb565::new(1, 2, 3),
                    alpha: 255,
                })
                .collect();
            assert_eq!(closed_convex(&Mesh::new(&v, &f)), want, "dent {dent}");
        }
    }
}
