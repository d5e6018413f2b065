//! The OFF scene parser (the scene-file contract in `docs/conventions.md`): Geomview's Object File Format with one colour per face.
//!
//! ```text
//! OFF                      # header (the counts may follow on the same line)
//! 3 1 0                    # vertex_count face_count edge_count (edge count ignored)
//! 0 0 6                    # one `x y z` per line
//! 180 0 0
//! 0 180 0
//! 3 0 1 2 255 0 0          # `n i0 .. i(n-1) [r g b [a]]`, colours 0..=255, default white
//! 3 0 1 2 0 0 255 128      # an optional fourth component: alpha, 0..=255, default 255 (opaque)
//! ```
//!
//! The format is read line by line, so every error can name its line: `#` starts a comment
//! anywhere on a line, blank lines are skipped, a vertex takes exactly one line and so does a
//! face. Every failure is an [`OffError`] that carries the file name and the 1-based line
//! number and prints as `scene.off:7: face has 2 vertices, need at least 3`. The parser never
//! panics, whatever the bytes.
//!
//! Coordinates are kept as `f32` (checked finite) with their line numbers, so converting them
//! to a renderer's number format ([`OffScene::vertices_in`]) can still blame the right line.

use core::fmt;
use zrow::pixelcolor::Rgb565;
use zrow::raster::MAX_FACE_VERTICES;
use zrow::{Scalar, Vec3};

/// Most vertices a file may declare: faces index them with 32 bits ([`zrow::MeshIndex`] for
/// `u32`). Files that large are refused long before, by their size ([`crate::model::MAX_FILE_BYTES`]).
pub const MAX_VERTICES: usize = u32::MAX as usize + 1;

/// One vertex as read: its position and the line it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OffVertex {
    /// `x y z`, all finite.
    pub position: [f32; 3],
    /// 1-based line number.
    pub line: usize,
}

/// One face as read: vertex indices (each checked against the vertex count), its colour, its
/// opacity and its line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OffFace {
    /// Vertex indices, 3..=[`MAX_FACE_VERTICES`] of them.
    pub indices: Vec<u32>,
    /// 8-bit RGB colour (white when the file gives none).
    pub color: [u8; 3],
    /// Opacity, the colour's optional fourth component: 0 = invisible, 255 = opaque (the
    /// default, also when the file gives no colour). For [`zrow::Face::alpha`].
    pub alpha: u8,
    /// 1-based line number.
    pub line: usize,
}

impl OffFace {
    /// The face colour in Rgb565, rounded to nearest: `r5 = (r·31 + 127) / 255`, likewise
    /// `g6` with 63 and `b5` with 31.
    pub fn rgb565(&self) -> Rgb565 {
        rgb8_to_rgb565(self.color)
    }
}

/// 8-bit RGB to Rgb565, rounding to nearest.
pub fn rgb8_to_rgb565([r, g, b]: [u8; 3]) -> Rgb565 {
    let scale = |c: u8, max: u32| ((c as u32 * max + 127) / 255) as u8;
    Rgb565::new(scale(r, 31), scale(g, 63), scale(b, 31))
}

/// A parsed OFF file.
#[derive(Clone, Debug, PartialEq)]
pub struct OffScene {
    /// The file name used in error messages (as given by the user).
    pub file: String,
    /// Vertices in file order.
    pub vertices: Vec<OffVertex>,
    /// Faces in file order (the scene order that breaks depth ties).
    pub faces: Vec<OffFace>,
}

impl OffScene {
    /// The vertices in number format `N`, or an error on the line of the first vertex that
    /// does not fit it (Q16.16 holds −32768 ≤ v < 32768).
    pub fn vertices_in<N: Scalar>(&self) -> Result<Vec<Vec3<N>>, OffError> {
        self.vertices
            .iter()
            .map(|v| {
                Vec3::<N>::from_f32(v.position).ok_or_else(|| {
                    // Name the first coordinate that does not fit.
                    let (axis, value) = ["x", "y", "z"]
                        .into_iter()
                        .zip(v.position)
                        .find(|&(_, c)| N::from_f32(c).is_none())
                        .unwrap_or(("x", v.position[0]));
                    OffError {
                        file: self.file.clone(),
                        line: v.line,
                        kind: OffErrorKind::DoesNotFit {
                            axis,
                            value,
                            format: N::NAME,
                        },
                    }
                })
            })
            .collect()
    }

    /// The line of face number `face` (0-based, as zrow's errors count), if there is one.
    pub fn face_line(&self, face: u32) -> Option<usize> {
        self.faces.get(face as usize).map(|f| f.line)
    }
}

/// A parse error: where, and what.
#[derive(Clone, Debug, PartialEq)]
pub struct OffError {
    /// File name, as given.
    pub file: String,
    /// 1-based line number (for an early end of file, the file's last line).
    pub line: usize,
    /// What is wrong.
    pub kind: OffErrorKind,
}

impl fmt::Display for OffError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.kind)
    }
}

impl std::error::Error for OffError {}

/// What is wrong with an OFF file. Each message says what was expected.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum OffErrorKind {
    /// The first line that is not blank or a comment does not start with `OFF`.
    MissingHeader {
        /// What was there instead (`None`: the file has no content at all).
        found: Option<String>,
    },
    /// The counts line is not three non-negative integers.
    BadCounts {
        /// Why.
        reason: String,
    },
    /// More vertices than 32-bit indices can reach.
    TooManyVertices {
        /// The declared count.
        count: u64,
    },
    /// The file ended before every declared vertex and face was read.
    UnexpectedEof {
        /// What was still expected, e.g. `vertex 3 of 8`.
        expected: String,
    },
    /// A value that should be a number is not one.
    NotANumber {
        /// What the value was for, e.g. `vertex y`.
        what: &'static str,
        /// The offending text.
        token: String,
    },
    /// A coordinate is NaN or infinite (or too large for `f32`).
    NotFinite {
        /// Which coordinate.
        axis: &'static str,
        /// The offending text.
        token: String,
    },
    /// A coordinate is finite but outside the chosen number format.
    DoesNotFit {
        /// Which coordinate.
        axis: &'static str,
        /// Its value.
        value: f32,
        /// The format's name (`q16.16`, `f32`).
        format: &'static str,
    },
    /// A vertex line does not hold exactly three coordinates.
    VertexArity {
        /// How many values it holds.
        found: usize,
    },
    /// A face declares fewer vertices than a polygon needs.
    TooFewFaceVertices {
        /// The declared count.
        n: u64,
    },
    /// A face declares more vertices than zrow accepts.
    TooManyFaceVertices {
        /// The declared count.
        n: u64,
    },
    /// A face lists fewer indices than it declares.
    MissingIndices {
        /// Declared.
        n: usize,
        /// Listed.
        found: usize,
    },
    /// A face refers to a vertex the file does not have.
    IndexOutOfRange {
        /// The index.
        index: u64,
        /// The file's vertex count.
        count: usize,
    },
    /// The values after a face's indices are neither `r g b` nor `r g b a`.
    ColorArity {
        /// How many values there are.
        found: usize,
    },
    /// A colour component is not an integer in 0..=255.
    BadColor {
        /// The offending text.
        token: String,
    },
    /// The alpha (fourth colour component) is not an integer in 0..=255.
    BadAlpha {
        /// The offending text.
        token: String,
    },
    /// Something follows the last face.
    TrailingContent,
    /// The line (outside its comment) is not UTF-8.
    NotUtf8,
}

impl fmt::Display for OffErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use OffErrorKind::*;
        match self {
            MissingHeader { found: None } => write!(f, "empty file: expected header `OFF`"),
            MissingHeader { found: Some(t) } => {
                write!(f, "expected header `OFF`, found `{}`", shown(t))
            }
            BadCounts { reason } => write!(
                f,
                "bad counts line: {reason} (expected `vertex_count face_count edge_count`)"
            ),
            TooManyVertices { count } => write!(
                f,
                "{count} vertices declared, at most {MAX_VERTICES} supported (32-bit indices)"
            ),
            UnexpectedEof { expected } => {
                write!(f, "unexpected end of file: expected {expected}")
            }
            NotANumber { what, token } => write!(f, "{what} `{}` is not a number", shown(token)),
            NotFinite { axis, token } => write!(
                f,
                "vertex {axis} `{}` is not finite (or too large for f32)",
                shown(token)
            ),
            DoesNotFit {
                axis,
                value,
                format,
            } => write!(
                f,
                "vertex {axis} = {value} does not fit the {format} number format"
            ),
            VertexArity { found } => {
                write!(
                    f,
                    "vertex needs 3 coordinates `x y z`, found {found} values"
                )
            }
            TooFewFaceVertices { n } => write!(f, "face has {n} vertices, need at least 3"),
            TooManyFaceVertices { n } => write!(
                f,
                "face has {n} vertices, at most {MAX_FACE_VERTICES} supported (split it)"
            ),
            MissingIndices { n, found } => {
                write!(f, "face declares {n} vertices but lists {found} indices")
            }
            IndexOutOfRange { index, count } => write!(
                f,
                "vertex index {index} out of range (the file has {count} vertices)"
            ),
            ColorArity { found } => write!(
                f,
                "face colour must be `r g b` or `r g b a`, found {found} values after the indices"
            ),
            BadColor { token } => write!(
                f,
                "colour value `{}` is not an integer in 0..=255",
                shown(token)
            ),
            BadAlpha { token } => write!(
                f,
                "alpha value `{}` is not an integer in 0..=255 (255 = opaque)",
                shown(token)
            ),
            TrailingContent => write!(f, "unexpected content after the last face"),
            NotUtf8 => write!(f, "line is not valid UTF-8"),
        }
    }
}

/// A token as quoted in a message: control characters escaped (so the message stays on one
/// line) and cut to 32 characters.
pub(crate) fn shown(token: &str) -> String {
    let mut s: String = token
        .chars()
        .take(32)
        .flat_map(char::escape_debug)
        .collect();
    if token.chars().count() > 32 {
        s.push('…');
    }
    s
}

/// The content lines of a file: comments and blank lines removed, each with its number.
struct Lines<'a> {
    /// What is left of the file.
    rest: &'a [u8],
    /// Number of the line `rest` starts on.
    number: usize,
    /// Number of the last line of the file (for an early end of file).
    last: usize,
}

impl<'a> Lines<'a> {
    fn new(data: &'a [u8]) -> Self {
        let data = data.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(data); // UTF-8 byte order mark
        let newlines = data.iter().filter(|&&b| b == b'\n').count();
        // A final line without a newline still counts.
        let last = newlines + usize::from(!data.is_empty() && !data.ends_with(b"\n"));
        Lines {
            rest: data,
            number: 1,
            last: last.max(1),
        }
    }

    /// The next line with content: its number and its tokens (`Err`: the number of a line
    /// that is not UTF-8).
    fn next(&mut self) -> Result<Option<(usize, Vec<&'a str>)>, usize> {
        while !self.rest.is_empty() {
            let (raw, rest) = match self.rest.iter().position(|&b| b == b'\n') {
                Some(i) => (&self.rest[..i], &self.rest[i + 1..]),
                None => (self.rest, &[][..]),
            };
            let number = self.number;
            self.rest = rest;
            self.number += 1;
            // `#` is ASCII, so cutting bytes there keeps a UTF-8 line UTF-8; comments may hold
            // any bytes.
            let text = raw.split(|&b| b == b'#').next().unwrap_or(raw);
            let text = std::str::from_utf8(text).map_err(|_| number)?;
            let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
            if !tokens.is_empty() {
                return Ok(Some((number, tokens)));
            }
        }
        Ok(None)
    }
}

/// Parses an OFF file. `file` names it in errors.
pub fn parse(file: &str, data: &[u8]) -> Result<OffScene, OffError> {
    let err = |line: usize, kind| OffError {
        file: file.to_owned(),
        line,
        kind,
    };
    let mut lines = Lines::new(data);
    let last = lines.last;

    // Header, and the counts (on the same line or the next).
    let (line, tokens) = match lines.next() {
        Ok(Some(l)) => l,
        Ok(None) => return Err(err(1, OffErrorKind::MissingHeader { found: None })),
        Err(line) => return Err(err(line, OffErrorKind::NotUtf8)),
    };
    if tokens[0] != "OFF" {
        let found = Some(tokens[0].to_owned());
        return Err(err(line, OffErrorKind::MissingHeader { found }));
    }
    let mut next = |expected: &dyn Fn() -> String| match lines.next() {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err(err(
            last,
            OffErrorKind::UnexpectedEof {
                expected: expected(),
            },
        )),
        Err(line) => Err(err(line, OffErrorKind::NotUtf8)),
    };
    let (line, counts) = if tokens.len() > 1 {
        (line, tokens[1..].to_vec())
    } else {
        next(&|| "the counts line `vertex_count face_count edge_count`".into())?
    };
    let (nv, nf) = parse_counts(&counts).map_err(|kind| err(line, kind))?;

    let mut vertices = Vec::with_capacity(nv.min(4096));
    for k in 0..nv {
        let (line, tokens) = next(&|| format!("vertex {} of {nv}", k + 1))?;
        let position = parse_vertex(&tokens).map_err(|kind| err(line, kind))?;
        vertices.push(OffVertex { position, line });
    }

    let mut faces = Vec::with_capacity(nf.min(4096));
    for k in 0..nf {
        let (line, tokens) = next(&|| format!("face {} of {nf}", k + 1))?;
        let (indices, color, alpha) = parse_face(&tokens, nv).map_err(|kind| err(line, kind))?;
        faces.push(OffFace {
            indices,
            color,
            alpha,
            line,
        });
    }

    match lines.next() {
        Ok(None) => Ok(OffScene {
            file: file.to_owned(),
            vertices,
            faces,
        }),
        Ok(Some((line, _))) => Err(err(line, OffErrorKind::TrailingContent)),
        Err(line) => Err(err(line, OffErrorKind::NotUtf8)),
    }
}

fn parse_counts(tokens: &[&str]) -> Result<(usize, usize), OffErrorKind> {
    let bad = |reason: String| OffErrorKind::BadCounts { reason };
    if tokens.len() != 3 {
        return Err(bad(format!("found {} values", tokens.len())));
    }
    let mut n = [0u64; 3];
    for (slot, (name, t)) in n.iter_mut().zip(
        ["vertex count", "face count", "edge count"]
            .iter()
            .zip(tokens),
    ) {
        *slot = t.parse().map_err(|_| {
            bad(format!(
                "{name} `{}` is not a non-negative integer",
                shown(t)
            ))
        })?;
    }
    if n[0] > MAX_VERTICES as u64 {
        return Err(OffErrorKind::TooManyVertices { count: n[0] });
    }
    let faces = usize::try_from(n[1])
        .ok()
        .filter(|&f| f <= u32::MAX as usize)
        .ok_or_else(|| bad(format!("face count {} is too large", n[1])))?;
    Ok((n[0] as usize, faces))
}

fn parse_vertex(tokens: &[&str]) -> Result<[f32; 3], OffErrorKind> {
    if tokens.len() != 3 {
        return Err(OffErrorKind::VertexArity {
            found: tokens.len(),
        });
    }
    let mut p = [0f32; 3];
    for ((slot, axis), t) in p.iter_mut().zip(["x", "y", "z"]).zip(tokens) {
        let v: f32 = t.parse().map_err(|_| OffErrorKind::NotANumber {
            what: match axis {
                "x" => "vertex x",
                "y" => "vertex y",
                _ => "vertex z",
            },
            token: (*t).to_owned(),
        })?;
        if !v.is_finite() {
            return Err(OffErrorKind::NotFinite {
                axis,
                token: (*t).to_owned(),
            });
        }
        *slot = v;
    }
    Ok(p)
}

/// A face line: its indices, its colour and its alpha (255 when not given).
fn parse_face(tokens: &[&str], nv: usize) -> Result<(Vec<u32>, [u8; 3], u8), OffErrorKind> {
    let integer = |what: &'static str, t: &str| {
        t.parse::<u64>().map_err(|_| OffErrorKind::NotANumber {
            what,
            token: t.to_owned(),
        })
    };
    let n = integer("face vertex count", tokens[0])?;
    if n < 3 {
        return Err(OffErrorKind::TooFewFaceVertices { n });
    }
    if n > MAX_FACE_VERTICES as u64 {
        return Err(OffErrorKind::TooManyFaceVertices { n });
    }
    let n = n as usize;
    let rest = &tokens[1..];
    if rest.len() < n {
        return Err(OffErrorKind::MissingIndices {
            n,
            found: rest.len(),
        });
    }
    let mut indices = Vec::with_capacity(n);
    for t in &rest[..n] {
        let index = integer("vertex index", t)?;
        if index >= nv as u64 {
            return Err(OffErrorKind::IndexOutOfRange { index, count: nv });
        }
        indices.push(index as u32); // < nv <= MAX_VERTICES, so it fits
    }
    let color = &rest[n..];
    let (rgb, alpha) = match color.len() {
        0 => ([255; 3], 255),
        3 | 4 => {
            let mut c = [0u8; 3];
            for (slot, t) in c.iter_mut().zip(color) {
                *slot = t.parse().map_err(|_| OffErrorKind::BadColor {
                    token: (*t).to_owned(),
                })?;
            }
            let alpha = match color.get(3) {
                None => 255,
                Some(t) => t.parse().map_err(|_| OffErrorKind::BadAlpha {
                    token: (*t).to_owned(),
                })?,
            };
            (c, alpha)
        }
        found => return Err(OffErrorKind::ColorArity { found }),
    };
    Ok((indices, rgb, alpha))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ok(text: &str) -> OffScene {
        parse("t.off", text.as_bytes()).unwrap_or_else(|e| panic!("{e}"))
    }

    fn fails(text: &str) -> String {
        match parse("t.off", text.as_bytes()) {
            Ok(s) => panic!("parsed: {s:?}"),
            Err(e) => e.to_string(),
        }
    }

    const TRIANGLE: &str = "OFF\n3 1 0\n0 0 1\n10 0 1\n0 10 1\n3 0 1 2 255 0 0\n";

    #[test]
    fn reads_a_triangle() {
        let s = ok(TRIANGLE);
        assert_eq!(s.vertices.len(), 3);
        assert_eq!(s.vertices[1].position, [10.0, 0.0, 1.0]);
        assert_eq!(s.vertices[1].line, 4);
        assert_eq!(s.faces[0].indices, [0, 1, 2]);
        assert_eq!(s.faces[0].color, [255, 0, 0]);
        assert_eq!(s.faces[0].line, 6);
    }

    #[test]
    fn comments_blank_lines_header_with_counts_alpha_and_default_colour() {
        let s = ok("# a scene\n\nOFF 4 2 0 # counts here\r\n\
                    0 0 0\n1 0 0 # trailing comment\n  \n0 1 0\n1 1 0\n\
                    3 0 1 2 # white\n3 1 3 2 10 20 30 40\n# end\n");
        assert_eq!(s.faces[0].color, [255, 255, 255]);
        assert_eq!(s.faces[0].alpha, 255);
        assert_eq!(s.faces[1].color, [10, 20, 30]);
        assert_eq!(s.faces[1].alpha, 40);
        assert_eq!(s.faces[1].line, 10);
    }

    #[test]
    fn alpha_is_the_optional_fourth_component_and_defaults_to_opaque() {
        let face = |colour: &str| {
            let s = ok(&format!(
                "OFF\n3 1 0\n0 0 1\n10 0 1\n0 10 1\n3 0 1 2{colour}\n"
            ));
            let f = &s.faces[0];
            (f.color, f.alpha)
        };
        assert_eq!(face(""), ([255; 3], 255));
        assert_eq!(face(" 255 0 0"), ([255, 0, 0], 255));
        assert_eq!(face(" 0 0 255 128"), ([0, 0, 255], 128));
        assert_eq!(face(" 1 2 3 0"), ([1, 2, 3], 0));
        assert_eq!(face(" 1 2 3 255 # opaque"), ([1, 2, 3], 255));
        assert_eq!(face(" 1 2 3 007"), ([1, 2, 3], 7));
    }

    #[test]
    fn colour_rounds_to_nearest_rgb565() {
        use zrow::pixelcolor::RgbColor;
        let c = rgb8_to_rgb565([255, 128, 4]);
        assert_eq!((c.r(), c.g(), c.b()), (31, 32, 0));
        assert_eq!(rgb8_to_rgb565([0, 0, 0]), Rgb565::BLACK);
        assert_eq!(rgb8_to_rgb565([255; 3]), Rgb565::WHITE);
    }

    #[test]
    fn every_error_names_file_and_line() {
        let cases: &[(&str, &str)] = &[
            ("", "t.off:1: empty file: expected header `OFF`"),
            ("# only a comment\n", "t.off:1: empty file"),
            ("\nCOFF\n", "t.off:2: expected header `OFF`, found `COFF`"),
            ("OFF\n3 1\n", "t.off:2: bad counts line: found 2 values"),
            ("OFF\n3 x 0\n", "t.off:2: bad counts line: face count `x`"),
            (
                "OFF\n-3 1 0\n",
                "t.off:2: bad counts line: vertex count `-3`",
            ),
            (
                "OFF\n4294967297 1 0\n",
                "t.off:2: 4294967297 vertices declared",
            ),
            (
                "OFF\n",
                "t.off:1: unexpected end of file: expected the counts",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n\n# x\n",
                "t.off:6: unexpected end of file: expected vertex 3 of 3",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0",
                "t.off:5: unexpected end of file: expected face 1 of 1",
            ),
            (
                "OFF\n1 0 0\n0 zero 0\n",
                "t.off:3: vertex y `zero` is not a number",
            ),
            (
                "OFF\n1 0 0\n0 0 nan\n",
                "t.off:3: vertex z `nan` is not finite",
            ),
            (
                "OFF\n1 0 0\n0 1e39 0\n",
                "t.off:3: vertex y `1e39` is not finite",
            ),
            ("OFF\n1 0 0\n0 0\n", "t.off:3: vertex needs 3 coordinates"),
            (
                "OFF\n1 0 0\n0 0 0 1\n",
                "t.off:3: vertex needs 3 coordinates",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                "t.off:6: vertex index 3 out of range (the file has 3 vertices)",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
                "t.off:6: vertex index `-1` is not a number",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                "t.off:6: face has 2 vertices, need at least 3",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n11 0 1 2 0 1 2 0 1 2 0 1\n",
                "t.off:6: face has 11 vertices, at most 10 supported",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
                "t.off:6: face declares 4 vertices but lists 3 indices",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 256 0 0\n",
                "t.off:6: colour value `256` is not an integer in 0..=255",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5 0 0\n",
                "t.off:6: colour value `0.5`",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0 0\n",
                "t.off:6: face colour must be `r g b` or `r g b a`, found 2 values",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0 0 0 0 0\n",
                "t.off:6: face colour must be `r g b` or `r g b a`, found 5 values",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0 0 0 256\n",
                "t.off:6: alpha value `256` is not an integer in 0..=255 (255 = opaque)",
            ),
            (
                "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2 9 9 9 0.5\n",
                "t.off:7: alpha value `0.5` is not an integer in 0..=255",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0 0 0 -1\n",
                "t.off:6: alpha value `-1` is not an integer",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0 0 0 opaque\n",
                "t.off:6: alpha value `opaque` is not an integer",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0 300 0 128\n",
                "t.off:6: colour value `300` is not an integer in 0..=255",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
                "t.off:7: unexpected content after the last face",
            ),
            (
                "OFF\n1 0 0\n0 \u{1}x 0\n",
                "t.off:3: vertex y `\\u{1}x` is not a number",
            ),
        ];
        for (text, want) in cases {
            let got = fails(text);
            assert!(got.starts_with(want), "{text:?}\n got: {got}\nwant: {want}");
            assert!(!got.contains('\n'), "{got:?} spans lines");
        }
    }

    #[test]
    fn non_utf8_is_an_error_outside_comments_only() {
        let mut text = b"OFF # caf\xE9\n0 0 0\n".to_vec();
        assert!(parse("t.off", &text).is_ok());
        text.extend_from_slice(b"\xFF\n");
        let e = parse("t.off", &text).unwrap_err();
        assert_eq!(e.to_string(), "t.off:3: line is not valid UTF-8");
    }

    #[test]
    fn coordinates_that_do_not_fit_the_format_name_their_line() {
        let s = ok("OFF\n2 0 0\n0 0 0\n1 40000 0\n");
        assert!(s.vertices_in::<f32>().is_ok());
        let e = s.vertices_in::<zrow::Q16_16>().unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.off:4: vertex y = 40000 does not fit the q16.16 number format"
        );
        assert_eq!(s.face_line(0), None);
    }
}
