//! Where finished rows go: the [`RowSink`] trait, two sinks, and [`Drawing`], a 3D scene as an
//! embedded-graphics [`Drawable`](embedded_graphics_core::Drawable).

use crate::error::{Error, RenderError};
use crate::method::{FrameStats, Renderer};
use crate::number::Scalar;
use crate::raster::Config;
use crate::scene::Scene;
use core::cell::RefCell;
use core::convert::Infallible;
use core::marker::PhantomData;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Drawable;

/// One finished row: the colour `color[x]` and the depth `depth[x]` of every pixel (the
/// `intensity[x]` and `depth[x]` of the scan-line method's description).
#[derive(Clone, Copy, Debug)]
pub struct Row<'a, N> {
    /// Row number, 0 at the top.
    pub y: u16,
    /// The colour of every pixel, left to right.
    pub color: &'a [Rgb565],
    /// The visible depth at every pixel (the format's maximum where nothing is drawn): the
    /// visible polygon's exact plane rounded once at the pixel centre, within half a unit of
    /// the format's last place ([`crate::Scalar::exact_plane`]). Empty when the sink said it
    /// does not read it ([`RowSink::WANTS_DEPTH`]) and the renderer skipped it.
    pub depth: &'a [N],
}

/// Whether depths handed to a sink come from each polygon's exact plane (the `exact-depth`
/// feature, on by default): see [`Row::depth`].
pub(crate) const EXACT_DEPTH: bool = cfg!(feature = "exact-depth");

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
        let n = row.color.len().min(self.width);
        if let Some(dst) = self.pixels.get_mut(start..start + n) {
            dst.copy_from_slice(&row.color[..n]);
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
        let x1 = (right.max(0) as usize).min(row.color.len());
        let Some(pixels) = row.color.get(x0..x1) else {
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

/// A scene drawn by a renderer, as an embedded-graphics [`Drawable`]: for a program that just
/// wants the scene in its display, like any other drawable.
///
/// `draw` renders the whole frame through a [`DrawTargetSink`] (clipped to the target) and
/// returns the display's error as `Err`; a scene the renderer rejects (a capacity too small,
/// bad input: [`Error`]) comes back as `Ok(Err(..))`, before any pixel is drawn. For a display
/// in another colour format, draw into `display.color_converted()` (embedded-graphics).
///
/// ```
/// use embedded_graphics::mock_display::MockDisplay;
/// use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
/// use embedded_graphics::prelude::*;
/// use zrow::{Config, Drawing, Face, Mesh, Scanline, ScreenScene, Vec3, Q16_16};
///
/// let q = |x, y, z| Vec3::<Q16_16>::from_f32([x, y, z]).unwrap();
/// let vertices = [q(2.0, 2.0, 1.0), q(30.0, 6.0, 1.0), q(6.0, 30.0, 1.0)];
/// let faces = [Face::new(&[0, 1, 2], Rgb565::GREEN)];
/// let scene = ScreenScene { mesh: Mesh::new(&vertices, &faces) };
/// let mut renderer = Scanline::<Q16_16, 32, 4, 4, 4>::new();
/// let drawing = Drawing::new(&mut renderer, &scene, Config::screen(32, 32));
///
/// let mut display = MockDisplay::<Rgb565>::new();
/// let stats = drawing
///     .draw(&mut display)
///     .unwrap() // the display did not fail
///     .unwrap(); // the renderer took the scene
/// assert_eq!(stats.polygons, 1);
/// assert_eq!(display.get_pixel(Point::new(8, 8)), Some(Rgb565::GREEN));
///
/// // A display in another colour format, through embedded-graphics' conversion.
/// let mut rgb888 = MockDisplay::<Rgb888>::new();
/// drawing.draw(&mut rgb888.color_converted()).unwrap().unwrap();
/// assert_eq!(rgb888.get_pixel(Point::new(8, 8)), Some(Rgb888::GREEN));
/// ```
pub struct Drawing<'a, N, R, S: ?Sized> {
    renderer: RefCell<&'a mut R>,
    scene: &'a S,
    config: Config,
    format: PhantomData<N>,
}

impl<'a, N, R, S: ?Sized> Drawing<'a, N, R, S> {
    /// `scene` under `config`, to be drawn by `renderer` (which keeps its tables between
    /// draws: make it once, like any zrow renderer).
    pub fn new(renderer: &'a mut R, scene: &'a S, config: Config) -> Self {
        Drawing {
            renderer: RefCell::new(renderer),
            scene,
            config,
            format: PhantomData,
        }
    }
}

impl<N, R, S> Drawable for Drawing<'_, N, R, S>
where
    N: Scalar,
    R: Renderer<N>,
    S: Scene<N> + ?Sized,
{
    type Color = Rgb565;
    /// The frame's statistics, or why the renderer rejected the scene.
    type Output = Result<FrameStats, Error>;

    fn draw<D: DrawTarget<Color = Rgb565>>(
        &self,
        target: &mut D,
    ) -> Result<Result<FrameStats, Error>, D::Error> {
        // Only a draw from inside this draw could find the renderer busy, and a display cannot
        // reach it; still, that is an error, not a panic.
        let Ok(mut renderer) = self.renderer.try_borrow_mut() else {
            return Ok(Err(Error::BadConfig));
        };
        match renderer.render(self.scene, &self.config, &mut DrawTargetSink(target)) {
            Ok(stats) => Ok(Ok(stats)),
            Err(RenderError::Scene(e)) => Ok(Err(e)),
            Err(RenderError::Sink(e)) => Err(e),
        }
    }
}
