//! Model files for model mode: OBJ (through `tobj`), STL (through `stl_io`, ASCII and binary)
//! and OFF (through [`crate::off`]), loaded into one [`LoadedModel`].
//!
//! - **OBJ**: polygons are kept as they are (zrow draws convex polygons; one with more than
//!   [`MAX_FACE_VERTICES`] vertices is split into a fan). A face takes the diffuse colour
//!   (`Kd`) of its material when the MTL file its `mtllib` line names gives one, else
//!   [`DEFAULT_RGB`]. A missing, unreadable or malformed MTL file is not an error: the faces
//!   are drawn in the default colour and [`LoadedModel::warnings`] says which file and why.
//!   Normals (`vn`) are kept per face corner when every corner has one (else a warning says
//!   where one is missing): [`LoadedModel::vertex_normals`] then uses them for smooth shading
//!   instead of computing them from the faces.
//! - **STL**: every triangle in [`DEFAULT_RGB`]. Binary and ASCII are told apart by the size
//!   the binary header promises, so a binary file whose header happens to start with `solid`
//!   still loads.
//! - **OFF** (the scene-file contract, `docs/conventions.md`): face colours kept (white where a face has none).
//!
//! **Normalised**: in `f32` (computed in `f64`), before any conversion to a renderer's number
//! format, the model is centred on the centre of its bounding box and scaled so that the box's
//! half-diagonal is 1: every vertex lies inside the unit sphere at the origin, and a box-shaped
//! model touches it at its corners. (The half-diagonal is `√3/2 ·` the largest extent for a
//! cube and less for a flat model, which is thus not drawn needlessly small.) A model of any
//! size, millimetres or kilometres, thus needs the same camera, and fits Q16.16 with room to
//! spare.
//!
//! **Input limits**: [`load`] reads only regular files of at most [`MAX_FILE_BYTES`] bytes, and
//! refuses anything else before reading a byte ([`read_input`]): a device such as `/dev/zero`,
//! a FIFO, a socket or a directory could never end or block forever, and a larger file would
//! need gigabytes of memory. The same holds for the MTL files an OBJ names. Within the limit,
//! loading and drawing take time and memory in proportion to the file.
//!
//! **Errors**: every malformed file is a [`ModelError`] naming the file and where: the line
//! (`FILE:LINE: message`) for the text formats, the triangle and its byte offset for binary STL.
//! `tobj`'s and `stl_io`'s own errors carry no position, so each text file is first checked
//! line by line here (OBJ: `v` holds 3 finite numbers, `f` at least 3 indices that are 1-based
//! or negative and refer to vertices already defined; ASCII STL: the `facet` / `outer loop` /
//! `vertex` ×3 / `endloop` / `endfacet` structure). Nothing in here panics, whatever the bytes.

use crate::error::Error;
use crate::off::shown;
use crate::off::{self, rgb8_to_rgb565};
use crate::vertex_normals::{self, VertexNormals};
use core::fmt;
use std::cell::RefCell;
use std::collections::HashMap;
use std::io::{self, Read};
use std::path::Path;
use zrow::pixelcolor::Rgb565;
use zrow::raster::MAX_FACE_VERTICES;
use zrow::{Face, Mesh, Scalar, Vec3, Vectors};

/// The colour of faces the file gives none for (STL, OBJ without material), 8-bit RGB.
pub const DEFAULT_RGB: [u8; 3] = [200, 200, 200];

/// Most vertices a model may have: its faces index them with 32 bits ([`zrow::MeshIndex`] for
/// `u32`; the converter, for the firmware, narrows them to `u8` or `u16`).
pub const MAX_VERTICES: usize = off::MAX_VERTICES;

/// Largest file [`load`] (and the `zrow-sim` commands) read: 256 MiB. That is about seven
/// million triangles in OFF; memory while drawing grows with the file, about nine times its size
/// (`bash scripts/host-scale.sh` measures it by model size).
pub const MAX_FILE_BYTES: u64 = 256 << 20;

/// Reads an input file whole, after checking that it is a regular file of at most
/// [`MAX_FILE_BYTES`] bytes. A directory, device, FIFO or socket is refused before it is opened,
/// and a file that grows past the limit while being read is refused too: reading never blocks on
/// a pipe nor runs without end.
///
/// ```
/// use zrow_model::model::read_input;
/// let err = read_input(std::path::Path::new("/dev/zero")).unwrap_err();
/// assert!(err.to_string().contains("not a regular file"), "{err}");
/// ```
pub fn read_input(path: &Path) -> Result<Vec<u8>, Error> {
    let io_error = |source: io::Error| Error::Io {
        path: path.display().to_string(),
        action: "read",
        source,
    };
    let refuse = |why: String| io_error(io::Error::new(io::ErrorKind::InvalidInput, why));
    let check = |meta: &std::fs::Metadata| {
        if !meta.is_file() {
            return Err(refuse(
                "not a regular file (a directory, device, pipe or socket is never read)".into(),
            ));
        }
        if meta.len() > MAX_FILE_BYTES {
            return Err(refuse(format!(
                "{} bytes, more than the {MAX_FILE_BYTES} bytes an input file may have",
                meta.len()
            )));
        }
        Ok(meta.len())
    };
    check(&std::fs::metadata(path).map_err(io_error)?)?;
    let file = std::fs::File::open(path).map_err(io_error)?;
    let len = check(&file.metadata().map_err(io_error)?)?;
    let mut data = Vec::with_capacity(len as usize);
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut data)
        .map_err(io_error)?;
    if data.len() as u64 > MAX_FILE_BYTES {
        return Err(refuse(format!(
            "grew past the {MAX_FILE_BYTES} bytes an input file may have while being read"
        )));
    }
    Ok(data)
}

/// Where in its file a vertex or face came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// A 1-based line of a text file.
    Line(usize),
    /// A triangle of a binary STL file: its 0-based number and the byte offset it starts at.
    Triangle {
        /// 0-based triangle number.
        index: usize,
        /// Byte offset of its 50-byte record.
        offset: u64,
    },
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::Line(line) => write!(f, "{line}"),
            Origin::Triangle { index, offset } => {
                write!(f, "triangle {index} (byte offset {offset})")
            }
        }
    }
}

/// A malformed or unusable model file: which file, where, what.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModelError {
    /// The file name, as given.
    pub file: String,
    /// Where in the file (`None`: the whole file is to blame).
    pub at: Option<Origin>,
    /// What is wrong and, where it helps, what to do.
    pub message: String,
}

impl ModelError {
    fn new(file: &str, at: Option<Origin>, message: impl Into<String>) -> Self {
        ModelError {
            file: file.to_owned(),
            at,
            message: message.into(),
        }
    }
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.at {
            Some(at) => write!(f, "{}:{at}: {}", self.file, self.message),
            None => write!(f, "{}: {}", self.file, self.message),
        }
    }
}

impl std::error::Error for ModelError {}

/// One face of a loaded model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModelFace {
    /// Vertex indices, 3..=[`MAX_FACE_VERTICES`], counter-clockwise seen from outside.
    pub indices: Vec<u32>,
    /// Its colour.
    pub color: Rgb565,
    /// Where it came from, if known.
    pub origin: Option<Origin>,
    /// The file's normal of each corner, as indices into [`LoadedModel::normals`] (an OBJ's
    /// `vn`), or empty: the file gives none.
    pub normals: Vec<u32>,
}

/// A model in memory, normalised into the unit sphere (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedModel {
    /// The file name used in messages.
    pub file: String,
    /// Normalised vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Where each vertex came from, if known (same length as `positions`).
    pub vertex_origins: Vec<Option<Origin>>,
    /// Faces, in file order.
    pub faces: Vec<ModelFace>,
    /// The normals the file gives (an OBJ's `vn`, unit length or not), which faces' corners
    /// refer to ([`ModelFace::normals`]); empty when the file gives none for some corner (then
    /// [`LoadedModel::warnings`] says so, and [`LoadedModel::vertex_normals`] computes them).
    pub normals: Vec<[f32; 3]>,
    /// One unit normal per vertex for smooth shading once [`LoadedModel::smoothed`] has made
    /// them, else empty; [`LoadedModel::with_mesh`] hands them to zrow
    /// ([`zrow::Mesh::vertex_normals`]).
    pub vertex_normals: Vec<[f32; 3]>,
    /// The normalisation: `normalised = (original − centre) · scale`.
    pub centre: [f32; 3],
    /// See `centre`.
    pub scale: f32,
    /// What was read but not used, one line each, naming the file: an OBJ's material library
    /// that is missing, unreadable or malformed (its faces are drawn in [`DEFAULT_RGB`]). The
    /// command line prints them on stderr as `warning: …`.
    pub warnings: Vec<String>,
}

impl LoadedModel {
    /// Calls `f` with the model as a zrow [`Mesh`] in number format `N`. Errors when a
    /// position does not fit `N`, naming the vertex's line (or triangle).
    pub fn with_mesh<N: Scalar, R>(
        &self,
        f: impl FnOnce(&Mesh<'_, N, u32>) -> R,
    ) -> Result<R, Error> {
        let mut vertices = Vec::with_capacity(self.positions.len());
        for (k, &p) in self.positions.iter().enumerate() {
            let v = Vec3::<N>::from_f32(p).ok_or_else(|| {
                ModelError::new(
                    &self.file,
                    self.vertex_origins.get(k).copied().flatten(),
                    format!(
                        "vertex {k} ({}, {}, {}) does not fit the {} number format",
                        p[0],
                        p[1],
                        p[2],
                        N::NAME
                    ),
                )
            })?;
            vertices.push(v);
        }
        let faces: Vec<Face<'_, u32>> = self
            .faces
            .iter()
            .map(|face| Face {
                indices: &face.indices,
                color: face.color,
                alpha: 255,
            })
            .collect();
        let normals: Vec<Vec3<N>> = self
            .vertex_normals
            .iter()
            .map(|&n| Vec3::from_f32(n).unwrap_or(Vec3::new(N::ZERO, N::ZERO, N::ZERO)))
            .collect();
        let mesh = Mesh::new(&vertices, &faces).with_vertex_normals(Vectors::Format(&normals));
        Ok(f(&mesh))
    }

    /// The same model ready for smooth shading: one normal per vertex
    /// ([`LoadedModel::vertex_normals`] with a crease angle of `crease_degrees`), the vertices
    /// that need several copied, the faces (same order, colours and origins) renumbered to
    /// them. Its mesh ([`LoadedModel::with_mesh`]) carries the normals.
    pub fn smoothed(&self, crease_degrees: f64) -> LoadedModel {
        let v = self.vertex_normals(crease_degrees);
        let pick = |k: &u32| *k as usize;
        let faces = self
            .faces
            .iter()
            .zip(v.faces)
            .map(|(f, indices)| ModelFace {
                indices,
                color: f.color,
                origin: f.origin,
                normals: Vec::new(),
            })
            .collect();
        LoadedModel {
            file: self.file.clone(),
            positions: v
                .source
                .iter()
                .map(|k| self.positions.get(pick(k)).copied().unwrap_or_default())
                .collect(),
            vertex_origins: v
                .source
                .iter()
                .map(|k| self.vertex_origins.get(pick(k)).copied().flatten())
                .collect(),
            faces,
            normals: Vec::new(),
            vertex_normals: v.normals.iter().map(|n| n.map(|c| c as f32)).collect(),
            centre: self.centre,
            scale: self.scale,
            warnings: self.warnings.clone(),
        }
    }

    /// One normal per vertex for smooth shading ([`crate::vertex_normals`]): the file's own when
    /// every face corner has one, else computed from the faces with a crease angle of
    /// `crease_degrees` (edges whose faces are farther apart stay sharp). Vertices that need
    /// several normals are split; the result renumbers the faces, in order.
    pub fn vertex_normals(&self, crease_degrees: f64) -> VertexNormals {
        let faces: Vec<&[u32]> = self.faces.iter().map(|f| &f.indices[..]).collect();
        let corners: Vec<&[u32]> = self.faces.iter().map(|f| &f.normals[..]).collect();
        let positions: Vec<[f64; 3]> = self.positions.iter().map(|p| p.map(f64::from)).collect();
        let (normals, _) = vertex_normals::from_file_or_faces(
            &positions,
            &faces,
            &self.normals,
            &corners,
            crease_degrees,
        );
        normals
    }

    /// Where face number `face` (0-based, as zrow's errors count) came from.
    pub fn face_origin(&self, face: u32) -> Option<Origin> {
        self.faces.get(face as usize).and_then(|f| f.origin)
    }
}

/// The formats [`load`] reads, by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelFormat {
    /// Wavefront OBJ (`.obj`), with its MTL.
    Obj,
    /// STL (`.stl`), ASCII or binary.
    Stl,
    /// OFF (`.off`).
    Off,
}

impl ModelFormat {
    /// The format of `path`, by its extension (any case).
    pub fn of(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "obj" => Some(ModelFormat::Obj),
            "stl" => Some(ModelFormat::Stl),
            "off" => Some(ModelFormat::Off),
            _ => None,
        }
    }
}

/// Loads the model at `path` (format by extension: `.obj`, `.stl`, `.off`) and normalises
/// it into the unit sphere.
pub fn load(path: &Path) -> Result<LoadedModel, Error> {
    let file = path.display().to_string();
    let format = ModelFormat::of(path).ok_or_else(|| {
        ModelError::new(
            &file,
            None,
            "unknown model format: expected a file ending in .obj, .stl or .off",
        )
    })?;
    let data = read_input(path)?;
    let dir = path.parent().unwrap_or(Path::new("."));
    parse(&file, format, &data, dir)
}

/// Parses a model from memory: `file` names it in errors, `dir` is where an OBJ's MTL files
/// are looked for. [`load`] without the file system.
pub fn parse(
    file: &str,
    format: ModelFormat,
    data: &[u8],
    dir: &Path,
) -> Result<LoadedModel, Error> {
    match format {
        ModelFormat::Obj => Ok(parse_obj(file, data, dir)?),
        ModelFormat::Stl => Ok(parse_stl(file, data)?),
        ModelFormat::Off => parse_off(file, data),
    }
}

/// A model before normalisation.
struct Raw {
    positions: Vec<[f32; 3]>,
    origins: Vec<Option<Origin>>,
    faces: Vec<ModelFace>,
    normals: Vec<[f32; 3]>,
}

/// Checks counts, normalises.
fn finish(file: &str, raw: Raw) -> Result<LoadedModel, ModelError> {
    if raw.positions.len() > MAX_VERTICES {
        return Err(ModelError::new(
            file,
            None,
            format!(
                "the model has {} vertices, at most {MAX_VERTICES} supported (32-bit indices): \
                 simplify it",
                raw.positions.len()
            ),
        ));
    }
    if raw.faces.is_empty() {
        return Err(ModelError::new(file, None, "the model has no faces"));
    }
    // Bounding box in f64, so that extreme f32 values cannot overflow.
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &raw.positions {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a] as f64);
            hi[a] = hi[a].max(p[a] as f64);
        }
    }
    let centre: [f64; 3] = core::array::from_fn(|a| (lo[a] + hi[a]) * 0.5);
    let half_diagonal = 0.5 * (0..3).map(|a| (hi[a] - lo[a]).powi(2)).sum::<f64>().sqrt();
    if !(half_diagonal > 0.0 && half_diagonal.is_finite()) {
        return Err(ModelError::new(
            file,
            None,
            "the model has zero size (all its vertices are one point)",
        ));
    }
    let scale = 1.0 / half_diagonal;
    let positions = raw
        .positions
        .iter()
        .map(|p| core::array::from_fn(|a| ((p[a] as f64 - centre[a]) * scale) as f32))
        .collect();
    Ok(LoadedModel {
        file: file.to_owned(),
        positions,
        vertex_origins: raw.origins,
        faces: raw.faces,
        normals: raw.normals,
        vertex_normals: Vec::new(),
        centre: centre.map(|c| c as f32),
        scale: scale as f32,
        warnings: Vec::new(),
    })
}

// ---------------------------------------------------------------------------------------------
// OFF

fn parse_off(file: &str, data: &[u8]) -> Result<LoadedModel, Error> {
    let scene = off::parse(file, data)?;
    let raw = Raw {
        positions: scene.vertices.iter().map(|v| v.position).collect(),
        origins: scene
            .vertices
            .iter()
            .map(|v| Some(Origin::Line(v.line)))
            .collect(),
        faces: scene
            .faces
            .iter()
            .map(|f| ModelFace {
                indices: f.indices.clone(),
                color: f.rgb565(),
                origin: Some(Origin::Line(f.line)),
                normals: Vec::new(),
            })
            .collect(),
        normals: Vec::new(),
    };
    Ok(finish(file, raw)?)
}

// ---------------------------------------------------------------------------------------------
// Text helpers

/// The lines of a text file with their 1-based numbers, comments (`#`) cut and tokens split;
/// `Err(line)` for a line that is not UTF-8.
fn text_lines(data: &[u8]) -> impl Iterator<Item = (usize, Result<Vec<&str>, ()>)> {
    let data = data.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(data);
    data.split(|&b| b == b'\n').enumerate().map(|(k, raw)| {
        let text = raw.split(|&b| b == b'#').next().unwrap_or(raw);
        let tokens = std::str::from_utf8(text)
            .map(|t| t.split_ascii_whitespace().collect())
            .map_err(|_| ());
        (k + 1, tokens)
    })
}

/// Parses a finite `f32`, or says why not.
fn finite(what: &str, token: &str) -> Result<f32, String> {
    match token.parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!(
            "{what} `{}` is not finite (or too large for f32)",
            shown(token)
        )),
        Err(_) => Err(format!("{what} `{}` is not a number", shown(token))),
    }
}

// ---------------------------------------------------------------------------------------------
// OBJ

/// What the line-by-line check of an OBJ file found: every `v` with its line, every `f` line.
struct ObjCheck {
    vertices: Vec<(usize, [f32; 3])>,
    face_lines: Vec<usize>,
    /// `vn` lines.
    normals: usize,
    /// Face corners without a normal index, and the first one's line.
    bare_corners: (usize, usize),
}

/// Resolves one OBJ index (1-based, or negative from the end) against `count` elements
/// defined so far.
fn obj_index(what: &str, token: &str, count: usize) -> Result<usize, String> {
    let i: i64 = token
        .parse()
        .map_err(|_| format!("{what} index `{}` is not an integer", shown(token)))?;
    let resolved = if i > 0 {
        i - 1
    } else if i < 0 {
        count as i64 + i
    } else {
        return Err(format!(
            "{what} index 0: OBJ indices start at 1 (or count back from -1)"
        ));
    };
    if resolved < 0 || resolved >= count as i64 {
        return Err(format!(
            "{what} index {i} out of range: {count} defined before this line"
        ));
    }
    Ok(resolved as usize)
}

fn check_obj(file: &str, data: &[u8]) -> Result<ObjCheck, ModelError> {
    let mut check = ObjCheck {
        vertices: Vec::new(),
        face_lines: Vec::new(),
        normals: 0,
        bare_corners: (0, 0),
    };
    let (mut texcoords, mut normals) = (0usize, 0usize);
    for (line, tokens) in text_lines(data) {
        let at = Some(Origin::Line(line));
        let err = |m: String| ModelError::new(file, at, m);
        let tokens = tokens.map_err(|_| err("line is not valid UTF-8".into()))?;
        let Some((&key, args)) = tokens.split_first() else {
            continue;
        };
        match key {
            "v" => {
                if !(3..=7).contains(&args.len()) {
                    return Err(err(format!(
                        "vertex needs 3 coordinates `v x y z`, found {} values",
                        args.len()
                    )));
                }
                let mut p = [0f32; 3];
                for (k, t) in args.iter().enumerate() {
                    let what = ["vertex x", "vertex y", "vertex z"]
                        .get(k)
                        .unwrap_or(&"vertex value");
                    let v = finite(what, t).map_err(err)?;
                    if let Some(slot) = p.get_mut(k) {
                        *slot = v;
                    }
                }
                check.vertices.push((line, p));
            }
            "vt" | "vn" => {
                let what = if key == "vt" {
                    "texture coordinate"
                } else {
                    "normal"
                };
                if args.is_empty() || args.len() > 4 {
                    return Err(err(format!("{what} needs 1 to 3 values")));
                }
                for t in args {
                    finite(what, t).map_err(err)?;
                }
                if key == "vt" {
                    texcoords += 1;
                } else {
                    normals += 1;
                }
            }
            "f" => {
                if args.len() < 3 {
                    return Err(err(format!(
                        "face has {} vertices, need at least 3",
                        args.len()
                    )));
                }
                for t in args {
                    let mut parts = t.split('/');
                    let v = parts.next().unwrap_or("");
                    obj_index("vertex", v, check.vertices.len()).map_err(err)?;
                    if let Some(vt) = parts.next().filter(|s| !s.is_empty()) {
                        obj_index("texture coordinate", vt, texcoords).map_err(err)?;
                    }
                    if let Some(vn) = parts.next().filter(|s| !s.is_empty()) {
                        obj_index("normal", vn, normals).map_err(err)?;
                    } else {
                        if check.bare_corners.0 == 0 {
                            check.bare_corners.1 = line;
                        }
                        check.bare_corners.0 += 1;
                    }
                    if parts.next().is_some() {
                        return Err(err(format!(
                            "face vertex `{}` has more than `v/vt/vn`",
                            shown(t)
                        )));
                    }
                }
                check.face_lines.push(line);
            }
            _ => {}
        }
    }
    check.normals = normals;
    Ok(check)
}

fn parse_obj(file: &str, data: &[u8], dir: &Path) -> Result<LoadedModel, ModelError> {
    let check = check_obj(file, data)?;
    #[allow(clippy::needless_update)] // more fields exist under tobj's optional features
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let warnings = RefCell::new(Vec::new());
    let (models, materials) =
        tobj::load_obj_buf(&mut std::io::Cursor::new(data), &options, |mtl| {
            let path = dir.join(mtl);
            let warn = |why: String| {
                warnings.borrow_mut().push(format!(
                    "{file}: material library {}: {why}; its faces are drawn in the default colour",
                    path.display()
                ));
                Err(tobj::LoadError::OpenFileFailed)
            };
            match read_input(&path) {
                Ok(bytes) => tobj::load_mtl_buf(&mut std::io::Cursor::new(bytes))
                    .or_else(|e| warn(format!("cannot parse it: {e}"))),
                Err(Error::Io { source, .. }) => warn(source.to_string()),
                Err(e) => warn(e.to_string()),
            }
        })
        .map_err(|e| ModelError::new(file, None, format!("cannot read OBJ: {e}")))?;
    let materials = materials.unwrap_or_default();
    let mut warnings = warnings.into_inner();
    // The file's normals, if every face corner has one (tobj fills gaps with a neighbour's).
    let (bare, bare_line) = check.bare_corners;
    let file_normals = check.normals > 0 && bare == 0;
    if check.normals > 0 && bare > 0 {
        warnings.push(format!(
            "{file}:{bare_line}: {bare} face corners have no normal (`v//vn`), the first here: \
             the file's normals are not used (smooth shading computes them from the faces)"
        ));
    }

    // Vertex lines by exact position (tobj re-indexes per object).
    let mut line_of: HashMap<[u32; 3], usize> = HashMap::new();
    for &(line, p) in &check.vertices {
        line_of.entry(p.map(f32::to_bits)).or_insert(line);
    }
    let default = rgb8_to_rgb565(DEFAULT_RGB);
    let mut raw = Raw {
        positions: Vec::new(),
        origins: Vec::new(),
        faces: Vec::new(),
        normals: Vec::new(),
    };
    let mut index_of: HashMap<[u32; 3], usize> = HashMap::new();
    let mut obj_face = 0usize; // faces as the file has them, to find their lines
    let tobj_faces: usize = models
        .iter()
        .map(|m| match m.mesh.face_arities.len() {
            0 => m.mesh.indices.len() / 3,
            n => n,
        })
        .sum();
    let lines_known = tobj_faces == check.face_lines.len();
    for model in &models {
        let mesh = &model.mesh;
        // tobj numbers vertices per object: share them again across objects.
        let mut local = Vec::with_capacity(mesh.positions.len() / 3);
        for p in mesh.positions.chunks_exact(3) {
            let p = [p[0], p[1], p[2]];
            let key = p.map(f32::to_bits);
            let i = *index_of.entry(key).or_insert_with(|| {
                raw.positions.push(p);
                raw.origins
                    .push(line_of.get(&key).map(|&l| Origin::Line(l)));
                raw.positions.len() - 1
            });
            local.push(i);
        }
        if raw.positions.len() > MAX_VERTICES {
            break; // `finish` reports it
        }
        let color = mesh
            .material_id
            .and_then(|m| materials.get(m))
            .and_then(|m| m.diffuse)
            .map_or(default, |kd| {
                rgb8_to_rgb565(kd.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8))
            });
        let arities: Vec<usize> = if mesh.face_arities.is_empty() {
            vec![3; mesh.indices.len() / 3]
        } else {
            mesh.face_arities.iter().map(|&a| a as usize).collect()
        };
        // This object's normals follow the earlier objects'.
        let normal_base = raw.normals.len();
        let with_normals = file_normals && mesh.normal_indices.len() == mesh.indices.len();
        if with_normals {
            raw.normals
                .extend(mesh.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]));
        }
        let mut next = 0usize;
        for arity in arities {
            let origin = lines_known
                .then(|| check.face_lines.get(obj_face).map(|&l| Origin::Line(l)))
                .flatten();
            obj_face += 1;
            let Some(ids) = mesh.indices.get(next..next + arity) else {
                return Err(ModelError::new(file, origin, "face indices missing"));
            };
            let normals: Vec<u32> = match mesh.normal_indices.get(next..next + arity) {
                Some(ns) if with_normals => ns
                    .iter()
                    .map(|&n| (normal_base + n as usize).min(u32::MAX as usize) as u32)
                    .collect(),
                _ => Vec::new(),
            };
            next += arity;
            let mut indices = Vec::with_capacity(arity);
            for &i in ids {
                let Some(&i) = local.get(i as usize) else {
                    return Err(ModelError::new(file, origin, "vertex index out of range"));
                };
                indices.push(i.min(u32::MAX as usize) as u32);
            }
            // A polygon beyond zrow's limit becomes a fan of polygons within it (the corners'
            // normals with them).
            if indices.len() <= MAX_FACE_VERTICES {
                raw.faces.push(ModelFace {
                    indices,
                    color,
                    origin,
                    normals,
                });
            } else {
                let mut start = 1;
                while start + 1 < indices.len() {
                    let end = (start + MAX_FACE_VERTICES - 1).min(indices.len());
                    let mut part = vec![indices[0]];
                    part.extend_from_slice(&indices[start..end]);
                    let part_normals = match (normals.first(), normals.get(start..end)) {
                        (Some(&n0), Some(rest)) => [&[n0][..], rest].concat(),
                        _ => Vec::new(),
                    };
                    raw.faces.push(ModelFace {
                        indices: part,
                        color,
                        origin,
                        normals: part_normals,
                    });
                    start = end - 1;
                }
            }
        }
    }
    let mut model = finish(file, raw)?;
    model.warnings = warnings;
    Ok(model)
}

// ---------------------------------------------------------------------------------------------
// STL

/// Size of a binary STL's header plus its triangle count.
const STL_HEADER: usize = 84;
/// Size of one binary STL triangle record.
const STL_RECORD: usize = 50;

fn parse_stl(file: &str, data: &[u8]) -> Result<LoadedModel, ModelError> {
    let declared = data
        .get(80..84)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
    let binary_size = declared.map(|n| STL_HEADER as u64 + STL_RECORD as u64 * n as u64);
    let looks_ascii = data.trim_ascii_start().starts_with(b"solid");
    let is_binary = match binary_size {
        Some(size) if size == data.len() as u64 => true,
        _ => !looks_ascii,
    };
    let (triangles, origins) = if is_binary {
        read_binary_stl(file, data)?
    } else {
        read_ascii_stl(file, data)?
    };
    let default = rgb8_to_rgb565(DEFAULT_RGB);
    // Share vertices that are bit-identical.
    let mut index_of: HashMap<[u32; 3], u32> = HashMap::new();
    let mut raw = Raw {
        positions: Vec::new(),
        origins: Vec::new(),
        faces: Vec::new(),
        normals: Vec::new(),
    };
    for (t, (tri, origin)) in triangles.iter().zip(&origins).enumerate() {
        let mut indices = Vec::with_capacity(3);
        for (k, v) in tri.iter().enumerate() {
            let key = v.map(f32::to_bits);
            let i = match index_of.get(&key) {
                Some(&i) => i,
                None => {
                    if raw.positions.len() >= MAX_VERTICES {
                        return Err(ModelError::new(
                            file,
                            None,
                            format!(
                                "the model has more than {MAX_VERTICES} distinct vertices (32-bit \
                                 indices; reached at triangle {t}): simplify it"
                            ),
                        ));
                    }
                    let i = raw.positions.len() as u32;
                    index_of.insert(key, i);
                    raw.positions.push(*v);
                    raw.origins.push(origin.vertex(k));
                    i
                }
            };
            indices.push(i);
        }
        raw.faces.push(ModelFace {
            indices,
            color: default,
            origin: Some(origin.face()),
            normals: Vec::new(),
        });
    }
    finish(file, raw)
}

/// Where an STL triangle and its three vertices came from.
#[derive(Clone, Copy, Debug)]
enum StlOrigin {
    /// ASCII: the `facet` line and the three `vertex` lines.
    Lines { facet: usize, vertices: [usize; 3] },
    /// Binary: the record.
    Record { index: usize, offset: u64 },
}

impl StlOrigin {
    fn face(self) -> Origin {
        match self {
            StlOrigin::Lines { facet, .. } => Origin::Line(facet),
            StlOrigin::Record { index, offset } => Origin::Triangle { index, offset },
        }
    }
    fn vertex(self, k: usize) -> Option<Origin> {
        Some(match self {
            StlOrigin::Lines { vertices, .. } => Origin::Line(*vertices.get(k)?),
            StlOrigin::Record { .. } => self.face(),
        })
    }
}

type StlTriangles = (Vec<[[f32; 3]; 3]>, Vec<StlOrigin>);

/// Reads the triangles with `stl_io` from `data` (already checked, so it fails only on
/// something the check missed).
fn stl_io_triangles(file: &str, data: &[u8]) -> Result<Vec<[[f32; 3]; 3]>, ModelError> {
    let mut cursor = std::io::Cursor::new(data);
    let reader = stl_io::create_stl_reader(&mut cursor)
        .map_err(|e| ModelError::new(file, None, format!("cannot read STL: {e}")))?;
    reader
        .map(|t| {
            t.map(|t| t.vertices.map(|v| v.0))
                .map_err(|e| ModelError::new(file, None, format!("cannot read STL: {e}")))
        })
        .collect()
}

fn read_binary_stl(file: &str, data: &[u8]) -> Result<StlTriangles, ModelError> {
    let err = |at, m: String| ModelError::new(file, at, m);
    if data.len() < STL_HEADER {
        return Err(err(
            None,
            format!(
                "truncated binary STL: {} bytes, but the header and triangle count alone take \
                 {STL_HEADER} (an ASCII STL starts with `solid`)",
                data.len()
            ),
        ));
    }
    let n = u32::from_le_bytes([data[80], data[81], data[82], data[83]]) as usize;
    let need = STL_HEADER as u64 + STL_RECORD as u64 * n as u64;
    if (data.len() as u64) < need {
        let whole = (data.len() - STL_HEADER) / STL_RECORD;
        let offset = (STL_HEADER + whole * STL_RECORD) as u64;
        return Err(err(
            Some(Origin::Triangle {
                index: whole,
                offset,
            }),
            format!(
                "truncated binary STL: the header declares {n} triangles ({need} bytes) but the \
                 file has {} bytes; this triangle is cut short",
                data.len()
            ),
        ));
    }
    let mut origins = Vec::with_capacity(n.min(1 << 20));
    for index in 0..n {
        let offset = STL_HEADER + index * STL_RECORD;
        let record = &data[offset..offset + STL_RECORD];
        let origin = Origin::Triangle {
            index,
            offset: offset as u64,
        };
        for (k, b) in record[12..48].chunks_exact(4).enumerate() {
            let v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            if !v.is_finite() {
                return Err(err(
                    Some(origin),
                    format!(
                        "vertex {} {} is not finite",
                        k / 3 + 1,
                        ["x", "y", "z"][k % 3]
                    ),
                ));
            }
        }
        origins.push(StlOrigin::Record {
            index,
            offset: offset as u64,
        });
    }
    // stl_io takes a file starting with `solid ` for ASCII; the binary header is free text,
    // so blank it out for stl_io when it would mislead it.
    let mut copy;
    let mut bytes = data;
    if bytes.starts_with(b"solid") {
        copy = data.to_vec();
        copy[..5].copy_from_slice(b"     ");
        bytes = &copy;
    }
    let triangles = stl_io_triangles(file, &bytes[..need as usize])?;
    Ok((triangles, origins))
}

fn read_ascii_stl(file: &str, data: &[u8]) -> Result<StlTriangles, ModelError> {
    #[derive(Clone, Copy, PartialEq)]
    enum Want {
        Solid,
        FacetOrEnd,
        OuterLoop,
        Vertex(usize),
        EndLoop,
        EndFacet,
        Nothing,
    }
    let mut want = Want::Solid;
    let mut origins = Vec::new();
    let mut facet = 0usize;
    let mut vertices = [0usize; 3];
    let mut last = 1;
    // For stl_io: the file with comments dropped and a name after `solid`.
    let mut clean = String::with_capacity(data.len());
    for (line, tokens) in text_lines(data) {
        let at = Some(Origin::Line(line));
        let err = |m: String| ModelError::new(file, at, m);
        let tokens = tokens.map_err(|_| err("line is not valid UTF-8".into()))?;
        if tokens.is_empty() {
            continue;
        }
        last = line;
        let expected = |what: &str| {
            err(format!(
                "expected `{what}`, found `{}`",
                shown(&tokens.join(" "))
            ))
        };
        let numbers = |what: &str, args: &[&str]| -> Result<(), ModelError> {
            if args.len() != 3 {
                return Err(err(format!(
                    "{what} needs 3 numbers, found {} values",
                    args.len()
                )));
            }
            for (t, axis) in args.iter().zip(["x", "y", "z"]) {
                finite(&format!("{what} {axis}"), t).map_err(err)?;
            }
            Ok(())
        };
        want = match (want, tokens[0]) {
            (Want::Solid, "solid") => {
                clean.push_str("solid model\n");
                Want::FacetOrEnd
            }
            (Want::Solid, _) => return Err(expected("solid NAME")),
            (Want::FacetOrEnd, "facet") => {
                if tokens.get(1) != Some(&"normal") {
                    return Err(expected("facet normal NX NY NZ"));
                }
                numbers("facet normal", &tokens[2..])?;
                facet = line;
                Want::OuterLoop
            }
            (Want::FacetOrEnd, "endsolid") => Want::Nothing,
            (Want::FacetOrEnd, _) => return Err(expected("facet normal NX NY NZ` or `endsolid")),
            (Want::OuterLoop, _) if tokens == ["outer", "loop"] => Want::Vertex(0),
            (Want::OuterLoop, _) => return Err(expected("outer loop")),
            (Want::Vertex(k), "vertex") => {
                numbers("vertex", &tokens[1..])?;
                vertices[k] = line;
                if k == 2 {
                    Want::EndLoop
                } else {
                    Want::Vertex(k + 1)
                }
            }
            (Want::Vertex(_), _) => {
                return Err(expected(
                    "vertex X Y Z` (a facet has exactly 3 vertices in STL",
                ))
            }
            (Want::EndLoop, _) if tokens == ["endloop"] => Want::EndFacet,
            (Want::EndLoop, _) => return Err(expected("endloop` (a facet has exactly 3 vertices")),
            (Want::EndFacet, _) if tokens == ["endfacet"] => {
                origins.push(StlOrigin::Lines { facet, vertices });
                Want::FacetOrEnd
            }
            (Want::EndFacet, _) => return Err(expected("endfacet")),
            (Want::Nothing, _) => {
                return Err(err(
                    "unexpected content after `endsolid` (one solid per file)".into(),
                ))
            }
        };
        if tokens[0] != "solid" {
            clean.push_str(&tokens.join(" "));
            clean.push('\n');
        }
    }
    if want != Want::Nothing {
        let what = match want {
            Want::Solid => "`solid NAME`",
            Want::FacetOrEnd => "`facet normal` or `endsolid`",
            Want::OuterLoop => "`outer loop`",
            Want::Vertex(_) => "`vertex X Y Z`",
            Want::EndLoop => "`endloop`",
            _ => "`endfacet`",
        };
        return Err(ModelError::new(
            file,
            Some(Origin::Line(last)),
            format!("unexpected end of file: expected {what}"),
        ));
    }
    let triangles = stl_io_triangles(file, clean.as_bytes())?;
    if triangles.len() != origins.len() {
        return Err(ModelError::new(
            file,
            None,
            "cannot read STL: stl_io and the line check disagree on the triangle count",
        ));
    }
    Ok((triangles, origins))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn obj(text: &str) -> Result<LoadedModel, String> {
        parse_obj("t.obj", text.as_bytes(), Path::new(".")).map_err(|e| e.to_string())
    }

    /// A unit square of two triangles, `vn` per corner: the file's normals are kept, a
    /// vertex split where its corners' normals differ, a fan split carries them.
    #[test]
    fn obj_normals_are_the_files_when_every_corner_has_one() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 0.6 0.8\n\
                    f 1//1 2//1 3//1\nf 1//2 3//1 4//1\n";
        let m = obj(text).unwrap();
        assert_eq!(m.normals.len(), 2);
        assert!(m.warnings.is_empty(), "{:?}", m.warnings);
        let normal = |f: usize, k: usize| m.normals[m.faces[f].normals[k] as usize];
        assert_eq!(normal(0, 0), [0.0, 0.0, 1.0]);
        assert_eq!(normal(1, 0), [0.0, 0.6, 0.8]);
        let v = m.vertex_normals(45.0);
        assert_eq!(v.source, [0, 1, 2, 0, 3]);
        let tilted = v.normals[v.faces[1][0] as usize];
        assert!((tilted[1] - 0.6).abs() < 1e-7 && (tilted[2] - 0.8).abs() < 1e-7);
        // A polygon with more corners than MAX_FACE_VERTICES, fanned into pieces: each piece's
        // corners keep their own normal.
        let (n, mut text, mut face) = (MAX_FACE_VERTICES + 3, String::new(), "f".to_owned());
        for k in 0..n {
            let a = k as f32 * std::f32::consts::TAU / n as f32;
            text += &format!("v {} {} 0\nvn {k} 0 1\n", a.cos(), a.sin());
            face += &format!(" {0}//{0}", k + 1);
        }
        let m = obj(&format!("{text}{face}\n")).unwrap();
        assert_eq!(m.faces.len(), 2);
        for f in &m.faces {
            assert_eq!(f.normals.len(), f.indices.len());
            for (&i, &n) in f.indices.iter().zip(&f.normals) {
                assert_eq!(m.normals[n as usize][0], i as f32, "vertex {i}");
            }
        }
    }

    /// Normals on some corners only: not used (a warning naming the line), computed instead.
    #[test]
    fn obj_normals_on_some_corners_only_are_not_used() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 3 2\n";
        let m = obj(text).unwrap();
        assert!(m.normals.is_empty());
        assert!(m.faces.iter().all(|f| f.normals.is_empty()));
        assert_eq!(m.warnings.len(), 1);
        assert!(
            m.warnings[0].starts_with("t.obj:6: 3 face corners"),
            "{}",
            m.warnings[0]
        );
        // From the faces: two faces back to back are 180° apart, a crease at any angle.
        let v = m.vertex_normals(45.0);
        assert_eq!(v.normals.len(), 6);
    }

    #[test]
    fn obj_quads_stay_quads_and_negative_indices_work() {
        let m = obj("v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\nf -4 -2 -1\n").unwrap();
        assert_eq!(m.faces.len(), 2);
        assert_eq!(m.faces[0].indices.len(), 4);
        assert_eq!(m.faces[1].origin, Some(Origin::Line(6)));
        assert_eq!(m.vertex_origins[2], Some(Origin::Line(3)));
        // Centred and scaled by 1 / half-diagonal = 1/√2.
        let s = 1.0 / 2f32.sqrt();
        assert!((m.positions[0][0] + s).abs() < 1e-6, "{:?}", m.positions[0]);
        assert!((m.positions[2][1] - s).abs() < 1e-6);
    }

    #[test]
    fn big_polygons_become_fans() {
        let mut text = String::new();
        for k in 0..14 {
            let a = k as f32 * std::f32::consts::TAU / 14.0;
            text += &format!("v {} {} 0\n", a.cos(), a.sin());
        }
        text += "f";
        for k in 1..=14 {
            text += &format!(" {k}");
        }
        let m = obj(&text).unwrap();
        assert_eq!(m.faces.len(), 2);
        assert!(m.faces.iter().all(|f| f.indices.len() <= MAX_FACE_VERTICES));
        let covered: usize = m.faces.iter().map(|f| f.indices.len() - 2).sum();
        assert_eq!(covered, 12); // triangles in a fan of 14 vertices
    }

    #[test]
    fn zero_size_and_empty_models_are_errors() {
        assert_eq!(
            obj("v 1 1 1\nf 1 1 1\n").unwrap_err(),
            "t.obj: the model has zero size (all its vertices are one point)"
        );
        assert_eq!(
            obj("v 1 1 1\n").unwrap_err(),
            "t.obj: the model has no faces"
        );
    }

    #[test]
    fn huge_coordinates_normalise_without_overflow() {
        let m = obj("v -3e38 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n").unwrap();
        assert!(m.positions.iter().all(|p| {
            let r = p.iter().map(|c| c * c).sum::<f32>().sqrt();
            r <= 1.0 + 1e-6
        }));
    }
}
