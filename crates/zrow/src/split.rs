//! Polygons split by another's plane, exactly — the pieces depth-sort and BSP order.
//!
//! Both object-order methods must sometimes cut a polygon in two by the plane of another
//! (one of them must be split by the plane of the other: Foley, van Dam, Feiner & Hughes
//! §15.5). In screen
//! space the two planes meet along the line where their depths are equal, so the part of `P`
//! in front of `Q`'s plane is exactly the set of `P`'s samples where `P` beats `Q`
//! ([`PolygonTable::beats`](crate::polygons::PolygonTable::beats): nearer, or as near and first in the scene). zrow keeps a piece as
//! that set, not as new vertices: a [`Piece`](crate::split::Piece) is a polygon, or a piece of it, restricted to
//! one side of another polygon's plane. Nothing is rounded, so
//!
//! - the two pieces of a split partition the parent's samples exactly (no crack, no overlap:
//!   both sides use the same boundary column in every row);
//! - a piece keeps its polygon's plane, colour and scene order, so its depths are the bits
//!   every other method computes and ties break the same way;
//! - painting pieces far to near gives exactly the per-sample nearest surface, provided the
//!   order is right for every pair of pieces that share a sample.
//!
//! The side test is linear along a row (the difference of two planes), so each constraint
//! narrows a row's span by one comparison at each end, and a bisection where they differ.
//! Everything else a method asks of a piece — its rows, columns and depth extent, whether it
//! lies wholly on one side of a plane, whether two pieces share a sample — is answered from
//! its spans, row by row.

use crate::error::{Error, Table};
use crate::number::Scalar;
use crate::polygons::{paint_span, PolygonTable};
use crate::raster::Config;
use crate::sink::{Row, RowSink};
use heapless::Vec;

/// "No piece": a piece with this parent is a whole polygon.
pub const NONE: u16 = u16::MAX;

/// A polygon, or a part of it on one side of another polygon's plane.
#[derive(Clone, Copy, Debug)]
pub struct Piece<N> {
    /// The polygon (table index) whose samples, plane and colour it has.
    pub poly: u16,
    /// The piece it was cut from ([`NONE`] for a whole polygon).
    pub parent: u16,
    /// The polygon whose plane cut it (meaningless for a whole polygon).
    pub by: u16,
    /// Which side it keeps: the samples where `poly` beats `by` (`true`), or the others.
    pub near: bool,
    /// First row with a sample.
    pub first_row: i16,
    /// Last row with a sample.
    pub last_row: i16,
    /// First column with a sample.
    pub first_col: i16,
    /// Last column with a sample.
    pub last_col: i16,
    /// Least depth over its samples.
    pub zmin: N,
    /// Greatest depth over its samples.
    pub zmax: N,
}

impl<N: Scalar> Piece<N> {
    fn new(poly: u16, parent: u16, by: u16, near: bool, first_row: i16, last_row: i16) -> Self {
        Piece {
            poly,
            parent,
            by,
            near,
            first_row,
            last_row,
            first_col: 0,
            last_col: 0,
            zmin: N::MAX,
            zmax: N::MAX,
        }
    }
}

/// The piece table: capacity `Q` pieces (whole polygons included).
pub struct Pieces<N, const Q: usize> {
    pieces: Vec<Piece<N>, Q>,
    /// Pieces made by splitting (for statistics).
    pub splits: u32,
}

impl<N: Scalar, const Q: usize> Default for Pieces<N, Q> {
    fn default() -> Self {
        Self::new()
    }
}

/// The sub-interval of `a..b` where `keep` holds, `keep` being monotone over it (true then
/// false, or false then true): the ends are checked, then the change is found by bisection.
fn narrow(a: i32, b: i32, keep: impl Fn(i32) -> bool) -> (i32, i32) {
    if a >= b {
        return (a, a);
    }
    let (ka, kb) = (keep(a), keep(b - 1));
    if ka == kb {
        return if ka { (a, b) } else { (a, a) };
    }
    // keep(lo) == ka, keep(hi) == kb: find the first column with kb.
    let (mut lo, mut hi) = (a, b - 1);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if keep(mid) == ka {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    if ka {
        (a, hi)
    } else {
        (hi, b)
    }
}

impl<N: Scalar, const Q: usize> Pieces<N, Q> {
    /// An empty table.
    pub const fn new() -> Self {
        Pieces {
            pieces: Vec::new(),
            splits: 0,
        }
    }
    /// Empties the table.
    pub fn clear(&mut self) {
        self.pieces.clear();
        self.splits = 0;
    }
    /// Number of pieces.
    pub fn len(&self) -> usize {
        self.pieces.len()
    }
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }
    /// Piece `k`.
    pub fn get(&self, k: u16) -> &Piece<N> {
        &self.pieces[k as usize]
    }

    /// Piece `k`'s covered columns at row `y`, clamped to `0..width` (empty: `xl >= xr`).
    ///
    /// Every constraint narrows the polygon's own span, so both pieces of one split see the
    /// same boundary whatever else cut them.
    pub fn span<const P: usize, const E: usize>(
        &self,
        t: &PolygonTable<N, P, E>,
        k: u16,
        y: i32,
        width: i32,
    ) -> (i32, i32) {
        let piece = &self.pieces[k as usize];
        let poly = piece.poly as usize;
        let (xl, xr) = t.span(poly, y);
        let full = (xl.max(0), xr.min(width));
        let (mut lo, mut hi) = full;
        let mut at = piece;
        while at.parent != NONE && lo < hi {
            let (by, near) = (at.by as usize, at.near);
            let (a, b) = narrow(full.0, full.1, |x| t.beats(poly, by, x, y) == near);
            (lo, hi) = (lo.max(a), hi.min(b));
            at = &self.pieces[at.parent as usize];
        }
        (lo, hi.max(lo))
    }

    /// Calls `f(y, xl, xr)` for every row of piece `k` with samples (`xl < xr`), top to bottom;
    /// stops when `f` returns `false`. Returns `false` if stopped.
    pub fn walk<const P: usize, const E: usize>(
        &self,
        t: &PolygonTable<N, P, E>,
        k: u16,
        width: i32,
        mut f: impl FnMut(i32, i32, i32) -> bool,
    ) -> bool {
        let p = &self.pieces[k as usize];
        for y in p.first_row as i32..=p.last_row as i32 {
            let (xl, xr) = self.span(t, k, y, width);
            if xl < xr && !f(y, xl, xr) {
                return false;
            }
        }
        true
    }

    /// Adds polygon `poly` whole. `Ok(None)` if it has no sample on screen.
    pub fn whole<const P: usize, const E: usize>(
        &mut self,
        t: &PolygonTable<N, P, E>,
        width: i32,
        poly: u16,
    ) -> Result<Option<u16>, Error> {
        let s = t.get(poly as usize);
        self.push(
            t,
            width,
            Piece::new(poly, NONE, 0, false, s.first_row, s.last_row),
        )
    }

    /// Adds the part of piece `k` on one side of polygon `by`'s plane (`near`: where `k`'s
    /// polygon beats `by`). `Ok(None)` if that part has no sample.
    pub fn part<const P: usize, const E: usize>(
        &mut self,
        t: &PolygonTable<N, P, E>,
        width: i32,
        k: u16,
        by: u16,
        near: bool,
    ) -> Result<Option<u16>, Error> {
        let p = self.pieces[k as usize];
        let r = self.push(
            t,
            width,
            Piece::new(p.poly, k, by, near, p.first_row, p.last_row),
        )?;
        self.splits += r.is_some() as u32;
        Ok(r)
    }

    /// Pushes a piece and measures its rows, columns and depth extent; pops it if empty.
    fn push<const P: usize, const E: usize>(
        &mut self,
        t: &PolygonTable<N, P, E>,
        width: i32,
        piece: Piece<N>,
    ) -> Result<Option<u16>, Error> {
        let poly = piece.poly;
        let k = self.pieces.len();
        if self.pieces.push(piece).is_err() {
            return Err(Error::Capacity {
                table: Table::Pieces,
                needed: Q as u32 + 1,
                capacity: Q as u32,
            });
        }
        let plane = t.get(poly as usize).plane;
        let mut m: Option<(i32, i32, i32, i32, N, N)> = None;
        self.walk(t, k as u16, width, |y, xl, xr| {
            let (za, zb) = (plane.at(xl, y), plane.at(xr - 1, y));
            let (zlo, zhi) = if za < zb { (za, zb) } else { (zb, za) };
            m = Some(match m {
                None => (y, y, xl, xr - 1, zlo, zhi),
                Some((r0, _, c0, c1, z0, z1)) => (
                    r0,
                    y,
                    c0.min(xl),
                    c1.max(xr - 1),
                    if zlo < z0 { zlo } else { z0 },
                    if zhi > z1 { zhi } else { z1 },
                ),
            });
            true
        });
        let Some((r0, r1, c0, c1, z0, z1)) = m else {
            self.pieces.pop();
            return Ok(None);
        };
        let p = &mut self.pieces[k];
        (p.first_row, p.last_row, p.first_col, p.last_col) =
            (r0 as i16, r1 as i16, c0 as i16, c1 as i16);
        (p.zmin, p.zmax) = (z0, z1);
        Ok(Some(k as u16))
    }

    /// Whether, at every sample of piece `k`, `keep(poly of k, x, y)` holds — the predicate
    /// being linear along a row, so checking each row's two ends suffices.
    pub fn all<const P: usize, const E: usize>(
        &self,
        t: &PolygonTable<N, P, E>,
        k: u16,
        width: i32,
        keep: impl Fn(i32, i32) -> bool,
    ) -> bool {
        self.walk(t, k, width, |y, xl, xr| keep(xl, y) && keep(xr - 1, y))
    }

    /// Where piece `k` lies against polygon `o`'s plane: `(near, far)` = whether `k`'s polygon
    /// beats `o` at every sample of `k`, and whether `o` beats it at every one (both false: it
    /// straddles the plane). One walk, stopped as soon as it straddles.
    pub fn sides<const P: usize, const E: usize>(
        &self,
        t: &PolygonTable<N, P, E>,
        k: u16,
        o: u16,
        width: i32,
    ) -> (bool, bool) {
        let pk = self.get(k).poly as usize;
        let (mut near, mut far) = (true, true);
        self.walk(t, k, width, |y, xl, xr| {
            for x in [xl, xr - 1] {
                if t.beats(pk, o as usize, x, y) {
                    far = false;
                } else {
                    near = false;
                }
            }
            near || far
        });
        (near, far)
    }

    /// Whether pieces `a` and `b` share a sample (their projections overlap).
    pub fn overlap<const P: usize, const E: usize>(
        &self,
        t: &PolygonTable<N, P, E>,
        a: u16,
        b: u16,
        width: i32,
    ) -> bool {
        let (pa, pb) = (self.get(a), self.get(b));
        if pa.poly == pb.poly {
            return false; // pieces of one polygon partition its samples
        }
        let (r0, r1) = (
            pa.first_row.max(pb.first_row) as i32,
            pa.last_row.min(pb.last_row) as i32,
        );
        (r0..=r1).any(|y| {
            let (al, ar) = self.span(t, a, y, width);
            let (bl, br) = self.span(t, b, y, width);
            al.max(bl) < ar.min(br)
        })
    }

    /// Cuts piece `k` by polygon `by`'s plane: `(near part, far part)`, either `None` if empty.
    pub fn split<const P: usize, const E: usize>(
        &mut self,
        t: &PolygonTable<N, P, E>,
        k: u16,
        by: u16,
        width: i32,
    ) -> Result<(Option<u16>, Option<u16>), Error> {
        let near = self.part(t, width, k, by, true)?;
        let far = self.part(t, width, k, by, false)?;
        Ok((near, far))
    }
}

/// Paints pieces in `order` (first = farthest) row by row — the painter's algorithm with one
/// row of memory — and sends each row to `sink`, top to bottom.
#[allow(clippy::too_many_arguments)] // the frame's inputs and the row buffers, each used once
pub fn paint_rows<N: Scalar, K: RowSink<N>, const P: usize, const E: usize, const Q: usize>(
    t: &PolygonTable<N, P, E>,
    pieces: &Pieces<N, Q>,
    order: &[u16],
    cfg: &Config,
    cue: &Option<crate::shading::Cue<N>>,
    depth: &mut [N],
    intensity: &mut [embedded_graphics_core::pixelcolor::Rgb565],
    sink: &mut K,
) -> Result<(), K::Error> {
    let w = (cfg.width as usize).min(depth.len()).min(intensity.len());
    for y in 0..cfg.height as i32 {
        depth[..w].fill(N::MAX);
        intensity[..w].fill(cfg.background);
        for &k in order {
            let p = pieces.get(k);
            if y < p.first_row as i32 || y > p.last_row as i32 {
                continue;
            }
            let s = t.get(p.poly as usize);
            let (xl, xr) = pieces.span(t, k, y, w as i32);
            paint_span(&mut depth[..w], &mut intensity[..w], s, cue, y, xl, xr);
        }
        if !(crate::sink::EXACT_DEPTH && K::WANTS_DEPTH) {
            // (For a sink that reads depth each piece had it: see `paint_span`.)
            crate::shading::Cue::shade_row_if_perspective(cue, &depth[..w], &mut intensity[..w]);
        }
        sink.write_row(&Row {
            y: y as u16,
            color: &intensity[..w],
            depth: &depth[..w],
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::narrow;

    #[test]
    fn narrow_finds_the_change_column() {
        for a in 0..6 {
            for b in a..12 {
                for t in a - 1..=b + 1 {
                    assert_eq!(narrow(a, b, |x| x < t), (a, t.clamp(a, b)), "{a} {b} {t}");
                    let want = if t.clamp(a, b) >= b {
                        (a, a)
                    } else {
                        (t.clamp(a, b), b)
                    };
                    let got = narrow(a, b, |x| x >= t);
                    assert!(
                        got == want || (got.0 >= got.1 && want.0 >= want.1),
                        "{a} {b} {t}"
                    );
                }
            }
        }
    }
}
