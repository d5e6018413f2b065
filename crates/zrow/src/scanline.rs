//! The scan-line method (Foley & van Dam §15.6; Sutherland, Sproull & Schumacker 1974), made
//! exact and fast.
//!
//! The method: for each scan line, set `depth[x]` to the maximum and `intensity[x]` to the
//! background; for each polygon crossing the line and each pixel inside it, compute the
//! polygon's depth z and keep it where `z < depth[x]`; hand the finished row on. Depth moves
//! incrementally: `z −= A/C` one pixel right, `z += (A/m + B)/C` one row down an edge.
//!
//! Here:
//!
//! - a **polygon table** keeps, for each polygon that survives geometry, where its snapped
//!   vertices are, its colour and its rows — a few bytes, in scene order (the order that
//!   breaks depth ties);
//! - polygons are **bucketed by first row** (a counting sort) instead of sorting an edge
//!   table: a polygon enters the active list on its first row and builds its two edges
//!   there, from its top vertex down each side (a convex polygon's left and right chains);
//!   when an edge ends, the next one down the same chain takes over;
//! - an **active list** holds the polygons the current row crosses, each with its left and
//!   right edge stepped exactly (`x += 1/m`, see [`crate::raster::Dda`]) and its depth at its
//!   left end, stepped down the edge by `dzdy + dzdx·Δx` — the textbook `(A/m + B)/C` (Foley, van Dam, Feiner & Hughes §15.6) with the
//!   pixel steps the edge actually takes, so it equals the plane at every pixel centre.
//!   Entries stay where they are; the row's order by left end is kept on four-byte keys (left
//!   end, slot), nearly sorted from one row to the next (sorted only for the rows that are
//!   swept: a heavy row is resolved by depth, in any order);
//! - **spans apart**: a mesh's spans mostly abut, one polygon's right edge the next one's left.
//!   For a sink that takes colours only, a flat row is painted span by span in key order while
//!   each begins at or after the end of the one before — each is then the visible surface
//!   wherever it lies, and nothing is compared; where a span meets the last one painted, the
//!   sweep below resolves the row from that one's start (and the next row, overlap coming in
//!   runs of rows, is swept from the outset, until one sweeps without any);
//! - **span coherence**: where one polygon is in front at both ends of its overlap with
//!   another it is in front throughout (depths are linear in x, so their difference cannot
//!   change sign in between). The row is filled from a *front* polygon with no per-pixel
//!   depth test up to the first column where another open polygon overtakes it — their
//!   intersection, found exactly by bisection — or it closes, or a newcomer opens in front of
//!   it. Work follows the visible changes along the row, not the pixels and not the polygons
//!   hidden behind the front.
//!
//! Ties go to the polygon that comes first in the scene: the winner is the least
//! `(depth, scene order)`. In Q16.16 depths step by wrapping integer additions, which equal the
//! direct plane evaluation bit for bit, so every span decision equals the per-pixel test
//! exactly (the property tests check this against an exact reference).
//!
//! The depth row is written only when someone reads it ([`RowSink::WANTS_DEPTH`], or the
//! perspective-correct depth cue), or a row is heavy; otherwise a row is its colours alone,
//! written span by span. A renderer for a sink that takes colours only can leave it out
//! altogether ([`NoDepth`](crate::scanline::NoDepth), `scanline_for!(N, REQ, display)`: a
//! row's width of depths less), sweeping its heavy rows too.
//!
//! Every capacity is checked while the tables are built, before the first row is sent.

use crate::error::{Error, RenderError, Table};
use crate::geometry::shade;
use crate::method::{FrameStats, Renderer};
use crate::number::{DepthPlane, Scalar};
use crate::raster::{
    canonical_with, fill_run, outline_triangle, outline_with_area, paint_run, row_at_or_below,
    Config, Dda, RasterVertex, MAX_POLYGON_VERTICES, MAX_VIEWPORT,
};
use crate::requirements::Requirements;
use crate::scene::{IntensityPlane, Scene, VertexBuffer, INDEXED_CORNERS};
use crate::shading::{Cue, Interpolation};
use crate::sink::{Row, RowSink, EXACT_DEPTH};
use embedded_graphics_core::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use heapless::Vec;

/// How a polygon record keeps its corners' slot numbers in the vertex buffer: `u16` (the
/// default, up to 65,536 slots: two bytes a corner, 12-byte records), [`Slot12`] (up to 4,096
/// slots packed in 12 bits: 10-byte records) or `u32` (host-sized scenes). Sealed.
pub trait Slot: Copy + core::fmt::Debug + 'static + sealed::Sealed {
    /// The largest vertex capacity the type can address.
    const MAX_SLOTS: usize;
    /// Up to [`INDEXED_CORNERS`] slot numbers, packed.
    #[doc(hidden)]
    type Corners: Copy + core::fmt::Debug;
    /// Packs slot numbers, each below [`Slot::MAX_SLOTS`].
    #[doc(hidden)]
    fn pack(c: [u32; INDEXED_CORNERS]) -> Self::Corners;
    /// Corner `k`'s slot number (`k` below [`INDEXED_CORNERS`]).
    #[doc(hidden)]
    fn corner(c: &Self::Corners, k: usize) -> usize;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for u16 {}
    impl Sealed for u32 {}
    impl Sealed for super::Slot12 {}
    impl<N, const K: usize> Sealed for [super::EdgeCue<N>; K] {}
    impl Sealed for super::Uncued {}
    impl<N, const W: usize> Sealed for super::Depths<N, W> {}
    impl Sealed for super::NoDepth {}
    impl<N, const K: usize> Sealed for [crate::scene::IntensityPlane<N>; K] {}
    impl Sealed for super::Flat {}
}

impl Slot for u16 {
    const MAX_SLOTS: usize = 1 << 16;
    type Corners = [u16; INDEXED_CORNERS];
    #[inline]
    fn pack(c: [u32; INDEXED_CORNERS]) -> Self::Corners {
        c.map(|v| v as u16)
    }
    #[inline]
    fn corner(c: &Self::Corners, k: usize) -> usize {
        c[k] as usize
    }
}

impl Slot for u32 {
    const MAX_SLOTS: usize = u32::MAX as usize;
    type Corners = [u32; INDEXED_CORNERS];
    #[inline]
    fn pack(c: [u32; INDEXED_CORNERS]) -> Self::Corners {
        c
    }
    #[inline]
    fn corner(c: &Self::Corners, k: usize) -> usize {
        c[k] as usize
    }
}

/// Slot numbers of 12 bits ([`Slot`]): up to 4,096 vertex slots, a polygon record's four
/// corners in 6 bytes instead of 8 (a record of 10 bytes). Each of three 16-bit words holds
/// a corner in its low 12 bits and a third of the fourth corner, which only polygons of four
/// corners have, in its high 4: reading one of a triangle's corners is a load and a mask.
#[derive(Clone, Copy, Debug, Default)]
pub struct Slot12;

impl Slot for Slot12 {
    const MAX_SLOTS: usize = 1 << 12;
    type Corners = [u16; 3];
    #[inline]
    fn pack(c: [u32; INDEXED_CORNERS]) -> Self::Corners {
        const { assert!(INDEXED_CORNERS == 4) };
        let word = |k: usize| (c[k] & 0xfff) as u16 | ((c[3] >> (4 * k) & 0xf) as u16) << 12;
        [word(0), word(1), word(2)]
    }
    #[inline]
    fn corner(c: &Self::Corners, k: usize) -> usize {
        match c.get(k) {
            Some(&w) => (w & 0xfff) as usize,
            None => (c[0] >> 12 | (c[1] >> 12) << 4 | (c[2] >> 12) << 8) as usize,
        }
    }
}

/// One polygon of the table: its corners in the vertex buffer, its colour, and, packed in 16
/// bits, its first row, winding and corner count (12 bytes with `u16` slots). Its last row is
/// not kept: [`last_row_of`] finds it from its corners where it is needed (counting the
/// active list, and, for a polygon of more than three corners, activating it and walking its
/// left side on).
#[derive(Clone, Copy, Debug)]
struct Polygon<S: Slot> {
    /// Up to [`INDEXED_CORNERS`] corners as slots of the vertex buffer, from the top one;
    /// more are a run of consecutive slots from the first.
    corners: S::Corners,
    color: Rgb565,
    /// First row (bits 5.., below [`MAX_VIEWPORT`] = 2^11), clockwise on the display (bit 4:
    /// its right side runs forward from the top vertex), corners − 3 (bits 0..4: 3 to
    /// [`MAX_POLYGON_VERTICES`]).
    packed: u16,
}

impl<S: Slot> Polygon<S> {
    /// `packed` of a polygon: `len` in 3..=[`MAX_POLYGON_VERTICES`], `first_row` in
    /// 0..[`MAX_VIEWPORT`] (the caller checks both).
    const fn pack(first_row: i16, clockwise: bool, len: usize) -> u16 {
        const {
            assert!(MAX_VIEWPORT as u32 <= 1 << 11 && MAX_POLYGON_VERTICES - 3 < 16);
        }
        (first_row as u16) << 5 | (clockwise as u16) << 4 | (len as u16 - 3)
    }
    /// How many corners.
    #[inline]
    fn len(&self) -> usize {
        (self.packed & 15) as usize + 3
    }
    /// Clockwise on the display (its right side runs forward from the top vertex).
    #[inline]
    fn clockwise(&self) -> bool {
        self.packed & 16 != 0
    }
    /// The first row whose sample line it covers.
    #[inline]
    fn first_row(&self) -> i32 {
        (self.packed >> 5) as i32
    }
}

/// A polygon's corners in order, read from the vertex buffer.
#[derive(Clone, Copy)]
struct Ring<'a, N, S: Slot> {
    vertices: &'a [RasterVertex<N>],
    polygon: &'a Polygon<S>,
}

impl<N: Scalar> Active<N> {
    /// Its plane's depth at the centre of pixel (0, `j`), `y` being the current row (the
    /// plane being set): stepped from `z_col`, which is at row `y` in the exact formats, at
    /// row [`Self::j_ref`] in f32. The bits [`DepthPlane::at`] gives (in f32 its value).
    #[inline]
    fn column_0_at(&self, y: i32, j: i32) -> N {
        let from = if N::EXACT_STEPS { y } else { self.j_ref() };
        self.z_col.step(self.dzdy, j.wrapping_sub(from))
    }

    /// Its plane's depth at the centre of pixel (`i`, `j`), `y` being the current row: one
    /// step along row `j` from [`Self::column_0_at`] (in f32 within a few units of the last
    /// place of the terms of [`DepthPlane::at`]).
    #[inline]
    fn plane_at(&self, y: i32, i: i32, j: i32) -> N {
        self.column_0_at(y, j).step(self.dzdx, i)
    }

    /// f32: its plane's reference row ([`Active::spare`]).
    #[inline]
    fn j_ref(&self) -> i32 {
        self.spare as i16 as i32
    }

    /// Its colour: kept in the entry in the exact formats, else the polygon table's (which
    /// holds polygon `poly`, or the entry is not in use and the colour no matter).
    #[inline]
    fn color<S: Slot>(&self, polygons: &[Polygon<S>]) -> Rgb565 {
        if N::EXACT_STEPS {
            Rgb565::from(RawU16::new(self.spare))
        } else {
            polygons
                .get(self.poly as usize)
                .map_or(Rgb565::BLACK, |p| p.color)
        }
    }

    /// This row's span's left end (unclamped; the span `xl..xr` may be empty).
    #[inline]
    fn xl(&self) -> i32 {
        self.dda[LEFT].x()
    }

    /// This row's span's right end (exclusive, unclamped).
    #[inline]
    fn xr(&self) -> i32 {
        self.dda[RIGHT].x()
    }

    /// The walk of side `side` ([`LEFT`] or [`RIGHT`]).
    #[inline]
    fn walk(&self, side: usize) -> Walk {
        Walk {
            dda: self.dda[side],
            last: (self.end[side] >> END_ROW) as i16,
            at: (self.end[side] & RING_POSITION) as u8,
        }
    }

    /// Sets the left side's walk to `w`, which ends on the polygon's last row if `last`.
    #[inline]
    fn set_left(&mut self, w: Walk, last: bool) {
        self.dda[LEFT] = w.dda;
        self.end[LEFT] = end_of(&w) | flag(last, LAST_EDGE);
    }

    /// Sets the right side's walk to `w` (keeping the [`PLANED`] flag).
    #[inline]
    fn set_right(&mut self, w: Walk) {
        self.dda[RIGHT] = w.dda;
        self.end[RIGHT] = end_of(&w) | (self.end[RIGHT] & PLANED);
    }

    /// Whether side `side`'s edge goes on below row `y`: its last row is later.
    #[inline]
    fn goes_below(&self, side: usize, y: i32) -> bool {
        (self.end[side] >> END_ROW) as i32 > y
    }

    /// Whether the plane (`dzdx`, `dzdy`, `z_col`, in f32 [`Self::j_ref`]) is set.
    #[inline]
    fn planed(&self) -> bool {
        self.end[RIGHT] & PLANED != 0
    }
}

/// [`Active::dda`]'s sides.
const LEFT: usize = 0;
const RIGHT: usize = 1;
/// [`Active::end`], a side's [`Walk::last`] and [`Walk::at`] in 16 bits: the last row from bit
/// [`END_ROW`] (rows are below [`MAX_VIEWPORT`] = 2^11), the position in the vertex ring in
/// the bits of [`RING_POSITION`] (below [`MAX_POLYGON_VERTICES`] = 16), and between them a flag:
/// the left side's edge ends on the polygon's last row ([`LAST_EDGE`]), the depth plane is set
/// ([`PLANED`], in the right side's).
const END_ROW: u32 = 5;
const RING_POSITION: u16 = 15;
const LAST_EDGE: u16 = 16;
const PLANED: u16 = 16;

/// `bit` if `on`.
#[inline]
fn flag(on: bool, bit: u16) -> u16 {
    on as u16 * bit
}

/// [`Active::end`] of a walk, without flags.
#[inline]
fn end_of(w: &Walk) -> u16 {
    end_bits(w.last as i32, w.at as usize)
}

/// [`Active::end`] of an edge whose last row is `last` and lower vertex at ring position `at`,
/// without flags.
#[inline]
fn end_bits(last: i32, at: usize) -> u16 {
    const {
        assert!((MAX_VIEWPORT as u32) << END_ROW <= 1 << 16 && MAX_POLYGON_VERTICES <= 16);
    }
    (last as u16) << END_ROW | at as u16
}

impl<N: Copy, S: Slot> Ring<'_, N, S> {
    fn len(&self) -> usize {
        self.polygon.len()
    }
    #[inline]
    fn get(&self, k: usize) -> &RasterVertex<N> {
        let c = &self.polygon.corners;
        let slot = if self.len() <= INDEXED_CORNERS {
            S::corner(c, k)
        } else {
            S::corner(c, 0) + k
        };
        &self.vertices[slot]
    }
    /// Calls `f` with the corners in the order [`canonical`](crate::raster::canonical) gives.
    fn ordered<R>(&self, f: impl FnOnce(&[RasterVertex<N>]) -> R) -> R
    where
        N: Default,
    {
        let mut out = [RasterVertex::default(); MAX_POLYGON_VERTICES];
        let n = canonical_with(
            self.len(),
            |k| *self.get(k),
            self.polygon.clockwise(),
            &mut out,
        );
        f(&out[..n])
    }
}

/// One side of an active polygon: the edge crossing the current row, walked exactly.
#[derive(Clone, Copy, Debug)]
struct Walk {
    dda: Dda,
    /// Last row of this edge.
    last: i16,
    /// Position, in the polygon's vertex ring, of the edge's lower vertex (where the next
    /// edge of this side starts).
    at: u8,
}

/// One entry of the active list: a polygon crossing the current row (52 bytes in a 32-bit
/// format: tested). Its colour is not kept (the polygon table has it), nor its last row: it
/// retires when its left edge, which covers every row it does, ends on that row
/// ([`LAST_EDGE`]).
#[derive(Clone, Copy, Debug)]
struct Active<N: Scalar> {
    /// The walks of its left and right edges ([`LEFT`], [`RIGHT`]): [`Walk::dda`], and the
    /// rest of [`Walk`] packed with a flag each ([`end_of`]).
    dda: [Dda; 2],
    end: [u16; 2],
    /// The depth plane's gradients (per pixel right, per row down), once something needed
    /// the plane ([`Planes::ensure`]): most polygons of a mesh never meet another in depth,
    /// and are drawn without one.
    dzdx: N,
    dzdy: N,
    /// The rest of the plane, its depth at column 0 of a row: in the exact formats of the
    /// current row (stepped a row down as the sweep moves: wrapping steps give the plane's
    /// own bits), in f32, which evaluates the plane afresh so that no error accumulates, of
    /// its reference row ([`DepthPlane::column_0`]), the row's depths evaluated from there
    /// when needed ([`Active::plane_at`]).
    z_col: N,
    /// f32: that reference row (within the guard band, so 16 bits: [`Active::j_ref`]). The
    /// exact formats, which need none: the polygon's colour, so that painting a span needs no
    /// lookup; f32 reads it from the polygon table ([`Active::color`]) and so keeps its
    /// entry at 52 bytes.
    spare: u16,
    /// Scene order: the index in the polygon table.
    poly: u16,
}

/// The affine depth cue's state for one active polygon: the factors and their steps per row on
/// its left and right edges, and the last rows of the edges they were set up for (20 bytes in a
/// 32-bit format).
#[derive(Clone, Copy, Debug)]
pub struct EdgeCue<N> {
    f: [N; 4],
    last: [i16; 2],
}

impl<N: Scalar> EdgeCue<N> {
    const ZERO: Self = EdgeCue {
        f: [N::ZERO; 4],
        last: [0; 2],
    };
}

/// Where a scan-line renderer keeps the affine depth cue's per-edge state (its `C` parameter):
/// `[EdgeCue<N>; A]`, one per active slot (the default), or [`Uncued`], none — 20 bytes less
/// per active slot in a 32-bit format, for a renderer that never draws with the affine depth
/// cue (a frame that asks for it is then [`Error::Unsupported`]; flat shading and the
/// perspective-correct cue need no per-edge state).
pub trait CueStore<N>: sealed::Sealed {
    /// The store with nothing set (all zero: a `static` renderer stays in `.bss`).
    const EMPTY: Self;
    /// Whether it keeps any state.
    const KEEPS: bool;
    /// Slot `k`'s state.
    #[doc(hidden)]
    fn at(&self, k: usize) -> Option<&EdgeCue<N>>;
    /// Slot `k`'s state, to set.
    #[doc(hidden)]
    fn at_mut(&mut self, k: usize) -> Option<&mut EdgeCue<N>>;
}

impl<N: Scalar, const K: usize> CueStore<N> for [EdgeCue<N>; K] {
    const EMPTY: Self = [EdgeCue::ZERO; K];
    const KEEPS: bool = true;
    #[inline]
    fn at(&self, k: usize) -> Option<&EdgeCue<N>> {
        self.get(k)
    }
    #[inline]
    fn at_mut(&mut self, k: usize) -> Option<&mut EdgeCue<N>> {
        self.get_mut(k)
    }
}

/// A scan-line renderer without the affine depth cue's per-edge state ([`CueStore`]):
/// `Scanline<N, W, V, P, A, u16, Uncued>`, or `scanline_for!(N, REQ, uncued)`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Uncued;

impl<N> CueStore<N> for Uncued {
    const EMPTY: Self = Uncued;
    const KEEPS: bool = false;
    #[inline]
    fn at(&self, _: usize) -> Option<&EdgeCue<N>> {
        None
    }
    #[inline]
    fn at_mut(&mut self, _: usize) -> Option<&mut EdgeCue<N>> {
        None
    }
}

/// Where a scan-line renderer keeps smooth shading's intensity planes (its `G` parameter):
/// [`Flat`], none (the default: a frame with a smooth-shaded polygon is then
/// [`Error::Unsupported`]), or `[IntensityPlane<N>; P]`, one per polygon of the table (24
/// bytes a polygon in a 32-bit format): `scanline_for!(N, REQ, gouraud)`.
pub trait ShadeStore<N>: sealed::Sealed {
    /// The store with nothing set (all zero: a `static` renderer stays in `.bss`).
    const EMPTY: Self;
    /// Whether it keeps any plane.
    const KEEPS: bool;
    /// Polygon `k`'s plane.
    #[doc(hidden)]
    fn at(&self, k: usize) -> Option<&IntensityPlane<N>>;
    /// Sets polygon `k`'s plane.
    #[doc(hidden)]
    fn set(&mut self, k: usize, plane: IntensityPlane<N>);
}

impl<N: Scalar, const K: usize> ShadeStore<N> for [IntensityPlane<N>; K] {
    const EMPTY: Self = [IntensityPlane {
        levels: DepthPlane {
            z_ref: N::ZERO,
            dzdx: N::ZERO,
            dzdy: N::ZERO,
            i_ref: 0,
            j_ref: 0,
        },
        dither: false,
    }; K];
    const KEEPS: bool = true;
    #[inline]
    fn at(&self, k: usize) -> Option<&IntensityPlane<N>> {
        self.get(k)
    }
    #[inline]
    fn set(&mut self, k: usize, plane: IntensityPlane<N>) {
        if let Some(p) = self.get_mut(k) {
            *p = plane;
        }
    }
}

/// A scan-line renderer that keeps no intensity plane ([`ShadeStore`]): it draws every
/// polygon in one colour (flat shading, or either depth cue).
#[derive(Clone, Copy, Debug, Default)]
pub struct Flat;

impl<N> ShadeStore<N> for Flat {
    const EMPTY: Self = Flat;
    const KEEPS: bool = false;
    #[inline]
    fn at(&self, _: usize) -> Option<&IntensityPlane<N>> {
        None
    }
    #[inline]
    fn set(&mut self, _: usize, _: IntensityPlane<N>) {}
}

/// Where a scan-line renderer keeps a row's depths (its `D` parameter): [`Depths`], the row
/// and its hierarchical depth (the default), or [`NoDepth`], none — a row's width of depths
/// and 64 bytes less in a 32-bit format, for a renderer whose sink takes colours only.
///
/// The sweep that resolves a row needs no depth row: it compares polygons' depth planes where
/// their spans meet. The row is kept for what does need it: a sink that reads depth
/// ([`RowSink::WANTS_DEPTH`]), the perspective-correct depth cue (its factor is taken from
/// the row's depths), and rows of heavy overlap, which the default renderer resolves pixel by
/// pixel against it (spans covering more than twice the row). Without it the first two are
/// [`Error::Unsupported`] and a heavy row is swept like any other — the same pixels, at the
/// sweep's cost (random400, 400 large triangles overlapping: 35.2 M instructions on the
/// emulated Cortex-M4 instead of 13.5 M, Q16.16).
pub trait DepthRow<N>: sealed::Sealed {
    /// The store with nothing set (all zero: a `static` renderer stays in `.bss`).
    const EMPTY: Self;
    /// Whether it keeps the row.
    const KEEPS: bool;
    /// The depth row and the hierarchical depth (empty if not kept).
    #[doc(hidden)]
    fn parts(&mut self) -> (&mut [N], &mut [N]);
}

/// A row of depths, `W` wide, and its hierarchical depth: the default [`DepthRow`].
#[derive(Clone, Copy, Debug)]
pub struct Depths<N, const W: usize> {
    row: [N; W],
    /// [`Scanline::resolve_by_depth`]'s hierarchical depth: the largest depth stored in each
    /// block of [`HIZ_BLOCK`] pixels (or more, for rows wider than 256 pixels).
    hiz: [N; HIZ_BLOCKS],
}

impl<N: Scalar, const W: usize> DepthRow<N> for Depths<N, W> {
    // All zero, so a `static` renderer lands in .bss, not copied from flash; the row is
    // rewritten in full before it is sent.
    const EMPTY: Self = Depths {
        row: [N::ZERO; W],
        hiz: [N::ZERO; HIZ_BLOCKS],
    };
    const KEEPS: bool = true;
    #[inline]
    fn parts(&mut self) -> (&mut [N], &mut [N]) {
        (&mut self.row, &mut self.hiz)
    }
}

/// A scan-line renderer without a depth row ([`DepthRow`]): `Scanline<N, W, V, P, A, S, C, G,
/// NoDepth>`, as [`Display`] (`scanline_for!(N, REQ, display)`) builds it, with [`Slot12`],
/// [`Uncued`] and [`Flat`].
#[derive(Clone, Copy, Debug, Default)]
pub struct NoDepth;

impl<N> DepthRow<N> for NoDepth {
    const EMPTY: Self = NoDepth;
    const KEEPS: bool = false;
    #[inline]
    fn parts(&mut self) -> (&mut [N], &mut [N]) {
        (&mut [], &mut [])
    }
}

/// The scan-line renderer as a display's is built: for a sink that takes colours only, flat
/// shaded — no depth row ([`NoDepth`]), no affine cue state ([`Uncued`]), corners in 12 bits
/// ([`Slot12`]: at most 4,096 vertex slots). `scanline_for!(N, REQ, display)` sizes it from a
/// [`Requirements`]; [`ram_bytes_display`] is its size.
pub type Display<N, const W: usize, const V: usize, const P: usize, const A: usize> =
    Scanline<N, W, V, P, A, Slot12, Uncued, Flat, NoDepth>;

/// The scan-line renderer.
///
/// - `N`: number format ([`crate::Q16_16`], [`crate::Q24_8`] or `f32`);
/// - `W`: row capacity (the widest frame, in pixels);
/// - `V`: vertex buffer (every vertex of the scene's meshes once, plus what clipping adds: see
///   [`Requirements::vertices`]; none for a scene that lends its snapped vertices,
///   [`crate::SnappedScene`], which the sweep then reads where they are);
/// - `P`: polygon table; `A`: active list (polygons crossing one row);
/// - `S`: the slot number type ([`Slot`]: `u16` up to 65,536 vertex slots, else `u32`);
/// - `C`: where the affine depth cue's per-edge state is kept ([`CueStore`]; [`Uncued`] for
///   a renderer that never draws with it: 20 bytes less per active slot);
/// - `G`: where smooth shading's intensity planes are kept ([`ShadeStore`]; [`Flat`], the
///   default, keeps none);
/// - `D`: where a row's depths are kept ([`DepthRow`]; [`NoDepth`] for a renderer whose sink
///   takes colours only: a row's width of depths less).
///
/// Choose the capacities with [`crate::requirements()`]. All memory is in the struct:
/// [`Scanline::RAM_BYTES`] is the whole of it.
pub struct Scanline<
    N: Scalar,
    const W: usize,
    const V: usize,
    const P: usize,
    const A: usize,
    S: Slot = u16,
    C = [EdgeCue<N>; A],
    G = Flat,
    D = Depths<N, W>,
> {
    /// The frame's vertex buffer: geometry writes every vertex here once, projected and
    /// snapped; polygons refer to it by slot.
    vertices: [RasterVertex<N>; V],
    /// The rest: the tables and rows of the sweep, which reads its vertices from the buffer
    /// or, if the scene lends them ([`Scene::lent_vertices`]), from the scene.
    sweep: Sweep<N, W, P, A, S, C, G, D>,
}

/// The scan-line renderer's state besides its vertex buffer.
struct Sweep<N: Scalar, const W: usize, const P: usize, const A: usize, S: Slot, C, G, D> {
    polygons: Vec<Polygon<S>, P>,
    /// Polygon numbers by first row (stable: scene order within a row).
    order: Vec<u16, P>,
    /// The active list's entries, by slot (slots `used..` never used this frame).
    active: [Active<N>; A],
    /// Their affine depth cue, by slot (if the renderer keeps it).
    cues: C,
    /// Smooth shading's intensity planes, by polygon (if the renderer keeps them; a flat
    /// polygon's plane is level 255 everywhere).
    shades: G,
    used: usize,
    /// One more than the last slot of `active` freed, 0 if none is free: a stack of the free
    /// slots, each free entry's `poly` holding the one freed before it (so counted). Zero when
    /// empty, like the rest of a new renderer, whose static is then zeroed at reset instead
    /// of copied from flash.
    free: u16,
    /// The occupied slots of `active` by left end this row, as sort keys: [`key`].
    sorted: Vec<u32, A>,
    /// Polygons open at the current piece of the row (their slots; those that closed behind
    /// the front are pruned when a new front is sought).
    open: Vec<u16, A>,
    /// The row's depths, if kept.
    depth: D,
    /// Whether to paint the next row's spans as they come ([`Self::paint_apart`]): no spans
    /// met in the last row swept.
    apart: bool,
    intensity: [Rgb565; W],
    /// This frame's depth cue, if `cued` (shading is not flat): see [`Self::frame_cue`].
    cue: Cue<N>,
    cued: bool,
    /// Edges walked so far this frame (for [`FrameStats::edges`]).
    edges: u32,
    /// The row being drawn and what drawing it needs from the configuration.
    row: RowState,
    /// Pixels the active spans cover in the current row, summed (overlaps counted again): what
    /// decides a heavy row. Only with a depth row (without one no row is resolved by depth,
    /// and it stays 0).
    cover: i32,
}

/// The row being drawn, and the configuration its sweep needs.
#[derive(Clone, Copy, Debug)]
struct RowState {
    y: i32,
    width: i32,
    /// Sub-pixel bits.
    s: u32,
    background: Rgb565,
    /// Whether the affine depth cue shades spans.
    cue: bool,
    /// Whether a painted run needs more than its colours: depths (someone reads them) or the
    /// cue ([`Scanline::paint_more`]).
    more: bool,
    /// Whether the sink reads depth: the row's depths are then each visible polygon's exact
    /// plane ([`Scalar::exact_plane`]), visibility and the perspective cue being decided on
    /// the stepped planes first. Only with the `exact-depth` feature: without it the field
    /// is not there, so a build that never hands depth on keeps the layout (and the
    /// register allocation) it had without it.
    #[cfg(feature = "exact-depth")]
    exact: bool,
    /// Columns of the colour row that may hold something other than the background from the
    /// row before (the buffer persists from row to row): background is written only there.
    stale: (i32, i32),
    /// Columns this row may have painted with a polygon, all that it did and perhaps a few
    /// it gave the background (the next row's `stale`).
    fresh: (i32, i32),
}

impl RowState {
    /// Whether the row's depths are to be each visible polygon's exact plane (the sink reads
    /// depth and the `exact-depth` feature is on).
    #[inline]
    fn exact(&self) -> bool {
        #[cfg(feature = "exact-depth")]
        return self.exact;
        #[cfg(not(feature = "exact-depth"))]
        false
    }
}

/// A row whose spans cover more than this many times its width is resolved pixel by pixel
/// ([`Scanline::resolve_by_depth`]): overlap that heavy costs the sweep more than a depth
/// test per covered pixel.
const HEAVY_COVER: i32 = 2;

/// Pixels in a block of [`Scanline::resolve_by_depth`]'s hierarchical depth, for rows up to
/// `HIZ_BLOCKS · HIZ_BLOCK` pixels wide (wider rows double it as often as needed).
const HIZ_BLOCK: usize = 16;
/// Blocks of the hierarchical depth (64 bytes in a 32-bit format).
const HIZ_BLOCKS: usize = 16;

impl<
        N: Scalar,
        const W: usize,
        const V: usize,
        const P: usize,
        const A: usize,
        S: Slot,
        C: CueStore<N>,
        G: ShadeStore<N>,
        D: DepthRow<N>,
    > Default for Scanline<N, W, V, P, A, S, C, G, D>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<
        N: Scalar,
        const W: usize,
        const V: usize,
        const P: usize,
        const A: usize,
        S: Slot,
        C: CueStore<N>,
        G: ShadeStore<N>,
        D: DepthRow<N>,
    > Scanline<N, W, V, P, A, S, C, G, D>
{
    /// Bytes of RAM the renderer occupies (all its tables and row buffers).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer.
    pub const fn new() -> Self {
        const {
            assert!(
                V <= S::MAX_SLOTS,
                "vertex capacity beyond the slot type: use wider slots (u16, u32)"
            );
            assert!(P < 1 << 16, "polygon capacity must be below 65536");
            assert!(A < 1 << 16, "active capacity must be below 65536");
        }
        Scanline {
            vertices: [RasterVertex {
                x: 0,
                y: 0,
                z: N::ZERO,
            }; V],
            sweep: Sweep {
                polygons: Vec::new(),
                order: Vec::new(),
                active: [Active {
                    dda: [Dda::ZERO; 2],
                    end: [0; 2],
                    dzdx: N::ZERO,
                    dzdy: N::ZERO,
                    z_col: N::ZERO,
                    spare: 0,
                    poly: 0,
                }; A],
                cues: C::EMPTY,
                shades: G::EMPTY,
                used: 0,
                free: 0,
                sorted: Vec::new(),
                open: Vec::new(),
                // All zero, so a `static` renderer lands in .bss, not copied from flash; both rows
                // are rewritten in full before each is sent.
                depth: D::EMPTY,
                apart: false,
                intensity: [Rgb565::BLACK; W],
                cue: Cue::UNSET,
                cued: false,
                edges: 0,
                cover: 0,
                row: RowState {
                    y: 0,
                    width: 0,
                    s: 0,
                    background: Rgb565::BLACK,
                    cue: false,
                    more: false,
                    #[cfg(feature = "exact-depth")]
                    exact: false,
                    stale: (0, 0),
                    fresh: (0, 0),
                },
            },
        }
    }

    /// Renders `scene` and sends its rows, top to bottom, to `sink`.
    ///
    /// Errors in the scene or the configuration — including any capacity the scene exceeds —
    /// are returned before the first row is sent.
    pub fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        if K::WANTS_DEPTH && !D::KEEPS {
            return Err(RenderError::Scene(Error::Unsupported {
                feature: "a sink that reads depth: this scan-line renderer keeps no depth row \
                          (its `D` parameter is `NoDepth`)",
            }));
        }
        let lent = scene.lent_vertices();
        let mut stats = self.sweep.prepare(&mut self.vertices, lent, scene, cfg)?;
        let vertices = match lent {
            Some(v) => v,
            None => &self.vertices[..],
        };
        self.sweep
            .run_rows(vertices, cfg, sink, &mut stats)
            .map_err(RenderError::Sink)?;
        Ok(stats)
    }
}

/// What [`Sweep::prepare`] counts as polygons come: how many the scene handed over, the first
/// outside the frame's vertices, whether any is smooth shaded.
#[derive(Default)]
struct Tally {
    polys: u32,
    uncached: Option<u32>,
    smooth: bool,
}

impl<
        N: Scalar,
        const W: usize,
        const P: usize,
        const A: usize,
        S: Slot,
        C: CueStore<N>,
        G: ShadeStore<N>,
        D: DepthRow<N>,
    > Sweep<N, W, P, A, S, C, G, D>
{
    /// Builds the polygon table, buckets it by first row and checks the active list's
    /// capacity.
    fn prepare(
        &mut self,
        buffer: &mut [RasterVertex<N>],
        lent: Option<&[RasterVertex<N>]>,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
    ) -> Result<FrameStats, Error> {
        cfg.validate(W)?;
        if lent.is_some_and(|v| v.len() > S::MAX_SLOTS) {
            return Err(Error::Unsupported {
                feature: "lent vertices beyond this renderer's slot type: use wider slots",
            });
        }
        let cue = Cue::for_frame(scene, cfg)?;
        if !C::KEEPS && cue.is_some_and(|c| c.interpolation == Interpolation::Affine) {
            return Err(Error::Unsupported {
                feature: "the affine depth cue: this scan-line renderer keeps no per-edge cue \
                          state (its `C` parameter is `Uncued`; the perspective-correct cue \
                          needs none)",
            });
        }
        if !D::KEEPS && cue.is_some_and(|c| c.interpolation == Interpolation::PerspectiveCorrect) {
            return Err(Error::Unsupported {
                feature: "the perspective-correct depth cue: this scan-line renderer keeps no \
                          depth row to take its factor from (its `D` parameter is `NoDepth`)",
            });
        }
        (self.cue, self.cued) = (cue.unwrap_or(Cue::UNSET), cue.is_some());
        self.polygons.clear();
        self.used = 0;
        self.cover = 0;
        self.apart = true;
        self.free = 0;
        self.sorted.clear();
        let mut tally = Tally::default();
        let (table, shades) = (&mut self.polygons, &mut self.shades);
        // Level 255 in the format: a flat polygon's intensity plane (only if planes are kept).
        let full = match G::KEEPS {
            true => N::from_f32(255.0).unwrap_or(N::ONE),
            false => N::ZERO,
        };
        // Where the frame's vertices lie (the buffer, or what the scene lends): a polygon is
        // kept by slot only if its vertices are those (compared as addresses, and within
        // them; a scene of its own might hand over others).
        let (frame, frame_len) = match lent {
            Some(v) => (v.as_ptr(), v.len()),
            None => (buffer.as_ptr(), buffer.len()),
        };
        let capacity = buffer.len();
        let mut buf = VertexBuffer::new(buffer);
        // The active list's difference array (see `max_active`), filled as polygons enter the
        // table while their rows are at hand, in the colour row (free until the first row is
        // drawn) when the frame is no taller than it.
        let height = cfg.height as usize;
        let counted = height <= W;
        let diff = &mut self.intensity[..height.min(W)];
        diff.fill(count_of(0));
        let t = &mut tally;
        scene.polygons(cfg, &mut buf, &mut move |poly| {
            let n = poly.corners.len();
            // Geometry's corners are always in range; a scene of its own may not be.
            let out_of_range = || poly.corner_error();
            let at = |k: usize| &poly.vertices[poly.corners[k] as usize];
            // The buffer has at most S::MAX_SLOTS slots.
            let slot = |k: usize| poly.corners[k];
            let (o, corners) = if let [a, b, c] = *poly.corners {
                let v = |i: u32| poly.vertices.get(i as usize);
                let (Some(a), Some(b), Some(c)) = (v(a), v(b), v(c)) else {
                    return Err(out_of_range().unwrap_or(Error::BadConfig));
                };
                let Some((o, top)) = outline_triangle([a, b, c], poly.area2, cfg) else {
                    return Ok(());
                };
                // Recorded from its top-left corner (the same ring).
                let corners = match top {
                    0 => [slot(0), slot(1), slot(2), 0],
                    1 => [slot(1), slot(2), slot(0), 0],
                    _ => [slot(2), slot(0), slot(1), 0],
                };
                (o, S::pack(corners))
            } else {
                if n > MAX_POLYGON_VERTICES {
                    // More than clipping makes: a scene of its own sent it (and the table
                    // packs the count in 4 bits).
                    return Err(Error::TooManyVertices { face: poly.face });
                }
                if let Some(e) = out_of_range() {
                    return Err(e);
                }
                let Some(o) = outline_with_area(n, at, poly.area2, cfg, poly.face)? else {
                    return Ok(());
                };
                let corners = if n <= INDEXED_CORNERS {
                    top_first(poly.corners, at)
                } else {
                    // A run of consecutive slots: only its first is kept.
                    [slot(0), 0, 0, 0]
                };
                (o, S::pack(corners))
            };
            t.polys += 1;
            // In the frame's buffer, and a polygon of more than INDEXED_CORNERS corners a run
            // of consecutive slots, as `Polygon::cached` promises (else treated as scratch).
            let cached = poly.cached
                && core::ptr::eq(poly.vertices.as_ptr(), frame)
                && poly.vertices.len() <= frame_len
                && (n <= INDEXED_CORNERS
                    || (1..n).all(|k| poly.corners[k] == poly.corners[0].wrapping_add(k as u32)));
            // Past a capacity, keep counting so the error can say what the scene needs.
            if !cached && t.uncached.is_none() {
                t.uncached = Some(poly.face);
            }
            t.smooth |= poly.intensity.is_some();
            if cached && table.len() < P {
                if G::KEEPS {
                    // A flat polygon: its colour at level 255, which is the colour itself.
                    let flat = IntensityPlane {
                        levels: DepthPlane {
                            z_ref: full,
                            dzdx: N::ZERO,
                            dzdy: N::ZERO,
                            i_ref: 0,
                            j_ref: 0,
                        },
                        dither: false,
                    };
                    shades.set(table.len(), poly.intensity.unwrap_or(flat));
                }
                let _ = table.push(Polygon {
                    corners,
                    color: poly.color,
                    packed: Polygon::<S>::pack(o.first_row, o.clockwise, n),
                });
                if counted {
                    let (first, after) = (o.first_row as usize, o.last_row as usize + 1);
                    let c = &mut diff[first];
                    *c = count_of(count(*c).wrapping_add(1));
                    if let Some(c) = diff.get_mut(after) {
                        *c = count_of(count(*c).wrapping_sub(1));
                    }
                }
            }
            Ok(())
        })?;
        let over = |table, needed, capacity: usize| Error::Capacity {
            table,
            needed,
            capacity: capacity as u32,
        };
        let Tally {
            polys,
            uncached,
            smooth,
        } = tally;
        if smooth && !G::KEEPS {
            return Err(Error::Unsupported {
                feature: "smooth shading (this Scanline's G is Flat: see scanline_for!)",
            });
        }
        if polys as usize > P {
            return Err(over(Table::Polygons, polys, P));
        }
        // Geometry hands polygons over in scratch when the buffer is full: too small, then;
        // with room, a scene of its own handed them so.
        if buf.needed() > capacity {
            return Err(over(Table::Vertices, buf.needed() as u32, capacity));
        }
        if let Some(face) = uncached {
            return Err(Error::NotInFrame { face });
        }
        let max_active = self.max_active(lent.unwrap_or(buf.as_slice()), cfg, counted)?;
        self.bucket(cfg);
        self.edges = 0;
        Ok(FrameStats {
            polygons: polys,
            max_active,
            ..FrameStats::default()
        })
    }

    /// Orders the polygon table by first row into `order`, scene order within a row: a
    /// counting sort whose counters borrow the colour row (free until the first row is drawn),
    /// a row's width of rows at a time (one pass unless the frame is taller than the row is
    /// wide).
    fn bucket(&mut self, cfg: &Config) {
        let height = cfg.height as usize;
        let (polygons, order) = (&self.polygons, &mut self.order);
        let first = |p: &Polygon<S>| p.first_row() as usize;
        order.clear();
        order.extend(core::iter::repeat_n(0, polygons.len()));
        // The counters are u16 (the polygon table holds fewer than 2^16), kept as Rgb565's
        // raw storage: a free conversion either way.
        let raw = |c: Rgb565| RawU16::from(c).into_inner();
        let of = |v: u16| Rgb565::from(RawU16::new(v));
        // Polygons placed so far (those starting above `base`).
        let (mut placed, mut base) = (0u16, 0usize);
        while base < height && W > 0 {
            let len = (height - base).min(W);
            let count = &mut self.intensity[..len];
            count.fill(of(0));
            for p in polygons {
                if let Some(c) = count.get_mut(first(p).wrapping_sub(base)) {
                    *c = of(raw(*c) + 1);
                }
            }
            for c in count.iter_mut() {
                let n = raw(*c);
                *c = of(placed);
                placed += n;
            }
            for (i, p) in polygons.iter().enumerate() {
                if let Some(c) = count.get_mut(first(p).wrapping_sub(base)) {
                    if let Some(o) = order.get_mut(raw(*c) as usize) {
                        *o = i as u16;
                    }
                    *c = of(raw(*c) + 1);
                }
            }
            base += len;
        }
    }

    /// Most polygons active in one row, checked against `A`: a difference array over the rows
    /// (+1 where a polygon starts, −1 after it ends), summed top to bottom. Its counters
    /// borrow the colour row, as [`Self::bucket`]'s do. `counted`: [`Self::prepare`] filled it
    /// as the polygons entered the table (a frame no taller than the row); otherwise it is
    /// built here, a row's width of rows at a time, from the polygons' corners.
    #[inline(always)]
    fn max_active(
        &mut self,
        vertices: &[RasterVertex<N>],
        cfg: &Config,
        counted: bool,
    ) -> Result<u32, Error> {
        let height = cfg.height as usize;
        let (raw, of) = (count, count_of);
        let (mut max, mut base) = (0u16, 0usize);
        if counted {
            let mut running = 0u16;
            for c in &self.intensity[..height] {
                running = running.wrapping_add(raw(*c));
                max = max.max(running);
            }
            base = height;
        }
        while base < height {
            let len = (height - base).min(W);
            let count = &mut self.intensity[..len];
            count.fill(of(0));
            // Polygons already open at this chunk's first row.
            let mut running = 0u16;
            for p in &self.polygons {
                let ring = Ring {
                    vertices,
                    polygon: p,
                };
                let (first, last) = (p.first_row() as usize, last_row_of(&ring, cfg) as usize);
                if first < base {
                    running += (last >= base) as u16;
                } else if first < base + len {
                    let c = &mut count[first - base];
                    *c = of(raw(*c).wrapping_add(1));
                }
                if (base..base + len).contains(&(last + 1)) {
                    let c = &mut count[last + 1 - base];
                    *c = of(raw(*c).wrapping_sub(1));
                }
            }
            // The polygons open at `base` were counted in `running`; their −1 (if in this
            // chunk) is in `count`, so the sum stays exact.
            for c in count.iter() {
                running = running.wrapping_add(raw(*c));
                max = max.max(running);
            }
            base += len;
        }
        if max as usize > A {
            return Err(Error::Capacity {
                table: Table::ActivePolygons,
                needed: max as u32,
                capacity: A as u32,
            });
        }
        Ok(max as u32)
    }

    fn run_rows<K: RowSink<N>>(
        &mut self,
        vertices: &[RasterVertex<N>],
        cfg: &Config,
        sink: &mut K,
        stats: &mut FrameStats,
    ) -> Result<(), K::Error> {
        let width = cfg.width as usize;
        // (Never without a depth row: `render` and `prepare` refuse such a frame.)
        let want_depth = D::KEEPS
            && (K::WANTS_DEPTH
                || self
                    .frame_cue()
                    .is_some_and(|c| c.interpolation == Interpolation::PerspectiveCorrect));
        // What every row of the frame shares; `y`, `stale` and `fresh` are set row by row.
        let cue = self
            .frame_cue()
            .is_some_and(|c| c.interpolation == Interpolation::Affine);
        self.row = RowState {
            y: 0,
            width: width as i32,
            s: cfg.subpixel_bits as u32,
            background: cfg.background,
            cue,
            more: want_depth || cue,
            #[cfg(feature = "exact-depth")]
            exact: K::WANTS_DEPTH,
            stale: (0, width as i32),
            // Before the first row, any column may hold something else: its `stale`.
            fresh: (0, width as i32),
        };
        let mut cursor = 0;
        for y in 0..cfg.height as i32 {
            // Polygons whose first row this is enter the active list (their keys after the
            // `old` ones).
            let old = self.sorted.len();
            while let Some(&i) = self.order.get(cursor) {
                if self.polygons[i as usize].first_row() != y {
                    break;
                }
                cursor += 1;
                self.activate(vertices, i, y, cfg, want_depth);
            }
            // What the row before painted is this row's `stale`.
            (self.row.y, self.row.stale, self.row.fresh) = (y, self.row.fresh, (width as i32, 0));
            // A row no polygon crosses (above and below a mesh, most of a frame's rows) is the
            // background (its colour written only where the row before left something else),
            // and nothing more is done for it: what `resolve_row` would do, without its sweep.
            let empty = self.sorted.is_empty();
            if empty {
                self.paint(vertices, 0, width as i32, None, want_depth);
                self.apart = true; // (`fresh` stays empty: nothing painted)
            } else {
                // A heavy row (see `resolve_row`) is resolved by depth over the active
                // polygons in any order: only the sweep needs them by left end.
                if self.cover <= HEAVY_COVER * width as i32 || self.row.cue || !D::KEEPS {
                    self.sort_active(old);
                }
                self.resolve_row(want_depth, stats, vertices);
            }
            let depth: &[N] = if want_depth {
                if !(EXACT_DEPTH && K::WANTS_DEPTH) {
                    // (A sink that reads depth had the cue on each piece, before its exact
                    // depths replaced the stepped ones.)
                    self.shade_painted();
                }
                &self.depth.parts().0[..width]
            } else {
                &[]
            };
            sink.write_row(&Row {
                y: y as u16,
                color: &self.intensity[..width],
                depth,
            })?;
            // (With no keys, stepping has nothing to do.)
            if !empty {
                self.advance(y, cfg, vertices);
            }
        }
        stats.edges = self.edges;
        Ok(())
    }

    /// The perspective-correct depth cue on the row just resolved, over the columns it painted
    /// with polygons (`fresh`): the rest is background, which the cue leaves alone. Out of
    /// line: the row loop keeps its registers for the frames without the cue.
    #[inline(never)]
    fn shade_painted(&mut self) {
        let (x0, x1) = self.row.fresh;
        let painted = x0.max(0) as usize..x1.clamp(0, self.row.width) as usize;
        let cue = self.frame_cue();
        if let (Some(depth), Some(colours)) = (
            self.depth.parts().0.get(painted.clone()),
            self.intensity.get_mut(painted),
        ) {
            Cue::shade_row_if_perspective(&cue, depth, colours);
        }
    }

    /// Polygon `i` enters the active list on row `y`, its first: its depth plane, and its two
    /// edges found down each side from its top vertex.
    #[inline(never)]
    fn activate(
        &mut self,
        vertices: &[RasterVertex<N>],
        i: u16,
        y: i32,
        cfg: &Config,
        want_depth: bool,
    ) {
        let slot = if let Some(a) = self.active.get((self.free as usize).wrapping_sub(1)) {
            let slot = self.free - 1;
            self.free = a.poly; // popped
            slot
        } else if self.used < A {
            self.used += 1;
            (self.used - 1) as u16
        } else {
            return; // cannot happen: `max_active` checked the capacity for every row
        };
        let cue = self.affine_cue();
        let p = &self.polygons[i as usize];
        let ring = Ring {
            vertices,
            polygon: p,
        };
        let a = &mut self.active[slot as usize];
        // Its two edges, written in place. Clockwise on the display: forward from the top runs
        // down the right side.
        let found = if ring.len() == 3 {
            triangle_sides(a, &ring, p.clockwise(), y, cfg)
        } else {
            let top = top_of(&ring) as u8;
            let left = walk_from(ring, top, !p.clockwise(), y, cfg);
            let right = walk_from(ring, top, p.clockwise(), y, cfg);
            if let (Some(left), Some(right)) = (left, right) {
                a.end[RIGHT] = 0; // not planed
                a.set_left(left, left.last as i32 == last_row_of(&ring, cfg));
                a.set_right(right);
            }
            left.is_some() && right.is_some()
        };
        if !found {
            (a.poly, self.free) = (self.free, slot + 1); // cannot happen: the outline covers row y
            return;
        }
        self.edges += 2;
        a.poly = i;
        if N::EXACT_STEPS {
            a.spare = RawU16::from(p.color).into_inner();
        }
        if want_depth || cue.is_some() {
            let planes = Planes {
                vertices,
                polygons: &self.polygons,
                s: cfg.subpixel_bits as u32,
                y,
            };
            planes.ensure(a);
        }
        if let (Some(c), Some(e)) = (cue, self.cues.at_mut(slot as usize)) {
            let (left, right) = (a.walk(LEFT), a.walk(RIGHT));
            e.f[0..2].copy_from_slice(&edge_cue(&c, a, &left, y));
            e.f[2..4].copy_from_slice(&edge_cue(&c, a, &right, y));
            e.last = [left.last, right.last];
        }
        if D::KEEPS {
            self.cover += span_cover(a.xl(), a.xr(), cfg.width as i32);
        }
        let _ = self.sorted.push(key(a.xl(), slot)); // at most A slots are occupied
    }

    /// The frame's cue, if shading is not flat.
    fn frame_cue(&self) -> Option<Cue<N>> {
        self.cued.then_some(self.cue)
    }

    /// The frame's cue if it is interpolated affinely (down edges and across spans).
    fn affine_cue(&self) -> Option<Cue<N>> {
        self.frame_cue()
            .filter(|c| c.interpolation == Interpolation::Affine)
    }

    /// Insertion sort of the keys (left end, then slot): the order barely changes from row to
    /// row, and what moves are four-byte keys, compared as they are. Run before every swept
    /// row; a heavy row, resolved by depth, takes the active polygons in any order and skips
    /// it (the next swept row sorts what has drifted meanwhile).
    ///
    /// The keys of the polygons that entered this row (the last, from `old` on) come in scene
    /// order, and most travel far: they are merged in ([`sort_keys`]), not inserted one place
    /// at a time.
    #[inline(never)]
    fn sort_active(&mut self, old: usize) {
        sort_keys(&mut self.sorted, old);
    }

    /// Retires what ends on row `y` and steps the rest to the next row: each edge one row
    /// down, or, where it ends, the next edge of its side; the span and its left depth.
    #[inline(never)]
    fn advance(&mut self, y: i32, cfg: &Config, vertices: &[RasterVertex<N>]) {
        let Sweep {
            active,
            free,
            polygons,
            edges,
            sorted,
            ..
        } = self;
        let mut kept = 0;
        let (mut cover, w) = (0, cfg.width as i32);
        let below = NextRow {
            polygons,
            vertices,
            y: y + 1,
            cfg,
        };
        let (mut found, mut head) = (0, *free);
        // A plain slice: its length stays in a register (the vector's is re-read after every
        // store through `a`).
        let keys: &mut [u32] = sorted;
        for i in 0..keys.len() {
            let slot = keys[i] as u16;
            let Some(a) = active.get_mut(slot as usize) else {
                continue; // cannot happen: keys hold occupied slots
            };
            // The left edge covers row `y`, so on the polygon's last row it ends there.
            if a.goes_below(LEFT, y) {
                a.dda[LEFT].step();
            } else if a.end[LEFT] & LAST_EDGE != 0 {
                (a.poly, head) = (head, slot + 1); // pushed (below A, so 2^16 − 1 at most)
                continue;
            } else {
                found += next_edge(a, LEFT, &below) as u32;
            }
            if a.goes_below(RIGHT, y) {
                a.dda[RIGHT].step();
            } else {
                found += next_edge(a, RIGHT, &below) as u32;
            }
            // Exact formats step (the same bits; unplaned, a harmless wrapping add to a value
            // nobody reads, cheaper than the test); f32 evaluates the plane where it is read.
            if N::EXACT_STEPS {
                a.z_col = a.z_col.step(a.dzdy, 1);
            }
            if D::KEEPS {
                cover += span_cover(a.xl(), a.xr(), w);
            }
            if let Some(k) = keys.get_mut(kept) {
                *k = key(a.xl(), slot); // kept <= i
            }
            kept += 1;
        }
        sorted.truncate(kept);
        (*edges, *free) = (*edges + found, head);
        self.cover = cover;
        if let Some(c) = self.affine_cue() {
            for &k in self.sorted.iter() {
                let k = k as u16 as usize;
                if let Some(e) = self.cues.at_mut(k) {
                    step_cue(&c, &self.active[k], e, y + 1);
                }
            }
        }
    }

    /// Sweeps the row left to right, filling it from a **front** polygon at a time.
    ///
    /// A polygon in front at both ends of an overlap is in front throughout, depths being
    /// linear in x — applied to whole overlaps: the front beats every other open polygon from
    /// the current column up to `until`, the first column where one of them wins (their
    /// crossing, found exactly by bisection: the sign of a linear difference changes once).
    /// Until then the row is filled with no depth test. A polygon that opens costs one check
    /// against the front (two depth evaluations, bisection only if they cross); one that
    /// closes behind it costs nothing. The front is sought again among the open polygons only
    /// when it closes, is overtaken at its crossing, or a newcomer is in front of it — that
    /// is, where the visible surface changes.
    ///
    /// Most spans of a mesh meet no other (neighbours abut): a span that no later span opens
    /// inside is filled at once, with no bookkeeping; the sweep above runs only from where
    /// spans overlap until nothing is open again.
    #[inline(never)]
    fn resolve_row(
        &mut self,
        want_depth: bool,
        stats: &mut FrameStats,
        vertices: &[RasterVertex<N>],
    ) {
        let w = self.row.width;
        // (Until `overlap` finds spans that meet.)
        let apart = core::mem::replace(&mut self.apart, true);
        if self.cover > HEAVY_COVER * w && !self.row.cue && D::KEEPS {
            self.resolve_by_depth(vertices);
            return;
        }
        // Spans that follow one another apart (a mesh's rows nearly always) are painted as
        // they come; the sweep takes over where one meets the one before it.
        // Not tried on the row after one where spans met: overlap comes in runs of rows (the
        // painting up to the meeting would be done again), until a row is swept without any.
        let (mut cur, mut k) = (0i32, 0usize);
        let painted = match (!G::KEEPS && apart, self.row.more) {
            (false, _) => None,
            (true, false) => Some(self.paint_apart::<false, false>(vertices)),
            (true, true) => self.paint_apart_more(vertices, want_depth),
        };
        if let Some(painted) = painted {
            match painted {
                Ok(painted_to) => {
                    let from = self.sorted.first().map_or(w, |&key| key_left(key).max(0));
                    self.row.fresh = (from, painted_to);
                    return;
                }
                Err(resume) => (cur, k) = resume,
            }
        }
        let painted_to = loop {
            if cur >= w {
                break cur;
            }
            // The next span that opens anything (passing over spans empty in this row or
            // already behind `cur`).
            let mut next = None;
            while let Some(&key) = self.sorted.get(k) {
                k += 1;
                let (slot, xl) = (key as u16 as usize, key_left(key).max(cur));
                let xr = self.active[slot].xr();
                if xr > xl {
                    next = Some((slot, xl, xr));
                    break;
                }
            }
            let Some((slot, start, xr)) = next.filter(|&(_, start, _)| start < w) else {
                self.paint(vertices, cur, w, None, want_depth);
                break cur;
            };
            self.paint(vertices, cur, start, None, want_depth);
            cur = start;
            // Alone unless a later span opens before this one ends.
            let mut j = k;
            let mut alone = true;
            while let Some(&key) = self.sorted.get(j) {
                let xl = key_left(key);
                if xl >= xr {
                    break;
                }
                if self.active[key as u16 as usize].xr() > xl.max(cur) {
                    alone = false;
                    break;
                }
                j += 1;
            }
            if alone {
                k = j; // the spans passed over are empty
                let end = xr.min(w);
                self.paint(vertices, cur, end, Some(slot), want_depth);
                cur = end;
            } else {
                // (It paints every column from `cur` to where it stops.)
                (cur, k) = self.overlap(vertices, cur, k, slot, want_depth, stats);
            }
        };
        // The columns painted with a polygon (the next row's `stale`), found once a row rather
        // than per span: up to where the last span painted ended, from the least left end (the
        // keys are sorted by it; columns before the first span painted, if any, got the
        // background this row and are only repainted with it on the next).
        let from = self.sorted.first().map_or(w, |&key| key_left(key).max(0));
        self.row.fresh = (from, painted_to);
    }

    /// [`Self::paint_apart`] for a row that wants depths or the affine cue too; `None` for one
    /// that wants both, or exact depths (the sweep paints those).
    fn paint_apart_more(
        &mut self,
        vertices: &[RasterVertex<N>],
        want_depth: bool,
    ) -> Option<Result<i32, (i32, usize)>> {
        match (want_depth, self.row.cue) {
            _ if self.row.exact() => None,
            (true, false) => Some(self.paint_apart::<true, false>(vertices)),
            (false, true) => Some(self.paint_apart::<false, true>(vertices)),
            _ => None,
        }
    }

    /// Paints the row's spans in the order of the keys while each begins at or after the end of
    /// the one before (none meets another: each is the visible surface wherever it lies), the
    /// columns between them with the background, as the sweep would; returns where the last
    /// span painted ends. `Err((cur, k))`: a span meets the one before it, painted from `cur`
    /// and taken at key `k` — the sweep resumes there (columns before `cur` are done, and it
    /// repaints every column from `cur` on). What the sweep's [`Self::paint_more`] adds, as it
    /// does: `DEPTH`, the depth row (each span its plane's depths, the background the format's
    /// maximum) for a row whose depths are read (the perspective-correct cue, a sink that
    /// reads depth); `CUE`, the affine depth cue across each span.
    #[inline(never)]
    fn paint_apart<const DEPTH: bool, const CUE: bool>(
        &mut self,
        vertices: &[RasterVertex<N>],
    ) -> Result<i32, (i32, usize)> {
        let Sweep {
            sorted,
            active,
            intensity,
            polygons,
            row,
            depth,
            cues,
            ..
        } = self;
        // (Within the colour row: `Config::validate` checked the width.)
        let w = row.width.min(W as i32);
        let depths = depth.parts().0;
        let background_depth = |depths: &mut [N], x0: i32, x1: i32| {
            if let Some(run) = depths.get_mut(x0 as usize..x1 as usize) {
                run.fill(N::MAX);
            }
        };
        // Painted up to `cur`; the last span with columns ends at `end` (unclamped).
        let (mut cur, mut end) = (0i32, i32::MIN);
        let mut keys = sorted.iter();
        while let Some(&key) = keys.next() {
            let slot = key as u16 as usize;
            let Some(a) = active.get_mut(slot) else {
                continue; // cannot happen: keys hold occupied slots
            };
            let (xl, xr) = (a.xl(), a.xr());
            // Spans with no columns on the row (empty, or off either end) are passed over: they
            // meet nothing there.
            let (x0, x1) = (xl.max(0), xr.min(w));
            if x0 >= x1 {
                continue;
            }
            if xl < end {
                // Meets the span before.
                let taken = sorted.len() - keys.len() - 1;
                return Err(resume_at(sorted.get(..taken).unwrap_or(&[]), active, w));
            }
            end = xr;
            if cur < x0 {
                fill_background(intensity, row.stale, row.background, cur, x0);
                if DEPTH {
                    background_depth(depths, cur, x0);
                }
            }
            if let Some(run) = intensity.get_mut(x0 as usize..x1 as usize) {
                fill_run(run, a.color(polygons));
            }
            if DEPTH {
                let planes = Planes {
                    vertices,
                    polygons,
                    s: row.s,
                    y: row.y,
                };
                planes.ensure(a);
                if let Some(run) = depths.get_mut(x0 as usize..x1 as usize) {
                    fill_depth(run, a, row.y, x0);
                }
            }
            if let (true, Some(e)) = (CUE, cues.at(slot)) {
                cue_span(intensity, a, e, x0, x1);
            }
            cur = x1;
        }
        fill_background(intensity, row.stale, row.background, cur, w);
        if DEPTH {
            background_depth(depths, cur, w);
        }
        Ok(cur)
    }

    /// The sweep from column `cur` where span `first` (already taken from the keys, up to
    /// `k`) meets others, until nothing is open; returns where it stopped and the next key.
    /// Out of line: a mesh's rows rarely come here, and the loop of spans alone keeps its
    /// registers.
    #[inline(never)]
    fn overlap(
        &mut self,
        vertices: &[RasterVertex<N>],
        mut cur: i32,
        mut k: usize,
        first: usize,
        want_depth: bool,
        stats: &mut FrameStats,
    ) -> (i32, usize) {
        /// No front polygon.
        const NONE: usize = usize::MAX;
        self.apart = false;
        let RowState { y, width: w, s, .. } = self.row;
        self.open.clear();
        let _ = self.open.push(first as u16);
        let planes = Planes {
            vertices,
            polygons: &self.polygons,
            s,
            y,
        };
        planes.ensure(&mut self.active[first]);
        // The front polygon: its slot, its index in `open`, where its span ends, and the first
        // column where another open polygon may overtake it.
        let (mut front, mut at, mut front_xr, mut until) = (NONE, 0usize, 0i32, i32::MAX);
        // Whether a front's run may be painted in one piece past spans that open behind it:
        // where a run's pixels do not depend on where it starts (flat colour, or a shade
        // stepped exactly) and nothing else is written per run (depths, the affine cue).
        // (A renderer with neither a depth row nor the affine cue's state writes nothing else:
        // known when it is built.)
        let more = (D::KEEPS || C::KEEPS) && self.row.more;
        let ahead = !more && (N::EXACT_STEPS || !G::KEEPS);
        loop {
            let (active, sorted, open) = (&mut self.active[..], &self.sorted[..], &mut self.open);
            // Spans opening at or before `cur` (left ends read from the keys).
            while let Some(&key) = sorted.get(k) {
                if key_left(key) > cur {
                    break;
                }
                k += 1;
                let slot = key as u16 as usize;
                if active[slot].xr() > cur {
                    ensure_plane(&mut active[slot], vertices, &self.polygons, s, y);
                    // (Painting ahead, no front is left here: each run goes on until the
                    // front ends, is overtaken or the row ends.)
                    let behind = !ahead
                        && front != NONE
                        && match challenge(active, front, slot, cur, y) {
                            Some(u) => {
                                until = until.min(u);
                                hidden(active, front, slot, u)
                            }
                            None => {
                                front = NONE; // the newcomer is in front
                                false
                            }
                        };
                    if !behind {
                        // Cannot fail: `open` has the active list's capacity.
                        let _ = open.push(slot as u16);
                    }
                }
            }
            let next_start = sorted.get(k).map_or(w, |&key| key_left(key)).min(w);
            if front == NONE {
                // Spans that closed behind the last front leave only now.
                open.retain(|&i| active[i as usize].xr() > cur);
                if open.is_empty() {
                    return (cur, k); // nothing open: back to spans alone
                }
                (front, at, until) = if open.len() == 1 {
                    (open[0] as usize, 0, i32::MAX)
                } else {
                    establish(active, open, cur, y)
                };
                front_xr = active[front].xr();
                stats.front_changes += 1;
            }
            let mut next = front_xr.min(until).min(w);
            // Where painting may go on past openings: each span opening behind the front
            // before it ends or is overtaken, challenged at its own first column (as if the
            // sweep had stopped there), up to the first that comes in front.
            let mut overtaken = false;
            while let (true, Some(&key)) = (ahead, sorted.get(k)) {
                let c = key_left(key);
                if c >= next {
                    break;
                }
                k += 1;
                let slot = key as u16 as usize;
                if active[slot].xr() > c {
                    ensure_plane(&mut active[slot], vertices, &self.polygons, s, y);
                    match challenge(active, front, slot, c, y) {
                        Some(u) => {
                            (until, next) = (until.min(u), next.min(u));
                            if !hidden(active, front, slot, u) {
                                let _ = open.push(slot as u16);
                            }
                        }
                        None => {
                            let _ = open.push(slot as u16);
                            (next, overtaken) = (c, true); // the newcomer is in front
                            break;
                        }
                    }
                }
            }
            if !ahead {
                next = next.min(next_start);
            }
            self.paint(vertices, cur, next, Some(front), want_depth);
            cur = next;
            if cur >= w {
                return (cur, k);
            }
            if overtaken {
                front = NONE;
            } else if front_xr <= cur {
                self.open.swap_remove(at); // closed
                front = NONE;
            } else if until <= cur {
                stats.crossings += 1; // overtaken
                front = NONE;
            }
        }
    }

    /// Fills columns `x0..x1` of the row from the polygon in `slot` (its colour, and its depth
    /// when someone reads it), or with the background.
    #[inline(always)]
    fn paint(
        &mut self,
        vertices: &[RasterVertex<N>],
        x0: i32,
        x1: i32,
        slot: Option<usize>,
        want_depth: bool,
    ) {
        if x0 >= x1 {
            return;
        }
        match slot {
            Some(i) => {
                let run = &mut self.intensity[x0 as usize..x1 as usize];
                let a = &self.active[i];
                let color = a.color(&self.polygons);
                if G::KEEPS {
                    let shade = self.shades.at(a.poly as usize);
                    paint_run(run, color, shade, x0, self.row.y);
                } else {
                    fill_run(run, color);
                }
            }
            None => {
                // Only where the row before left something else.
                let (b0, b1) = (x0.max(self.row.stale.0), x1.min(self.row.stale.1));
                if b0 < b1 {
                    fill_run(
                        &mut self.intensity[b0 as usize..b1 as usize],
                        self.row.background,
                    );
                }
            }
        }
        if self.row.more {
            self.paint_more(vertices, x0, x1, slot, want_depth);
        }
    }

    /// Resolves a row of heavy overlap pixel by pixel (the scan-line z-buffer: Foley & van
    /// Dam §15.4): each span is depth-tested into the depth row, the visible polygon being the
    /// least (depth, scene order) as in the sweep, so the result is the same. While the spans
    /// are drawn the colour row holds each pixel's polygon number (a free reuse of its bits),
    /// turned into colours at the end.
    ///
    /// A hierarchical depth (Greene, Kass & Miller 1993, at the scale of a row) keeps the
    /// farthest depth stored in each block of pixels: depth being linear along the row, a
    /// span's nearest depth over a block is at one of its ends, and where that is farther
    /// than the block's farthest, no pixel of the block can win — the block, or the whole
    /// span, is passed over exactly.
    #[inline(never)]
    fn resolve_by_depth(&mut self, vertices: &[RasterVertex<N>]) {
        /// No polygon.
        const NOBODY: u16 = u16::MAX;
        let raw = |c: Rgb565| RawU16::from(c).into_inner();
        let of = |v: u16| Rgb565::from(RawU16::new(v));
        let max = |m: N, &d: &N| if d > m { d } else { m };
        let RowState {
            y,
            width,
            s,
            background,
            ..
        } = self.row;
        let w = width as usize;
        let planes = Planes {
            vertices,
            polygons: &self.polygons,
            s,
            y,
        };
        self.row.fresh = (0, width);
        let (depth, hiz) = self.depth.parts();
        let (depth, owner) = (&mut depth[..w], &mut self.intensity[..w]);
        depth.fill(N::MAX);
        owner.fill(of(NOBODY));
        // Blocks of `1 << shift` pixels, at most HIZ_BLOCKS of them.
        let mut shift = HIZ_BLOCK.trailing_zeros();
        while w > HIZ_BLOCKS << shift {
            shift += 1;
        }
        let hiz = &mut hiz[..w.div_ceil(1 << shift)];
        hiz.fill(N::MAX);
        // First the occluders: a span that covers a whole block bounds the depth the block
        // ends with by its own farthest depth there (an end of the block: depth is linear,
        // and its evaluation monotone), so before any pixel is tested every block starts
        // with the least such bound. A block's bound only ever falls: it is at all times
        // at least the farthest depth the block will end with, which is what passing a span
        // over needs.
        let block = 1usize << shift;
        // Worth a pass only where spans are long: on average two blocks or more.
        let long = self.cover as usize >= 2 * block * self.sorted.len();
        for &key in self.sorted.iter().filter(|_| long) {
            let a = &mut self.active[key as u16 as usize];
            let (x0, x1) = (a.xl().max(0) as usize, a.xr().min(width).max(0) as usize);
            let (first, end) = (x0.div_ceil(block), x1 >> shift);
            if first >= end {
                continue; // no whole block
            }
            if !a.planed() {
                // Checked here: the heavy rows meet each polygon once a row, its plane once.
                planes.ensure(a);
            }
            let (dzdx, row) = (a.dzdx, RowDepths::new(a, y));
            let rising = dzdx >= N::ZERO;
            for b in first..end.min(hiz.len()) {
                let far_x = if rising {
                    ((b + 1) << shift) - 1
                } else {
                    b << shift
                };
                let far = row.at(far_x as i32);
                if far < hiz[b] {
                    hiz[b] = far;
                }
            }
        }
        for &key in &self.sorted {
            let a = &mut self.active[key as u16 as usize];
            let (x0, x1) = (a.xl().max(0), a.xr().min(width));
            if x0 >= x1 {
                continue;
            }
            if !a.planed() {
                planes.ensure(a);
            }
            let (dzdx, row) = (a.dzdx, RowDepths::new(a, y));
            let (x0, x1) = (x0 as usize, x1 as usize);
            // Depth is linear along the row: its least over a stretch is at the stretch's
            // left end if it grows to the right, else at its right end.
            let rising = dzdx >= N::ZERO;
            let near_of = |z0: N, len: i32| {
                if rising {
                    z0
                } else {
                    z0.step(dzdx, len - 1)
                }
            };
            let z_start = row.at(x0 as i32);
            if x1 - x0 <= 1 << shift {
                // A short span (one or two blocks): tested pixel by pixel unless its blocks'
                // bounds pass it over. The bounds are left as they are (still bounds: writes
                // only lower depths).
                let bound = max(hiz[x0 >> shift], &hiz[(x1 - 1) >> shift]);
                if near_of(z_start, (x1 - x0) as i32) <= bound {
                    let (d, o) = (&mut depth[x0..x1], &mut owner[x0..x1]);
                    test_pixels::<N, false>(&row, x0, d, o);
                }
                continue;
            }
            // Hidden all along if its nearest depth is beyond every block's bound (stopping at
            // the first block it may win in: a plain loop, the iterators cost more).
            let near = near_of(z_start, (x1 - x0) as i32);
            let (bl, br) = (x0 >> shift, (x1 - 1) >> shift);
            let mut b = bl;
            while b <= br && near > hiz[b] {
                b += 1;
            }
            if b > br {
                continue; // hidden all along
            }
            // The blocks before `b` are passed over: hidden there too.
            let (mut b0, mut z0) = if b > bl {
                let start = b << shift;
                (start, z_start.step(dzdx, (start - x0) as i32))
            } else {
                (x0, z_start)
            };
            while b0 < x1 {
                let b = b0 >> shift;
                let b1 = ((b + 1) << shift).min(x1);
                let len = (b1 - b0) as i32;
                // Exact formats step from block to block; f32 evaluates the block's nearer
                // end only (the same bits as evaluating both and choosing).
                let near = if N::EXACT_STEPS {
                    near_of(z0, len)
                } else {
                    row.at(if rising { b0 } else { b1 - 1 } as i32)
                };
                if near <= hiz[b] {
                    let whole = b0 == b << shift && b1 == ((b + 1) << shift).min(w);
                    let (d, o) = (&mut depth[b0..b1], &mut owner[b0..b1]);
                    if whole {
                        // The block's farthest depth now, from the pass itself (the span
                        // covers the block), if below its bound.
                        if let Some(far) = test_pixels::<N, true>(&row, b0, d, o) {
                            if far < hiz[b] {
                                hiz[b] = far;
                            }
                        }
                    } else {
                        // A span covering part of the block leaves the bound as it is: still
                        // a bound (depths only fall).
                        test_pixels::<N, false>(&row, b0, d, o);
                    }
                }
                if N::EXACT_STEPS {
                    z0 = z0.step(dzdx, len);
                }
                b0 = b1;
            }
        }
        if G::KEEPS || self.row.exact() {
            return self.owners_to_shades(vertices, background);
        }
        // Owners to colours; neighbours mostly share an owner, so the last lookup is kept.
        let (mut last, mut color) = (NOBODY, background);
        for c in owner.iter_mut() {
            let o = raw(*c);
            if o != last {
                last = o;
                color = match self.polygons.get(o as usize) {
                    Some(p) => p.color,
                    None => background, // NOBODY
                };
            }
            *c = color;
        }
    }

    /// [`Self::resolve_by_depth`]'s owners to colours under smooth shading: each owner's
    /// intensity plane at its pixels, stepped along the row from where a run of it starts.
    fn owners_to_shades(&mut self, vertices: &[RasterVertex<N>], background: Rgb565) {
        let raw = |c: Rgb565| RawU16::from(c).into_inner();
        let y = self.row.y;
        let width = (self.row.width.max(0) as usize).min(W);
        let mut x = 0;
        while x < width {
            let owner = &mut self.intensity[..width];
            let o = raw(owner[x]);
            let same = owner[x..].iter().position(|&c| raw(c) != o);
            let end = same.map_or(width, |n| x + n);
            let run = &mut owner[x..end];
            match self.polygons.get(o as usize) {
                Some(p) => paint_run(run, p.color, self.shades.at(o as usize), x as i32, y),
                None => fill_run(run, background), // NOBODY
            }
            if self.row.exact() && (o as usize) < self.polygons.len() {
                self.exact_depths(vertices, o as usize, x, end);
            }
            x = end;
        }
    }

    /// The depth (when read) and affine cue of a piece [`Self::paint`] coloured.
    #[cold]
    #[inline(never)]
    fn paint_more(
        &mut self,
        vertices: &[RasterVertex<N>],
        x0: i32,
        x1: i32,
        slot: Option<usize>,
        want_depth: bool,
    ) {
        let (a0, a1) = (x0 as usize, x1 as usize);
        let Some(slot) = slot else {
            if want_depth {
                self.depth.parts().0[a0..a1].fill(N::MAX);
            }
            return;
        };
        if want_depth {
            let planes = Planes {
                vertices,
                polygons: &self.polygons,
                s: self.row.s,
                y: self.row.y,
            };
            planes.ensure(&mut self.active[slot]);
            let y = self.row.y;
            fill_depth(&mut self.depth.parts().0[a0..a1], &self.active[slot], y, x0);
            if self.row.exact() {
                let poly = self.active[slot].poly as usize;
                self.exact_depths(vertices, poly, a0, a1);
            }
        }
        if let (true, Some(e)) = (self.row.cue, self.cues.at(slot)) {
            cue_span(&mut self.intensity, &self.active[slot], e, x0, x1);
        }
    }

    /// For a sink that reads depth: columns `a0..a1` of the row, coloured by polygon `poly`
    /// and holding its stepped depths, get the perspective cue from those depths, then the
    /// polygon's exact depths ([`Scalar::exact_run`]; its plane found again from its vertices,
    /// a cost only such a sink pays).
    #[cold]
    #[inline(never)]
    fn exact_depths(&mut self, vertices: &[RasterVertex<N>], poly: usize, a0: usize, a1: usize) {
        let (Some(depth), Some(colours)) = (
            self.depth.parts().0.get_mut(a0..a1),
            self.intensity.get_mut(a0..a1),
        ) else {
            return;
        };
        let cue = self.cued.then_some(self.cue);
        Cue::shade_row_if_perspective(&cue, depth, colours);
        let Some(p) = self.polygons.get(poly) else {
            return;
        };
        let ring = Ring {
            vertices,
            polygon: p,
        };
        if let Some(e) = exact_of(&ring, self.row.s) {
            N::exact_run(&e, a0 as i32, self.row.y, depth);
        }
    }
}

impl<
        N: Scalar,
        const W: usize,
        const V: usize,
        const P: usize,
        const A: usize,
        S: Slot,
        C: CueStore<N>,
        G: ShadeStore<N>,
        D: DepthRow<N>,
    > Renderer<N> for Scanline<N, W, V, P, A, S, C, G, D>
{
    const NAME: &'static str = "scanline";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        Scanline::render(self, scene, cfg, sink)
    }
}

/// The walk of the edge from `p` down to `q` (at position `at` of its polygon's ring) at row
/// `y`, if the edge goes down and covers `y` (its first row being at or above `y`).
#[inline]
fn edge_walk<N>(
    p: &RasterVertex<N>,
    q: &RasterVertex<N>,
    at: usize,
    y: i32,
    cfg: &Config,
) -> Option<Walk> {
    edge_last(p, q, y, cfg).map(|last| Walk {
        dda: Dda::between(p.x, p.y, q.x, q.y, y, cfg.subpixel_bits as u32),
        last: last as i16,
        at: at as u8,
    })
}

/// The last sample row of the edge from `p` down to `q`, if the edge goes down and covers
/// row `y` (what [`edge_walk`] walks, and [`next_edge`] writes in place).
#[inline(always)]
fn edge_last<N>(p: &RasterVertex<N>, q: &RasterVertex<N>, y: i32, cfg: &Config) -> Option<i32> {
    let (s, h, height) = (cfg.subpixel_bits as u32, cfg.half(), cfg.height as i32);
    let last = row_at_or_below(q.y, s, h).min(height) - 1;
    (q.y > p.y && last >= y).then_some(last)
}

/// The edge of one side of a polygon that crosses row `y`, walking its vertex ring from
/// position `at` (forward or backward) downwards; `None` if the side ends above `y`.
fn walk_from<N: Copy, S: Slot>(
    ring: Ring<'_, N, S>,
    at: u8,
    forward: bool,
    y: i32,
    cfg: &Config,
) -> Option<Walk> {
    let n = ring.len();
    let mut at = at as usize;
    let mut p = *ring.get(at);
    for _ in 0..n {
        let next = match forward {
            true if at + 1 == n => 0,
            true => at + 1,
            false if at == 0 => n - 1,
            false => at - 1,
        };
        let q = *ring.get(next);
        if q.y < p.y {
            return None; // past the bottom
        }
        if let Some(w) = edge_walk(&p, &q, next, y, cfg) {
            return Some(w);
        }
        (at, p) = (next, q);
    }
    None
}

/// A triangle's left and right edges at row `y`, its first, written into `a`: each side's
/// walk from the top vertex, to its neighbour, or on to the third corner where that first edge
/// ends above `y` (what [`walk_from`] finds, without walking a ring), the left one flagged if
/// it ends on the triangle's last row, and no plane. `false` if a side has no edge there
/// (cannot happen: the outline covers row `y`).
#[inline]
fn triangle_sides<N: Scalar, S: Slot>(
    a: &mut Active<N>,
    ring: &Ring<'_, N, S>,
    clockwise: bool,
    y: i32,
    cfg: &Config,
) -> bool {
    // Recorded from its top vertex ([`top_first`]).
    let v = [ring.get(0), ring.get(1), ring.get(2)];
    let (s, h, height) = (cfg.subpixel_bits as u32, cfg.half(), cfg.height as i32);
    // The last sample row of an edge ending at corner `k` (each worked out once).
    let last = |k: usize| row_at_or_below(v[k].y, s, h).min(height) - 1;
    let (l1, l2) = (last(1), last(2));
    // Down one side, through corner `n` then `m`: the edge covering row `y` (from, to, its
    // last row), as `edge_walk` takes it.
    let side = |n: usize, ln: i32, m: usize, lm: i32| {
        if v[n].y > v[0].y && ln >= y {
            Some((0, n, ln))
        } else if v[m].y > v[n].y && lm >= y {
            Some((n, m, lm))
        } else {
            None
        }
    };
    let (Some(forward), Some(backward)) = (side(1, l1, 2, l2), side(2, l2, 1, l1)) else {
        return false;
    };
    let (left, right) = match clockwise {
        true => (backward, forward),
        false => (forward, backward),
    };
    let dda = |d: &mut Dda, (p, q, _): (usize, usize, i32)| {
        d.set_between(v[p].x, v[p].y, v[q].x, v[q].y, y, s)
    };
    let end = |(_, q, last): (usize, usize, i32)| end_bits(last, q);
    // Its first two edges: one of them ends at its lowest corner, its last row.
    let lowest = left.2.max(right.2);
    let [l, r] = &mut a.dda;
    dda(l, left);
    dda(r, right);
    a.end = [end(left) | flag(left.2 == lowest, LAST_EDGE), end(right)];
    true
}

/// The next edge down one side of an active polygon, from where its current edge ended, at
/// row `at_row.y` (out of the row loop: it happens once or twice per polygon); whether one
/// was found.
#[cold]
#[inline(never)]
fn next_edge<N: Scalar, S: Slot>(
    a: &mut Active<N>,
    side: usize,
    at_row: &NextRow<'_, N, S>,
) -> bool {
    let NextRow {
        polygons,
        vertices,
        y,
        cfg,
    } = *at_row;
    let p = &polygons[a.poly as usize];
    let ring = Ring {
        vertices,
        polygon: p,
    };
    let at = (a.end[side] & RING_POSITION) as u8;
    // Clockwise on the display: forward from the top runs down the right side.
    let forward = (side == RIGHT) == p.clockwise();
    let triangle = ring.len() == 3;
    if triangle {
        // A triangle's side has two edges (from its top, recorded first): the second runs
        // from the end of the first to the third corner, forward or backward round the
        // ring, its lowest. (Beyond it the side turns up: nothing more, as `walk_from` would
        // find.) `edge_walk`'s, written in place.
        let at = at as usize;
        let to = if forward { (at + 1) % 3 } else { (at + 2) % 3 };
        let (p, q) = (ring.get(at), ring.get(to));
        if let Some(last) = edge_last(p, q, y, cfg) {
            let s = cfg.subpixel_bits as u32;
            a.dda[side].set_between(p.x, p.y, q.x, q.y, y, s);
            // The second edge of a side is its last: on the left, the polygon's.
            let keep = match side {
                RIGHT => a.end[RIGHT] & PLANED,
                _ => LAST_EDGE,
            };
            a.end[side] = end_bits(last, to) | keep;
            return true;
        }
    }
    let next = match triangle {
        true => None,
        false => walk_from(ring, at, forward, y, cfg),
    };
    match (next, side) {
        (Some(next), RIGHT) => a.set_right(next),
        (Some(next), _) => {
            let last = triangle || next.last as i32 == last_row_of(&ring, cfg);
            a.set_left(next, last);
        }
        // Cannot happen (a polygon's left side covers every row it does): retire it.
        (None, LEFT) => {
            a.end[LEFT] |= LAST_EDGE;
            return false;
        }
        (None, _) => return false,
    }
    true
}

/// What [`next_edge`] reads besides the active entry, in one place: the row loop that calls
/// it keeps one address for them instead of six arguments' worth of registers.
#[derive(Clone, Copy)]
struct NextRow<'a, N, S: Slot> {
    polygons: &'a [Polygon<S>],
    vertices: &'a [RasterVertex<N>],
    /// The row the next edge is walked from.
    y: i32,
    cfg: &'a Config,
}

/// The affine cue one row down: each edge's factor stepped, or set up again where the edge
/// changed.
fn step_cue<N: Scalar>(c: &Cue<N>, a: &Active<N>, e: &mut EdgeCue<N>, y: i32) {
    for side in [LEFT, RIGHT] {
        let w = a.walk(side);
        let k = 2 * side;
        if e.last[side] == w.last {
            e.f[k] = e.f[k].add(e.f[k + 1]);
        } else {
            let v = edge_cue(c, a, &w, y);
            e.f[k..k + 2].copy_from_slice(&v);
            e.last[side] = w.last;
        }
    }
}

/// Affine cue on one edge from row `y`: the exact factor where the edge crosses `y` and the
/// linear step per row to where it crosses its last row (Gouraud down an edge).
fn edge_cue<N: Scalar>(c: &Cue<N>, a: &Active<N>, w: &Walk, y: i32) -> [N; 2] {
    // Depth at the crossing: the plane at column x, stepped back by the fraction.
    let on_edge =
        |d: &Dda, row: i32| c.at_depth(a.plane_at(y, d.x(), row).sub(a.dzdx.mul(d.fraction())));
    let cue = on_edge(&w.dda, y);
    let rows = w.last as i32 - y;
    if rows <= 0 {
        return [cue, N::ZERO];
    }
    // The walk at the edge's last row: stepped there (exact, the same state as set up there).
    let mut end = w.dda;
    for _ in 0..rows {
        end.step();
    }
    let n = N::from_int(rows);
    [
        cue,
        on_edge(&end, w.last as i32)
            .sub(cue)
            .div(n)
            .unwrap_or(N::ZERO),
    ]
}

/// Where the sweep resumes a row that [`Scanline::paint_apart`] painted up to a span that
/// meets the one before it, `keys` being the keys it took before that span: at the last span
/// it painted (the spans since began and ended before it, beyond the row's ends), from its
/// start — the column and the key; at the start of the row if it painted none.
#[cold]
#[inline(never)]
fn resume_at<N: Scalar>(keys: &[u32], active: &[Active<N>], w: i32) -> (i32, usize) {
    let span = |k: u32| active.get(k as u16 as usize);
    let painted = |b: &Active<N>| b.xr() > b.xl() && b.xr() > 0 && b.xl() < w;
    let last = keys.iter().rposition(|&k| span(k).is_some_and(painted));
    last.map_or((0, 0), |at| {
        let x0 = keys.get(at).and_then(|&k| span(k)).map_or(0, |b| b.xl());
        (x0.max(0), at)
    })
}

/// Fills columns `x0..x1` of a colour row with the background, only where the row before left
/// something else (`stale`).
#[inline(always)]
fn fill_background(row: &mut [Rgb565], stale: (i32, i32), background: Rgb565, x0: i32, x1: i32) {
    let (b0, b1) = (x0.max(stale.0), x1.min(stale.1));
    if b0 < b1 {
        if let Some(run) = row.get_mut(b0 as usize..b1 as usize) {
            fill_run(run, background);
        }
    }
}

/// Pixels of a row `0..w` that the span `xl..xr` covers.
#[inline]
fn span_cover(xl: i32, xr: i32, w: i32) -> i32 {
    (xr.min(w) - xl.max(0)).max(0)
}

/// Depth-tests one polygon's span into a piece of row (`depth` and `owner` from column `x0`):
/// where it is nearer, or as near and first in the scene, it takes the pixel. `None` if it
/// took none; else, with `FAR`, the farthest depth the pixels hold afterwards (found in the
/// same pass), without, any value.
#[inline]
fn test_pixels<N: Scalar, const FAR: bool>(
    row: &RowDepths<'_, N>,
    x0: usize,
    depth: &mut [N],
    owner: &mut [Rgb565],
) -> Option<N> {
    let raw = |c: Rgb565| RawU16::from(c).into_inner();
    let of = |v: u16| Rgb565::from(RawU16::new(v));
    let (poly, dzdx, z_row) = (row.a.poly, row.a.dzdx, row.z_row);
    // One length for both rows, so the indexing below needs no checks.
    let n = depth.len().min(owner.len());
    let (depth, owner) = (&mut depth[..n], &mut owner[..n]);
    let (mut wrote, mut most) = (false, N::ZERO);
    // f32 evaluates each pixel, `z_row + dzdx·x`; with an FPU x is counted in f32 (exact
    // below 2^24, so the same bits as `depth_at` without an integer conversion a pixel).
    let mut z = row.at(x0 as i32);
    let mut xf = N::from_int(x0 as i32);
    for i in 0..n {
        // Exact formats step (the same bits); f32 evaluates each pixel.
        if !N::EXACT_STEPS {
            if FPU {
                z = z_row.add(dzdx.mul(xf));
                xf = xf.add(N::ONE);
            } else {
                z = z_row.step(dzdx, (x0 + i) as i32);
            }
        }
        let mut d = depth[i];
        // `nearer`, written out: the owner is read only on a tie (measured: 3 % of
        // random400 when read every pixel).
        if z < d || (z == d && poly < raw(owner[i])) {
            (depth[i], owner[i], wrote) = (z, of(poly), true);
            d = z;
        }
        if FAR && (i == 0 || d > most) {
            most = d;
        }
        if N::EXACT_STEPS {
            z = z.step(dzdx, 1);
        }
    }
    wrote.then_some(most)
}

/// A sort key: the left end (biased to unsigned; spans lie within the guard band, far inside
/// ±2^15) above the slot, so keys order by left end, then slot.
#[inline]
fn key(xl: i32, slot: u16) -> u32 {
    ((xl + 0x8000) as u32) << 16 | slot as u32
}

/// The left end a key holds.
#[inline]
fn key_left(key: u32) -> i32 {
    (key >> 16) as i32 - 0x8000
}

/// Depth of an active polygon at the centre of pixel `x` of the current row `y` (in fixed
/// point the plane's own bits: wrapping steps are exact).
#[inline]
fn depth_at<N: Scalar>(a: &Active<N>, y: i32, x: i32) -> N {
    a.plane_at(y, x, y)
}

/// [`depth_at`] for many columns of the current row: f32 evaluates the row's depth at column
/// 0 once (`z_row`); the exact formats step from the entry's, which is the row's.
struct RowDepths<'a, N: Scalar> {
    a: &'a Active<N>,
    y: i32,
    z_row: N,
}

impl<'a, N: Scalar> RowDepths<'a, N> {
    #[inline]
    fn new(a: &'a Active<N>, y: i32) -> Self {
        let z_row = if N::EXACT_STEPS {
            N::ZERO // not read
        } else {
            a.column_0_at(y, y)
        };
        RowDepths { a, y, z_row }
    }

    /// The depth at the centre of pixel `x`.
    #[inline]
    fn at(&self, x: i32) -> N {
        if N::EXACT_STEPS {
            depth_at(self.a, self.y, x)
        } else {
            self.z_row.step(self.a.dzdx, x)
        }
    }
}

/// [`Scanline::sort_active`]'s sort of distinct keys, ascending: the first `old` (the keys
/// that were active on the row before, in last row's order: nearly sorted) and the rest (the
/// polygons that entered this row, in scene order) are each sorted by insertion, then merged
/// from the back, each earlier key moving at most once however far the new ones go; up to
/// [`INSERT_ALL`] keys in all, one insertion sort does it more cheaply.
#[inline(always)]
fn sort_keys(keys: &mut [u32], old: usize) {
    if keys.len() < 2 {
        return;
    }
    if old >= keys.len() {
        insertion_sort(keys); // no new keys (most rows)
    } else {
        merge_new_keys(keys, old);
    }
}

/// [`sort_keys`] where keys `old..` are new. Out of line: its buffer stays off the stack
/// frame of the common case.
#[inline(never)]
fn merge_new_keys(keys: &mut [u32], old: usize) {
    if keys.len() <= INSERT_ALL {
        insertion_sort(keys); // few keys: the new ones cannot travel far
        return;
    }
    let (head, tail) = keys.split_at_mut(old);
    insertion_sort(head);
    insertion_sort(tail);
    let m = tail.len();
    match (head.last(), tail.first()) {
        (Some(&h), Some(&t)) if h > t => {}
        _ => return, // one part empty, or already in order
    }
    if m > MERGE_KEYS {
        insertion_sort(keys); // both parts sorted: correct, if slower
        return;
    }
    let mut new = [0u32; MERGE_KEYS];
    new[..m].copy_from_slice(&keys[old..]);
    // From the largest new key down: the earlier keys above it move up past every new key
    // still to place (`r` of them, this one included), then it lands below them.
    let mut o = old;
    for r in (1..=m).rev() {
        let k = new[r - 1];
        while o > 0 {
            let e = keys[o - 1];
            if e <= k {
                break;
            }
            keys[o - 1 + r] = e;
            o -= 1;
        }
        keys[o + r - 1] = k;
    }
}

/// Most keys [`sort_keys`] merges in (polygons entering one row); more are sorted by insertion.
const MERGE_KEYS: usize = 16;

/// Up to this many keys in all, [`merge_new_keys`] sorts them all by insertion instead: a new
/// key then moves past at most this many, cheaper than setting up the merge.
const INSERT_ALL: usize = 32;

/// Sorts `v` ascending by insertion: cheap for the few keys that move a place or two. Out of
/// line: [`sort_keys`] calls it from three places.
#[inline(never)]
fn insertion_sort(v: &mut [u32]) {
    // Each run in order is passed over with one compare a key; the key after it moves down.
    let mut from = 0;
    while let Some(p) = v
        .get(from..)
        .and_then(|t| t.windows(2).position(|w| w[0] > w[1]))
    {
        let i = from + p + 1;
        let Some(&k) = v.get(i) else {
            return; // cannot happen: the pair's second key
        };
        let mut j = i;
        while j > 0 && v[j - 1] > k {
            v[j] = v[j - 1];
            j -= 1;
        }
        v[j] = k;
        from = i;
    }
}

/// Affine depth cue across `x0..x1` (already filled with the polygon's colour): the factor
/// interpolated linearly between the edges' crossings of the row (one division per span).
fn cue_span<N: Scalar>(intensity: &mut [Rgb565], a: &Active<N>, e: &EdgeCue<N>, x0: i32, x1: i32) {
    let (cl, cr) = (a.dda[LEFT].crossing::<N>(), a.dda[RIGHT].crossing::<N>());
    let slope = e.f[2].sub(e.f[0]).div_inline(cr.sub(cl)).unwrap_or(N::ZERO);
    let at = N::from_int;
    let mut f = e.f[0].add(at(x0).sub(cl).mul(slope));
    for c in &mut intensity[x0 as usize..x1 as usize] {
        *c = shade(*c, f);
        f = f.add(slope);
    }
}

/// The depth of one polygon across a piece of row starting at column `x0`: stepped one pixel
/// at a time in exact formats (the plane's bits), evaluated at each pixel in f32 (so a depth
/// does not depend on where the row was split into pieces).
#[inline]
fn fill_depth<N: Scalar>(depth: &mut [N], a: &Active<N>, y: i32, x0: i32) {
    let (z_row, dzdx) = (a.column_0_at(y, y), a.dzdx);
    if N::EXACT_STEPS {
        let mut z = z_row.step(dzdx, x0);
        for d in depth {
            *d = z;
            z = z.step(dzdx, 1);
        }
    } else if FPU {
        // x counted in f32, exact below 2^24: the bits of `depth_at` (see `test_pixels`).
        let mut xf = N::from_int(x0);
        for d in depth {
            *d = z_row.add(dzdx.mul(xf));
            xf = xf.add(N::ONE);
        }
    } else {
        for (x, d) in (x0..).zip(depth) {
            *d = z_row.step(dzdx, x);
        }
    }
}

/// Whether `f32` arithmetic is in hardware: without an FPU (a Cortex-M3 or M0) an `f32` add
/// is a library call dearer than converting an integer, so x is converted a pixel instead
/// of counted in `f32` (the same bits either way).
const FPU: bool = !cfg!(all(target_arch = "arm", not(target_abi = "eabihf")));

/// [`Planes::ensure`] for the sweep, the view built only for a polygon without a plane (it
/// asks for one at every span that opens: ~2,800 times on the interlocked demo frame, for ~200
/// planes). Built in `ensure`'s call instead, the view was put on the stack at every ask (the
/// interlocked frame +49 k: tried).
#[inline(always)]
fn ensure_plane<N: Scalar, S: Slot>(
    a: &mut Active<N>,
    vertices: &[RasterVertex<N>],
    polygons: &[Polygon<S>],
    s: u32,
    y: i32,
) {
    if !a.planed() {
        Planes {
            vertices,
            polygons,
            s,
            y,
        }
        .set(a);
    }
}

/// What computing a depth plane on demand needs: the vertex buffer, the polygon table, the
/// sub-pixel bits, the current row.
struct Planes<'a, N, S: Slot> {
    vertices: &'a [RasterVertex<N>],
    polygons: &'a [Polygon<S>],
    s: u32,
    y: i32,
}

impl<N: Scalar, S: Slot> Planes<'_, N, S> {
    /// Sets `a`'s depth plane (in the exact formats its depth at column 0 of the current row)
    /// if not yet set:
    /// the plane through its vertices in canonical order, the same bits whenever computed.
    /// The test in line (where spans meet, most polygons are asked again and again), the
    /// plane out of line.
    #[inline(always)]
    fn ensure(&self, a: &mut Active<N>) {
        if !a.planed() {
            self.set(a);
        }
    }

    /// [`Self::ensure`] of a polygon that has no plane yet.
    #[inline(never)]
    fn set(&self, a: &mut Active<N>) {
        let ring = Ring {
            vertices: self.vertices,
            polygon: &self.polygons[a.poly as usize],
        };
        // Cannot be `None`: the outline has a nonzero area. A zero plane is harmless.
        let plane = plane_of(&ring, self.s).unwrap_or(DepthPlane {
            z_ref: N::ZERO,
            dzdx: N::ZERO,
            dzdy: N::ZERO,
            i_ref: 0,
            j_ref: 0,
        });
        (a.dzdx, a.dzdy) = (plane.dzdx, plane.dzdy);
        if N::EXACT_STEPS {
            a.z_col = plane.at(0, self.y);
        } else {
            // Within the guard band (at most 2^13 pixels off the screen), so 16 bits.
            (a.z_col, a.spare) = (plane.column_0(), plane.j_ref as i16 as u16);
        }
        a.end[RIGHT] |= PLANED;
    }
}

/// A counter kept in the colour row (the counting sort's and the active count's): the
/// `Rgb565`'s raw storage, a free conversion either way.
#[inline]
fn count(c: Rgb565) -> u16 {
    RawU16::from(c).into_inner()
}

/// [`count`]'s inverse.
#[inline]
fn count_of(v: u16) -> Rgb565 {
    Rgb565::from(RawU16::new(v))
}

/// A polygon's last row: the last whose sample line it covers, clamped to the frame, as its
/// outline found it when it entered the table (`raster::outline_with_area`).
fn last_row_of<N: Copy, S: Slot>(ring: &Ring<'_, N, S>, cfg: &Config) -> i32 {
    let bottom = if ring.len() <= INDEXED_CORNERS {
        // Up to four corners as slots.
        let c = &ring.polygon.corners;
        (0..ring.len()).fold(i32::MIN, |m, k| {
            m.max(ring.vertices.get(S::corner(c, k)).map_or(m, |v| v.y))
        })
    } else {
        (0..ring.len()).fold(i32::MIN, |m, k| m.max(ring.get(k).y))
    };
    let (s, h) = (cfg.subpixel_bits as u32, cfg.half());
    row_at_or_below(bottom, s, h).min(cfg.height as i32) - 1
}

/// The top-left vertex of a polygon (least y, then least x): where both its sides start.
/// A polygon of up to [`INDEXED_CORNERS`] corners is recorded from it ([`top_first`]).
#[inline]
fn top_of<N: Copy, S: Slot>(ring: &Ring<'_, N, S>) -> usize {
    if ring.len() <= INDEXED_CORNERS {
        return 0;
    }
    top_index(ring.len(), |k| ring.get(k))
}

/// Of `n` vertices, the top-left one (least y, then least x).
#[inline]
fn top_index<'a, N: 'a>(n: usize, v: impl Fn(usize) -> &'a RasterVertex<N>) -> usize {
    if n == 3 {
        let p = |k: usize| (v(k).y, v(k).x);
        let (a, b, c) = (p(0), p(1), p(2));
        return match (a <= b, a <= c, b <= c) {
            (true, true, _) => 0,
            (false, _, true) => 1,
            _ => 2,
        };
    }
    (0..n).min_by_key(|&k| (v(k).y, v(k).x)).unwrap_or(0)
}

/// A polygon's indexed corners turned to start at its top-left vertex (the same ring, so the
/// same winding): activation then starts both sides at corner 0.
#[inline]
fn top_first<'a, N: 'a>(
    slots: &[u32],
    at: impl Fn(usize) -> &'a RasterVertex<N>,
) -> [u32; INDEXED_CORNERS] {
    let n = slots.len();
    let top = top_index(n, at);
    let c = |k: usize| slots[k];
    if let [_, _, _] = slots {
        return match top {
            0 => [c(0), c(1), c(2), 0],
            1 => [c(1), c(2), c(0), 0],
            _ => [c(2), c(0), c(1), 0],
        };
    }
    let mut corners = [0; INDEXED_CORNERS];
    for (k, corner) in corners.iter_mut().take(n).enumerate() {
        *corner = c(if top + k >= n { top + k - n } else { top + k });
    }
    corners
}

/// Calls `f` with a polygon's vertices in canonical order (from the top-left vertex,
/// clockwise on the display), so the same polygon always gets the same plane bits.
#[inline]
fn canonical_of<N: Scalar, S: Slot, R>(
    ring: &Ring<'_, N, S>,
    f: impl FnOnce(&[RasterVertex<N>]) -> R,
) -> R {
    if ring.len() == 3 {
        // Recorded from its top-left corner ([`top_of`] is 0).
        let (g, h) = if ring.polygon.clockwise() {
            (1, 2)
        } else {
            (2, 1)
        };
        let v = |k: usize| *ring.get(k);
        f(&[v(0), v(g), v(h)])
    } else {
        ring.ordered(f)
    }
}

/// The depth plane of a polygon, through its vertices in canonical order.
fn plane_of<N: Scalar, S: Slot>(ring: &Ring<'_, N, S>, s: u32) -> Option<DepthPlane<N>> {
    canonical_of(ring, |v| N::depth_plane(v, s))
}

/// [`plane_of`]'s exact plane ([`Scalar::exact_plane`]), from the same vertices in the same
/// order.
fn exact_of<N: Scalar, S: Slot>(ring: &Ring<'_, N, S>, s: u32) -> Option<N::ExactPlane> {
    canonical_of(ring, |v| N::exact_plane(v, s))
}

/// The visibility rule: a polygon at depth `zp`, number `p` (scene order), is visible over one
/// at depth `zq`, number `q`, if nearer, or as near and first in the scene.
#[inline]
fn nearer<N: Scalar>((zp, p): (N, u16), (zq, q): (N, u16)) -> bool {
    zp < zq || (zp == zq && p < q)
}

/// Whether the polygon in slot `p` is visible over the one in slot `q` at column `x` of row
/// `y` ([`nearer`]). Both have their planes ([`Planes::ensure`]).
#[inline]
fn beats<N: Scalar>(active: &[Active<N>], p: usize, q: usize, x: i32, y: i32) -> bool {
    let (a, b) = (&active[p], &active[q]);
    nearer((depth_at(a, y, x), a.poly), (depth_at(b, y, x), b.poly))
}

/// How long front `p` holds against `q` from column `x` of row `y` on: `None` if `q` is in
/// front at `x`, else the first column where `q` wins within the stretch both cover
/// (`i32::MAX` if none). Depths are linear in x, so `p − q` changes sign at most once: check
/// the stretch's far end, then bisect (in Q16.16 exactly: the steps are exact integer
/// arithmetic).
#[inline(always)]
fn challenge<N: Scalar>(active: &[Active<N>], p: usize, q: usize, x: i32, y: i32) -> Option<i32> {
    let (a, b) = (&active[p], &active[q]);
    let (zp, zq) = (RowDepths::new(a, y), RowDepths::new(b, y));
    let wins = |x: i32| nearer((zp.at(x), a.poly), (zq.at(x), b.poly));
    if !wins(x) {
        return None;
    }
    let mut hi = a.xr().min(b.xr()) - 1;
    if wins(hi) {
        return Some(i32::MAX);
    }
    let mut lo = x; // p wins at lo, q at hi
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if wins(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(hi)
}

/// Whether the polygon in slot `q`, which front `p` holds off until column `until`
/// ([`challenge`]), can be left out of the open spans: `p` is nearer across all of `q`'s span
/// that is left (`until` is "never" and `q` closes no later than `p`), so `q` is never the
/// visible one while `p` is open — the order at a column being total, any polygon `q` would
/// beat there `p` beats too — and never the first to overtake a front either, `p` being
/// open wherever `q` is.
#[inline]
fn hidden<N: Scalar>(active: &[Active<N>], p: usize, q: usize, until: i32) -> bool {
    until == i32::MAX && active[q].xr() <= active[p].xr()
}

/// The polygon in front at column `x` of row `y` among the slots `open` (not empty): its
/// slot, its index in `open`, and the first column where another open polygon overtakes it.
fn establish<N: Scalar>(active: &[Active<N>], open: &[u16], x: i32, y: i32) -> (usize, usize, i32) {
    // The visible one: least depth, then first in the scene.
    let mut at = 0;
    for i in 1..open.len() {
        if beats(active, open[i] as usize, open[at] as usize, x, y) {
            at = i;
        }
    }
    let p = open[at] as usize;
    let mut until = i32::MAX;
    for &q in open {
        if q as usize != p {
            if let Some(u) = challenge(active, p, q as usize, x, y) {
                until = until.min(u);
            }
        }
    }
    (p, at, until)
}

/// RAM the scan-line renderer (`u16` slots) needs for a scene with these requirements, in
/// bytes: its tables at exactly the sizes required, its two rows and its fixed state —
/// `Scanline::<N, W, V, P, A>::RAM_BYTES` with the capacities set to the requirements, but for
/// the few bytes that align each table (tested).
pub fn ram_bytes<N: Scalar>(req: &Requirements) -> usize {
    ram_bytes_uncued::<N>(req) + req.active_polygons as usize * core::mem::size_of::<EdgeCue<N>>()
}

/// [`ram_bytes`] for a renderer without the affine depth cue's state
/// (`Scanline<N, W, V, P, A, u16, Uncued>`, `scanline_for!(N, REQ, uncued)`).
pub fn ram_bytes_uncued<N: Scalar>(req: &Requirements) -> usize {
    use core::mem::size_of;
    size_of::<Scanline<N, 0, 0, 0, 0, u16, Uncued>>()
        + req.vertices as usize * size_of::<RasterVertex<N>>()
        + req.polygons as usize * (size_of::<Polygon<u16>>() + size_of::<u16>())
        + req.active_polygons as usize
            * (size_of::<Active<N>>() + size_of::<u16>() + size_of::<u32>())
        + req.width as usize * (size_of::<N>() + size_of::<Rgb565>())
}

/// [`ram_bytes_uncued`] for a renderer that keeps no depth row either and packs its slot
/// numbers in 12 bits (`Scanline<N, W, V, P, A, Slot12, Uncued, Flat, NoDepth>`,
/// `scanline_for!(N, REQ, display)`): a row's width of depths, the hierarchical depth and 2
/// bytes a polygon less.
pub fn ram_bytes_display<N: Scalar>(req: &Requirements) -> usize {
    use core::mem::size_of;
    size_of::<Display<N, 0, 0, 0, 0>>()
        + req.vertices as usize * size_of::<RasterVertex<N>>()
        + req.polygons as usize * (size_of::<Polygon<Slot12>>() + size_of::<u16>())
        + req.active_polygons as usize
            * (size_of::<Active<N>>() + size_of::<u16>() + size_of::<u32>())
        + req.width as usize * size_of::<Rgb565>()
}

/// [`ram_bytes`] for a smooth-shading renderer (`Scanline<N, W, V, P, A, u16, Uncued,
/// [IntensityPlane<N>; P]>`, `scanline_for!(N, REQ, gouraud)`): [`ram_bytes_uncued`] and an
/// intensity plane per polygon.
pub fn ram_bytes_gouraud<N: Scalar>(req: &Requirements) -> usize {
    ram_bytes_uncued::<N>(req) + req.polygons as usize * core::mem::size_of::<IntensityPlane<N>>()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Q16_16, Q24_8};

    #[test]
    fn sort_keys_sorts() {
        let mut seed = 0x9e37_79b9u32;
        let mut next = || crate::number::xorshift32(&mut seed);
        for n in [0usize, 1, 2, 3, 4, 9, 65, 300] {
            for sorted_head in [0, n / 2, n.saturating_sub(3), n] {
                // Distinct keys: a left end in the high half, a distinct slot in the low.
                // `old` past the end, at the end, within (new keys to merge, 16 at most and
                // more), and at the start.
                for old in [n + 1, n, n.saturating_sub(5), n.saturating_sub(20), 0] {
                    let mut v = [0u32; 300];
                    for (s, k) in v[..n].iter_mut().enumerate() {
                        *k = (next() % 64) << 16 | s as u32;
                    }
                    v[..sorted_head].sort_unstable();
                    let mut want = v;
                    want[..n].sort_unstable();
                    sort_keys(&mut v[..n], old);
                    assert_eq!(v, want, "n {n}, head {sorted_head}, old {old}");
                }
            }
        }
    }

    /// 12-bit slots give back every corner packed, the fourth included, in 10-byte records.
    #[test]
    fn slot12_packs_four_corners() {
        assert_eq!(core::mem::size_of::<Polygon<Slot12>>(), 10);
        assert_eq!(core::mem::size_of::<Polygon<u16>>(), 12);
        let mut seed = 0x2545_f491u32;
        let mut next = || {
            let seed = crate::number::xorshift32(&mut seed);
            seed % 4096
        };
        for _ in 0..10_000 {
            let c = [next(), next(), next(), next()];
            let packed = Slot12::pack(c);
            for (k, &want) in c.iter().enumerate() {
                assert_eq!(Slot12::corner(&packed, k), want as usize, "{c:?}");
            }
        }
        let edge = [4095, 0, 4095, 4095];
        let packed = Slot12::pack(edge);
        for (k, &want) in edge.iter().enumerate() {
            assert_eq!(Slot12::corner(&packed, k), want as usize);
        }
    }

    /// The active entry's size, as its doc says: a field added or a layout that pads shows
    /// here, and in every frame's RAM.
    #[test]
    fn active_entries_are_52_bytes() {
        use core::mem::size_of;
        assert_eq!(size_of::<Active<Q16_16>>(), 52);
        assert_eq!(size_of::<Active<Q24_8>>(), 52);
        assert_eq!(size_of::<Active<f32>>(), 52);
    }

    /// `ram_bytes` is the struct's size at those capacities, but for the padding that aligns
    /// each table (a few bytes each; either way, as a small table may fill padding the fixed
    /// part has).
    #[test]
    fn ram_bytes_is_the_size_of_the_renderer() {
        fn check<N: Scalar, const W: usize, const V: usize, const P: usize, const A: usize>() {
            let req = Requirements {
                polygons: P as u32,
                edges: 0,
                vertices: V as u32,
                active_polygons: A as u32,
                width: W as u16,
            };
            let (formula, size) = (ram_bytes::<N>(&req), Scanline::<N, W, V, P, A>::RAM_BYTES);
            assert!(
                formula.abs_diff(size) <= 32,
                "{formula} vs {size} ({} {W} {V} {P} {A})",
                N::NAME
            );
            let (formula, size) = (
                ram_bytes_display::<N>(&req),
                Display::<N, W, V, P, A>::RAM_BYTES,
            );
            assert!(
                formula.abs_diff(size) <= 32,
                "display: {formula} vs {size} ({} {W} {V} {P} {A})",
                N::NAME
            );
        }
        check::<Q16_16, 240, 500, 454, 65>();
        check::<f32, 240, 1200, 400, 297>();
        check::<Q16_16, 240, 4096, 2000, 300>();
        check::<Q24_8, 64, 7, 3, 1>();
        check::<Q16_16, 1, 0, 0, 0>();
    }
}
