//! The BSP tree (Fuchs, Kedem & Naylor 1980; Foley, van Dam, Feiner & Hughes §15.5.2).
//!
//! The algorithm. **Build:** choose a polygon; its plane divides space in two; sort
//! the remaining polygons into those in front of it and those behind (by substituting their
//! points in its plane equation); a polygon on both sides is split into two; redo this on each
//! side until every subspace holds one polygon. **Render:** for a viewpoint V, at each node:
//! if V is in front of the node's plane, draw the subtree behind, then the node, then the
//! subtree in front; if V is behind, the reverse. Painting in that order is correct for any V.
//! Back-face culling comes free on the way: a node whose plane has V behind it faces away, so
//! it is not drawn (its subtrees still are).
//!
//! Here the tree is built by inserting the polygons one at a time in scene order: each one
//! descends from the root, going to the side of each node's plane it lies on, and is split
//! where it straddles one; it becomes a node where it reaches an empty side. That is the
//! textbook's recursive build with the first polygon of each subspace as the chosen one.
//!
//! The tree is built over the frame's projected polygons, in screen space: perspective maps
//! planes to planes and keeps sides, so it is a BSP tree of the view, and the viewpoint is at
//! z = −∞ (screen space: smaller z is nearer). A polygon's front side is
//! the viewer's side when it faces the viewer (counter-clockwise on the display), the far side
//! when it does not. A static scene's tree could be built once in world space and reused for
//! every view; here the scenes move, so the tree is rebuilt per frame.
//!
//! Made exact as depth-sort is ([`crate::split`]): "in front of the plane" is decided per
//! sample by [`PolygonTable::beats`](crate::polygons::PolygonTable::beats) (ties to the polygon first in the scene), and splits are
//! sample sets, not new vertices. Then, for two pieces on opposite sides of a node, the one on
//! the viewer's side is nearer at every sample they share, so the in-order walk paints exactly
//! the per-sample nearest surface.
//!
//! Bounds: the tree's depth is below `D` (deeper is a typed [`Table::BspDepth`](crate::Table::BspDepth) error, and
//! both the insertion and the walk use explicit stacks of that size — no recursion), pieces at
//! most `Q`. Inserting a closed mesh in its own order makes a deep tree (each face lies in
//! front of the ones before it): the 1,000-face torus needs a depth in the hundreds. Every
//! error comes before the first row. Rows are then painted from the order into one row
//! buffer and leave top to bottom.

use crate::error::{Error, RenderError, Table};
use crate::method::{FrameStats, Renderer};
use crate::number::Scalar;
use crate::polygons::PolygonTable;
use crate::raster::{Config, Cull};
use crate::scene::Scene;
use crate::sink::RowSink;
use crate::split::{paint_rows, Pieces, NONE};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use heapless::Vec;

/// A node of the tree: a piece and the subtrees on either side of its polygon's plane.
#[derive(Clone, Copy, Debug)]
struct Node {
    piece: u16,
    /// Subtree on the side the polygon faces ([`NONE`] if empty).
    front: u16,
    /// Subtree on the other side.
    back: u16,
}

/// The BSP renderer: rows of `W` pixels, `P` polygons, `E` edges, `Q` pieces (polygons plus
/// the parts splitting makes; also the node capacity), tree depth below `D`.
pub struct Bsp<
    N: Scalar,
    const W: usize,
    const P: usize,
    const E: usize,
    const Q: usize,
    const D: usize,
> {
    table: PolygonTable<N, P, E>,
    pieces: Pieces<N, Q>,
    nodes: Vec<Node, Q>,
    /// Pieces waiting to descend further: (piece, node, depth of that node).
    pending: Vec<(u16, u16, u16), D>,
    /// The in-order walk's stack: (node, whether its first subtree is done).
    walk: Vec<(u16, bool), D>,
    /// Paint order, farthest first.
    order: Vec<u16, Q>,
    depth: [N; W],
    intensity: [Rgb565; W],
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const Q: usize, const D: usize>
    Default for Bsp<N, W, P, E, Q, D>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const Q: usize, const D: usize>
    Bsp<N, W, P, E, Q, D>
{
    /// Bytes of RAM the renderer occupies.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer.
    pub const fn new() -> Self {
        const { assert!(Q < NONE as usize, "piece capacity must be below 65535") };
        Bsp {
            table: PolygonTable::new(),
            pieces: Pieces::new(),
            nodes: Vec::new(),
            pending: Vec::new(),
            walk: Vec::new(),
            order: Vec::new(),
            depth: [N::ZERO; W],
            intensity: [Rgb565::BLACK; W],
        }
    }

    /// Renders `scene` and sends its rows, top to bottom, to `sink`.
    pub fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        cfg.validate(W)?;
        // Back faces stay in the tree (their planes still divide space); culled on the walk.
        self.table.build(scene, cfg, true, K::WANTS_DEPTH)?;
        let w = cfg.width as i32;
        self.build(w)?;
        self.traverse(cfg.cull == Cull::Back)?;
        let cue = crate::shading::Cue::for_rows(scene, cfg)?;
        let stats = FrameStats {
            polygons: self.order.len() as u32,
            edges: self.table.edge_count() as u32,
            splits: self.pieces.splits,
            ..FrameStats::default()
        };
        paint_rows(
            &self.table,
            &self.pieces,
            &self.order,
            cfg,
            &cue,
            &mut self.depth,
            &mut self.intensity,
            sink,
        )
        .map_err(RenderError::Sink)?;
        Ok(stats)
    }

    /// Inserts every polygon, in scene order.
    fn build(&mut self, w: i32) -> Result<(), Error> {
        self.pieces.clear();
        self.nodes.clear();
        for i in 0..self.table.len() {
            let Some(k) = self.pieces.whole(&self.table, w, i as u16)? else {
                continue;
            };
            if self.nodes.is_empty() {
                self.node(k)?;
                continue;
            }
            self.pending.clear();
            self.push_pending(k, 0, 0)?;
            while let Some((k, n, d)) = self.pending.pop() {
                let node = self.nodes[n as usize];
                let o = self.pieces.get(node.piece).poly;
                let facing = !self.table.get(o as usize).back;
                let (near, far) = self.pieces.sides(&self.table, k, o, w);
                // (piece, goes to the front side?)
                let parts: [Option<(u16, bool)>; 2] = if near || far {
                    [Some((k, near == facing)), None]
                } else {
                    let (a, b) = self.pieces.split(&self.table, k, o, w)?;
                    [a.map(|a| (a, facing)), b.map(|b| (b, !facing))]
                };
                for (part, front) in parts.into_iter().flatten() {
                    let child = if front { node.front } else { node.back };
                    if child == NONE {
                        let c = self.node(part)?;
                        let at = &mut self.nodes[n as usize];
                        if front {
                            at.front = c;
                        } else {
                            at.back = c;
                        }
                    } else {
                        self.push_pending(part, child, d + 1)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// Queues piece `k` to descend from node `n` at depth `d`; the node it will become is at
    /// depth `d + 1`, which must stay below `D` so the walk's stack holds the deepest path.
    fn push_pending(&mut self, k: u16, n: u16, d: u16) -> Result<(), Error> {
        let deep = Error::Capacity {
            table: Table::BspDepth,
            needed: d as u32 + 2,
            capacity: D as u32,
        };
        if d as usize + 1 >= D {
            return Err(deep);
        }
        self.pending.push((k, n, d)).map_err(|_| deep)
    }

    fn node(&mut self, piece: u16) -> Result<u16, Error> {
        let n = self.nodes.len() as u16;
        self.nodes
            .push(Node {
                piece,
                front: NONE,
                back: NONE,
            })
            .map_err(|_| Error::Capacity {
                table: Table::Pieces,
                needed: Q as u32 + 1,
                capacity: Q as u32,
            })?;
        Ok(n)
    }

    /// The in-order walk for the viewpoint at z = −∞: at each node, the subtree on the far
    /// side, the node (unless culled), then the subtree on the viewer's side.
    fn traverse(&mut self, cull: bool) -> Result<(), Error> {
        self.order.clear();
        self.walk.clear();
        if self.nodes.is_empty() {
            return Ok(());
        }
        let deep = Error::Capacity {
            table: Table::BspDepth,
            needed: D as u32 + 1,
            capacity: D as u32,
        };
        // The side the viewer is not on, then the side it is on.
        let sides = |s: &Self, n: u16| {
            let node = s.nodes[n as usize];
            let facing = !s.table.get(s.pieces.get(node.piece).poly as usize).back;
            if facing {
                (node.back, node.front)
            } else {
                (node.front, node.back)
            }
        };
        self.walk.push((0, false)).map_err(|_| deep)?;
        while let Some((n, first_done)) = self.walk.pop() {
            let (far, near) = sides(self, n);
            if !first_done {
                self.walk.push((n, true)).map_err(|_| deep)?;
                if far != NONE {
                    self.walk.push((far, false)).map_err(|_| deep)?;
                }
                continue;
            }
            let piece = self.nodes[n as usize].piece;
            let back = self.table.get(self.pieces.get(piece).poly as usize).back;
            if !(cull && back) {
                // Cannot fail: at most one entry per node, and nodes ≤ Q.
                let _ = self.order.push(piece);
            }
            if near != NONE {
                self.walk.push((near, false)).map_err(|_| deep)?;
            }
        }
        Ok(())
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const Q: usize, const D: usize>
    Renderer<N> for Bsp<N, W, P, E, Q, D>
{
    const NAME: &'static str = "bsp";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        Bsp::render(self, scene, cfg, sink)
    }
}
