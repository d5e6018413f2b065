//! The command line (the render command of `docs/conventions.md`):
//!
//! ```text
//! zrow-sim render --screen SCENE.off --size 240x240 --algo scanline --out OUT.png
//! ```
//!
//! and model mode (OBJ, STL or OFF, seen by a camera orbiting the origin,
//! [`crate::model_render`]):
//!
//! ```text
//! zrow-sim render-model --model FILE [--yaw DEG] [--pitch DEG] [--distance D] [--size WxH]
//!                       [--algo scanline] [--format q16.16|f32] [--smooth DEG]
//!                       [--dither] [--lines hidden|outline] --out OUT.png
//! ```
//!
//! and the converter (a model to const Rust data for flash, [`crate::convert`]):
//!
//! ```text
//! zrow-sim convert --model FILE --out FILE.rs [--format q16.16|f32] [--size WxH]
//!                  [--distance D] [--name NAME] [--checks N] [--strict] [--compact]
//!                  [--smooth DEG]
//! ```
//!
//! Flags may come in any order, as `--flag value` or `--flag=value` (`--strict` and
//! `--compact` take no value). `--screen` (`--model`) and
//! `--out` are required; `--size` defaults to 240x240 (the ST7789 panel), `--algo` to `scanline` and
//! `--format` to `q16.16`. A flag given twice, an unknown flag or a bad value is a usage error.

use crate::model_render::{Lines, View};
use crate::output::{print, Output};
use crate::render::{Algo, Format};
use crate::SimError;
use std::ffi::OsString;
use std::path::PathBuf;

/// The help text (`zrow-sim --help`).
pub const USAGE: &str = "\
zrow-sim: render zrow scenes on the host

usage:
  zrow-sim [--model FILE [--smooth DEG]] [--paused]
                      the window: turning demo scenes (and the model, first, smooth shaded
                      with --smooth)
                      keys: m method, f Q16.16/f32, space pause, s/Right step, n next scene,
                      c culling, q/Esc quit; without SDL or a display it writes zrow-demo.png
  zrow-sim render --screen SCENE.off --out OUT.png [--size WxH] [--algo NAME] [--format FMT]
  zrow-sim render-model --model FILE --out OUT.png [--yaw DEG] [--pitch DEG] [--distance D]
                        [--size WxH] [--algo NAME] [--format FMT] [--smooth DEG]
                        [--dither] [--lines hidden|outline]

  --screen FILE   OFF scene in screen space (x right, y down in pixels, z depth, smaller nearer)
  --out FILE      PNG to write (8-bit RGB, exactly WxH, background black)
  --size WxH      frame size, each side 1..=2048 (default 240x240)
  --algo NAME     hidden-surface method: scanline, zbuffer, tiled, depth-sort, warnock,
                  bsp, abuffer, or auto: the cheapest method exact for the scene
                  (cull-only, ordered or scanline; default scanline)
  --format FMT    number format: q16.16 or f32 (default q16.16)

  --model FILE    OBJ (with its MTL colours), STL (ASCII or binary) or OFF model; it is scaled
                  into the unit sphere at the origin, lit from the upper front right
  --yaw DEG       camera angle about the vertical axis, 0 = from the front (default 30)
  --pitch DEG     camera elevation, -89..=89 (default 20)
  --distance D    camera distance from the origin, 0 < D < 20 (default 3)
  --smooth DEG    smooth (Gouraud) shading: each vertex lit with its own normal (the OBJ's vn,
                  else averaged from the faces within DEG degrees, 0..=180; 45 keeps a cube's
                  edges sharp), the intensity interpolated across each face; default flat
  --dither        with --smooth: each channel dithered to Rgb565 by a 4x4 Bayer matrix, so
                  slow gradients do not band
  --lines KIND    hidden: a hidden-line drawing, the visible edges 1 px wide in black on
                  white; outline: the shaded model with its visible edges in white over it.
                  The diagonal inside a flat quad is not an edge; every method draws them

  zrow-sim convert --model FILE --out FILE.rs [--format FMT] [--size WxH] [--distance D]
                   [--name NAME] [--checks N] [--strict] [--compact] [--smooth DEG]
                  writes the model as const Rust data for flash (normalised positions in the
                  format, per-face normals, u8 or u16 indices, Rgb565 colours) with the
                  scan-line capacities measured over all orientations at that size and
                  distance, and prints the report (changes made, quantisation error, RAM)
  --name NAME     the model's name in the file (default: the model's file stem)
  --checks N      random extra orientations that check the sampled capacities (default 10000,
                  at most 1000000)
  --strict        refuse to split or triangulate faces, and non-manifold models: an error
  --compact       positions as 16-bit integers at 2^-14 (zrow::Vectors::Compact): 6 bytes
                  a vertex instead of 12, each coordinate within 2^-15 of the model's
  --smooth DEG    also one normal per vertex for smooth shading (VERTEX_NORMALS): the OBJ's
                  own (vn) when every face corner has one, else averaged from the faces, smooth
                  across edges whose faces are at most DEG degrees apart (0..=180; 45 keeps a
                  cube's edges sharp); a vertex that needs several normals is copied

Input files must be regular files of at most 256 MiB (a device, FIFO or directory is refused
before it is read). --out is checked before any work and replaced only once fully written.

On bad input it prints one line `error: FILE:LINE: message` and exits non-zero.";

/// Largest frame side (zrow's largest viewport).
pub const MAX_SIDE: u16 = zrow::raster::MAX_VIEWPORT;

/// What to do.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Print [`USAGE`].
    Help,
    /// Render to a PNG (`render`, `render-model`) or convert a model (`convert`): one
    /// variant, so a front end dispatches them all with [`render`].
    Render(RenderArgs),
}

/// What to render: the arguments of `render` or of `render-model`.
#[derive(Clone, Debug, PartialEq)]
pub enum RenderArgs {
    /// `render`: a screen-space scene.
    Screen(ScreenArgs),
    /// `render-model`: a model seen by the orbiting camera.
    Model(RenderModelArgs),
    /// `convert`: a model to const Rust data (writes a `.rs` file, not a PNG).
    Convert(ConvertArgs),
}

/// The arguments of `convert`.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvertArgs {
    /// The model file.
    pub model: PathBuf,
    /// The Rust file to write.
    pub out: PathBuf,
    /// Format, size, distance, name, strictness, views.
    pub options: crate::convert::ConvertOptions,
}

/// The arguments of `render`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScreenArgs {
    /// The OFF scene.
    pub screen: PathBuf,
    /// The PNG to write.
    pub out: PathBuf,
    /// Frame width in pixels.
    pub width: u16,
    /// Frame height in pixels.
    pub height: u16,
    /// The method.
    pub algo: Algo,
    /// The number format.
    pub format: Format,
}

/// The arguments of `render-model`.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderModelArgs {
    /// The model file (`.obj`, `.stl` or `.off`).
    pub model: PathBuf,
    /// The PNG to write.
    pub out: PathBuf,
    /// Frame width in pixels.
    pub width: u16,
    /// Frame height in pixels.
    pub height: u16,
    /// The method.
    pub algo: Algo,
    /// The number format.
    pub format: Format,
    /// Where the camera is.
    pub view: View,
    /// Smooth (Gouraud) shading with vertex normals within this crease angle in degrees
    /// (`--smooth DEG`), or flat.
    pub smooth: Option<f64>,
    /// Shaded, a hidden-line drawing or an outline drawing (`--lines hidden|outline`).
    pub lines: Lines,
    /// Smooth shading dithered (`--dither`, with `--smooth`).
    pub dither: bool,
}

fn usage(msg: impl Into<String>) -> SimError {
    SimError::Usage(msg.into())
}

/// Parses `WxH` with each side in 1..=[`MAX_SIDE`].
pub fn parse_size(s: &str) -> Option<(u16, u16)> {
    let (w, h) = s.split_once(['x', 'X'])?;
    let side = |t: &str| t.parse::<u16>().ok().filter(|v| (1..=MAX_SIDE).contains(v));
    Some((side(w)?, side(h)?))
}

/// The flags each command takes (as listed in messages).
const RENDER_FLAGS: &[&str] = &["--screen", "--out", "--size", "--algo", "--format"];
const RENDER_MODEL_FLAGS: &[&str] = &[
    "--model",
    "--out",
    "--size",
    "--algo",
    "--format",
    "--yaw",
    "--pitch",
    "--distance",
    "--smooth",
    "--lines",
    "--dither",
];

const CONVERT_FLAGS: &[&str] = &[
    "--model",
    "--out",
    "--format",
    "--size",
    "--distance",
    "--name",
    "--checks",
    "--strict",
    "--compact",
    "--smooth",
];

/// `a, b or c`.
fn or_list(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => (*one).to_owned(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// Parses the arguments after the program name.
pub fn parse_args(args: impl IntoIterator<Item = OsString>) -> Result<Command, SimError> {
    let mut args = args.into_iter();
    let expected = "expected `render`, `render-model` or `convert`";
    let Some(cmd) = args.next() else {
        return Err(usage(format!("missing command: {expected}")));
    };
    let (name, allowed) = match cmd.to_str() {
        Some("render") => ("render", RENDER_FLAGS),
        Some("render-model") => ("render-model", RENDER_MODEL_FLAGS),
        Some("convert") => ("convert", CONVERT_FLAGS),
        Some("-h" | "--help" | "help") => return Ok(Command::Help),
        Some(other) => {
            return Err(usage(format!(
                "unknown command `{}`: {expected}",
                other.escape_debug()
            )))
        }
        None => return Err(usage(format!("command is not valid UTF-8: {expected}"))),
    };

    let mut paths: Vec<(&str, PathBuf)> = Vec::new();
    let mut size = None;
    let mut algo = None;
    let mut format = None;
    let mut view = View::default();
    let mut angles: Vec<&str> = Vec::new();
    let mut strict = false;
    let mut compact = false;
    let mut name_flag = None;
    let mut checks = None;
    let mut smooth = None;
    let mut lines = None;
    let mut dither = false;
    while let Some(arg) = args.next() {
        let text = arg
            .to_str()
            .ok_or_else(|| usage("argument is not valid UTF-8: expected a flag"))?;
        if matches!(text, "-h" | "--help") {
            return Ok(Command::Help);
        }
        // `--flag=value` or `--flag value`.
        let (flag, value) = match text.split_once('=') {
            Some((flag, value)) if flag.starts_with("--") => (flag, Some(OsString::from(value))),
            _ => (text, None),
        };
        let Some(&flag) = allowed.iter().find(|&&f| f == flag) else {
            return Err(usage(format!(
                "unknown argument `{}`: expected {}",
                flag.escape_debug(),
                or_list(allowed)
            )));
        };
        if matches!(flag, "--strict" | "--compact" | "--dither") {
            if value.is_some() {
                return Err(usage(format!("{flag} takes no value")));
            }
            let set = match flag {
                "--strict" => &mut strict,
                "--compact" => &mut compact,
                _ => &mut dither,
            };
            if std::mem::replace(set, true) {
                return Err(usage(format!("{flag} given twice")));
            }
            continue;
        }
        let value = match value.or_else(|| args.next()) {
            Some(v) => v,
            None => return Err(usage(format!("{flag} needs a value"))),
        };
        let text_value = || {
            value
                .to_str()
                .map(str::to_owned)
                .ok_or_else(|| usage(format!("{flag} value is not valid UTF-8")))
        };
        let slot_taken = match flag {
            "--screen" | "--out" | "--model" => {
                let taken = paths.iter().any(|(f, _)| *f == flag);
                paths.push((flag, PathBuf::from(&value)));
                taken
            }
            "--size" => {
                let v = text_value()?;
                let parsed = parse_size(&v).ok_or_else(|| {
                    usage(format!(
                        "bad --size `{}`: expected WxH with each side 1..={MAX_SIDE}, e.g. 240x240",
                        v.escape_debug()
                    ))
                })?;
                size.replace(parsed).is_some()
            }
            "--algo" => {
                let v = text_value()?;
                let parsed = Algo::from_name(&v).ok_or_else(|| {
                    usage(format!(
                        "unknown --algo `{}`: accepted names are {}",
                        v.escape_debug(),
                        Algo::names()
                    ))
                })?;
                algo.replace(parsed).is_some()
            }
            "--format" => {
                let v = text_value()?;
                let parsed = Format::from_name(&v).ok_or_else(|| {
                    usage(format!(
                        "unknown --format `{}`: accepted names are {}",
                        v.escape_debug(),
                        Format::names()
                    ))
                })?;
                format.replace(parsed).is_some()
            }
            "--name" => name_flag.replace(text_value()?).is_some(),
            "--checks" => {
                let v = text_value()?;
                let parsed = v.parse::<usize>().ok().ok_or_else(|| {
                    usage(format!(
                        "bad --checks `{}`: expected a count",
                        v.escape_debug()
                    ))
                })?;
                checks.replace(parsed).is_some()
            }
            "--smooth" => {
                let v = text_value()?;
                let parsed = v
                    .parse::<f64>()
                    .ok()
                    .filter(|d| (0.0..=180.0).contains(d))
                    .ok_or_else(|| {
                        usage(format!(
                            "bad --smooth `{}`: expected a crease angle in degrees, 0..=180",
                            v.escape_debug()
                        ))
                    })?;
                smooth.replace(parsed).is_some()
            }
            "--lines" => {
                let v = text_value()?;
                let parsed = Lines::ALL
                    .iter()
                    .find(|(n, _)| *n == v)
                    .map(|&(_, l)| l)
                    .ok_or_else(|| {
                        usage(format!(
                            "unknown --lines `{}`: accepted names are hidden, outline",
                            v.escape_debug()
                        ))
                    })?;
                lines.replace(parsed).is_some()
            }
            _ => {
                // --yaw, --pitch, --distance
                let v = text_value()?;
                let parsed = v
                    .parse::<f32>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| {
                        usage(format!(
                            "bad {flag} `{}`: expected a number",
                            v.escape_debug()
                        ))
                    })?;
                match flag {
                    "--yaw" => view.yaw_deg = parsed,
                    "--pitch" => view.pitch_deg = parsed,
                    _ => view.distance = parsed,
                }
                let taken = angles.contains(&flag);
                angles.push(flag);
                taken
            }
        };
        if slot_taken {
            return Err(usage(format!("{flag} given twice")));
        }
    }
    let path = |flag: &str| {
        paths
            .iter()
            .find(|(f, _)| *f == flag)
            .map(|(_, p)| p.clone())
    };
    let out = path("--out");
    let (width, height) = size.unwrap_or((240, 240));
    let (algo, format) = (algo.unwrap_or(Algo::Scanline), format.unwrap_or_default());
    if name == "render" {
        let screen = path("--screen").ok_or_else(|| usage("render needs --screen SCENE.off"))?;
        let out = out.ok_or_else(|| usage("render needs --out OUT.png"))?;
        return Ok(Command::Render(RenderArgs::Screen(ScreenArgs {
            screen,
            out,
            width,
            height,
            algo,
            format,
        })));
    }
    if name == "convert" {
        let model = path("--model").ok_or_else(|| usage("convert needs --model FILE"))?;
        let out = out.ok_or_else(|| usage("convert needs --out FILE.rs"))?;
        let defaults = crate::convert::ConvertOptions::default();
        let stem = model
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let stem: String = stem
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let options = crate::convert::ConvertOptions {
            format,
            width,
            height,
            distance: view.distance,
            strict,
            compact,
            name: name_flag.unwrap_or(if stem.is_empty() {
                defaults.name.clone()
            } else {
                stem
            }),
            check_views: checks.unwrap_or(defaults.check_views),
            smooth,
            ..defaults
        };
        View {
            distance: options.distance,
            ..View::default()
        }
        .validate()
        .map_err(|m| usage(format!("bad view: {m}")))?;
        return Ok(Command::Render(RenderArgs::Convert(ConvertArgs {
            model,
            out,
            options,
        })));
    }
    let model = path("--model").ok_or_else(|| usage("render-model needs --model FILE"))?;
    let out = out.ok_or_else(|| usage("render-model needs --out OUT.png"))?;
    view.validate()
        .map_err(|m| usage(format!("bad view: {m}")))?;
    if dither && smooth.is_none() {
        return Err(usage(
            "--dither needs --smooth DEG (it dithers smooth shading)",
        ));
    }
    Ok(Command::Render(RenderArgs::Model(RenderModelArgs {
        model,
        out,
        width,
        height,
        algo,
        format,
        view,
        smooth,
        lines: lines.unwrap_or_default(),
        dither,
    })))
}

/// Runs `render`, `render-model` or `convert`.
pub fn render(args: &RenderArgs) -> Result<(), SimError> {
    match args {
        RenderArgs::Screen(a) => render_screen(a),
        RenderArgs::Model(a) => render_model(a),
        RenderArgs::Convert(a) => convert(a),
    }
}

/// Loads the model at `path` ([`crate::model::load`]) and prints its warnings on stderr.
pub(crate) fn load_model(path: &std::path::Path) -> Result<crate::model::LoadedModel, SimError> {
    let model = crate::model::load(path)?;
    for w in &model.warnings {
        eprintln!("warning: {w}");
    }
    Ok(model)
}

/// The converter's progress on stderr: a bar once a conversion has run for a second, and only
/// when stderr is a terminal (a log or a pipe gets nothing).
struct ProgressBar {
    start: std::time::Instant,
    terminal: bool,
    bar: std::sync::OnceLock<indicatif::ProgressBar>,
}

impl Default for ProgressBar {
    fn default() -> Self {
        use std::io::IsTerminal;
        ProgressBar {
            start: std::time::Instant::now(),
            terminal: std::io::stderr().is_terminal(),
            bar: std::sync::OnceLock::new(),
        }
    }
}

impl ProgressBar {
    fn update(&self, done: usize, total: usize) {
        if !self.terminal || self.start.elapsed() < std::time::Duration::from_secs(1) {
            return;
        }
        let bar = self.bar.get_or_init(|| {
            let bar = indicatif::ProgressBar::new(total as u64);
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "measuring views {bar:40} {pos}/{len} ({eta} left)",
            ) {
                bar.set_style(style);
            }
            bar
        });
        bar.set_position(done as u64);
    }

    fn finish(&self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }
}

/// Runs `convert`: loads and converts the model, writes the Rust file, prints the report and
/// the time the conversion took on stdout.
pub fn convert(args: &ConvertArgs) -> Result<(), SimError> {
    let out = Output::open(&args.out)?;
    let start = std::time::Instant::now();
    let model = load_model(&args.model)?;
    let bar = ProgressBar::default();
    let converted = crate::convert::convert_model_with(&model, &args.options, &|done, total| {
        bar.update(done, total)
    });
    bar.finish();
    let converted = converted?;
    let took = start.elapsed();
    out.write(converted.rust.as_bytes())?;
    print(&converted.report.to_string())?;
    print(&format!(
        "wrote {} ({} bytes of Rust) in {:.0} ms",
        args.out.display(),
        converted.rust.len(),
        took.as_secs_f64() * 1e3
    ))
}

/// Runs `render`: reads and parses the scene, renders it, writes the PNG.
pub fn render_screen(args: &ScreenArgs) -> Result<(), SimError> {
    let out = Output::open(&args.out)?;
    let name = args.screen.display().to_string();
    let data = crate::model::read_input(&args.screen)?;
    let scene = crate::off::parse(&name, &data)?;
    let image =
        crate::render::render_screen(&scene, args.width, args.height, args.algo, args.format)?;
    out.write(&crate::png_io::encode_for(&image, &args.out)?)
}

/// Runs `render-model`: loads the model, renders the view, writes the PNG.
pub fn render_model(args: &RenderModelArgs) -> Result<(), SimError> {
    let out = Output::open(&args.out)?;
    let mut model = load_model(&args.model)?;
    if let Some(crease) = args.smooth {
        model = model.smoothed(crease);
    }
    let image = crate::model_render::render_model_lines(
        &model,
        &args.view,
        (args.width, args.height),
        args.algo,
        args.format,
        crate::model_render::Style {
            lines: args.lines,
            dither: args.dither,
        },
    )?;
    out.write(&crate::png_io::encode_for(&image, &args.out)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Command, SimError> {
        parse_args(args.iter().map(OsString::from))
    }

    #[test]
    fn flags_in_any_order_with_defaults() {
        let want = ScreenArgs {
            screen: "a.off".into(),
            out: "b.png".into(),
            width: 320,
            height: 200,
            algo: Algo::Scanline,
            format: Format::F32,
        };
        let a = [
            "render",
            "--size",
            "320x200",
            "--out",
            "b.png",
            "--format=f32",
            "--screen",
            "a.off",
        ];
        assert_eq!(
            parse(&a).unwrap(),
            Command::Render(RenderArgs::Screen(want.clone()))
        );
        let b = ["render", "--screen=a.off", "--out", "b.png"];
        let Command::Render(RenderArgs::Screen(got)) = parse(&b).unwrap() else {
            panic!()
        };
        assert_eq!((got.width, got.height), (240, 240));
        assert_eq!((got.algo, got.format), (Algo::Scanline, Format::Q16_16));
        assert_eq!(parse(&["--help"]).unwrap(), Command::Help);
    }

    #[test]
    fn render_model_flags_and_defaults() {
        let a = [
            "render-model",
            "--out=m.png",
            "--yaw",
            "-45",
            "--model",
            "m.stl",
            "--format",
            "f32",
        ];
        let Command::Render(RenderArgs::Model(got)) = parse(&a).unwrap() else {
            panic!()
        };
        assert_eq!(got.model, PathBuf::from("m.stl"));
        assert_eq!(got.out, PathBuf::from("m.png"));
        assert_eq!((got.width, got.height, got.format), (240, 240, Format::F32));
        let want = View {
            yaw_deg: -45.0,
            ..View::default()
        };
        assert_eq!(got.view, want);
        assert_eq!(got.smooth, None);
        assert_eq!(got.lines, Lines::Off);
        let a = [
            "render-model",
            "--model=m.obj",
            "--out=m.png",
            "--smooth",
            "30",
            "--lines=outline",
        ];
        let Command::Render(RenderArgs::Model(got)) = parse(&a).unwrap() else {
            panic!()
        };
        assert_eq!(got.smooth, Some(30.0));
        assert_eq!(got.lines, Lines::Outline);
        assert!(!got.dither);
        let mut dithered = a.to_vec();
        dithered.push("--dither");
        let Command::Render(RenderArgs::Model(got)) = parse(&dithered).unwrap() else {
            panic!()
        };
        assert!(got.dither);
        let e = parse(&["render-model", "--model=m.obj", "--out=m.png", "--dither"])
            .unwrap_err()
            .to_string();
        assert!(e.contains("--dither needs --smooth DEG"), "{e}");
        let mut hidden = a;
        hidden[5] = "--lines=hidden";
        let Command::Render(RenderArgs::Model(got)) = parse(&hidden).unwrap() else {
            panic!()
        };
        assert_eq!(got.lines, Lines::Hidden);
        let mut bad = a;
        bad[5] = "--lines=dashed";
        let e = parse(&bad).unwrap_err().to_string();
        assert!(
            e.contains("unknown --lines `dashed`: accepted names are hidden, outline"),
            "{e}"
        );
    }

    #[test]
    fn convert_flags_and_defaults() {
        let a = [
            "convert",
            "--model",
            "dir/my model.obj",
            "--out=m.rs",
            "--strict",
            "--format",
            "f32",
            "--compact",
            "--distance",
            "4",
            "--smooth=30",
        ];
        let Command::Render(RenderArgs::Convert(got)) = parse(&a).unwrap() else {
            panic!()
        };
        assert_eq!(got.options.smooth, Some(30.0));
        assert_eq!(got.model, PathBuf::from("dir/my model.obj"));
        assert_eq!(got.out, PathBuf::from("m.rs"));
        let o = &got.options;
        assert_eq!(
            (o.name.as_str(), o.strict, o.compact, o.format),
            ("my_model", true, true, Format::F32)
        );
        assert_eq!(
            (o.width, o.height, o.distance, o.check_views),
            (240, 240, 4.0, 10_000)
        );
        let b = [
            "convert", "--model", "a.stl", "--out", "a.rs", "--name", "ico",
        ];
        let Command::Render(RenderArgs::Convert(got)) = parse(&b).unwrap() else {
            panic!()
        };
        assert_eq!(
            (
                got.options.name.as_str(),
                got.options.strict,
                got.options.compact
            ),
            ("ico", false, false)
        );
        for (args, want) in [
            (&["convert", "--out", "a.rs"][..], "convert needs --model"),
            (&["convert", "--model", "a.obj"][..], "convert needs --out"),
            (
                &["convert", "--strict", "--strict"][..],
                "--strict given twice",
            ),
            (
                &["convert", "--compact", "--compact"][..],
                "--compact given twice",
            ),
            (
                &["convert", "--compact=yes"][..],
                "--compact takes no value",
            ),
            (&["render", "--compact"][..], "unknown argument `--compact`"),
            (&["convert", "--checks", "many"][..], "bad --checks `many`"),
            (&["convert", "--smooth", "200"][..], "bad --smooth `200`"),
            (&["convert", "--smooth", "NaN"][..], "bad --smooth `NaN`"),
            (
                &["convert", "--smooth", "9", "--smooth", "9"][..],
                "--smooth given twice",
            ),
            (&["convert", "--yaw", "3"][..], "unknown argument `--yaw`"),
        ] {
            let e = parse(args).unwrap_err().to_string();
            assert!(e.contains(want), "{args:?}: {e}");
        }
    }

    #[test]
    fn usage_errors_say_what_is_accepted() {
        let cases: &[(&[&str], &str)] = &[
            (&[], "missing command"),
            (&["render", "--yaw", "3"], "unknown argument `--yaw`"),
            (
                &["render-model", "--screen", "a.off"],
                "unknown argument `--screen`",
            ),
            (
                &["render-model", "--out", "a.png"],
                "render-model needs --model",
            ),
            (
                &["render-model", "--model", "a.obj"],
                "render-model needs --out",
            ),
            (
                &[
                    "render-model",
                    "--model=a.obj",
                    "--out=b.png",
                    "--pitch",
                    "95",
                ],
                "bad view: pitch 95",
            ),
            (&["render-model", "--yaw", "north"], "bad --yaw `north`"),
            (
                &["render-model", "--smooth", "200"],
                "bad --smooth `200`: expected a crease angle in degrees, 0..=180",
            ),
            (
                &["render-model", "--distance", "1", "--distance", "2"],
                "--distance given twice",
            ),
            (&["draw"], "unknown command `draw`"),
            (
                &["render", "--algo", "painter"],
                "unknown --algo `painter`: accepted names are scanline, zbuffer",
            ),
            (
                &["render", "--format", "q8"],
                "accepted names are q16.16, f32",
            ),
            (&["render", "--size", "0x10"], "bad --size `0x10`"),
            (&["render", "--size", "2049x10"], "bad --size"),
            (&["render", "--size", "240"], "bad --size"),
            (&["render", "--size"], "--size needs a value"),
            (&["render", "--out", "a", "--out", "b"], "--out given twice"),
            (
                &["render", "--colour", "red"],
                "unknown argument `--colour`",
            ),
            (&["render", "--out", "a.png"], "render needs --screen"),
            (&["render", "--screen", "a.off"], "render needs --out"),
        ];
        for (args, want) in cases {
            let e = parse(args).unwrap_err();
            assert_eq!(e.exit_code(), 2);
            let msg = e.to_string();
            assert!(msg.contains(want), "{args:?}: {msg}");
            assert!(!msg.contains('\n'));
        }
        assert_eq!(parse_size("2048X1"), Some((2048, 1)));
    }
}
