//! Rendering a preset: its format and depth store are types, picked here once.

use embedded_graphics_core::pixelcolor::{raw::RawU16, Rgb565};
use std::convert::Infallible;
use std::time::{Duration, Instant};
use zrow::presets::{DepthStore, Format, Preset};
use zrow::scene::{Polygon, VertexBuffer};
use zrow::shading::Shading;
use zrow::tiled::Tiled;
use zrow::{Config, Error, Renderer, Row, RowSink, Scalar, Scanline, Scene, Q16_16, Q24_8};

/// Frame side of every measurement.
pub const SIZE: usize = zrow_scenes::SIZE as usize;
const P: usize = 2048;
const E: usize = 3 * P;
const A: usize = 512;
/// Band height of the tiled store.
pub const BAND: usize = 16;

/// A captured frame.
#[derive(Clone, Debug, Default)]
pub struct Frame {
    /// Colours, row-major.
    pub colour: Vec<Rgb565>,
    /// Depth as `f64` (`f64::INFINITY` where nothing is drawn).
    pub depth: Vec<f64>,
}

pub(crate) struct Capture<'a>(pub &'a mut Frame);

impl<N: Scalar> RowSink<N> for Capture<'_> {
    type Error = Infallible;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Infallible> {
        let y = row.y as usize;
        let w = row.color.len();
        self.0.colour[y * w..(y + 1) * w].copy_from_slice(row.color);
        for (d, &z) in self.0.depth[y * w..(y + 1) * w].iter_mut().zip(row.depth) {
            *d = if z == N::MAX {
                f64::INFINITY
            } else {
                z.to_f64()
            };
        }
        Ok(())
    }
}

/// Draws each polygon in a colour that encodes its face number + 1 (flat, unlit): which face
/// is visible at each pixel.
pub struct IdScene<'a, N: Scalar>(pub &'a dyn Scene<N>);

impl<N: Scalar> Scene<N> for IdScene<'_, N> {
    fn polygons(
        &self,
        cfg: &Config,
        vertices: &mut VertexBuffer<'_, N>,
        f: &mut dyn FnMut(&Polygon<'_, N>) -> Result<(), Error>,
    ) -> Result<(), Error> {
        self.0.polygons(cfg, vertices, &mut |p| {
            let mut p = *p;
            p.color = Rgb565::from(RawU16::new((p.face + 1) as u16));
            f(&p)
        })
    }
}

/// The face number an ID colour encodes (`None` for the background).
pub fn face_of(c: Rgb565) -> Option<u32> {
    use embedded_graphics_core::pixelcolor::IntoStorage;
    c.into_storage().checked_sub(1).map(u32::from)
}

/// Everything measured from one render of a scene by a preset.
pub struct Rendered {
    /// The frame as the preset draws it.
    pub frame: Frame,
    /// The visible face per pixel (an ID render with flat shading).
    pub ids: Vec<Option<u32>>,
    /// Median host time per frame.
    pub host: Duration,
    /// RAM of the renderer as built.
    pub ram: usize,
}

/// A renderer for each (format, store).
trait Make<N: Scalar>: Renderer<N> + Sized {
    fn make() -> Box<Self>;
}
impl<N: Scalar> Make<N> for Scanline<N, SIZE, E, P, A> {
    fn make() -> Box<Self> {
        Box::new(Self::new())
    }
}
impl<N: Scalar> Make<N> for Tiled<N, SIZE, BAND, P, E> {
    fn make() -> Box<Self> {
        Box::new(Self::new())
    }
}

/// Calls `f` with the preset's renderer type and format: the one place presets become types.
macro_rules! dispatch {
    ($p:expr, $f:ident ( $($arg:expr),* )) => {
        match ($p.format, $p.store) {
            (Format::Q16_16, DepthStore::Row32) => $f::<Q16_16, Scanline<Q16_16, SIZE, E, P, A>>($($arg),*),
            (Format::Q16_16, DepthStore::Tile16) => $f::<Q16_16, Tiled<Q16_16, SIZE, BAND, P, E>>($($arg),*),
            (Format::Q24_8, DepthStore::Row32) => $f::<Q24_8, Scanline<Q24_8, SIZE, E, P, A>>($($arg),*),
            (Format::Q24_8, DepthStore::Tile16) => $f::<Q24_8, Tiled<Q24_8, SIZE, BAND, P, E>>($($arg),*),
            (Format::F32, DepthStore::Row32) => $f::<f32, Scanline<f32, SIZE, E, P, A>>($($arg),*),
            (Format::F32, DepthStore::Tile16) => $f::<f32, Tiled<f32, SIZE, BAND, P, E>>($($arg),*),
        }
    };
}

pub(crate) fn draw<N: Scalar, R: Renderer<N>>(
    r: &mut R,
    scene: &dyn Scene<N>,
    cfg: &Config,
    size: usize,
) -> Result<Frame, String> {
    let mut frame = Frame {
        colour: vec![Rgb565::new(0, 0, 0); size * size],
        depth: vec![f64::INFINITY; size * size],
    };
    r.render(scene, cfg, &mut Capture(&mut frame))
        .map_err(|e| format!("{e:?}"))?;
    Ok(frame)
}

/// The median time of `f` over about `time_for` (at least 5 runs, at most 101).
pub(crate) fn median(
    time_for: Duration,
    mut f: impl FnMut() -> Result<(), String>,
) -> Result<Duration, String> {
    let mut times = vec![];
    let start = Instant::now();
    while times.len() < 5 || (start.elapsed() < time_for && times.len() < 101) {
        let t = Instant::now();
        f()?;
        times.push(t.elapsed());
    }
    times.sort();
    Ok(times[times.len() / 2])
}

fn scene_run<N: zrow_scenes::Format, R: Make<N>>(
    p: &Preset,
    name: &str,
    time_for: Duration,
) -> Result<Rendered, String> {
    let mut r = R::make();
    zrow_scenes::with_preset_scene::<N, _>(name, p, |scene, cfg, _| {
        let frame = draw(&mut *r, scene, cfg, SIZE)?;
        let mut flat = *cfg;
        flat.shading = Shading::Flat;
        let id = draw(&mut *r, &IdScene(scene), &flat, SIZE)?;
        let host = median(time_for, || draw(&mut *r, scene, cfg, SIZE).map(|_| ()))?;
        Ok(Rendered {
            frame,
            ids: id.colour.iter().map(|&c| face_of(c)).collect(),
            host,
            ram: R::RAM_BYTES,
        })
    })
    .ok_or_else(|| format!("unknown scene {name}"))?
}

/// Renders preset scene `name` with `p` (and its ID render), timing it for about `time_for`.
pub fn run(p: &Preset, name: &str, time_for: Duration) -> Result<Rendered, String> {
    dispatch!(p, scene_run(p, name, time_for))
}

/// A scene built in the preset's format by the caller.
pub trait Build {
    /// Calls `f` with the scene in format `N`.
    fn build<N: Scalar>(&self, f: &mut dyn FnMut(&dyn Scene<N>));
}

fn built<N: Scalar, R: Make<N>>(
    b: &impl Build,
    cfg: &Config,
    size: usize,
) -> Result<Frame, String> {
    let mut r = R::make();
    let mut out = Err("scene not built".to_string());
    b.build::<N>(&mut |s| out = draw(&mut *r, &IdScene(s), cfg, size));
    out
}

/// Renders a caller-built scene with the preset's types as an ID render (colours are face
/// numbers + 1).
pub fn run_ids<B: Build>(p: &Preset, b: &B, cfg: &Config, size: usize) -> Result<Frame, String> {
    dispatch!(p, built(b, cfg, size))
}
