//! Where finished rows go: the [`RowSink`] trait and two sinks.

use core::convert::Infallible;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::primitives::Rectangle;

/// One finished row: its `intensity[x]` and `depth[x]`.
#[derive(Clone, Copy, Debug)]
pub struct Row<'a, N> {
    /// Row number, 0 at the top.
    pub y: u16,
    /// The colour of every pixel, left to right.
    pub intensity: &'a [Rgb565],
    /// The visible depth at every pixel (the format's maximum where nothing is drawn); empty
    /// when the sink said it does not read it ([`RowSink::WANTS_DEPTH`]) and the renderer
    /// skipped it.
    pub depth: &'a [N],
}

/// Receives rows top to bottom, each complete. Like embedded-graphics' `DrawTarget`, it says
/// how it fails: `Infallible` for memory, the bus error on a display.
pub trait RowSink<N> {
    /// The sink's error.
    type Error;
    /// Whether the sink reads [`Row::depth`]. A sink that only shows colours says `false`, and
    /// renderers that need no depth row of their own (the scan-line method) then skip writing
    /// one: [`Row::depth`] is empty. Default `true`.
    const WANTS_DEPTH: bool = true;
    /// Takes one row.
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Self::Error>;
}

/// An in-memory frame over the caller's pixels (row-major, `width` a row). Rows or columns
/// that do not fit are ignored.
pub struct FrameBuffer<'a> {
    pixels: &'a mut [Rgb565],
    width: usize,
}

impl<'a> FrameBuffer<'a> {
    /// Wraps a pixel slice whose rows are `width` long.
    pub fn new(pixels: &'a mut [Rgb565], width: usize) -> Self {
        FrameBuffer { pixels, width }
    }
    /// The pixel at (x, y), if inside.
    pub fn pixel(&self, x: usize, y: usize) -> Option<Rgb565> {
        if x >= self.width {
            return None;
        }
        self.pixels.get(y * self.width + x).copied()
    }
    /// All pixels.
    pub fn pixels(&self) -> &[Rgb565] {
        self.pixels
    }
}

impl<N> RowSink<N> for FrameBuffer<'_> {
    type Error = Infallible;
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Infallible> {
        let start = row.y as usize * self.width;
        let n = row.intensity.len().min(self.width);
        if let Some(dst) = self.pixels.get_mut(start..start + n) {
            dst.copy_from_slice(&row.intensity[..n]);
        }
        Ok(())
    }
}

/// Sends rows to any embedded-graphics [`DrawTarget`] (a display driver, the simulator, a
/// frame buffer) whose colour converts from [`Rgb565`] (`Rgb565` itself, `Rgb888`, `Gray8`,
/// `BinaryColor` by embedded-graphics' threshold, ...). Rows and columns outside the target's
/// bounding box are left out, so a frame larger than the display is clipped, never drawn out of
/// bounds.
pub struct DrawTargetSink<'a, D>(pub &'a mut D);

impl<N, D> RowSink<N> for DrawTargetSink<'_, D>
where
    D: DrawTarget,
    D::Color: From<Rgb565>,
{
    type Error = D::Error;
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), D::Error> {
        let bounds = self.0.bounding_box();
        let (top, left) = (bounds.top_left.y as i64, bounds.top_left.x as i64);
        let (bottom, right) = (
            top + bounds.size.height as i64,
            left + bounds.size.width as i64,
        );
        let y = row.y as i64;
        if y < top || y >= bottom {
            return Ok(());
        }
        // Columns of the row that land on the target: left.max(0) .. right.min(len).
        let x0 = left.max(0) as usize;
        let x1 = (right.max(0) as usize).min(row.intensity.len());
        let Some(pixels) = row.intensity.get(x0..x1) else {
            return Ok(()); // nothing of this row is on the target
        };
        let area = Rectangle::new(
            Point::new(x0 as i32, row.y as i32),
            Size::new(pixels.len() as u32, 1),
        );
        self.0
            .fill_contiguous(&area, pixels.iter().map(|&c| D::Color::from(c)))
    }
}
