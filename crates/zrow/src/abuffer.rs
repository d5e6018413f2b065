//! Transparency in the A-buffer spirit: translucent faces blended over the opaque surface,
//! one row at a time (Carpenter's A-buffer, 1984; Foley, van Dam, Feiner & Hughes §15.4).
//!
//! The z-buffer's limit: a depth buffer keeps one depth and one colour per pixel, so a pixel can
//! have only one surface colour. That is right for opaque surfaces; with transparent ones the
//! pixel colour combines the surface's colour with contributions from the surfaces behind, and
//! one depth per pixel cannot store every surface contributing to it. The **A-buffer** fixes it:
//! Carpenter's accumulation buffer keeps, per pixel, a *list* of the fragments that cover it,
//! and resolves the list — sorted by depth — into one colour.
//!
//! Here the list is kept for one row, as everything in zrow is. Per row `y`, top to bottom:
//!
//! 1. **The opaque surface**: the row is cleared (background, maximum depth) and every opaque
//!    polygon (`alpha == 255`) crossing it paints its span with a strict `<` depth test, in
//!    scene order — a scan-line z-buffer, so ties go to the polygon first in the scene. Each
//!    pixel remembers which polygon it shows (`owner`).
//! 2. **The coverage list**: every translucent polygon (`0 < alpha < 255`) crossing the row adds
//!    a [`Fragment`](crate::abuffer::Fragment) for each pixel of its span where it is *visible
//!    over the opaque surface* by the tie rule every method uses
//!    ([`crate::polygons::PolygonTable::beats`]): nearer, or
//!    exactly as near and earlier in the scene than the polygon that owns the pixel. Where no
//!    opaque polygon covers the pixel every fragment counts. A face with `alpha == 0` draws
//!    nothing at all.
//! 3. **Resolve**: the row's fragments are sorted by (column, depth far → near, and at equal
//!    depth the *earlier* polygon last — it counts as nearer, as it wins a tie) and blended
//!    over the opaque colour back to front with [`blend`](crate::abuffer::blend).
//!
//! Translucent faces do not write depth: the row's `depth[x]` is the opaque surface's (the
//! format's maximum where no opaque polygon covers the pixel).
//!
//! **Exactness.** Coverage and depth come from the shared
//! [`PolygonTable`](crate::polygons::PolygonTable) — exact top-left spans, depth started at each
//! span's left end from the polygon's [`crate::number::DepthPlane`] and stepped by `dzdx` (in
//! Q16.16 the same bits as every other method). With every face opaque, step 2 and 3 do nothing and the method is a scan-line
//! z-buffer: the same picture as the z-buffer, bit for bit, and as the exact reference.
//! Blending is integer arithmetic with one rounding to nearest per channel, the same in both
//! number formats.
//!
//! **Capacity.** The fragment list holds one row; how many fragments a row needs depends on the
//! scene. Before the first row is sent every row is checked: the sum of the translucent spans'
//! widths (clamped to the screen) bounds the row's fragments, and only a row whose bound exceeds
//! `F` is counted exactly (its opaque surface drawn and its fragments counted, not stored).
//! A scene that needs more than `F` in some row fails with
//! [`Error::Capacity`](crate::Error::Capacity) naming [`Table::Fragments`](crate::Table::Fragments)
//! and the exact count of the worst row.
//!
//! **Cost.** Every row asks every polygon whose rows include it for its span
//! ([`PolygonTable::span`](crate::polygons::PolygonTable::span), a few integer divisions):
//! O(rows × polygons) setup work, plus the pixels painted and a sort of each row's fragments.
//!
//! ```
//! use zrow::abuffer::{blend, ABuffer};
//! use zrow::{Config, Face, FrameBuffer, Mesh, ScreenScene, Vec3};
//! use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
//!
//! // A red opaque square at depth 2 and, in front of it, a half-transparent blue one.
//! let v = [
//!     Vec3::new(0.0f32, 0.0, 2.0), Vec3::new(8.0, 0.0, 2.0),
//!     Vec3::new(8.0, 8.0, 2.0), Vec3::new(0.0, 8.0, 2.0),
//!     Vec3::new(4.0, 0.0, 1.0), Vec3::new(8.0, 0.0, 1.0),
//!     Vec3::new(8.0, 8.0, 1.0), Vec3::new(4.0, 8.0, 1.0),
//! ];
//! let faces = [
//!     Face::new(&[0, 1, 2, 3], Rgb565::RED),
//!     Face::translucent(&[4, 5, 6, 7], Rgb565::BLUE, 128),
//! ];
//! let scene = ScreenScene { mesh: Mesh::new(&v, &faces) };
//! // 8-pixel rows, 2 polygons, 8 edges, 8 fragments in a row.
//! let mut r = ABuffer::<f32, 8, 2, 8, 8>::new();
//! let mut pixels = [Rgb565::BLACK; 64];
//! r.render(&scene, &Config::screen(8, 8), &mut FrameBuffer::new(&mut pixels, 8)).unwrap();
//! assert_eq!(pixels[0], Rgb565::RED);
//! assert_eq!(pixels[4], blend(Rgb565::RED, Rgb565::BLUE, 128));
//! ```

use crate::error::{Error, RenderError, Table};
use crate::method::{FrameStats, Renderer};
use crate::number::Scalar;
use crate::polygons::{PolygonTable, Stored};
use crate::raster::{color_at, Config};
use crate::scene::Scene;
use crate::sink::{Row, RowSink};
use core::cmp::Ordering;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use heapless::Vec;

/// `owner` of a pixel no opaque polygon covers.
const NONE: u16 = u16::MAX;

/// One translucent polygon's sample in the current row: the A-buffer's list entry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fragment<N> {
    /// Column.
    pub x: u16,
    /// The polygon's depth at the pixel centre.
    pub depth: N,
    /// The polygon's colour at the pixel (smooth shaded, if it is).
    pub color: Rgb565,
    /// The polygon's opacity (1..=254).
    pub alpha: u8,
    /// The polygon's index in the polygon table (its place in the scene).
    pub poly: u16,
}

/// Blends `over` with opacity `alpha` onto `under`, per Rgb565 channel, in integers:
/// `c = (u·(255 − a) + o·a + 127) / 255`.
///
/// That is the exact value `u·(255 − a)/255 + o·a/255` rounded to nearest (255 is odd, so the
/// exact value is never halfway between two integers): error at most 0.5 of a channel step.
/// `alpha` 0 gives `under`, 255 gives `over`; the result never leaves the channel's range.
pub fn blend(under: Rgb565, over: Rgb565, alpha: u8) -> Rgb565 {
    let a = alpha as u16;
    // At most 63·255 + 127 = 16,192: fits u16.
    let mix = |u: u8, o: u8| ((u as u16 * (255 - a) + o as u16 * a + 127) / 255) as u8;
    Rgb565::new(
        mix(under.r(), over.r()),
        mix(under.g(), over.g()),
        mix(under.b(), over.b()),
    )
}

/// Far before near, as a total order (so sorting never meets an inconsistent comparison):
/// the format's own order, and where it has none (f32 NaN) IEEE 754's total order.
fn far_first<N: Scalar>(a: N, b: N) -> Ordering {
    b.partial_cmp(&a)
        .unwrap_or_else(|| b.to_f64().total_cmp(&a.to_f64()))
}

/// The A-buffer renderer.
///
/// - `N`: number format ([`crate::Q16_16`] or `f32`);
/// - `W`: row capacity (the widest frame, in pixels);
/// - `P`: polygon-table capacity (below 65,535); `E`: edge-table capacity;
/// - `F`: fragment-list capacity — translucent samples visible over the opaque surface in one
///   row (an upper bound for a row: the sum of its translucent spans' widths).
///
/// All memory is in the struct ([`ABuffer::RAM_BYTES`]):
/// `PolygonTable::<N, P, E>::RAM_BYTES + W·(size_of::<N>() + 2 + 2) + F·size_of::<Fragment<N>>()`
/// plus a few words.
pub struct ABuffer<N: Scalar, const W: usize, const P: usize, const E: usize, const F: usize> {
    table: PolygonTable<N, P, E>,
    depth: [N; W],
    intensity: [Rgb565; W],
    /// The opaque polygon each pixel shows, or `NONE`.
    owner: [u16; W],
    fragments: Vec<Fragment<N>, F>,
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const F: usize> Default
    for ABuffer<N, W, P, E, F>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const F: usize>
    ABuffer<N, W, P, E, F>
{
    /// Bytes of RAM the renderer occupies (polygon table, row buffers, fragment list).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer (all zero, so a `static` one sits in `.bss`).
    pub const fn new() -> Self {
        const {
            assert!(P < NONE as usize, "polygon capacity must be below 65535");
        }
        ABuffer {
            table: PolygonTable::new(),
            depth: [N::ZERO; W],
            intensity: [Rgb565::BLACK; W],
            owner: [0; W],
            fragments: Vec::new(),
        }
    }

    /// Renders `scene` and sends its rows, top to bottom, to `sink`.
    ///
    /// Errors in the scene or the configuration — including a polygon, edge or fragment
    /// capacity the scene exceeds — are returned before the first row is sent.
    pub fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        cfg.validate(W)?;
        self.table.build(scene, cfg, false, K::WANTS_DEPTH)?;
        // `validate` checked width <= W, so every `..w` below is in range.
        let w = cfg.width as usize;
        self.check_fragments(cfg)?;
        let cue = crate::shading::Cue::for_rows(scene, cfg)?;
        for y in 0..cfg.height as i32 {
            opaque_row(
                &self.table,
                &mut self.depth[..w],
                &mut self.intensity[..w],
                &mut self.owner[..w],
                y,
                cfg.background,
            );
            let frags = &mut self.fragments;
            frags.clear();
            each_fragment(&self.table, &self.depth[..w], &self.owner[..w], y, |f| {
                // Cannot fail: `check_fragments` counted this row's fragments against `F`.
                let _ = frags.push(f);
            });
            resolve(frags, &mut self.intensity[..w]);
            crate::shading::Cue::shade_row_if_perspective(
                &cue,
                &self.depth[..w],
                &mut self.intensity[..w],
            );
            #[cfg(feature = "exact-depth")]
            if crate::sink::EXACT_DEPTH && K::WANTS_DEPTH {
                // The sink's depths: each opaque surface's exact plane.
                self.table
                    .exact_row(&self.owner[..w], y, &mut self.depth[..w]);
            }
            sink.write_row(&Row {
                y: y as u16,
                color: &self.intensity[..w],
                depth: &self.depth[..w],
            })
            .map_err(RenderError::Sink)?;
        }
        Ok(FrameStats {
            polygons: self.table.len() as u32,
            edges: self.table.edge_count() as u32,
            ..FrameStats::default()
        })
    }

    /// Checks every row's fragments against `F`, before any row is sent.
    ///
    /// A row's fragments are at most the sum of its translucent spans' clamped widths; a row
    /// whose bound exceeds `F` is drawn (opaque surface only, into the row buffers, which no
    /// row has used yet) and its fragments counted exactly. The error reports the worst row's
    /// exact count.
    fn check_fragments(&mut self, cfg: &Config) -> Result<(), Error> {
        let t = &self.table;
        if !t.polygons().iter().any(translucent) {
            return Ok(());
        }
        let w = cfg.width as usize;
        let mut needed = 0u32;
        for y in 0..cfg.height as i32 {
            let mut bound = 0usize;
            for (i, p) in t.polygons().iter().enumerate() {
                if translucent(p) && crosses(p, y) {
                    let (x0, x1) = clamp(t.span(i, y), w);
                    bound += (x1 - x0) as usize;
                }
            }
            if bound <= F {
                continue;
            }
            let (depth, owner) = (&mut self.depth[..w], &mut self.owner[..w]);
            opaque_row(t, depth, &mut self.intensity[..w], owner, y, cfg.background);
            let mut count = 0u32;
            each_fragment(t, depth, owner, y, |_| count += 1);
            needed = needed.max(count);
        }
        if needed as usize > F {
            return Err(Error::Capacity {
                table: Table::Fragments,
                needed,
                capacity: F as u32,
            });
        }
        Ok(())
    }
}

fn translucent<N: Scalar>(p: &Stored<N>) -> bool {
    p.alpha > 0 && p.alpha < 255
}

fn crosses<N: Scalar>(p: &Stored<N>, y: i32) -> bool {
    p.first_row as i32 <= y && y <= p.last_row as i32
}

/// A span `xl..xr` clamped to a row of `w` pixels: `0 <= x0 <= x1 <= w`.
fn clamp((xl, xr): (i32, i32), w: usize) -> (i32, i32) {
    let x1 = xr.clamp(0, w as i32);
    (xl.clamp(0, x1), x1)
}

/// Step 1: the opaque surface of row `y` — a scan-line z-buffer over the opaque polygons, in
/// scene order, strict `<` (ties to the earlier polygon). All slices have the frame's width.
fn opaque_row<N: Scalar, const P: usize, const E: usize>(
    t: &PolygonTable<N, P, E>,
    depth: &mut [N],
    intensity: &mut [Rgb565],
    owner: &mut [u16],
    y: i32,
    background: Rgb565,
) {
    depth.fill(N::MAX);
    intensity.fill(background);
    owner.fill(NONE);
    let w = depth.len().min(intensity.len()).min(owner.len());
    for (i, p) in t.polygons().iter().enumerate() {
        if p.alpha != 255 || !crosses(p, y) {
            continue;
        }
        let (x0, x1) = clamp(t.span(i, y), w);
        let mut z = p.plane.at(x0, y);
        // In range: 0 <= x0 <= x1 <= w, the shortest slice's length.
        let run = depth[x0 as usize..x1 as usize]
            .iter_mut()
            .zip(&mut intensity[x0 as usize..x1 as usize])
            .zip(&mut owner[x0 as usize..x1 as usize])
            .zip(x0..x1);
        for (((d, c), o), x) in run {
            if z < *d {
                *d = z;
                *c = color_at(p.color, p.intensity(), x, y);
                *o = i as u16; // i < P < NONE
            }
            z = z.step(p.plane.dzdx, 1);
        }
    }
}

/// Step 2: calls `f` with every fragment of row `y`, given its opaque surface — each sample
/// of a translucent polygon (0 < alpha < 255) that beats the opaque polygon owning the pixel
/// (nearer, or as near and earlier in the scene), or any sample where no opaque polygon is.
/// Polygons in scene order, columns left to right.
fn each_fragment<N: Scalar, const P: usize, const E: usize>(
    t: &PolygonTable<N, P, E>,
    depth: &[N],
    owner: &[u16],
    y: i32,
    mut f: impl FnMut(Fragment<N>),
) {
    let w = depth.len().min(owner.len());
    for (i, p) in t.polygons().iter().enumerate() {
        if !translucent(p) || !crosses(p, y) {
            continue;
        }
        let i = i as u16; // i < P < NONE
        let (x0, x1) = clamp(t.span(i as usize, y), w);
        let mut z = p.plane.at(x0, y);
        // In range: 0 <= x0 <= x1 <= w, the shorter slice's length.
        let run = depth[x0 as usize..x1 as usize]
            .iter()
            .zip(&owner[x0 as usize..x1 as usize])
            .zip(x0..x1);
        for ((&zo, &o), x) in run {
            if o == NONE || z < zo || (z == zo && i < o) {
                f(Fragment {
                    x: x as u16, // x < w <= MAX_VIEWPORT
                    depth: z,
                    color: color_at(p.color, p.intensity(), x, y),
                    alpha: p.alpha,
                    poly: i,
                });
            }
            z = z.step(p.plane.dzdx, 1);
        }
    }
}

/// Step 3: sorts the row's fragments by column, then back to front — far to near, and at
/// equal depth the later polygon first (the earlier one wins the tie, so it goes on top) —
/// and blends each over the row's colour.
fn resolve<N: Scalar>(frags: &mut [Fragment<N>], intensity: &mut [Rgb565]) {
    frags.sort_unstable_by(|a, b| {
        a.x.cmp(&b.x)
            .then_with(|| far_first(a.depth, b.depth))
            .then(b.poly.cmp(&a.poly))
    });
    for f in frags.iter() {
        if let Some(c) = intensity.get_mut(f.x as usize) {
            *c = blend(*c, f.color, f.alpha);
        }
    }
}

impl<N: Scalar, const W: usize, const P: usize, const E: usize, const F: usize> Renderer<N>
    for ABuffer<N, W, P, E, F>
{
    const NAME: &'static str = "abuffer";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        ABuffer::render(self, scene, cfg, sink)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blend_rounds_to_nearest_and_keeps_the_ends() {
        let (r, b) = (Rgb565::RED, Rgb565::BLUE);
        // 31·127/255 = 15.44 → 15, 31·128/255 = 15.56 → 16.
        assert_eq!(blend(r, b, 128), Rgb565::new(15, 0, 16));
        assert_eq!(blend(r, b, 0), r);
        assert_eq!(blend(r, b, 255), b);
        for a in 0..=255u8 {
            for (u, o) in [(0u8, 63u8), (63, 0), (17, 40), (63, 63)] {
                let exact = (u as f64 * (255 - a) as f64 + o as f64 * a as f64) / 255.0;
                let got = blend(Rgb565::new(0, u, 0), Rgb565::new(0, o, 0), a).g() as f64;
                assert!(
                    (got - exact).abs() <= 0.5,
                    "a={a} u={u} o={o}: {got} vs {exact}"
                );
            }
        }
    }

    #[test]
    fn far_first_is_total_even_for_nan() {
        assert_eq!(far_first(1.0f32, 2.0), Ordering::Greater);
        assert_eq!(far_first(2.0f32, 1.0), Ordering::Less);
        assert_eq!(far_first(0.0f32, -0.0), Ordering::Equal);
        assert_eq!(far_first(f32::NAN, f32::NAN), Ordering::Equal);
        let mut v = [f32::NAN, 1.0, -f32::NAN, 3.0, f32::INFINITY, 0.0];
        v.sort_unstable_by(|a, b| far_first(*a, *b)); // must not panic
        assert_eq!(&v[1..5], &[f32::INFINITY, 3.0, 1.0, 0.0]);
    }
}
