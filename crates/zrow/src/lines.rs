//! Hidden-line drawings: the edges a viewer sees, 1 px wide, with the hidden ones removed
//! (the first figure of the hidden-surface literature; Foley & van Dam §15.3, Appel 1967),
//! decided by the same visibility as a shaded frame.
//!
//! A frame is drawn twice over in spirit but once in fact: the method renders **facets**
//! ([`Shading::Facets`](crate::shading::Shading::Facets): every polygon opaque, in the raw
//! value of its facet), so each row says which surface is visible at each pixel; the
//! [`HiddenLines`](crate::lines::HiddenLines) sink turns that into a line drawing row by row. A pixel is on a line where
//! the visible facet changes: it shows a facet, and one of its four neighbours in the frame
//! shows the background or a facet with a smaller number. Each boundary is thus marked once,
//! on one side, 1 px wide — a silhouette on the object's own pixels, an edge between two
//! visible facets on the side of the later one — and an edge is drawn exactly where one of
//! the two surfaces it separates is the visible one. Faces that continue a flat facet (a quad
//! split into triangles) share its number, so the diagonal inside is not a line.
//!
//! ```
//! use zrow::lines::HiddenLines;
//! use zrow::shading::Shading;
//! use zrow::{Config, Face, FrameBuffer, Mesh, Q16_16, Scanline, ScreenScene, Vec3};
//! use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
//!
//! // A square (two triangles: one facet) half over a triangle behind it.
//! let q = |x: f32, y: f32, z: f32| Vec3::<Q16_16>::from_f32([x, y, z]).unwrap();
//! let vertices = [
//!     q(2.0, 2.0, 1.0), q(10.0, 2.0, 1.0), q(10.0, 10.0, 1.0), q(2.0, 10.0, 1.0),
//!     q(6.0, 6.0, 5.0), q(15.0, 6.0, 5.0), q(6.0, 15.0, 5.0),
//! ];
//! let faces = [
//!     Face { indices: &[0u16, 1, 2], color: Rgb565::RED, alpha: 255 },
//!     Face { indices: &[0, 2, 3], color: Rgb565::RED, alpha: 255 },
//!     Face { indices: &[4, 5, 6], color: Rgb565::GREEN, alpha: 255 },
//! ];
//! let scene = ScreenScene { mesh: Mesh::new(&vertices, &faces) };
//! let mut cfg = Config::screen(16, 16);
//! cfg.shading = Shading::Facets;
//!
//! let mut pixels = [Rgb565::BLACK; 16 * 16];
//! let frame = FrameBuffer::new(&mut pixels, 16);
//! let mut lines = HiddenLines::<_, 16>::new(frame, 16, Rgb565::WHITE, Rgb565::BLACK);
//! Scanline::<Q16_16, 16, 8, 3, 3>::new().render(&scene, &cfg, &mut lines).unwrap();
//! let frame = lines.into_inner();
//! assert_eq!(frame.pixel(2, 5), Some(Rgb565::WHITE)); // the square's left side
//! assert_eq!(frame.pixel(5, 5), Some(Rgb565::BLACK)); // no diagonal inside the square
//! assert_eq!(frame.pixel(10, 8), Some(Rgb565::WHITE)); // the triangle's edge meets the square
//! assert_eq!(frame.pixel(8, 8), Some(Rgb565::BLACK)); // its edge hidden behind the square
//! ```
//!
//! Lines **over the shaded surfaces** (an outline drawing) take a second frame: draw the
//! shaded frame, then the facets through a [`HiddenLines`](crate::lines::HiddenLines) whose sink writes only the line
//! pixels over it (a frame buffer, or a panel that keeps its own memory).
//!
//! Cost: the facet frame is a flat-shaded frame without lighting; the sink compares each
//! pixel with its four neighbours and keeps two rows of facet numbers (`4·W` bytes) and one
//! row of colours (`2·W`).

use crate::sink::{Row, RowSink};
use embedded_graphics_core::pixelcolor::{IntoStorage, Rgb565};

/// A [`RowSink`] that takes rows of facets ([`Shading::Facets`](crate::shading::Shading::Facets))
/// and hands `sink` the hidden-line drawing: `line` where the visible facet changes,
/// `background` elsewhere, rows in order, each once. A row waits for the next (its lower
/// neighbours); the last row (`height − 1`) goes out at once. Rows are at most `W` pixels
/// (columns beyond are left out); the rows handed on carry no depth.
pub struct HiddenLines<S, const W: usize> {
    sink: S,
    height: u16,
    line: Rgb565,
    background: Rgb565,
    /// Facets of two rows: `rows[held]` waits for the row below it, the other is the row
    /// above it (valid when `above_y` is `Some`).
    rows: [[u16; W]; 2],
    held: usize,
    above_y: Option<u16>,
    held_y: Option<u16>,
    width: usize,
    out: [Rgb565; W],
}

impl<S, const W: usize> HiddenLines<S, W> {
    /// Lines in `line` on `background`, for frames `height` rows high, handed to `sink`.
    pub const fn new(sink: S, height: u16, line: Rgb565, background: Rgb565) -> Self {
        HiddenLines {
            sink,
            height,
            line,
            background,
            rows: [[0; W]; 2],
            held: 0,
            above_y: None,
            held_y: None,
            width: 0,
            out: [background; W],
        }
    }

    /// The sink back.
    pub fn into_inner(self) -> S {
        self.sink
    }

    /// The sink.
    pub fn sink(&mut self) -> &mut S {
        &mut self.sink
    }

    /// Marks the held row against its neighbours (`below`, if any) and hands it on.
    fn flush<N>(&mut self, y: u16, below: Option<&[Rgb565]>) -> Result<(), S::Error>
    where
        S: RowSink<N>,
    {
        let n = self.width;
        let (row, out) = (&self.rows[self.held][..n], &mut self.out[..n]);
        let above = self.above_y.map(|_| &self.rows[1 - self.held][..n]);
        let below = below.and_then(|b| b.get(..n));
        for x in 0..row.len().min(out.len()) {
            let id = row[x];
            // A facet with a smaller one among its four neighbours (a missing neighbour counts
            // as `id`); the background (0) never is.
            let edge = id != 0 && {
                let left = if x > 0 { row[x - 1] } else { id };
                let right = row.get(x + 1).copied().unwrap_or(id);
                let up = above.and_then(|a| a.get(x)).copied().unwrap_or(id);
                let down = below.and_then(|b| b.get(x)).map_or(id, |&c| raw(c));
                left.min(right).min(up).min(down) < id
            };
            out[x] = match edge {
                true => self.line,
                false => self.background,
            };
        }
        let row = Row {
            y,
            color: &self.out[..n],
            depth: &[],
        };
        self.sink.write_row(&row)
    }
}

/// A pixel's facet number.
fn raw(c: Rgb565) -> u16 {
    c.into_storage()
}

impl<N, S: RowSink<N>, const W: usize> RowSink<N> for HiddenLines<S, W> {
    type Error = S::Error;
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), S::Error> {
        if row.y == 0 || self.held_y.and_then(|y| y.checked_add(1)) != Some(row.y) {
            // A new frame (or rows out of order: start again from this one).
            self.above_y = None;
            self.held_y = None;
        }
        if let Some(y) = self.held_y {
            self.flush::<N>(y, Some(row.color))?;
            self.held = 1 - self.held;
            self.above_y = Some(y);
        }
        let n = row.color.len().min(W);
        for (d, &c) in self.rows[self.held].iter_mut().zip(&row.color[..n]) {
            *d = raw(c);
        }
        if self.above_y.is_some() && n != self.width {
            self.above_y = None; // a row of another width: no neighbours above
        }
        self.width = n;
        self.held_y = Some(row.y);
        if row.y.saturating_add(1) >= self.height {
            self.flush::<N>(row.y, None)?;
            self.held_y = None;
        }
        Ok(())
    }
}
