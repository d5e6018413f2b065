//! A precomputed BSP order for a static scene of convex solids (the BSP tree of Fuchs, Kedem &
//! Naylor 1980, Foley, van Dam, Feiner & Hughes §15.5.2), made cheap: the tree is built **once**, over whole objects, and each frame
//! only walks it.
//!
//! The BSP tree splits polygons by polygon planes so that, for any viewpoint, an in-order
//! walk paints far to near. When a static scene is made of separate closed convex solids, a
//! tree over the *objects* needs no split at all: a plane that leaves every object of a set
//! wholly on one side (a face plane of one of them, when one exists) divides the set, and the
//! viewer's side of each plane says which half to paint first. Within one convex solid, back
//! faces culled, no two faces overlap on screen ([`crate::cullonly`]). So painting the objects
//! in the walk's order, each by culling alone, is the whole of hidden-surface removal: no depth
//! test, no sort, no split — for any camera, as long as the objects do not move relative to
//! each other.
//!
//! - [`build`](crate::bsporder::build) (once, at start-up or on the build host; `O(K²·F·V)` for `K` objects) checks that
//!   every object is a closed convex solid ([`crate::structure::closed_convex`]) and finds the
//!   planes, or says why not ([`OrderError`](crate::bsporder::OrderError)).
//! - [`BspOrder::render`](crate::bsporder::BspOrder::render) takes the eye from the scene's camera, walks the tree (one plane test
//!   per node), reorders the scene's objects far to near and paints them with
//!   [`CullOnly`](crate::cullonly::CullOnly).
//!
//! **Exact** where objects do not touch: then, at any sample two objects share, the one on
//! the viewer's side of their separating plane is the nearer. (Touching objects meet at equal
//! depth, where the reference gives the sample to the object first in the scene and this order
//! to the nearer-sorted one.) RAM ([`BspOrder::RAM_BYTES`](crate::bsporder::BspOrder::RAM_BYTES)): the cull-only renderer's and room
//! for `K` object references.

use crate::error::{Error, RenderError};
use crate::method::FrameStats;
use crate::number::Scalar;
use crate::raster::Config;
use crate::scene::{MeshIndex, ModelScene, Object};
use crate::sink::RowSink;
use crate::structure::closed_convex;
use heapless::Vec;

/// A node of the precomputed order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OrderNode {
    /// A plane `a·x + b·y + c·z = d` (world space) with objects wholly on each side: `front`
    /// (where `a·x + b·y + c·z > d`) and `back`, as node indices.
    Split {
        /// `[a, b, c, d]`.
        plane: [f32; 4],
        /// Node of the objects in front.
        front: u16,
        /// Node of the objects behind.
        back: u16,
    },
    /// One object (its index in the scene's objects).
    Leaf(u16),
}

/// Why a scene has no precomputed order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrderError {
    /// Object `0` is not a closed convex solid.
    NotConvex(u16),
    /// No face plane separates the objects of some set (they may overlap, interlock, or need
    /// a plane that is no face's): the scene needs a depth-resolving method.
    NotSeparable,
    /// More objects or nodes than the capacity `K`, or no objects.
    Capacity,
}

/// Builds the order for `objects` (placed by their transforms, which must not change after):
/// every object a closed convex solid, every set divided by a face plane of one of its
/// objects. Nodes go to `out` (at most `2K − 1`); the root is node 0.
pub fn build<N: Scalar, I: MeshIndex, const K: usize>(
    objects: &[Object<'_, N, I>],
    out: &mut Vec<OrderNode, K>,
) -> Result<(), OrderError> {
    out.clear();
    if objects.is_empty() || objects.len() > K || objects.len() > u16::MAX as usize {
        return Err(OrderError::Capacity);
    }
    for (k, o) in objects.iter().enumerate() {
        if !closed_convex(o.mesh) {
            return Err(OrderError::NotConvex(k as u16));
        }
    }
    let mut set: Vec<u16, K> = (0..objects.len() as u16).collect();
    node(objects, &mut set, out)?;
    Ok(())
}

/// A world-space vertex of object `o`, in `f64`.
fn world<N: Scalar, I: MeshIndex>(o: &Object<'_, N, I>, i: usize) -> Option<[f64; 3]> {
    let v = o.transform.apply(o.mesh.vertices.get(i)?);
    Some([v.x.to_f64(), v.y.to_f64(), v.z.to_f64()])
}

/// Which side of `plane` object `o` lies on: `Some(true)` in front, `Some(false)` behind
/// (within `tol` of the plane counts as either), `None` if it straddles.
fn side<N: Scalar, I: MeshIndex>(o: &Object<'_, N, I>, plane: [f64; 4], tol: f64) -> Option<bool> {
    let (mut front, mut back) = (false, false);
    for i in 0..o.mesh.vertices.len() {
        let p = world(o, i)?;
        let d = plane[0] * p[0] + plane[1] * p[1] + plane[2] * p[2] - plane[3];
        front |= d > tol;
        back |= d < -tol;
    }
    match (front, back) {
        (true, true) => None,
        (f, _) => Some(f),
    }
}

/// Appends the subtree for the objects in `set` (reordered in place) and returns its index.
fn node<N: Scalar, I: MeshIndex, const K: usize>(
    objects: &[Object<'_, N, I>],
    set: &mut [u16],
    out: &mut Vec<OrderNode, K>,
) -> Result<u16, OrderError> {
    let at = out.len() as u16;
    if let [only] = set {
        out.push(OrderNode::Leaf(*only))
            .map_err(|_| OrderError::Capacity)?;
        return Ok(at);
    }
    let plane = separating_plane(objects, set).ok_or(OrderError::NotSeparable)?;
    // Reserve this node, then partition: front objects first.
    out.push(OrderNode::Leaf(0))
        .map_err(|_| OrderError::Capacity)?;
    let mut split = 0;
    for k in 0..set.len() {
        let o = objects.get(set[k] as usize).ok_or(OrderError::Capacity)?;
        if side(o, plane.0, plane.1) == Some(true) {
            set.swap(split, k);
            split += 1;
        }
    }
    let (front_set, back_set) = set.split_at_mut(split);
    let front = node(objects, front_set, out)?;
    let back = node(objects, back_set, out)?;
    let p = plane.0.map(|c| c as f32);
    if let Some(n) = out.get_mut(at as usize) {
        *n = OrderNode::Split {
            plane: p,
            front,
            back,
        };
    }
    Ok(at)
}

/// A face plane (outward normal, `f64`) of an object in `set` with every object of `set` on
/// one side and both sides occupied, and its tolerance.
fn separating_plane<N: Scalar, I: MeshIndex>(
    objects: &[Object<'_, N, I>],
    set: &[u16],
) -> Option<([f64; 4], f64)> {
    for &k in set {
        let o = objects.get(k as usize)?;
        let extent = (0..o.mesh.vertices.len())
            .filter_map(|i| world(o, i))
            .fold(0.0f64, |m, p| {
                m.max(p[0].abs()).max(p[1].abs()).max(p[2].abs())
            });
        for f in o.mesh.faces {
            let idx = f.indices;
            let (Some(a), Some(b), Some(c)) = (
                idx.first().and_then(|i| world(o, i.index())),
                idx.get(1).and_then(|i| world(o, i.index())),
                idx.get(2).and_then(|i| world(o, i.index())),
            ) else {
                continue;
            };
            let (u, v) = (sub(b, a), sub(c, a));
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            if len2 == 0.0 || !len2.is_finite() {
                continue;
            }
            // Unit normal without a square root in core: Newton on 1/sqrt, from f32's guess.
            let mut inv = 1.0 / (len2 as f32).sqrt_approx() as f64;
            for _ in 0..3 {
                inv *= 1.5 - 0.5 * len2 * inv * inv;
            }
            let n = n.map(|c| c * inv);
            let plane = [n[0], n[1], n[2], n[0] * a[0] + n[1] * a[1] + n[2] * a[2]];
            let tol = 1e-6 * extent.max(1e-30);
            let (mut front, mut back) = (0, 0);
            let ok = set.iter().all(|&j| {
                match objects.get(j as usize).and_then(|q| side(q, plane, tol)) {
                    Some(true) => {
                        front += 1;
                        true
                    }
                    Some(false) => {
                        back += 1;
                        true
                    }
                    None => false,
                }
            });
            if ok && front > 0 && back > 0 {
                return Some((plane, tol));
            }
        }
    }
    None
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `sqrt` for `f32` in `no_std` (micromath), to seed the Newton steps.
trait SqrtApprox {
    fn sqrt_approx(self) -> f32;
}
impl SqrtApprox for f32 {
    fn sqrt_approx(self) -> f32 {
        micromath::F32Ext::sqrt(self)
    }
}

/// The eye of a view transform `[R | t]` (world → camera, `R` a rotation): `−Rᵀ·t`.
fn eye<N: Scalar>(view: &crate::math::Affine<N>) -> [f64; 3] {
    let m = view.m.map(|r| r.map(|c| c.to_f64()));
    let mut e = [0.0; 3];
    for (i, ei) in e.iter_mut().enumerate() {
        *ei = -(m[0][i] * m[0][3] + m[1][i] * m[1][3] + m[2][i] * m[2][3]);
    }
    e
}

/// The precomputed-order renderer: the tree, and a cull-only renderer with rows of `W` pixels,
/// `P` polygons, `E` edges; `K` objects at most.
pub struct BspOrder<'t, N: Scalar, const W: usize, const P: usize, const E: usize, const K: usize> {
    tree: &'t [OrderNode],
    paint: crate::cullonly::CullOnly<N, W, P, E>,
}

impl<'t, N: Scalar, const W: usize, const P: usize, const E: usize, const K: usize>
    BspOrder<'t, N, W, P, E, K>
{
    /// Bytes of RAM the renderer occupies (the tree itself may live in flash).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// A renderer walking `tree` (from [`build`], root first).
    pub const fn new(tree: &'t [OrderNode]) -> Self {
        BspOrder {
            tree,
            paint: crate::cullonly::CullOnly::new(),
        }
    }

    /// The objects' order for the scene's camera, far to near (indices into its objects).
    pub fn order<I: MeshIndex>(&self, scene: &ModelScene<'_, N, I>) -> Result<Vec<u16, K>, Error> {
        let e = eye(&scene.camera.view);
        let mut order = Vec::new();
        // Explicit stack: (node, whether its far side is done). Depth < nodes ≤ 2K.
        let mut stack: Vec<(u16, bool), K> = Vec::new();
        let bad = Error::BadConfig;
        stack.push((0, false)).map_err(|_| bad)?;
        let mut steps = 0usize;
        while let Some((n, far_done)) = stack.pop() {
            steps += 1;
            if steps > 4 * self.tree.len() + 4 {
                return Err(bad); // a malformed tree (a cycle): never loop forever
            }
            match self.tree.get(n as usize).ok_or(bad)? {
                OrderNode::Leaf(k) => order.push(*k).map_err(|_| bad)?,
                OrderNode::Split { plane, front, back } => {
                    let d =
                        plane[0] as f64 * e[0] + plane[1] as f64 * e[1] + plane[2] as f64 * e[2]
                            - plane[3] as f64;
                    // The eye in front: the back objects are farther, painted first.
                    let (far, near) = if d > 0.0 {
                        (*back, *front)
                    } else {
                        (*front, *back)
                    };
                    if far_done {
                        stack.push((near, false)).map_err(|_| bad)?;
                    } else {
                        stack.push((n, true)).map_err(|_| bad)?;
                        stack.push((far, false)).map_err(|_| bad)?;
                    }
                }
            }
        }
        Ok(order)
    }

    /// Renders `scene` (its objects as given to [`build`]) and sends its rows, top to bottom,
    /// to `sink`. `cfg` must cull back faces (the order relies on it).
    pub fn render<I: MeshIndex, S: RowSink<N>>(
        &mut self,
        scene: &ModelScene<'_, N, I>,
        cfg: &Config,
        sink: &mut S,
    ) -> Result<FrameStats, RenderError<S::Error>> {
        if cfg.cull != crate::Cull::Back {
            return Err(Error::BadConfig.into());
        }
        let order = self.order(scene)?;
        let mut objects: Vec<Object<'_, N, I>, K> = Vec::new();
        for k in order {
            let o = scene.objects.get(k as usize).ok_or(Error::BadConfig)?;
            objects.push(*o).map_err(|_| Error::BadConfig)?;
        }
        if objects.len() != scene.objects.len() {
            return Err(Error::BadConfig.into());
        }
        let far_to_near = ModelScene {
            objects: &objects,
            camera: scene.camera,
            light: scene.light,
        };
        self.paint.render(&far_to_near, cfg, sink)
    }
}
