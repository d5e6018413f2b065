//! The command line (GUIDE §2):
//!
//! ```text
//! zrow-sim render --screen SCENE.off --size 240x240 --algo scanline --out OUT.png
//! ```
//!
//! Flags may come in any order, as `--flag value` or `--flag=value`. `--screen` and `--out`
//! are required; `--size` defaults to 240x240 (the ST7789 panel), `--algo` to `scanline` and
//! `--format` to `q16.16`. A flag given twice, an unknown flag or a bad value is a usage error.

use crate::error::SimError;
use crate::render::{Algo, Format};
use std::ffi::OsString;
use std::path::PathBuf;

/// The help text (`zrow-sim --help`).
pub const USAGE: &str = "\
zrow-sim: render zrow scenes on the host

usage:
  zrow-sim render --screen SCENE.off --out OUT.png [--size WxH] [--algo NAME] [--format FMT]

  --screen FILE   OFF scene in screen space (x right, y down in pixels, z depth, smaller nearer)
  --out FILE      PNG to write (8-bit RGB, exactly WxH, background black)
  --size WxH      frame size, each side 1..=2048 (default 240x240)
  --algo NAME     hidden-surface method: scanline (default scanline)
  --format FMT    number format: q16.16 or f32 (default q16.16)

On bad input it prints one line `error: FILE:LINE: message` and exits non-zero.";

/// Largest frame side (zrow's largest viewport).
pub const MAX_SIDE: u16 = zrow::raster::MAX_VIEWPORT;

/// What to do.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Command {
    /// Print [`USAGE`].
    Help,
    /// Render a screen-space scene to a PNG.
    Render(RenderArgs),
}

/// The arguments of `render`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RenderArgs {
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

fn usage(msg: impl Into<String>) -> SimError {
    SimError::Usage(msg.into())
}

/// Parses `WxH` with each side in 1..=[`MAX_SIDE`].
pub fn parse_size(s: &str) -> Option<(u16, u16)> {
    let (w, h) = s.split_once(['x', 'X'])?;
    let side = |t: &str| t.parse::<u16>().ok().filter(|v| (1..=MAX_SIDE).contains(v));
    Some((side(w)?, side(h)?))
}

/// Parses the arguments after the program name.
pub fn parse_args(args: impl IntoIterator<Item = OsString>) -> Result<Command, SimError> {
    let mut args = args.into_iter();
    let Some(cmd) = args.next() else {
        return Err(usage("missing command: expected `render`"));
    };
    match cmd.to_str() {
        Some("render") => {}
        Some("-h" | "--help" | "help") => return Ok(Command::Help),
        Some(other) => {
            return Err(usage(format!(
                "unknown command `{}`: expected `render`",
                other.escape_debug()
            )))
        }
        None => return Err(usage("command is not valid UTF-8: expected `render`")),
    }

    let (mut screen, mut out, mut size, mut algo, mut format) = (None, None, None, None, None);
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
        if !matches!(
            flag,
            "--screen" | "--out" | "--size" | "--algo" | "--format"
        ) {
            return Err(usage(format!(
                "unknown argument `{}`: expected --screen, --out, --size, --algo or --format",
                flag.escape_debug()
            )));
        }
        let flag = flag.to_owned();
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
        let slot_taken = match flag.as_str() {
            "--screen" => screen.replace(PathBuf::from(&value)).is_some(),
            "--out" => out.replace(PathBuf::from(&value)).is_some(),
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
            _ => {
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
        };
        if slot_taken {
            return Err(usage(format!("{flag} given twice")));
        }
    }
    let screen = screen.ok_or_else(|| usage("render needs --screen SCENE.off"))?;
    let out = out.ok_or_else(|| usage("render needs --out OUT.png"))?;
    let (width, height) = size.unwrap_or((240, 240));
    Ok(Command::Render(RenderArgs {
        screen,
        out,
        width,
        height,
        algo: algo.unwrap_or(Algo::Scanline),
        format: format.unwrap_or_default(),
    }))
}

/// Runs `render`: reads and parses the scene, renders it, writes the PNG.
pub fn render(args: &RenderArgs) -> Result<(), SimError> {
    let name = args.screen.display().to_string();
    let data = std::fs::read(&args.screen).map_err(|source| SimError::Io {
        path: name.clone(),
        action: "read",
        source,
    })?;
    let scene = crate::off::parse(&name, &data)?;
    let image =
        crate::render::render_screen(&scene, args.width, args.height, args.algo, args.format)?;
    crate::png_io::write(&image, &args.out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Command, SimError> {
        parse_args(args.iter().map(OsString::from))
    }

    #[test]
    fn flags_in_any_order_with_defaults() {
        let want = RenderArgs {
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
        assert_eq!(parse(&a).unwrap(), Command::Render(want.clone()));
        let b = ["render", "--screen=a.off", "--out", "b.png"];
        let Command::Render(got) = parse(&b).unwrap() else {
            panic!()
        };
        assert_eq!((got.width, got.height), (240, 240));
        assert_eq!((got.algo, got.format), (Algo::Scanline, Format::Q16_16));
        assert_eq!(parse(&["--help"]).unwrap(), Command::Help);
    }

    #[test]
    fn usage_errors_say_what_is_accepted() {
        let cases: &[(&[&str], &str)] = &[
            (&[], "missing command"),
            (&["draw"], "unknown command `draw`"),
            (
                &["render", "--algo", "zbuffer"],
                "unknown --algo `zbuffer`: accepted names are scanline",
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
