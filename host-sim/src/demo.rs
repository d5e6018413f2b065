//! The demo the simulator window shows, and its headless fallback.
//!
//! The scenes are zrow-scenes' [`DEMOS`](zrow_scenes::DEMOS) (`interlocked`: two rings linked
//! through each other and a cube piercing both, turning, so the visible surfaces change every
//! frame; then `cube` and `mesh1k`). Every frame goes through the same core as the board:
//! [`zrow::Scanline`] sends its rows through [`zrow::DrawTargetSink`] into an embedded-graphics
//! display (the simulator's, here). The top [`STATUS_ROWS`] rows are then overdrawn with a
//! status line: method, number format, scene, render time on this host, polygons drawn, and the
//! RAM the scan-line method needs for this very frame (its exact requirement,
//! [`zrow::requirements()`]) beside the board's RAM ([`BOARD_RAM`]).
//!
//! `--model FILE` (OBJ, STL or OFF, see [`crate::model`]) puts the model first: the camera
//! orbits it under the fixed light of [`crate::model_render`], at the demo's turning angle;
//! with `--smooth DEG` it turns smooth shaded (Gouraud, vertex normals within that crease
//! angle, as `render-model --smooth`).
//!
//! Everything here works without SDL: [`first_frame`] and [`write_png`] give the frame the
//! window opens on as a PNG. The window itself is `crate::window` (feature `window`).

use crate::model::LoadedModel;
use crate::model_render;
use crate::render::{Algo, Format};
use crate::SimError;
use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use embedded_graphics::text::{Baseline, Text};
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use zrow::{Cull, DrawTargetSink, FrameStats, RenderError, Renderer, Scanline, Q16_16};

/// Frame side in pixels (the ST7789 panel).
pub const SIZE: u32 = zrow_scenes::SIZE as u32;
/// The window shows each frame pixel as `SCALE × SCALE` screen pixels.
pub const SCALE: u32 = 2;
/// Rows at the top that the status line covers (two lines of the 6×10 font).
pub const STATUS_ROWS: u32 = 22;
/// RAM of the board the demo firmware runs on (the STM32F411's 128 KiB), shown beside the
/// frame's requirement.
pub const BOARD_RAM: usize = 128 * 1024;
/// Radians the scene turns per frame.
pub const STEP: f32 = 0.03;
/// The window's title.
pub const TITLE: &str = "zrow-sim demo";
/// The PNG the default command writes when there is no window.
pub const FALLBACK_PNG: &str = "zrow-demo.png";

/// Polygon-table capacity of the demo renderer (the demos need at most 1,000, `mesh1k` with
/// culling off).
pub const DEMO_POLYGONS: usize = 2048;
/// Edge-table capacity of the demo renderer.
pub const DEMO_EDGES: usize = 8192;
/// Active-list capacity of the demo renderer.
pub const DEMO_ACTIVE: usize = 1024;

/// Pieces (polygons plus split parts) for the demo's depth-sort and BSP.
pub const DEMO_PIECES: usize = 16384;
/// Deepest BSP tree the demo builds (a closed mesh inserted in its own order is deep).
pub const DEMO_BSP_DEPTH: usize = 2048;

/// The demo's renderer: 240-pixel rows and the capacities above (checked against every demo
/// scene, turned, in both formats, culled or not, by a test), with an intensity plane per
/// polygon so that a model loaded with `--smooth` turns smooth shaded.
pub type DemoScanline<N> = Scanline<
    N,
    { SIZE as usize },
    DEMO_EDGES,
    DEMO_POLYGONS,
    DEMO_ACTIVE,
    u16,
    [zrow::scanline::EdgeCue<N>; DEMO_ACTIVE],
    [zrow::IntensityPlane<N>; DEMO_POLYGONS],
>;
/// The demo's z-buffer (240×240).
pub type DemoZBuffer<N> = zrow::ZBuffer<N, { SIZE as usize }, { SIZE as usize }>;
/// The demo's depth-sort.
pub type DemoDepthSort<N> =
    zrow::depthsort::DepthSort<N, { SIZE as usize }, DEMO_POLYGONS, DEMO_EDGES, DEMO_PIECES>;
/// The demo's A-buffer (fragments per row).
pub type DemoABuffer<N> =
    zrow::abuffer::ABuffer<N, { SIZE as usize }, DEMO_POLYGONS, DEMO_EDGES, 4096>;
/// The demo's tiled 16-bit z-buffer (bands of 16 rows).
pub type DemoTiled<N> = zrow::tiled::Tiled<N, { SIZE as usize }, 16, DEMO_POLYGONS, DEMO_EDGES>;
/// The demo's Warnock (bands of 16 rows; list room for every polygon in a band, 6 times).
pub type DemoWarnock<N> = zrow::warnock::Warnock<
    N,
    { SIZE as usize },
    16,
    DEMO_POLYGONS,
    DEMO_EDGES,
    { 6 * DEMO_POLYGONS },
>;
/// The demo's BSP tree.
pub type DemoBsp<N> =
    zrow::bsp::Bsp<N, { SIZE as usize }, DEMO_POLYGONS, DEMO_EDGES, DEMO_PIECES, DEMO_BSP_DEPTH>;

/// What the window shows: method, format, scene, culling, angle, pause.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Index into [`Algo::ALL`].
    pub method: usize,
    /// Number format.
    pub format: Format,
    /// Which scene: with a model, 0 is the model and `k + 1` is `DEMOS[k]`; else `DEMOS[k]`.
    pub scene: usize,
    /// A model was loaded (`--model`): it is scene 0.
    pub has_model: bool,
    /// Back-face culling on.
    pub cull: bool,
    /// The scene's turn, radians.
    pub angle: f32,
    /// Frozen (only single steps move it).
    pub paused: bool,
}

impl Default for View {
    fn default() -> Self {
        View {
            method: 0,
            format: Format::Q16_16,
            scene: 0,
            has_model: false,
            cull: true,
            angle: 0.0,
            paused: false,
        }
    }
}

/// What a key asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// `m`: the next method of [`Algo::ALL`].
    NextMethod,
    /// `f`: Q16.16 ↔ f32.
    ToggleFormat,
    /// Space: pause or resume.
    TogglePause,
    /// `s` or Right: one step (pauses).
    Step,
    /// `n`: the next demo scene.
    NextScene,
    /// `c`: back-face culling on or off.
    ToggleCull,
    /// Escape or `q`.
    Quit,
}

impl View {
    /// The method shown.
    pub fn algo(&self) -> Algo {
        Algo::ALL[self.method % Algo::ALL.len()].1
    }

    /// How many scenes there are to cycle through.
    pub fn scene_count(&self) -> usize {
        zrow_scenes::DEMOS.len() + self.has_model as usize
    }

    /// Whether the loaded model is shown.
    pub fn shows_model(&self) -> bool {
        self.has_model && self.scene % self.scene_count() == 0
    }

    /// The scene shown (`model` for the loaded model).
    pub fn scene_name(&self) -> &'static str {
        if self.shows_model() {
            return "model";
        }
        let k = self.scene % self.scene_count() - self.has_model as usize;
        zrow_scenes::DEMOS[k]
    }

    /// Applies a key's action (`Quit` is the caller's).
    pub fn apply(&mut self, action: Action) {
        match action {
            Action::NextMethod => self.method = (self.method + 1) % Algo::ALL.len(),
            Action::ToggleFormat => {
                self.format = match self.format {
                    Format::Q16_16 => Format::F32,
                    Format::F32 => Format::Q16_16,
                }
            }
            Action::TogglePause => self.paused = !self.paused,
            Action::Step => {
                self.paused = true;
                self.advance();
            }
            Action::NextScene => self.scene = (self.scene + 1) % self.scene_count(),
            Action::ToggleCull => self.cull = !self.cull,
            Action::Quit => {}
        }
    }

    /// Turns the scene one step.
    pub fn advance(&mut self) {
        self.angle = (self.angle + STEP) % std::f32::consts::TAU;
    }
}

/// Every method in one number format, boxed (their tables are too big for a stack) and made
/// when first used.
pub struct Methods<N: zrow::Scalar> {
    scanline: Option<Box<DemoScanline<N>>>,
    zbuffer: Option<Box<DemoZBuffer<N>>>,
    tiled: Option<Box<DemoTiled<N>>>,
    warnock: Option<Box<DemoWarnock<N>>>,
    depth_sort: Option<Box<DemoDepthSort<N>>>,
    bsp: Option<Box<DemoBsp<N>>>,
    abuffer: Option<Box<DemoABuffer<N>>>,
}

impl<N: zrow::Scalar> Methods<N> {
    fn new() -> Self {
        Methods {
            scanline: None,
            zbuffer: None,
            tiled: None,
            warnock: None,
            depth_sort: None,
            bsp: None,
            abuffer: None,
        }
    }
}

/// The renderers, one set per format.
pub struct Renderers {
    q16: Methods<Q16_16>,
    f32: Methods<f32>,
}

impl Default for Renderers {
    fn default() -> Self {
        Self::new()
    }
}

impl Renderers {
    /// All renderers, empty.
    pub fn new() -> Self {
        Renderers {
            q16: Methods::new(),
            f32: Methods::new(),
        }
    }
}

/// One rendered frame: how long it took and what it drew, or why it drew nothing.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Wall time of the render on this host, rows into the display included.
    pub time: Duration,
    /// The frame's statistics, or the error (one line).
    pub result: Result<FrameStats, String>,
    /// Bytes of RAM the scan-line method needs for exactly this frame (its renderer sized to
    /// the frame's [`zrow::requirements()`]), when they were measured.
    pub needs: Option<usize>,
}

/// Renders `view` into `display` (its top-left 240×240); `model` is the `--model` one, if
/// any. Never panics: a scene or capacity error is returned in [`Frame::result`] and leaves
/// the display as it was (zrow fails before the first row).
pub fn render<D>(
    renderers: &mut Renderers,
    view: &View,
    model: Option<&LoadedModel>,
    display: &mut D,
) -> Frame
where
    D: DrawTarget<Color = Rgb565>,
    D::Error: core::fmt::Debug,
{
    match view.format {
        Format::Q16_16 => render_in(&mut renderers.q16, view, model, display),
        Format::F32 => render_in(&mut renderers.f32, view, model, display),
    }
}

fn render_in<N, D>(
    m: &mut Methods<N>,
    view: &View,
    model: Option<&LoadedModel>,
    display: &mut D,
) -> Frame
where
    N: zrow_scenes::Format,
    D: DrawTarget<Color = Rgb565>,
    D::Error: core::fmt::Debug,
{
    match view.algo() {
        // `auto` in the window: the scan-line method (see `Methods::ram_bytes`).
        Algo::Scanline | Algo::Auto | Algo::CullOnly | Algo::Ordered => {
            render_with(made(&mut m.scanline), view, model, display)
        }
        Algo::ZBuffer => render_with(made(&mut m.zbuffer), view, model, display),
        Algo::Tiled => render_with(made(&mut m.tiled), view, model, display),
        Algo::Warnock => render_with(made(&mut m.warnock), view, model, display),
        Algo::DepthSort => render_with(made(&mut m.depth_sort), view, model, display),
        Algo::Bsp => render_with(made(&mut m.bsp), view, model, display),
        Algo::ABuffer => render_with(made(&mut m.abuffer), view, model, display),
    }
}

/// The renderer in `slot`, made now if it was not yet.
fn made<R: Default>(slot: &mut Option<Box<R>>) -> &mut R {
    slot.get_or_insert_with(Box::default)
}

fn render_with<N, D, R: Renderer<N>>(
    renderer: &mut R,
    view: &View,
    model: Option<&LoadedModel>,
    display: &mut D,
) -> Frame
where
    N: zrow_scenes::Format,
    D: DrawTarget<Color = Rgb565>,
    D::Error: core::fmt::Debug,
{
    let name = view.scene_name();
    let start = Instant::now();
    let cull = if view.cull { Cull::Back } else { Cull::None };
    // The render's time, and the frame's exact requirement (measured after it, not timed).
    let mut time = Duration::ZERO;
    let mut needs = None;
    let out = match model.filter(|_| view.shows_model()) {
        // The camera orbits the model (turning by the demo's angle) under the fixed light.
        Some(model) => {
            let orbit = model_render::View {
                yaw_deg: view.angle.to_degrees(),
                ..model_render::View::default()
            };
            let drawn = model_render::with_scene::<N, _>(
                model,
                &orbit,
                SIZE as u16,
                SIZE as u16,
                |scene, cfg| {
                    let mut cfg = *cfg;
                    cfg.cull = cull;
                    let out = renderer.render(scene, &cfg, &mut DrawTargetSink(&mut *display));
                    time = start.elapsed();
                    needs = scanline_needs(scene, &cfg);
                    Some(out)
                },
            );
            match drawn {
                // A model beyond the window's fixed capacities: renderers sized to the model.
                Ok(Some(Err(RenderError::Scene(zrow::Error::Capacity { .. })))) => {
                    let sized = model_render::render_model_culled(
                        model,
                        &orbit,
                        (SIZE as u16, SIZE as u16),
                        view.algo(),
                        view.format,
                        cull,
                    );
                    let time = start.elapsed();
                    let (result, needs) = match sized {
                        Ok((image, req)) => {
                            let area = Rectangle::new(Point::zero(), Size::new(SIZE, SIZE));
                            let needs = Some(zrow::scanline::ram_bytes::<N>(&req));
                            match display.fill_contiguous(&area, image.pixels) {
                                Ok(()) => (
                                    Ok(FrameStats {
                                        polygons: req.polygons,
                                        edges: req.edges,
                                        max_active: req.active_polygons,
                                        ..FrameStats::default()
                                    }),
                                    needs,
                                ),
                                Err(e) => (Err(format!("display: {e:?}")), needs),
                            }
                        }
                        Err(e) => (Err(e.to_string()), None),
                    };
                    return Frame {
                        time,
                        result,
                        needs,
                    };
                }
                Ok(out) => out,
                Err(e) => {
                    return Frame {
                        time: start.elapsed(),
                        result: Err(e.to_string()),
                        needs: None,
                    }
                }
            }
        }
        None => zrow_scenes::with_scene::<N, _>(name, view.angle, |scene, cfg, _faces| {
            let mut cfg = *cfg;
            cfg.cull = cull;
            let out = renderer.render(scene, &cfg, &mut DrawTargetSink(&mut *display));
            time = start.elapsed();
            needs = scanline_needs(scene, &cfg);
            out
        }),
    };
    if time.is_zero() {
        time = start.elapsed();
    }
    let result = match out {
        None => Err(format!("{name} does not fit {}", view.format.name())),
        Some(Ok(stats)) => Ok(stats),
        Some(Err(RenderError::Scene(e))) => Err(e.to_string()),
        Some(Err(RenderError::Sink(e))) => Err(format!("display: {e:?}")),
    };
    Frame {
        time,
        result,
        needs,
    }
}

/// Bytes of RAM the scan-line method needs for exactly this frame: its renderer sized to the
/// frame's requirements. `None` if the scene cannot be measured (then it did not render).
fn scanline_needs<N: zrow::Scalar>(
    scene: &(impl zrow::Scene<N> + ?Sized),
    cfg: &zrow::Config,
) -> Option<usize> {
    zrow::requirements(scene, cfg)
        .ok()
        .map(|req| match cfg.shading.is_smooth() {
            true => zrow::scanline::ram_bytes_gouraud::<N>(&req),
            false => zrow::scanline::ram_bytes::<N>(&req),
        })
}

/// The two status lines (each at most 40 characters, the width of the 6×10 font).
pub fn status_text(view: &View, frame: &Frame, time: Duration) -> [String; 2] {
    let mut first = format!(
        "{} {} {}{}",
        view.algo().name(),
        view.format.name(),
        view.scene_name(),
        if view.cull { "" } else { " nocull" },
    );
    if view.paused {
        first += " [paused]";
    }
    let second = match &frame.result {
        Ok(stats) => {
            let us = time.as_micros();
            let t = if us < 10_000 {
                format!("{us}us")
            } else {
                format!("{:.1}ms", us as f64 / 1000.0)
            };
            let needs = match frame.needs {
                Some(bytes) => {
                    format!(" needs {:.1}K/{}K", bytes as f64 / 1024.0, BOARD_RAM / 1024)
                }
                None => String::new(),
            };
            format!("{t} {} polys{needs}", stats.polygons)
        }
        Err(e) => format!("error: {e}"),
    };
    [first, second].map(|s| s.chars().take(40).collect())
}

/// Draws the status line over the top [`STATUS_ROWS`] rows. `time` is the render time to show
/// (the window shows a running average).
pub fn draw_status<D>(display: &mut D, view: &View, frame: &Frame, time: Duration)
where
    D: DrawTarget<Color = Rgb565>,
{
    let bar = Rectangle::new(Point::zero(), Size::new(SIZE, STATUS_ROWS));
    // Drawing into the simulator cannot fail; a driver's error here only loses the status.
    let _ = bar
        .into_styled(PrimitiveStyle::with_fill(Rgb565::new(2, 4, 4)))
        .draw(display);
    let colour = if frame.result.is_ok() {
        Rgb565::new(31, 58, 8)
    } else {
        Rgb565::new(31, 16, 12)
    };
    let style = MonoTextStyle::new(&FONT_6X10, colour);
    for (i, line) in status_text(view, frame, time).iter().enumerate() {
        let at = Point::new(1, 1 + 10 * i as i32);
        let _ = Text::with_baseline(line, at, style, Baseline::Top).draw(display);
    }
}

/// A blank 240×240 simulator display.
pub fn new_display() -> SimulatorDisplay<Rgb565> {
    SimulatorDisplay::new(Size::new(SIZE, SIZE))
}

/// The frame the window opens on (first scene, angle 0), status line included, with the
/// pause flag shown as given.
pub fn first_frame(paused: bool, model: Option<&LoadedModel>) -> SimulatorDisplay<Rgb565> {
    let mut display = new_display();
    let view = View {
        paused,
        has_model: model.is_some(),
        ..View::default()
    };
    let mut renderers = Renderers::new();
    let frame = render(&mut renderers, &view, model, &mut display);
    draw_status(&mut display, &view, &frame, frame.time);
    display
}

/// Writes `display` as a PNG, each pixel `scale × scale` (the simulator's output image).
pub fn write_png(
    display: &SimulatorDisplay<Rgb565>,
    path: &Path,
    scale: u32,
) -> Result<(), SimError> {
    let settings = OutputSettingsBuilder::new().scale(scale).build();
    display
        .to_rgb_output_image(&settings)
        .save_png(path)
        .map_err(|e| SimError::Io {
            path: path.display().to_string(),
            action: "write",
            source: std::io::Error::other(e),
        })
}

/// Options of the demo (`zrow-sim --demo`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DemoArgs {
    /// `--paused`: open frozen on the first frame.
    pub paused: bool,
    /// `--dump-expected FILE`: write the first (paused) frame as the window shows it (2×) and
    /// exit, without opening a window.
    pub dump_expected: Option<PathBuf>,
    /// `--frames N`: quit after N window updates.
    pub frames: Option<u64>,
    /// `--model FILE`: an OBJ, STL or OFF model to orbit (shown first).
    pub model: Option<PathBuf>,
    /// `--smooth DEG`: the model smooth shaded, its vertex normals within this crease angle
    /// (as `render-model --smooth`).
    pub smooth: Option<f64>,
}

/// The demo's flags, for [`is_demo`] and messages (`--demo` alone: the demo as it starts).
pub const FLAGS: [&str; 6] = [
    "--demo",
    "--paused",
    "--dump-expected",
    "--frames",
    "--model",
    "--smooth",
];

/// Whether the arguments (after the program name) are the demo's: none, or starting with one
/// of [`FLAGS`].
pub fn is_demo(args: &[OsString]) -> bool {
    args.first().is_none_or(|a| {
        a.to_str()
            .is_some_and(|a| FLAGS.contains(&a.split_once('=').map_or(a, |(f, _)| f)))
    })
}

/// Parses the demo's flags.
pub fn parse_args(args: &[OsString]) -> Result<DemoArgs, SimError> {
    let usage = |m: String| SimError::Usage(m);
    let mut out = DemoArgs::default();
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let text = arg
            .to_str()
            .ok_or_else(|| usage("argument is not valid UTF-8".into()))?;
        let (flag, inline) = match text.split_once('=') {
            Some((f, v)) => (f, Some(OsString::from(v))),
            None => (text, None),
        };
        let mut value = || {
            inline
                .clone()
                .or_else(|| it.next().cloned())
                .ok_or_else(|| usage(format!("{flag} needs a value")))
        };
        match flag {
            "--demo" if inline.is_none() => {}
            "--paused" if inline.is_none() => out.paused = true,
            "--dump-expected" => out.dump_expected = Some(PathBuf::from(value()?)),
            "--model" => out.model = Some(PathBuf::from(value()?)),
            "--smooth" => {
                let v = value()?;
                let deg = v
                    .to_str()
                    .and_then(|v| v.parse::<f64>().ok())
                    .filter(|d| (0.0..=180.0).contains(d))
                    .ok_or_else(|| {
                        usage(format!(
                            "bad --smooth `{}`: expected a crease angle in degrees, 0..=180",
                            v.to_string_lossy()
                        ))
                    })?;
                out.smooth = Some(deg);
            }
            "--frames" => {
                let v = value()?;
                let n = v
                    .to_str()
                    .and_then(|v| v.parse().ok())
                    .ok_or_else(|| usage(format!("bad --frames `{}`", v.to_string_lossy())))?;
                out.frames = Some(n);
            }
            _ => {
                return Err(usage(format!(
                "unknown demo argument `{}`: expected --demo, --model FILE, --smooth DEG, --paused, --dump-expected FILE or --frames N",
                text.escape_debug()
            )))
            }
        }
    }
    Ok(out)
}

/// `zrow-sim --demo`: the window when this build has one and a display is there, else one
/// line saying so and [`FALLBACK_PNG`]. `EG_SIMULATOR_DUMP=FILE` dumps the first frame as the
/// simulator does, `--dump-expected FILE` likewise without the environment.
pub fn run(args: &[OsString]) -> Result<(), SimError> {
    let args = parse_args(args)?;
    // A model that does not load is an error (file and line), before any window opens.
    if args.smooth.is_some() && args.model.is_none() {
        return Err(SimError::Usage("--smooth needs --model FILE".into()));
    }
    let model = args
        .model
        .as_deref()
        .map(crate::cli::load_model)
        .transpose()?
        .map(|m| match args.smooth {
            Some(crease) => m.smoothed(crease),
            None => m,
        });
    let model = model.as_ref();
    if let Some(path) = &args.dump_expected {
        return write_png(&first_frame(true, model), path, SCALE);
    }
    if std::env::var_os("EG_SIMULATOR_DUMP").is_some() {
        // The simulator's own switch: it writes the PNG and exits the process.
        let settings = OutputSettingsBuilder::new().scale(SCALE).build();
        let mut window = embedded_graphics_simulator::Window::new(TITLE, &settings);
        window.update(&first_frame(args.paused, model));
        return Ok(());
    }
    #[cfg(feature = "window")]
    let why = match crate::window::run(&args, model) {
        Ok(()) => return Ok(()),
        Err(crate::window::NoWindow(why)) => format!(
            "no window: {why}; wrote the first demo frame to {FALLBACK_PNG} instead \
             (run from a desktop session, or under Xvfb, for the window)"
        ),
    };
    #[cfg(not(feature = "window"))]
    let why = format!(
        "no window in this build: wrote the first demo frame to {FALLBACK_PNG}; for the window: \
         sudo apt-get install -y libsdl2-dev && cargo run --release -p zrow-sim --features window"
    );
    write_png(&first_frame(false, model), Path::new(FALLBACK_PNG), 1)?;
    crate::output::print(&format!("zrow-sim: {why}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::RgbColor;

    #[test]
    fn the_capacities_fit_every_demo_view() {
        for &name in &zrow_scenes::DEMOS {
            for step in 0..64 {
                let angle = step as f32 * std::f32::consts::TAU / 64.0;
                for cull in [Cull::Back, Cull::None] {
                    let req = zrow_scenes::with_scene::<Q16_16, _>(name, angle, |s, cfg, _| {
                        let cfg = zrow::Config { cull, ..*cfg };
                        zrow::requirements(s, &cfg).unwrap()
                    })
                    .unwrap();
                    assert!(req.polygons as usize <= DEMO_POLYGONS, "{name} {req:?}");
                    assert!(req.edges as usize <= DEMO_EDGES, "{name} {req:?}");
                    assert!(
                        req.active_polygons as usize <= DEMO_ACTIVE,
                        "{name} {req:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn every_view_renders_and_the_status_fits() {
        let mut renderers = Renderers::new();
        let mut display = new_display();
        let mut view = View::default();
        for _ in 0..zrow_scenes::DEMOS.len() {
            for _ in 0..2 {
                for _ in 0..2 {
                    let frame = render(&mut renderers, &view, None, &mut display);
                    let stats = frame.result.clone().unwrap();
                    assert!(stats.polygons > 0, "{view:?}");
                    for line in status_text(&view, &frame, frame.time) {
                        assert!(line.len() <= 40, "{line}");
                    }
                    view.apply(Action::ToggleCull);
                }
                view.apply(Action::ToggleFormat);
            }
            view.apply(Action::NextScene);
        }
        assert_eq!(view.scene, 0);
        view.apply(Action::Step);
        assert!(view.paused && view.angle == STEP);
        for &(_, algo) in &Algo::ALL[1..] {
            view.apply(Action::NextMethod);
            assert_eq!(view.algo(), algo);
        }
        view.apply(Action::NextMethod);
        assert_eq!(view.algo(), Algo::Scanline);
    }

    /// `m` cycles through every method; each draws the scan-line method's picture of every
    /// demo scene (their tables are big: a thread with a big stack builds them). The tiled
    /// 16-bit z-buffer may pick the other surface where two are closer than its depth
    /// resolution (where the cube pierces a ring: 1 pixel of the first frame; its resolution
    /// is held to the reference in `crates/zrow/tests/extremes_depth.rs`, item 17): a few
    /// pixels at most.
    #[test]
    fn every_method_draws_the_same_demo_frames() {
        std::thread::Builder::new()
            .stack_size(256 << 20)
            .spawn(|| {
                let mut renderers = Renderers::new();
                let mut view = View::default();
                for _ in 0..zrow_scenes::DEMOS.len() {
                    let mut want = new_display();
                    render(&mut renderers, &view, None, &mut want)
                        .result
                        .unwrap();
                    for _ in 1..Algo::ALL.len() {
                        view.apply(Action::NextMethod);
                        let mut got = new_display();
                        let frame = render(&mut renderers, &view, None, &mut got);
                        assert!(frame.result.is_ok(), "{view:?}: {:?}", frame.result);
                        let px = |d: &SimulatorDisplay<Rgb565>| {
                            (0..SIZE as i32)
                                .flat_map(|y| (0..SIZE as i32).map(move |x| Point::new(x, y)))
                                .map(|p| d.get_pixel(p))
                                .collect::<Vec<_>>()
                        };
                        let differ = px(&want)
                            .iter()
                            .zip(&px(&got))
                            .filter(|(a, b)| a != b)
                            .count();
                        let allowed = if view.algo() == Algo::Tiled { 8 } else { 0 };
                        assert!(differ <= allowed, "{view:?}: {differ} pixels differ");
                    }
                    view.apply(Action::NextMethod);
                    view.apply(Action::NextScene);
                }
            })
            .unwrap()
            .join()
            .unwrap();
    }

    #[test]
    fn the_status_line_shows_the_frames_exact_requirement_beside_the_board() {
        let view = View::default();
        let mut display = new_display();
        let frame = render(&mut Renderers::new(), &view, None, &mut display);
        let want =
            zrow_scenes::with_scene::<Q16_16, _>(view.scene_name(), view.angle, |s, c, _| {
                zrow::scanline::ram_bytes::<Q16_16>(&zrow::requirements(s, c).unwrap())
            })
            .unwrap();
        assert_eq!(frame.needs, Some(want));
        let [_, second] = status_text(&view, &frame, frame.time);
        let shown = format!("needs {:.1}K/128K", want as f64 / 1024.0);
        assert!(second.ends_with(&shown), "{second} vs {shown}");
    }

    #[test]
    fn the_first_frame_is_drawn_below_the_status_line() {
        let display = first_frame(true, None);
        let lit = (STATUS_ROWS as i32..SIZE as i32)
            .flat_map(|y| (0..SIZE as i32).map(move |x| Point::new(x, y)))
            .filter(|&p| display.get_pixel(p) != Rgb565::BLACK)
            .count();
        assert!(lit > 5_000, "only {lit} pixels drawn");
        let frame = Frame {
            time: Duration::from_micros(1234),
            result: Err("polygon table holds 2 but this scene needs 9".into()),
            needs: None,
        };
        let [_, second] = status_text(&View::default(), &frame, frame.time);
        assert!(second.starts_with("error: polygon table"), "{second}");
    }

    #[test]
    fn demo_arguments() {
        let os = |v: &[&str]| v.iter().map(OsString::from).collect::<Vec<_>>();
        assert!(is_demo(&os(&[])));
        assert!(is_demo(&os(&["--demo"])));
        assert!(is_demo(&os(&["--paused"])));
        assert!(is_demo(&os(&["--dump-expected=x.png"])));
        assert!(!is_demo(&os(&["render"])));
        assert!(is_demo(&os(&["--model", "a.obj"])));
        assert_eq!(
            parse_args(&os(&["--model", "a.obj"])).unwrap().model,
            Some(PathBuf::from("a.obj"))
        );
        let a = parse_args(&os(&["--paused", "--dump-expected", "e.png", "--frames=3"])).unwrap();
        assert_eq!(
            a,
            DemoArgs {
                paused: true,
                dump_expected: Some("e.png".into()),
                frames: Some(3),
                model: None,
                smooth: None,
            }
        );
        assert!(parse_args(&os(&["--frames", "x"])).is_err());
        assert!(parse_args(&os(&["--dump-expected"])).is_err());
    }

    #[test]
    fn a_model_is_the_first_scene_and_the_camera_orbits_it() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/models/torus.off");
        let model = crate::model::load(Path::new(path)).unwrap();
        let mut renderers = Renderers::new();
        let mut view = View {
            has_model: true,
            ..View::default()
        };
        assert_eq!(view.scene_name(), "model");
        let mut a = new_display();
        let first = render(&mut renderers, &view, Some(&model), &mut a);
        let polygons = first.result.unwrap().polygons;
        assert!(polygons > 10);
        view.angle = 1.0; // the camera moves round the model: another picture
        let mut b = new_display();
        render(&mut renderers, &view, Some(&model), &mut b)
            .result
            .unwrap();
        assert_ne!(a, b);
        // `n` goes on to the demos, and back round to the model.
        view.apply(Action::NextScene);
        assert_eq!(view.scene_name(), zrow_scenes::DEMOS[0]);
        for _ in 0..zrow_scenes::DEMOS.len() {
            view.apply(Action::NextScene);
        }
        assert!(view.shows_model());
    }

    /// `display` shows `model` at the demo's turn `angle` as `render-model` draws it (Q16.16,
    /// scan-line), pixel for pixel; returns that orbit view.
    fn shows_as_render_model(
        display: &SimulatorDisplay<Rgb565>,
        model: &LoadedModel,
        angle: f32,
    ) -> model_render::View {
        let orbit = model_render::View {
            yaw_deg: angle.to_degrees(),
            ..model_render::View::default()
        };
        let (side, q16) = (SIZE as u16, Format::Q16_16);
        let want = model_render::render_model_image(model, &orbit, side, side, Algo::Scanline, q16)
            .unwrap();
        for (k, &c) in want.pixels.iter().enumerate() {
            let p = Point::new((k % SIZE as usize) as i32, (k / SIZE as usize) as i32);
            assert_eq!(display.get_pixel(p), c, "pixel {p:?}");
        }
        orbit
    }

    /// `--model FILE --smooth DEG`: the window turns the torus smooth shaded — the frame
    /// `render-model --smooth` draws, not flat, not an error — and the status line counts the
    /// intensity planes in the RAM the frame needs.
    #[test]
    fn a_smoothed_model_turns_smooth_shaded() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/models/torus.off");
        let os = |v: &[&str]| v.iter().map(OsString::from).collect::<Vec<_>>();
        let a = parse_args(&os(&["--model", path, "--smooth=45"])).unwrap();
        assert_eq!(a.smooth, Some(45.0));
        assert!(parse_args(&os(&["--smooth", "200"])).is_err());
        let flat = crate::model::load(Path::new(path)).unwrap();
        let smooth = flat.smoothed(45.0);
        let view = View {
            has_model: true,
            angle: 0.5,
            ..View::default()
        };
        let (mut s, mut f) = (new_display(), new_display());
        let frame = render(&mut Renderers::new(), &view, Some(&smooth), &mut s);
        frame.result.as_ref().unwrap();
        render(&mut Renderers::new(), &view, Some(&flat), &mut f)
            .result
            .unwrap();
        assert_ne!(s, f, "smooth looks flat");
        let orbit = shows_as_render_model(&s, &smooth, 0.5);
        let side = SIZE as u16;
        let req = model_render::measure_model::<Q16_16>(&smooth, &orbit, side, side).unwrap();
        assert_eq!(
            frame.needs,
            Some(zrow::scanline::ram_bytes_gouraud::<Q16_16>(&req))
        );
    }

    /// A model whose view needs more than the window's fixed capacities is drawn by
    /// renderers sized to it: the frame the command line draws, not a capacity error.
    #[test]
    fn a_model_beyond_the_window_capacities_still_draws() {
        let model = crate::bands::tests::torus(80, 40);
        let view = View {
            has_model: true,
            ..View::default()
        };
        let mut display = new_display();
        let frame = render(&mut Renderers::new(), &view, Some(&model), &mut display);
        let stats = frame.result.unwrap();
        assert!(stats.polygons as usize > DEMO_POLYGONS, "{stats:?}");
        shows_as_render_model(&display, &model, 0.0);
    }
}
