//! Bring your own model: an OBJ, STL or OFF model converted to const Rust data for flash,
//! with the scan-line renderer's capacities measured over every orientation it may be seen in.
//!
//! ```text
//! zrow-sim convert --model FILE --out FILE.rs [--format q16.16|f32] [--size WxH]
//!                  [--distance D] [--name NAME] [--strict] [--compact] [--smooth DEG]
//! ```
//!
//! or, from a build script, [`write_for_build`] (then `zrow::include_mesh!("NAME")`). The
//! command is the simulator's (`zrow-sim`); this crate is all a build script needs.
//!
//! **Validate, never silently change.** Every change to the model is a line of the
//! [`Report`] naming the file and line; `--strict` ([`ConvertOptions::strict`]) turns each change
//! into an error instead:
//!
//! - a polygon with more than [`MAX_FACE_VERTICES`] vertices: the loader ([`crate::model`])
//!   splits it into a fan of convex polygons of at most [`MAX_FACE_VERTICES`] vertices; the
//!   converter finds the pieces (consecutive faces from one line) and reports the split;
//! - a non-planar face: a vertex farther than [`PLANAR_TOLERANCE`] (a fraction of the model's
//!   radius, see there) from the face's best-fit plane (Newell's normal through the centroid,
//!   in `f64`). It is replaced by a fan of triangles;
//! - a non-manifold model: an edge used by more than two faces, or by two faces in the same
//!   direction (inconsistent orientation, which breaks back-face culling). Nothing is changed;
//!   the report gives the count and the first offending face. Open edges (used once) are
//!   listed for information only: an open mesh is drawn correctly, its holes show;
//! - vertices no face uses are dropped (the data holds what the scene needs);
//! - the scale: the loader normalises every model into the unit sphere (centre of the bounding
//!   box at the origin, half-diagonal 1), so no model is too large (or too small) for Q16.16.
//!   The converter keeps that normalisation; the report gives the scale and the centre
//!   (`original = position / scale + centre`) and the quantisation error in the model's own
//!   units as well as in normalised units and LSB.
//!
//! **Quantise.** Positions are rounded to nearest in the chosen format ([`Format`]): Q16.16
//! bits `round(x · 65536)` from the loader's `f32` positions (the error is at most half an LSB
//! per coordinate, `√3/2` LSB as a distance), f32 copies them exactly (error 0; the loader's own
//! rounding to `f32`, at most 2⁻²⁵ relative, is not counted). Normals are one per face,
//! Newell's normal in `f64` from the unquantised positions, unit length, then rounded to the
//! format (a degenerate face gets the zero vector). With `--compact`
//! ([`ConvertOptions::compact`]) positions are rounded to nearest at 2^-14 instead and emitted
//! as 16-bit integers (`zrow::Vectors::Compact`, [`COMPACT_SHIFT`]): 6 bytes a vertex
//! instead of 12, each coordinate within 2^-15 of the loader's (a unit-sphere model on a
//! 240-pixel screen: about a 40,000th of its width), exact in both formats. Colours are Rgb565. Faces index vertices
//! with the narrowest type: `u8` up to 256 vertices, else `u16` (more than 65,536: an error).
//!
//! **Requirements under every orientation.** The capacities of [`zrow::Scanline`] depend on the
//! view. The converter puts the model (its quantised data, exactly what flash will hold) in a
//! [`ModelScene`] as model mode draws it: the simulator's perspective camera
//! ([`crate::camera`]: 60° field of view, near 0.1, far 20) at `distance` from the
//! origin, back faces culled, `width × height` pixels. It turns the model through
//! [`ConvertOptions::directions`] view directions on a Fibonacci sphere plus the six axis
//! directions, each with [`ConvertOptions::rolls`] roll angles evenly spaced over a turn, and
//! measures each view with [`zrow::requirements()`]: polygons on screen (front-facing, after
//! clipping), edges, the most polygons active in one row. The capacities are the maxima over
//! those views. Sampling can miss a worse view, so [`ConvertOptions::check_views`] further
//! orientations, uniformly random (Shoemake's quaternions, seeded), are measured too; the
//! report gives by how much they exceeded the sampled maxima, the emitted capacities take
//! the maximum over both sets and then add [`MARGIN_PERCENT`] (at least 1) to each, for views
//! neither set saw. The depth range (eye distance of the vertices, and zrow's depth values)
//! is measured over the same views and bounded exactly over all orientations
//! (`distance ± the largest vertex radius`).
//!
//! The measured mesh carries the normals, so culling and shading are the firmware's: model
//! mode takes a mesh's precomputed normals instead of the cross product ([`zrow::Mesh::normals`]).
//!
//! **Emit.** A Rust file of items (`include!`-able, no inner attributes; a build script's copy
//! comes in with `zrow::include_mesh!`): `NAME`, `VERTICES`, `NORMALS`, `FACES` (`u8` or `u16`
//! indices), `MESH` (`zrow::Mesh::with_normals`) — or, for a model of triangles alone,
//! `TRIANGLES` and `COLORS` (one colour, or one per triangle) instead of `FACES`, and `MESH`
//! from `zrow::Mesh::triangles_with_normals`: no 12-byte `zrow::Face` per face, less than half
//! the flash — with [`ConvertOptions::smooth`] (`--smooth DEG`) `VERTEX_NORMALS`, one unit
//! normal per vertex ([`crate::vertex_normals`]: the file's own, or averaged from the faces
//! within the crease angle; a vertex that needs several normals is copied, before the
//! capacities are measured, so `VERTEX_SLOTS` counts the copies) — the consts `WIDTH`, `HEIGHT`, `POLYGONS`,
//! `EDGES`, `VERTEX_SLOTS`, `ACTIVE`, and `pub type Renderer = zrow::Scanline<N, WIDTH, VERTEX_SLOTS, POLYGONS,
//! ACTIVE>` — and, when `VERTEX_SLOTS` is at most 4,096, `pub type Display`, the same capacities
//! as a display's renderer is built (`zrow::scanline_for!(N, REQ, display)`: no depth row, no
//! affine cue state, 12-bit slots; for a sink that takes colours only) — every public item documented, the whole report in a header comment. Colours are built with
//! `zrow::Rgb565::new` (zrow re-exports the colour type), so the including crate needs zrow
//! alone.

use crate::camera::{light, View, FAR, NEAR};
use crate::error::Error;
use crate::format::Format;
use crate::model::{LoadedModel, ModelError, Origin};
use core::fmt::{self, Write as _};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use zrow::pixelcolor::{Rgb565, RgbColor};
use zrow::raster::{RasterVertex, MAX_FACE_VERTICES};
use zrow::{Affine, Config, Face, Mesh, ModelScene, Object, Requirements, Scalar, Vec3, Q16_16};

/// Largest distance of a vertex from its face's best-fit plane that still counts as planar,
/// as a fraction of the model's radius (the half-diagonal of its bounding box, which the
/// loader scales to 1): 10⁻⁴, i.e. 6.55 Q16.16 LSB of the normalised model, or 0.012 pixels
/// when the model spans 240 pixels. Well above the rounding of a planar face's coordinates
/// to `f32` (about 10⁻⁷), well below anything visible.
pub const PLANAR_TOLERANCE: f64 = 1e-4;

/// The margin added to every measured capacity, percent (rounded up, at least 1): covers
/// orientations neither the sampled nor the random views hit. See the module doc.
pub const MARGIN_PERCENT: u32 = 2;

/// Most vertices a model may have (16-bit indices).
pub const MAX_VERTICES: usize = u16::MAX as usize + 1;

/// Most vertices `u8` indices can address.
pub const MAX_U8_VERTICES: usize = u8::MAX as usize + 1;

/// What the converter does.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvertOptions {
    /// The number format of the emitted positions and normals.
    pub format: Format,
    /// Frame width in pixels (1..=2048).
    pub width: u16,
    /// Frame height in pixels (1..=2048).
    pub height: u16,
    /// Camera distance from the origin (the model fits the unit sphere), 0 < d < 20.
    pub distance: f32,
    /// Refuse every change (fan split, triangulation) and a non-manifold model: an error
    /// naming the face's line instead of a report line.
    pub strict: bool,
    /// Positions as compact 16-bit integers at 2^-[`COMPACT_SHIFT`]
    /// (`zrow::Vectors::Compact`): half the vertices' flash, positions rounded to 2^-14.
    pub compact: bool,
    /// The model's name (`NAME` in the emitted file, `NAME.rs` for [`write_for_build`]): ASCII
    /// letters, digits, `_` and `-`.
    pub name: String,
    /// View directions on the Fibonacci sphere (besides the six axis directions).
    pub directions: usize,
    /// Roll angles per direction, evenly spaced over a turn (at least 1).
    pub rolls: usize,
    /// Worst sampled views the local search starts from, per capacity.
    pub refine_starts: usize,
    /// Steps of each local search.
    pub refine_steps: usize,
    /// Uniformly random extra orientations measured to check the capacities.
    pub check_views: usize,
    /// Seed of the random orientations.
    pub seed: u64,
    /// Per-vertex normals for smooth shading, `VERTEX_NORMALS` ([`crate::vertex_normals`]):
    /// `Some(crease angle, degrees)` emits them, the file's own (an OBJ's `vn`) when every face
    /// corner has one, else computed from the faces with that crease angle; vertices that need
    /// several normals are split. `None`: none emitted.
    pub smooth: Option<f64>,
}

impl Default for ConvertOptions {
    /// Q16.16, 240 × 240, distance 3 (the simulator's camera), not strict, name `model`,
    /// 256 directions × 8 rolls, local search from the 8 worst views × 150 steps per
    /// capacity, 10,000 check views, seed 1.
    fn default() -> Self {
        ConvertOptions {
            format: Format::Q16_16,
            width: 240,
            height: 240,
            distance: View::default().distance,
            strict: false,
            compact: false,
            name: "model".into(),
            directions: 256,
            rolls: 8,
            refine_starts: 8,
            refine_steps: 150,
            check_views: 10_000,
            seed: 1,
            smooth: None,
        }
    }
}

/// The integer type faces index vertices with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IndexType {
    /// Up to 256 vertices.
    U8,
    /// Up to 65,536 vertices.
    U16,
}

impl IndexType {
    /// The narrowest type for `vertices` vertices (`None`: more than 65,536).
    pub fn for_vertices(vertices: usize) -> Option<Self> {
        if vertices <= MAX_U8_VERTICES {
            Some(IndexType::U8)
        } else if vertices <= MAX_VERTICES {
            Some(IndexType::U16)
        } else {
            None
        }
    }
    /// `u8` or `u16`.
    pub fn name(self) -> &'static str {
        match self {
            IndexType::U8 => "u8",
            IndexType::U16 => "u16",
        }
    }
    /// Bytes per index.
    pub fn bytes(self) -> usize {
        match self {
            IndexType::U8 => 1,
            IndexType::U16 => 2,
        }
    }
}

/// One face of the converted model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConvertedFace {
    /// Indices into [`Converted::vertices`].
    pub indices: Vec<u32>,
    /// Its colour.
    pub color: Rgb565,
    /// Where it came from.
    pub origin: Option<Origin>,
}

/// Position error of the quantised vertices (Euclidean distance to the loader's position).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct QuantError {
    /// Largest distance, normalised units.
    pub max: f64,
    /// Mean distance, normalised units.
    pub mean: f64,
    /// Largest error of one coordinate, normalised units.
    pub max_coordinate: f64,
    /// One LSB in normalised units: 2⁻¹⁶ for Q16.16; for f32 the ulp of 1.0, 2⁻²³ (the
    /// largest ulp inside the unit sphere).
    pub lsb: f64,
}

/// The views measured and what they needed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ViewStats {
    /// Sampled views: `(directions + 6) × rolls`.
    pub sampled: usize,
    /// Views measured by the local search.
    pub refined: usize,
    /// Random check views.
    pub checked: usize,
    /// Maxima over the sampled views.
    pub sampled_max: Requirements,
    /// Maxima over the sampled views and the local search (the capacities before the margin).
    pub refined_max: Requirements,
    /// Maxima over the random views.
    pub checked_max: Requirements,
    /// Random views that needed more than the capacities (refined maxima plus the margin) in
    /// some capacity; each raised the capacities to what it needed.
    pub checked_exceeding: usize,
}

/// Depth over the views.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DepthRange {
    /// Nearest and farthest eye distance of a vertex over the measured views.
    pub measured: (f64, f64),
    /// Exact bound over every orientation: `distance ∓ largest vertex radius`.
    pub bound: (f64, f64),
    /// zrow's depth values (`256 · (1 − near/w) · far/(far − near)`) at `bound`.
    pub depth: (f64, f64),
}

/// Flash bytes of the emitted data on a 32-bit target (4-byte pointers and lengths).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FlashBytes {
    /// `VERTICES`: 12 bytes each, 6 compact.
    pub vertices: usize,
    /// `NORMALS`: 12 bytes each (6 compact); and `VERTEX_NORMALS` when emitted.
    pub normals: usize,
    /// `FACES`: 12 bytes each (slice 8, colour 2, alpha 1, padding 1); for a model of
    /// triangles, `COLORS`: 2 bytes each (one for all, or one per triangle).
    pub faces: usize,
    /// The index arrays the faces point to.
    pub indices: usize,
    /// `MESH`: a `zrow::Mesh` on a 32-bit target, [`MESH_BYTES`].
    pub mesh: usize,
}

impl FlashBytes {
    /// All of it.
    pub fn total(&self) -> usize {
        self.vertices + self.normals + self.faces + self.indices + self.mesh
    }
}

/// What the converter did and found (its [`fmt::Display`] is the text the command prints and
/// the emitted file's header).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Report {
    /// The model file.
    pub file: String,
    /// Number format name.
    pub format: &'static str,
    /// Positions emitted compact ([`ConvertOptions::compact`]).
    pub compact: bool,
    /// Frame size.
    pub size: (u16, u16),
    /// Camera distance.
    pub distance: f32,
    /// Vertices emitted.
    pub vertices: usize,
    /// Faces emitted.
    pub faces: usize,
    /// Index type name.
    pub index: &'static str,
    /// The loader's normalisation: `normalised = (original − centre) · scale`.
    pub centre: [f32; 3],
    /// See `centre`.
    pub scale: f32,
    /// One line per change or finding, each starting `FILE:LINE:` when a line is to blame.
    pub notes: Vec<String>,
    /// Vertex quantisation error.
    pub position_error: QuantError,
    /// Largest error of a normal's coordinate after quantisation (face and vertex normals).
    pub normal_error: f64,
    /// The views.
    pub views: ViewStats,
    /// The emitted capacities.
    pub capacities: Requirements,
    /// The depth range.
    pub depth: DepthRange,
    /// [`zrow::scanline::ram_bytes`] at the capacities.
    pub scanline_ram: usize,
    /// [`zrow::scanline::ram_bytes_display`] at the capacities, when they allow the display's
    /// renderer (at most 4,096 vertex slots: [`zrow::scanline::Slot12`]).
    pub display_ram: Option<usize>,
    /// Frame buffer (Rgb565) plus a 16-bit z-buffer: `W·H·4`.
    pub frame_z16_ram: usize,
    /// Frame buffer plus a 32-bit z-buffer: `W·H·6`.
    pub frame_z32_ram: usize,
    /// Flash bytes of the emitted data.
    pub flash: FlashBytes,
    /// RAM of back-face culling alone (`zrow::cullonly::CullOnly`) at the capacities, when
    /// the model is one closed convex solid ([`crate::structure::closed_convex`], the core's rule): then it draws
    /// the model exactly with no depth test, and `Cheapest` in the emitted file is it.
    pub cull_only_ram: Option<usize>,
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (w, h) = self.size;
        writeln!(f, "zrow-sim convert {}", self.file)?;
        writeln!(
            f,
            "  {} vertices ({} indices), {} faces, {}{}",
            self.vertices,
            self.index,
            self.faces,
            self.format,
            if self.compact {
                ", positions compact (16-bit at 2^-14)"
            } else {
                ""
            }
        )?;
        let [cx, cy, cz] = self.centre;
        writeln!(
            f,
            "  normalised into the unit sphere: position = (original - ({cx}, {cy}, {cz})) * {}",
            self.scale
        )?;
        if self.notes.is_empty() {
            writeln!(f, "  checks: nothing changed, nothing to report")?;
        }
        for note in &self.notes {
            writeln!(f, "  {note}")?;
        }
        let e = &self.position_error;
        let s = f64::from(self.scale);
        writeln!(
            f,
            "  position error: max {:.3e} mean {:.3e} (normalised units), max {:.3e} mean \
             {:.3e} (model units); max {:.3} LSB per coordinate, {:.3} LSB as a distance",
            e.max,
            e.mean,
            e.max / s,
            e.mean / s,
            e.max_coordinate / e.lsb,
            e.max / e.lsb
        )?;
        writeln!(
            f,
            "  normal error: max {:.3e} per coordinate ({:.3} LSB)",
            self.normal_error,
            self.normal_error
                / if self.format == Format::F32.name() {
                    lsb(Format::F32)
                } else {
                    lsb(Format::Q16_16)
                }
        )?;
        let v = &self.views;
        writeln!(
            f,
            "  views at {w}x{h}, distance {}: {} sampled, {} by local search from the worst, {} \
             random checks ({} needed more than the capacities)",
            self.distance, v.sampled, v.refined, v.checked, v.checked_exceeding
        )?;
        let row = |name: &str, r: &Requirements| {
            format!(
                "    {name:<14} polygons {:>6}  edges {:>6}  active {:>5}",
                r.polygons, r.edges, r.active_polygons
            )
        };
        writeln!(f, "{}", row("sampled max", &v.sampled_max))?;
        writeln!(f, "{}", row("searched max", &v.refined_max))?;
        writeln!(f, "{}", row("random max", &v.checked_max))?;
        writeln!(
            f,
            "{} (searched max + {MARGIN_PERCENT}%, at least 1{})",
            row("emitted", &self.capacities),
            if v.checked_exceeding > 0 {
                ", raised to the random max"
            } else {
                ""
            }
        )?;
        let d = &self.depth;
        writeln!(
            f,
            "  depth: eye distance {:.4}..{:.4} measured, {:.4}..{:.4} over all orientations \
             (zrow depth {:.3}..{:.3} of 256){}",
            d.measured.0,
            d.measured.1,
            d.bound.0,
            d.bound.1,
            d.depth.0,
            d.depth.1,
            if d.bound.0 < f64::from(NEAR) {
                ": the near plane clips some views"
            } else {
                ""
            }
        )?;
        let display = match self.display_ram {
            Some(ram) => format!(" ({ram} as a display's: `Display`)"),
            None => String::new(),
        };
        writeln!(
            f,
            "  RAM: scan-line {} bytes{display}; frame buffer + 16-bit z-buffer {} bytes, + \
             32-bit z-buffer {} bytes",
            self.scanline_ram, self.frame_z16_ram, self.frame_z32_ram
        )?;
        match self.cull_only_ram {
            Some(ram) => writeln!(
                f,
                "  structure: one closed convex solid: back-face culling alone draws it exactly \
                 (Cheapest = zrow::cullonly::CullOnly, {ram} bytes, no depth test)"
            )?,
            None => writeln!(
                f,
                "  structure: not one closed convex solid: Cheapest = the scan-line Renderer"
            )?,
        }
        let fl = &self.flash;
        write!(
            f,
            "  flash (32-bit target): {} bytes = vertices {} + normals {} + faces {} + indices \
             {} + mesh {}",
            fl.total(),
            fl.vertices,
            fl.normals,
            fl.faces,
            fl.indices,
            fl.mesh
        )
    }
}

/// A converted model: the data, the capacities, the report and the Rust source.
#[derive(Clone, Debug, PartialEq)]
pub struct Converted {
    /// The number format.
    pub format: Format,
    /// The index type.
    pub index: IndexType,
    /// The emitted positions, exactly (every Q16.16 and f32 value is an `f64`).
    pub vertices: Vec<[f64; 3]>,
    /// For each emitted vertex, its index in the loaded model's `positions` (vertices are
    /// renumbered in order of first use; unused ones are dropped).
    pub source: Vec<usize>,
    /// The faces.
    pub faces: Vec<ConvertedFace>,
    /// The emitted normals, exactly, one per face.
    pub normals: Vec<[f64; 3]>,
    /// The emitted per-vertex normals, exactly, one per vertex ([`ConvertOptions::smooth`]), or
    /// empty.
    pub vertex_normals: Vec<[f64; 3]>,
    /// The emitted capacities (`width` is the frame width).
    pub capacities: Requirements,
    /// What was done and found.
    pub report: Report,
    /// The Rust source.
    pub rust: String,
}

impl Converted {
    /// The positions in format `N`. Exact when `N` is the converted format (every value lies
    /// in the unit sphere, where Q16.16 values have at most 17 significant bits and so convert
    /// through `f32` exactly).
    pub fn vertices_in<N: Scalar>(&self) -> Option<Vec<Vec3<N>>> {
        to_vec3(&self.vertices)
    }
    /// The normals in format `N` (exact as for [`Converted::vertices_in`]).
    pub fn normals_in<N: Scalar>(&self) -> Option<Vec<Vec3<N>>> {
        to_vec3(&self.normals)
    }
    /// Calls `f` with the model as a zrow [`Mesh`] in format `N`, with its normals, as the
    /// firmware will draw it (`None`: a value does not fit `N`). Indices are `u32` here
    /// whatever [`Converted::index`] says: zrow draws `u8`, `u16` and `u32` meshes bit for bit
    /// alike.
    pub fn with_mesh<N: Scalar, R>(&self, f: impl FnOnce(&Mesh<'_, N, u32>) -> R) -> Option<R> {
        let vertices = self.vertices_in::<N>()?;
        let normals = self.normals_in::<N>()?;
        let faces = zrow_faces(&self.faces);
        Some(f(&Mesh::with_normals(&vertices, &faces, &normals)))
    }
}

fn to_vec3<N: Scalar>(values: &[[f64; 3]]) -> Option<Vec<Vec3<N>>> {
    values
        .iter()
        .map(|v| Vec3::from_f32(v.map(|c| c as f32)))
        .collect()
}

fn zrow_faces(faces: &[ConvertedFace]) -> Vec<Face<'_, u32>> {
    faces
        .iter()
        .map(|f| Face {
            indices: &f.indices,
            color: f.color,
            alpha: 255,
        })
        .collect()
}

/// Loads the model at `path` ([`crate::model::load`]) and converts it ([`convert_model`]).
pub fn convert(path: &Path, opts: &ConvertOptions) -> Result<Converted, Error> {
    convert_model(&crate::model::load(path)?, opts)
}

/// For build scripts: converts the model at `path` and writes `out_dir/NAME.rs` (`NAME` from
/// `name`, which overrides [`ConvertOptions::name`]), prints `cargo:rerun-if-changed=` for the
/// model (and its MTL file when it is an OBJ, by the same stem), and returns the report.
/// Include the result with `zrow::include_mesh!("NAME")`.
pub fn write_for_build(
    path: &Path,
    opts: &ConvertOptions,
    out_dir: &Path,
    name: &str,
) -> Result<Report, Error> {
    let opts = ConvertOptions {
        name: name.to_owned(),
        ..opts.clone()
    };
    println!("cargo:rerun-if-changed={}", path.display());
    let mtl = path.with_extension("mtl");
    if crate::model::ModelFormat::of(path) == Some(crate::model::ModelFormat::Obj) && mtl.exists() {
        println!("cargo:rerun-if-changed={}", mtl.display());
    }
    let converted = convert(path, &opts)?;
    let out: PathBuf = out_dir.join(format!("{name}.rs"));
    std::fs::write(&out, &converted.rust).map_err(|source| Error::Io {
        path: out.display().to_string(),
        action: "write",
        source,
    })?;
    Ok(converted.report)
}

fn model_error(file: &str, at: Option<Origin>, message: String) -> Error {
    Error::Model(ModelError {
        file: file.to_owned(),
        at,
        message,
    })
}

/// `FILE:LINE: ` or `FILE: `.
fn place(file: &str, at: Option<Origin>) -> String {
    match at {
        Some(at) => format!("{file}:{at}: "),
        None => format!("{file}: "),
    }
}

type P3 = [f64; 3];

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Newell's normal of a polygon (not normalised; its length is twice the area for a planar
/// polygon) and the centroid of its vertices.
fn newell(points: &[P3]) -> (P3, P3) {
    let mut c = [0.0; 3];
    for p in points {
        for (ci, pi) in c.iter_mut().zip(p) {
            *ci += pi / points.len() as f64;
        }
    }
    (crate::vertex_normals::newell(points), c)
}

fn unit(n: P3) -> Option<P3> {
    let len = dot(n, n).sqrt();
    (len > 1e-300).then(|| n.map(|c| c / len))
}

/// Largest distance of a vertex from the best-fit plane (0 for a degenerate polygon).
fn planarity(points: &[P3]) -> f64 {
    let (n, c) = newell(points);
    match unit(n) {
        Some(n) => points
            .iter()
            .map(|&p| dot(sub(p, c), n).abs())
            .fold(0.0, f64::max),
        None => 0.0,
    }
}

/// Bytes of a `zrow::Mesh` on a 32-bit target (its positions, faces, face normals and vertex
/// normals: four two-variant enums over slices), checked at compile time by `zrow-byo` when
/// built for one.
pub const MESH_BYTES: usize = 52;

/// Compact positions ([`ConvertOptions::compact`]) are integers at 2^-`COMPACT_SHIFT`: the unit
/// sphere in ±16,384, with room to spare in 16 bits.
pub const COMPACT_SHIFT: u8 = 14;

/// Rounds a position to a compact integer's value at 2^-[`COMPACT_SHIFT`] (exact in both
/// formats), returned as `f64`.
fn quantise_compact(x: f64) -> f64 {
    let unit = f64::from(1u32 << COMPACT_SHIFT);
    (x * unit).round() / unit
}

/// Rounds to the format; returns the value as `f64` (exact).
fn quantise(format: Format, x: f64) -> f64 {
    match format {
        Format::Q16_16 => (x * 65536.0).round() / 65536.0,
        Format::F32 => f64::from(x as f32),
    }
}

fn lsb(format: Format) -> f64 {
    match format {
        Format::Q16_16 => 1.0 / 65536.0,
        Format::F32 => f64::from(f32::EPSILON),
    }
}

/// Converts a loaded model (see the module doc for every step).
///
/// Errors: bad options ([`Error::Usage`]); under `strict` a change or a non-manifold edge,
/// else a face zrow rejects (non-convex, …) or more than 65,536 vertices
/// ([`Error::Model`] naming the file and line).
pub fn convert_model(model: &LoadedModel, opts: &ConvertOptions) -> Result<Converted, Error> {
    convert_model_with(model, opts, &|_, _| {})
}

/// [`convert_model`], calling `progress(done, total)` as views are measured (from several
/// threads; the command line draws a progress bar with it).
pub fn convert_model_with(
    model: &LoadedModel,
    opts: &ConvertOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Converted, Error> {
    check_options(opts)?;
    let file = model.file.as_str();
    let mut notes = Vec::new();
    let pos: Vec<P3> = model.positions.iter().map(|p| p.map(f64::from)).collect();

    // 1. Fan splits made by the loader: consecutive faces from one line sharing the first
    // vertex (a file line holds one face, so only the split makes several).
    let mut k = 0;
    while k < model.faces.len() {
        let first = &model.faces[k];
        let mut end = k + 1;
        while let Some(next) = model.faces.get(end) {
            let same = first.origin.is_some()
                && next.origin == first.origin
                && next.indices.first() == first.indices.first();
            if !same {
                break;
            }
            end += 1;
        }
        if end - k > 1 {
            let n: usize = model.faces[k..end]
                .iter()
                .map(|f| f.indices.len() - 2)
                .sum::<usize>()
                + 2;
            let msg = format!(
                "polygon with {n} vertices (more than {MAX_FACE_VERTICES}) split into a fan \
                 of {} convex polygons",
                end - k
            );
            if opts.strict {
                return Err(model_error(file, first.origin, format!("{msg} (--strict)")));
            }
            notes.push(format!("{}{msg}", place(file, first.origin)));
        }
        k = end;
    }

    // 2. Planarity: non-planar faces become fans of triangles (with the file's corner normals,
    // kept beside them for smooth shading).
    let mut faces: Vec<ConvertedFace> = Vec::with_capacity(model.faces.len());
    let mut corner_normals: Vec<Vec<u32>> = Vec::with_capacity(model.faces.len());
    for face in &model.faces {
        let points: Vec<P3> = face
            .indices
            .iter()
            .filter_map(|&i| pos.get(i as usize).copied())
            .collect();
        let off = if points.len() > 3 {
            planarity(&points)
        } else {
            0.0
        };
        if off > PLANAR_TOLERANCE {
            let msg = format!(
                "face with {} vertices is not planar (a vertex is {off:.3e} from its best-fit \
                 plane, tolerance {PLANAR_TOLERANCE:e})",
                points.len()
            );
            if opts.strict {
                return Err(model_error(file, face.origin, format!("{msg} (--strict)")));
            }
            notes.push(format!(
                "{}{msg}: split into {} triangles (fan)",
                place(file, face.origin),
                points.len() - 2
            ));
            for w in 1..face.indices.len() - 1 {
                faces.push(ConvertedFace {
                    indices: vec![face.indices[0], face.indices[w], face.indices[w + 1]],
                    color: face.color,
                    origin: face.origin,
                });
                corner_normals.push(
                    [0, w, w + 1]
                        .iter()
                        .filter_map(|&k| face.normals.get(k).copied())
                        .collect(),
                );
            }
        } else {
            faces.push(ConvertedFace {
                indices: face.indices.clone(),
                color: face.color,
                origin: face.origin,
            });
            corner_normals.push(face.normals.clone());
        }
    }

    // 3. Unused vertices dropped.
    let mut remap = vec![u32::MAX; pos.len()];
    let mut kept: Vec<usize> = Vec::new();
    for face in &mut faces {
        for i in &mut face.indices {
            let slot = &mut remap[*i as usize];
            if *slot == u32::MAX {
                *slot = kept.len() as u32;
                kept.push(*i as usize);
            }
            *i = *slot;
        }
    }
    if kept.len() < pos.len() {
        notes.push(format!(
            "{}{} vertices no face uses dropped",
            place(file, None),
            pos.len() - kept.len()
        ));
    }
    let mut exact: Vec<P3> = kept.iter().map(|&i| pos[i]).collect();

    // 4. Manifold check (on the vertices as the file shares them).
    manifold(file, &faces, opts.strict, &mut notes)?;

    // 5. Per-vertex normals, on request: vertices split where they need several.
    let smooth = opts.smooth.map(|crease| {
        let indices: Vec<&[u32]> = faces.iter().map(|f| &f.indices[..]).collect();
        let corners: Vec<&[u32]> = corner_normals.iter().map(|c| &c[..]).collect();
        let (split, given) = crate::vertex_normals::from_file_or_faces(
            &exact,
            &indices,
            &model.normals,
            &corners,
            crease,
        );
        let from = if given {
            "the file's normals (vn)".to_owned()
        } else {
            format!("averaged from the faces, crease angle {crease}°")
        };
        notes.push(format!(
            "{}smooth shading: vertex normals {from}; {} vertices become {} ({} copies where a \
             vertex needs several normals)",
            place(file, None),
            exact.len(),
            split.source.len(),
            split.source.len() - exact.len().min(split.source.len())
        ));
        kept = split.source.iter().map(|&i| kept[i as usize]).collect();
        exact = split.source.iter().map(|&i| exact[i as usize]).collect();
        for (face, renumbered) in faces.iter_mut().zip(split.faces) {
            face.indices = renumbered;
        }
        (split.normals, split.source)
    });
    let (smooth, unsplit) = match smooth {
        Some((normals, source)) => (Some(normals), Some(source)),
        None => (None, None),
    };
    let index = IndexType::for_vertices(kept.len()).ok_or_else(|| {
        model_error(
            file,
            None,
            format!(
                "the model uses {} vertices, at most {MAX_VERTICES} supported (16-bit indices): \
                 simplify it",
                kept.len()
            ),
        )
    })?;

    // 6. Quantisation.
    let (vertices, position_lsb): (Vec<P3>, f64) = if opts.compact {
        let v = exact.iter().map(|p| p.map(quantise_compact)).collect();
        (v, 1.0 / f64::from(1u32 << COMPACT_SHIFT))
    } else {
        let v = exact
            .iter()
            .map(|p| p.map(|c| quantise(opts.format, c)))
            .collect();
        (v, lsb(opts.format))
    };
    let position_error = quant_error(&exact, &vertices, position_lsb);
    let mut degenerate = (0usize, None);
    let mut normals = Vec::with_capacity(faces.len());
    let mut normal_error = 0.0f64;
    let mut quantise_normal = |n: P3| {
        let q = if opts.compact {
            n.map(quantise_compact)
        } else {
            n.map(|c| quantise(opts.format, c))
        };
        for (a, b) in n.iter().zip(&q) {
            normal_error = normal_error.max((a - b).abs());
        }
        q
    };
    for face in &faces {
        let points: Vec<P3> = face.indices.iter().map(|&i| exact[i as usize]).collect();
        let n = unit(newell(&points).0);
        if n.is_none() {
            if degenerate.0 == 0 {
                degenerate.1 = face.origin;
            }
            degenerate.0 += 1;
        }
        normals.push(quantise_normal(n.unwrap_or([0.0; 3])));
    }
    if degenerate.0 > 0 {
        notes.push(format!(
            "{}{} faces have zero area (kept; zrow skips them), the first here",
            place(file, degenerate.1),
            degenerate.0
        ));
    }
    let vertex_normals: Vec<P3> = smooth
        .unwrap_or_default()
        .into_iter()
        .map(&mut quantise_normal)
        .collect();

    // 7. Requirements over the views.
    let (views, measured_depth) = match opts.format {
        Format::Q16_16 => measure_all::<Q16_16>(file, &vertices, &faces, &normals, opts, progress)?,
        Format::F32 => measure_all::<f32>(file, &vertices, &faces, &normals, opts, progress)?,
    };
    // The check views never lower the capacities; if one needed more, it raises them (and
    // the report says so).
    let capacities = with_margin(&views.refined_max).max(views.checked_max);
    let capacities = Requirements {
        width: opts.width,
        ..capacities
    };
    let radius = vertices
        .iter()
        .map(|&v| dot(v, v).sqrt())
        .fold(0.0, f64::max);
    let d = f64::from(opts.distance);
    let bound = (
        (d - radius).max(f64::from(NEAR)),
        (d + radius).min(f64::from(FAR)),
    );
    let zdepth = |w: f64| {
        let (n, f) = (f64::from(NEAR), f64::from(FAR));
        f64::from(zrow::geometry::DEPTH_RANGE) * (1.0 - n / w) * f / (f - n)
    };
    let depth = DepthRange {
        measured: measured_depth,
        bound,
        depth: (zdepth(bound.0), zdepth(bound.1)),
    };
    let (w, h) = (opts.width as usize, opts.height as usize);
    let scanline_ram = match opts.format {
        Format::Q16_16 => zrow::scanline::ram_bytes::<Q16_16>(&capacities),
        Format::F32 => zrow::scanline::ram_bytes::<f32>(&capacities),
    };
    let display_ram = (capacities.vertices as usize
        <= <zrow::scanline::Slot12 as zrow::scanline::Slot>::MAX_SLOTS)
        .then(|| match opts.format {
            Format::Q16_16 => zrow::scanline::ram_bytes_display::<Q16_16>(&capacities),
            Format::F32 => zrow::scanline::ram_bytes_display::<f32>(&capacities),
        });
    let flash = FlashBytes {
        vertices: if opts.compact { 6 } else { 12 } * vertices.len(),
        normals: if opts.compact { 6 } else { 12 } * (normals.len() + vertex_normals.len()),
        faces: if triangles_only(&faces) {
            2 * triangle_colors(&faces).len()
        } else {
            12 * faces.len()
        },
        indices: faces.iter().map(|f| f.indices.len()).sum::<usize>() * index.bytes(),
        mesh: MESH_BYTES,
    };
    let report = Report {
        file: file.to_owned(),
        format: opts.format.name(),
        compact: opts.compact,
        size: (opts.width, opts.height),
        distance: opts.distance,
        vertices: vertices.len(),
        faces: faces.len(),
        index: index.name(),
        centre: model.centre,
        scale: model.scale,
        notes,
        position_error,
        normal_error,
        views,
        capacities,
        depth,
        scanline_ram,
        display_ram,
        frame_z16_ram: w * h * 4,
        frame_z32_ram: w * h * 6,
        flash,
        cull_only_ram: None,
    };
    let mut converted = Converted {
        format: opts.format,
        index,
        vertices,
        source: kept,
        faces,
        normals,
        vertex_normals,
        capacities,
        report,
        rust: String::new(),
    };
    // Judged on the emitted values (the format's rounding), as the firmware will hold them,
    // with the copies smooth shading made of a vertex shared again: the same positions, the
    // same solid (culling alone draws it exactly either way).
    let convex = match opts.format {
        Format::Q16_16 => closed_convex_shared::<Q16_16>(&converted, unsplit.as_deref()),
        Format::F32 => closed_convex_shared::<f32>(&converted, unsplit.as_deref()),
    };
    if convex == Some(true) {
        let (p, e) = (capacities.polygons as usize, capacities.edges as usize);
        converted.report.cull_only_ram = Some(match opts.format {
            Format::Q16_16 => cull_only_ram::<Q16_16>(w, p, e),
            Format::F32 => cull_only_ram::<f32>(w, p, e),
        });
    }
    converted.rust = emit(&converted, &opts.name);
    Ok(converted)
}

/// [`crate::structure::closed_convex`] of the converted mesh in `N`, its vertices' copies
/// (`unsplit[k]`: the vertex copy `k` was made of) shared again.
fn closed_convex_shared<N: Scalar>(c: &Converted, unsplit: Option<&[u32]>) -> Option<bool> {
    let Some(unsplit) = unsplit else {
        return c.with_mesh::<N, _>(crate::structure::closed_convex);
    };
    let copies = c.vertices_in::<N>()?;
    let mut shared =
        vec![Vec3::<N>::default(); unsplit.iter().max().map_or(0, |&m| m as usize + 1)];
    for (&to, v) in unsplit.iter().zip(copies) {
        shared[to as usize] = v;
    }
    let faces: Vec<ConvertedFace> = c
        .faces
        .iter()
        .map(|f| ConvertedFace {
            indices: f
                .indices
                .iter()
                .map(|&i| unsplit.get(i as usize).copied().unwrap_or(i))
                .collect(),
            ..f.clone()
        })
        .collect();
    let normals = c.normals_in::<N>()?;
    let faces = zrow_faces(&faces);
    Some(crate::structure::closed_convex(&Mesh::with_normals(
        &shared, &faces, &normals,
    )))
}

/// `CullOnly::<N, W, P, E>::RAM_BYTES` at run-time capacities: linear in each (computed from
/// the struct's size at small ones; padding may add a few bytes).
fn cull_only_ram<N: Scalar>(w: usize, p: usize, e: usize) -> usize {
    type C<N, const W: usize, const P: usize, const E: usize> =
        zrow::cullonly::CullOnly<N, W, P, E>;
    let base = C::<N, 1, 1, 1>::RAM_BYTES;
    let slope = [
        C::<N, 65, 1, 1>::RAM_BYTES - base,
        C::<N, 1, 65, 1>::RAM_BYTES - base,
        C::<N, 1, 1, 65>::RAM_BYTES - base,
    ];
    let caps = [w.max(1), p.max(1), e.max(1)];
    base + caps
        .iter()
        .zip(slope)
        .map(|(&c, s)| (c - 1) * s / 64)
        .sum::<usize>()
}

fn check_options(opts: &ConvertOptions) -> Result<(), Error> {
    let usage = |m: String| Err(Error::Usage(m));
    let max = zrow::raster::MAX_VIEWPORT;
    if !(1..=max).contains(&opts.width) || !(1..=max).contains(&opts.height) {
        return usage(format!(
            "bad size {}x{}: each side must be 1..={max}",
            opts.width, opts.height
        ));
    }
    View {
        distance: opts.distance,
        ..View::default()
    }
    .validate()
    .or_else(|m| usage(format!("bad view: {m}")))?;
    let name_ok = !opts.name.is_empty()
        && opts
            .name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
    if !name_ok {
        return usage(format!(
            "bad name `{}`: use ASCII letters, digits, `_` and `-`",
            opts.name.escape_debug()
        ));
    }
    if opts.rolls == 0 {
        return usage("rolls must be at least 1".into());
    }
    if opts.check_views > MAX_VIEWS {
        return usage(format!(
            "bad --checks {}: at most {MAX_VIEWS} (a million views of a 1,000-face model take \
             minutes; the default is {})",
            opts.check_views,
            ConvertOptions::default().check_views
        ));
    }
    let sampled = (opts.directions.saturating_add(6)).saturating_mul(opts.rolls);
    let searched = (4 * opts.refine_starts).saturating_mul(opts.refine_steps);
    if sampled > MAX_VIEWS || searched > MAX_VIEWS {
        return usage(format!(
            "too many views: (directions + 6) x rolls and 4 x refine starts x steps must each \
             be at most {MAX_VIEWS}"
        ));
    }
    Ok(())
}

/// Edges used by more than two faces, or twice in one direction: reported (an error under
/// `strict`). Open edges are counted for information.
fn manifold(
    file: &str,
    faces: &[ConvertedFace],
    strict: bool,
    notes: &mut Vec<String>,
) -> Result<(), Error> {
    // Per undirected edge: uses, and faces per direction.
    let mut uses: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    let mut over = (0usize, None::<(usize, Option<Origin>)>);
    let mut same_dir = (0usize, None::<(usize, Option<Origin>)>);
    for (no, face) in faces.iter().enumerate() {
        let n = face.indices.len();
        for k in 0..n {
            let (a, b) = (face.indices[k], face.indices[(k + 1) % n]);
            let entry = uses.entry((a.min(b), a.max(b))).or_default();
            let (fwd, back) = entry;
            if a < b {
                *fwd += 1;
            } else {
                *back += 1;
            }
            if *fwd + *back == 3 {
                over.0 += 1;
                over.1.get_or_insert((no, face.origin));
            }
            let this = if a < b { *fwd } else { *back };
            if this == 2 {
                same_dir.0 += 1;
                same_dir.1.get_or_insert((no, face.origin));
            }
        }
    }
    let open = uses.values().filter(|(f, b)| f + b == 1).count();
    for (count, first, what) in [
        (over.0, over.1, "used by more than two faces"),
        (
            same_dir.0,
            same_dir.1,
            "used twice in the same direction (inconsistent orientation: back-face culling \
             will drop faces that face the camera)",
        ),
    ] {
        if let Some((no, origin)) = first {
            let msg = format!(
                "non-manifold: {count} edges {what}; the first at face {no} (0-based, after \
                 splits)"
            );
            if strict {
                return Err(model_error(file, origin, format!("{msg} (--strict)")));
            }
            notes.push(format!("{}{msg}", place(file, origin)));
        }
    }
    if open > 0 {
        notes.push(format!(
            "{}open mesh: {open} edges belong to one face only (kept: holes show)",
            place(file, None)
        ));
    }
    Ok(())
}

/// Distances between the exact and the quantised positions.
pub fn quant_error(exact: &[[f64; 3]], quantised: &[[f64; 3]], lsb: f64) -> QuantError {
    let mut e = QuantError {
        lsb,
        ..QuantError::default()
    };
    let mut sum = 0.0;
    for (a, b) in exact.iter().zip(quantised) {
        let d = sub(*a, *b);
        let dist = dot(d, d).sqrt();
        sum += dist;
        e.max = e.max.max(dist);
        e.max_coordinate = d.iter().fold(e.max_coordinate, |m, c| m.max(c.abs()));
    }
    e.mean = if exact.is_empty() {
        0.0
    } else {
        sum / exact.len() as f64
    };
    e
}

/// A rotation (rows), model → world.
type Rot = [[f64; 3]; 3];

/// The rotation that turns direction `d` (unit) to +z (towards the eye), then rolls by `roll`
/// radians about z.
fn facing(d: P3, roll: f64) -> Rot {
    // A vector not parallel to d.
    let helper = if d[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cross = |a: P3, b: P3| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let x = unit(cross(helper, d)).unwrap_or([1.0, 0.0, 0.0]);
    let y = cross(d, x);
    let (s, c) = roll.sin_cos();
    let xr = [0, 1, 2].map(|k| c * x[k] - s * y[k]);
    let yr = [0, 1, 2].map(|k| s * x[k] + c * y[k]);
    [xr, yr, d]
}

/// Shoemake's uniformly random rotation from three uniforms in [0, 1).
fn random_rotation(u: [f64; 3]) -> Rot {
    use std::f64::consts::TAU;
    let (a, b) = ((1.0 - u[0]).sqrt(), u[0].sqrt());
    let (x, y, z, w) = (
        a * (TAU * u[1]).sin(),
        a * (TAU * u[1]).cos(),
        b * (TAU * u[2]).sin(),
        b * (TAU * u[2]).cos(),
    );
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - z * w),
            2.0 * (x * z + y * w),
        ],
        [
            2.0 * (x * y + z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - x * w),
        ],
        [
            2.0 * (x * z - y * w),
            2.0 * (y * z + x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// The sampled orientations: `directions` on a Fibonacci sphere plus the six axis directions,
/// each with `rolls` rolls.
pub fn sampled_rotations(directions: usize, rolls: usize) -> Vec<[[f64; 3]; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut dirs: Vec<P3> = (0..directions)
        .map(|k| {
            let z = 1.0 - (2 * k + 1) as f64 / directions as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * k as f64;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect();
    for axis in 0..3 {
        for sign in [1.0, -1.0] {
            let mut d = [0.0; 3];
            d[axis] = sign;
            dirs.push(d);
        }
    }
    let mut out = Vec::with_capacity(dirs.len() * rolls);
    for d in dirs {
        for r in 0..rolls {
            out.push(facing(d, std::f64::consts::TAU * r as f64 / rolls as f64));
        }
    }
    out
}

/// xorshift64: uniforms in [0, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        let s = &mut self.0;
        *s ^= *s << 13;
        *s ^= *s >> 7;
        *s ^= *s << 17;
        (*s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `count` uniformly random rotations (xorshift64 from `seed`).
pub fn random_rotations(count: usize, seed: u64) -> Vec<[[f64; 3]; 3]> {
    random_rotation_stream(seed).take(count).collect()
}

/// Uniformly random rotations without end, the sequence [`random_rotations`] begins.
fn random_rotation_stream(seed: u64) -> impl Iterator<Item = Rot> {
    let mut rng = Rng(seed.max(1));
    std::iter::repeat_with(move || random_rotation([rng.next(), rng.next(), rng.next()]))
}

/// A rotation by `angle` radians about a uniformly random axis (Rodrigues).
fn small_rotation(rng: &mut Rng, angle: f64) -> Rot {
    let z = 2.0 * rng.next() - 1.0;
    let phi = std::f64::consts::TAU * rng.next();
    let r = (1.0 - z * z).max(0.0).sqrt();
    let [x, y, z] = [r * phi.cos(), r * phi.sin(), z];
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
}

/// `a · b` (b first, then a).
fn compose(a: &Rot, b: &Rot) -> Rot {
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

/// A measured capacity plus [`MARGIN_PERCENT`], rounded up, at least 1.
pub fn with_margin(req: &Requirements) -> Requirements {
    req.with_margin(MARGIN_PERCENT)
}

/// What `mesh` needs seen in orientation `rot` by the converter's camera.
pub fn measure_view<N: Scalar, I: zrow::MeshIndex>(
    mesh: &Mesh<'_, N, I>,
    rot: &[[f64; 3]; 3],
    opts: &ConvertOptions,
) -> Result<Requirements, zrow::Error> {
    measure_view_in(mesh, rot, opts, &mut [])
}

/// [`measure_view`] with a vertex buffer of `slots` ([`zrow::requirements_with`]: the same
/// result, faster with room for the mesh's vertices).
fn measure_view_in<N: Scalar, I: zrow::MeshIndex>(
    mesh: &Mesh<'_, N, I>,
    rot: &[[f64; 3]; 3],
    opts: &ConvertOptions,
    slots: &mut [RasterVertex<N>],
) -> Result<Requirements, zrow::Error> {
    let r = rot.map(|row| row.map(|c| c as f32));
    let transform = Affine::from_f32([
        [r[0][0], r[0][1], r[0][2], 0.0],
        [r[1][0], r[1][1], r[1][2], 0.0],
        [r[2][0], r[2][1], r[2][2], 0.0],
    ])
    .ok_or(zrow::Error::BadConfig)?;
    let camera = View {
        yaw_deg: 0.0,
        pitch_deg: 0.0,
        distance: opts.distance,
    }
    .camera::<N>()
    .ok_or(zrow::Error::BadConfig)?;
    let objects = [Object { mesh, transform }];
    let scene = ModelScene {
        objects: &objects,
        camera,
        light: light(),
    };
    let cfg = Config::model(opts.width, opts.height);
    zrow::requirements_with(&scene, &cfg, slots)
}

/// Most views of each kind (sampled, searched, random checks) a conversion measures.
pub const MAX_VIEWS: usize = 1_000_000;

/// Views measured per batch of random checks (a batch of rotations is held at once).
const CHECK_BATCH: usize = 4096;

/// Measures every sampled and random view; returns the statistics and the measured eye
/// distance range. The views are split over the machine's cores (each with a vertex buffer of
/// its own, so every shared vertex is projected once per view); the results do not depend on
/// the number of cores. `progress` is called with the views measured so far and the total.
fn measure_all<N: Scalar + Send + Sync>(
    file: &str,
    vertices: &[P3],
    faces: &[ConvertedFace],
    normals: &[P3],
    opts: &ConvertOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(ViewStats, (f64, f64)), Error> {
    let misfit = || {
        model_error(
            file,
            None,
            format!("a position does not fit the {} format", N::NAME),
        )
    };
    let verts: Vec<Vec3<N>> = to_vec3(vertices).ok_or_else(misfit)?;
    let norms: Vec<Vec3<N>> = to_vec3(normals).ok_or_else(misfit)?;
    let zfaces = zrow_faces(faces);
    // The data the firmware will hold, normals included (model mode culls and shades with
    // them).
    let mesh = Mesh::with_normals(&verts, &zfaces, &norms);
    let blame = |e: zrow::Error| match e.face() {
        Some(face) => model_error(
            file,
            faces.get(face as usize).and_then(|f| f.origin),
            e.to_string(),
        ),
        None => Error::Scene {
            file: file.to_owned(),
            line: None,
            error: e,
        },
    };
    let d = f64::from(opts.distance);
    // One view: what it needs, and its eye distance range.
    let measure = |rot: &Rot, slots: &mut Vec<RasterVertex<N>>| {
        let mut depth = (f64::INFINITY, f64::NEG_INFINITY);
        for v in vertices {
            let w = d - dot(rot[2], *v);
            depth = (depth.0.min(w), depth.1.max(w));
        }
        let req = measure_view_in(&mesh, rot, opts, slots).map_err(blame)?;
        Ok::<_, Error>((req, depth))
    };
    let sampled = sampled_rotations(opts.directions, opts.rolls);
    let starts = opts.refine_starts.min(sampled.len());
    let total = sampled.len() + 4 * starts * opts.refine_steps + opts.check_views;
    let done = std::sync::atomic::AtomicUsize::new(0);
    let tick = |n: usize| {
        let now = done.fetch_add(n, std::sync::atomic::Ordering::Relaxed) + n;
        progress(now, total);
    };
    let mut depth = (f64::INFINITY, f64::NEG_INFINITY);
    let mut widen = |(lo, hi): (f64, f64)| depth = (depth.0.min(lo), depth.1.max(hi));
    let mut stats = ViewStats::default();

    let mut seen: Vec<(Requirements, Rot)> = Vec::with_capacity(sampled.len());
    for (rot, r) in sampled
        .iter()
        .zip(on_cores(&sampled, vertices.len(), |rot, slots| {
            let r = measure(rot, slots);
            tick(1);
            r
        }))
    {
        let (req, range) = r?;
        widen(range);
        stats.sampled_max = stats.sampled_max.max(req);
        stats.sampled += 1;
        seen.push((req, *rot));
    }
    // Local search from the worst sampled views, one capacity at a time: turn the model by a
    // random small rotation, keep the new orientation when it needs at least as much. Each
    // search has a random stream of its own, so the searches run on any number of cores.
    stats.refined_max = stats.sampled_max;
    let keys: [fn(&Requirements) -> u32; 4] = [
        |r| r.polygons,
        |r| r.edges,
        |r| r.vertices,
        |r| r.active_polygons,
    ];
    let mut searches = Vec::new();
    for (k, key) in keys.iter().enumerate() {
        seen.sort_by_key(|(r, _)| std::cmp::Reverse(key(r)));
        searches.extend(
            seen.iter()
                .take(starts)
                .enumerate()
                .map(|(s, &start)| (k, s, start)),
        );
    }
    let sampled_max = stats.sampled_max;
    let searched = on_cores(
        &searches,
        vertices.len(),
        |&(k, s, (mut best, mut rot)), slots| {
            let key = keys[k];
            let stream = (k * starts + s) as u64 + 1;
            let mut rng = Rng((opts.seed ^ stream.wrapping_mul(0x9E37_79B9_7F4A_7C15)) | 1);
            let mut out = (sampled_max, (f64::INFINITY, f64::NEG_INFINITY), 0);
            for step in 0..opts.refine_steps {
                // 4° down to 0.04°.
                let t = step as f64 / opts.refine_steps.max(1) as f64;
                let angle = (4.0f64 * 0.01f64.powf(t)).to_radians();
                let turned = compose(&small_rotation(&mut rng, angle), &rot);
                let (req, (lo, hi)) = measure(&turned, slots)?;
                tick(1);
                out = (
                    out.0.max(req),
                    (out.1 .0.min(lo), out.1 .1.max(hi)),
                    out.2 + 1,
                );
                if key(&req) >= key(&best) {
                    (best, rot) = (req, turned);
                }
            }
            Ok::<_, Error>(out)
        },
    );
    for r in searched {
        let (max, range, count) = r?;
        widen(range);
        stats.refined_max = stats.refined_max.max(max);
        stats.refined += count;
    }
    let capacities = with_margin(&stats.refined_max);
    let mut rotations = random_rotation_stream(opts.seed);
    let mut left = opts.check_views;
    while left > 0 {
        let batch: Vec<Rot> = rotations.by_ref().take(left.min(CHECK_BATCH)).collect();
        left -= batch.len();
        for r in on_cores(&batch, vertices.len(), |rot, slots| {
            let r = measure(rot, slots);
            tick(1);
            r
        }) {
            let (req, range) = r?;
            widen(range);
            if req.polygons > capacities.polygons
                || req.edges > capacities.edges
                || req.vertices > capacities.vertices
                || req.active_polygons > capacities.active_polygons
            {
                stats.checked_exceeding += 1;
            }
            stats.checked_max = stats.checked_max.max(req);
            stats.checked += 1;
        }
    }
    Ok((stats, depth))
}

/// `f` on every item, the items split in contiguous runs over the machine's cores (each run
/// with a vertex buffer of `vertices` slots, plus room for what clipping makes); the results
/// in item order.
fn on_cores<T: Sync, R: Send, N: Scalar + Send>(
    items: &[T],
    vertices: usize,
    f: impl Fn(&T, &mut Vec<RasterVertex<N>>) -> R + Sync,
) -> Vec<R> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let run = items.len().div_ceil(cores).max(1);
    let slots = || vec![RasterVertex::<N>::default(); vertices + 256];
    std::thread::scope(|s| {
        let workers: Vec<_> = items
            .chunks(run)
            .map(|chunk| {
                let f = &f;
                s.spawn(move || {
                    let mut slots = slots();
                    chunk.iter().map(|t| f(t, &mut slots)).collect::<Vec<R>>()
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect()
    })
}

/// A value as a Rust expression of the format.
fn literal(format: Format, x: f64) -> String {
    match format {
        Format::Q16_16 => format!("zrow::Q16_16::from_bits({})", (x * 65536.0) as i32),
        Format::F32 => format!("{:?}f32", x as f32),
    }
}

fn vec3_literal(format: Format, v: &P3) -> String {
    format!(
        "zrow::Vec3::new({}, {}, {})",
        literal(format, v[0]),
        literal(format, v[1]),
        literal(format, v[2])
    )
}

/// The Rust source (see the module doc).
/// Whether every face is a triangle (emitted as `zrow::Faces::Triangles`).
fn triangles_only(faces: &[ConvertedFace]) -> bool {
    !faces.is_empty() && faces.iter().all(|f| f.indices.len() == 3)
}

/// The colours a model of triangles is emitted with: one, if every triangle has it, else one
/// per triangle.
fn triangle_colors(faces: &[ConvertedFace]) -> Vec<zrow::Rgb565> {
    match faces.first() {
        Some(f) if faces.iter().all(|g| g.color == f.color) => vec![f.color],
        _ => faces.iter().map(|f| f.color).collect(),
    }
}

/// `pub static NAME` holding `values` with the doc comment `doc`, up to its closing `];`
/// (written by what follows): 16-bit integers at 2^-[`COMPACT_SHIFT`] for a compact
/// conversion, else the format's `zrow::Vec3` literals.
fn emit_vectors(s: &mut String, doc: &str, name: &str, values: &[[f64; 3]], c: &Converted) {
    let n = values.len();
    if c.report.compact {
        let _ = writeln!(
            s,
            "{doc}, as 16-bit integers at 2^-{COMPACT_SHIFT}\n/// (`zrow::Vectors::Compact`).\n\
             pub static {name}: [[i16; 3]; {n}] = ["
        );
        let unit = f64::from(1u32 << COMPACT_SHIFT);
        for p in values {
            let [x, y, z] = p.map(|c| (c * unit) as i16);
            let _ = writeln!(s, "    [{x}, {y}, {z}],");
        }
    } else {
        let (n_type, what) = match c.format {
            Format::Q16_16 => ("zrow::Q16_16", "16.16 fixed point, rounded to nearest"),
            Format::F32 => ("f32", "f32"),
        };
        let _ = writeln!(
            s,
            "{doc} ({what}).\npub static {name}: [zrow::Vec3<{n_type}>; {n}] = ["
        );
        for p in values {
            let _ = writeln!(s, "    {},", vec3_literal(c.format, p));
        }
    }
}

fn emit(c: &Converted, name: &str) -> String {
    let n_type = match c.format {
        Format::Q16_16 => "zrow::Q16_16",
        Format::F32 => "f32",
    };
    let i_type = c.index.name();
    let r = &c.report;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// Generated by the zrow-model converter (zrow_model::convert): do not edit.\n//"
    );
    for line in r.to_string().lines() {
        let _ = writeln!(s, "// {line}");
    }
    let f = c.faces.len();
    let _ = writeln!(
        s,
        "\n/// The model's name.\npub const NAME: &str = {name:?};\n"
    );
    emit_vectors(
        &mut s,
        "/// Vertex positions, normalised into the unit sphere",
        "VERTICES",
        &c.vertices,
        c,
    );
    let (positions, normals) = if c.report.compact {
        ("&[]", "&[]")
    } else {
        ("&VERTICES", "&NORMALS")
    };
    let _ = writeln!(s, "];\n");
    emit_vectors(
        &mut s,
        "/// One unit normal per face, model space: Newell's, computed in f64 from the \
         unquantised positions",
        "NORMALS",
        &c.normals,
        c,
    );
    if !c.vertex_normals.is_empty() {
        let _ = writeln!(s, "];\n");
        emit_vectors(
            &mut s,
            "/// One unit normal per vertex, model space, for smooth (Gouraud) shading: the \
             file's own or\n/// averaged from the faces within the crease angle (the report \
             says which); `MESH` carries\n/// them: smooth under `zrow::shading::Shading::Gouraud`, \
             flat otherwise",
            "VERTEX_NORMALS",
            &c.vertex_normals,
            c,
        );
    }
    let rgb = |c: &zrow::Rgb565| format!("zrow::Rgb565::new({}, {}, {})", c.r(), c.g(), c.b());
    let mesh = if triangles_only(&c.faces) {
        let _ = writeln!(
            s,
            "];\n\n/// Triangles: vertex indices counter-clockwise seen from outside.\n\
             pub static TRIANGLES: [[{i_type}; 3]; {f}] = ["
        );
        for face in &c.faces {
            let _ = writeln!(s, "    {:?},", face.indices);
        }
        let colors = triangle_colors(&c.faces);
        let k = colors.len();
        let which = if k == 1 {
            "every triangle's"
        } else {
            "one per triangle"
        };
        let _ = writeln!(
            s,
            "];\n\n/// Rgb565 colours: {which}.\npub static COLORS: [zrow::Rgb565; {k}] = ["
        );
        for color in &colors {
            let _ = writeln!(s, "    {},", rgb(color));
        }
        format!("zrow::Mesh::triangles_with_normals({positions}, &TRIANGLES, &COLORS, {normals})")
    } else {
        let _ = writeln!(
            s,
            "];\n\n/// Faces: vertex indices counter-clockwise seen from outside, Rgb565 colours.\n\
             pub static FACES: [zrow::Face<'static, {i_type}>; {f}] = ["
        );
        for face in &c.faces {
            let _ = writeln!(
                s,
                "    zrow::Face {{ indices: &{:?}, color: {}, alpha: 255 }},",
                face.indices,
                rgb(&face.color)
            );
        }
        format!("zrow::Mesh::with_normals({positions}, &FACES, {normals})")
    };
    let mesh = if c.report.compact {
        format!(
            "{mesh}\n        .with_positions(zrow::Vectors::Compact {{ raw: &VERTICES, shift: {COMPACT_SHIFT} }})\n        .with_normal_vectors(zrow::Vectors::Compact {{ raw: &NORMALS, shift: {COMPACT_SHIFT} }})"
        )
    } else {
        mesh
    };
    let mesh = match (c.vertex_normals.is_empty(), c.report.compact) {
        (true, _) => mesh,
        (false, true) => format!(
            "{mesh}\n        .with_vertex_normals(zrow::Vectors::Compact {{ raw: &VERTEX_NORMALS, shift: {COMPACT_SHIFT} }})"
        ),
        (false, false) => {
            format!("{mesh}\n        .with_vertex_normals(zrow::Vectors::Format(&VERTEX_NORMALS))")
        }
    };
    let cap = &c.capacities;
    let _ = writeln!(
        s,
        "];\n\n/// The mesh, for a [`zrow::Object`].\n\
         pub static MESH: zrow::Mesh<'static, {n_type}, {i_type}> =\n    {mesh};\n\n\
         /// Row width the capacities were measured for (pixels).\npub const WIDTH: usize = {};\n\
         /// Frame height the capacities were measured for (pixels).\npub const HEIGHT: usize = {};\n\
         /// Polygon table capacity: most polygons on screen in any orientation, plus the margin.\n\
         pub const POLYGONS: usize = {};\n\
         /// Edge table capacity: most edges in any orientation, plus the margin.\n\
         pub const EDGES: usize = {};\n\
         /// Vertex pool capacity (the scan-line method): most vertex slots in any orientation,\n\
         /// plus the margin.\n\
         pub const VERTEX_SLOTS: usize = {};\n\
         /// Active list capacity: most polygons crossing one row, plus the margin.\n\
         pub const ACTIVE: usize = {};\n\n\
         /// The scan-line renderer sized for this model: {} bytes of RAM.\n\
         pub type Renderer = zrow::Scanline<{n_type}, WIDTH, VERTEX_SLOTS, POLYGONS, ACTIVE>;",
        r.size.0,
        r.size.1,
        cap.polygons,
        cap.edges,
        cap.vertices,
        cap.active_polygons,
        r.scanline_ram
    );
    if let Some(ram) = r.display_ram {
        let _ = writeln!(
            s,
            "\n/// The scan-line renderer sized for this model as a display's is built\n\
             /// (`zrow::scanline_for!(N, REQ, display)`): no depth row, no affine depth cue state,\n\
             /// corners in 12 bits; for a sink that takes colours only, flat shaded ({ram} bytes of\n\
             /// RAM).\n\
             pub type Display = zrow::scanline::Display<{n_type}, WIDTH, VERTEX_SLOTS, POLYGONS, ACTIVE>;"
        );
    }
    let _ = match r.cull_only_ram {
        Some(ram) => writeln!(
            s,
            "\n/// The cheapest exact renderer for this model: it is one closed convex solid, so\n\
             /// back-face culling alone draws it exactly, with no depth test ({ram} bytes of RAM).\n\
             pub type Cheapest = zrow::cullonly::CullOnly<{n_type}, WIDTH, POLYGONS, EDGES>;"
        ),
        None => writeln!(
            s,
            "\n/// The cheapest exact renderer for this model: it is not one closed convex solid, so\n\
             /// the scan-line renderer.\npub type Cheapest = Renderer;"
        ),
    };
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A vertex buffer (of any size, clipping included: at distance 0.6 the near plane
    /// cuts the torus) changes nothing measured, and the views split over any number of
    /// threads give what one thread gives.
    #[test]
    fn slots_and_cores_change_nothing_measured() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/models/torus.off");
        let model = crate::model::load(std::path::Path::new(path)).unwrap();
        let clipped = model
            .with_mesh::<Q16_16, _>(|mesh| {
                let vertices = mesh.vertices.len();
                let mut clipped = 0;
                for distance in [3.0, 0.6] {
                    let opts = ConvertOptions {
                        distance,
                        ..ConvertOptions::default()
                    };
                    let rotations = random_rotations(200, 99);
                    let alone: Vec<_> = rotations
                        .iter()
                        .map(|r| measure_view(mesh, r, &opts).unwrap())
                        .collect();
                    for extra in [0, 5, 256] {
                        let split = on_cores(&rotations, vertices + extra, |r, slots| {
                            measure_view_in(mesh, r, &opts, slots).unwrap()
                        });
                        assert_eq!(split, alone, "distance {distance}, {extra} extra slots");
                    }
                    let few = &mut [RasterVertex::default(); 7];
                    for (r, want) in rotations.iter().zip(&alone) {
                        assert_eq!(measure_view_in(mesh, r, &opts, few).unwrap(), *want);
                    }
                    clipped += alone
                        .iter()
                        .filter(|r| r.vertices as usize > vertices)
                        .count();
                }
                clipped
            })
            .unwrap();
        assert!(clipped > 0, "no view made vertices by clipping");
    }

    /// `compact`: positions on the 2^-14 grid within half a step of the plain conversion's
    /// exact ones, 6 bytes a vertex, the same capacities (sampling only) and the same faces.
    #[test]
    fn compact_positions_halve_the_vertices_flash() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/models/torus.off");
        let model = crate::model::load(std::path::Path::new(path)).unwrap();
        let quick = ConvertOptions {
            directions: 16,
            rolls: 2,
            refine_starts: 1,
            refine_steps: 4,
            check_views: 0,
            ..ConvertOptions::default()
        };
        let plain = convert_model(&model, &quick).unwrap();
        let compact = convert_model(
            &model,
            &ConvertOptions {
                compact: true,
                ..quick.clone()
            },
        )
        .unwrap();
        let step = 1.0 / f64::from(1u32 << COMPACT_SHIFT);
        assert_eq!(plain.vertices.len(), compact.vertices.len());
        for (p, c) in plain.vertices.iter().zip(&compact.vertices) {
            for (a, b) in p.iter().zip(c) {
                assert_eq!((b / step).fract(), 0.0, "{b} is on the grid");
                assert!((a - b).abs() <= step / 2.0 + 1.0 / 131_072.0, "{a} as {b}");
            }
        }
        assert_eq!(
            compact.report.flash.vertices * 2,
            plain.report.flash.vertices
        );
        assert_eq!(compact.faces.len(), plain.faces.len());
        assert!(compact.report.position_error.max_coordinate <= step / 2.0);
        assert!(compact.rust.contains("pub static VERTICES: [[i16; 3]; "));
        assert!(compact
            .rust
            .contains("zrow::Vectors::Compact { raw: &VERTICES, shift: 14 }"));
        assert!(!plain.rust.contains("Vectors::Compact"));
    }

    #[test]
    fn index_type_boundaries() {
        assert_eq!(IndexType::for_vertices(256), Some(IndexType::U8));
        assert_eq!(IndexType::for_vertices(257), Some(IndexType::U16));
        assert_eq!(IndexType::for_vertices(65_536), Some(IndexType::U16));
        assert_eq!(IndexType::for_vertices(65_537), None);
    }

    #[test]
    fn rotations_are_orthonormal_and_face_their_direction() {
        let mut all = sampled_rotations(20, 3);
        assert_eq!(all.len(), 26 * 3);
        all.extend(random_rotations(50, 7));
        for r in &all {
            for i in 0..3 {
                for j in 0..3 {
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((dot(r[i], r[j]) - want).abs() < 1e-12, "{r:?}");
                }
            }
            // Right-handed: x × y = z.
            let z = [
                r[0][1] * r[1][2] - r[0][2] * r[1][1],
                r[0][2] * r[1][0] - r[0][0] * r[1][2],
                r[0][0] * r[1][1] - r[0][1] * r[1][0],
            ];
            assert!(dot(z, r[2]) > 0.999_999, "{r:?}");
        }
        // The direction turned towards the eye is the last row.
        let r = facing([0.0, 0.0, -1.0], 0.3);
        assert_eq!(r[2], [0.0, 0.0, -1.0]);
    }

    #[test]
    fn planarity_measures_the_distance_to_the_plane() {
        let square = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        assert_eq!(planarity(&square), 0.0);
        let mut bent = square;
        bent[2][2] = 0.4; // alternate vertices ±0.1 from the best-fit plane
        assert!(
            (planarity(&bent) - 0.1).abs() < 0.01,
            "{}",
            planarity(&bent)
        );
    }

    #[test]
    fn q16_16_rounds_to_nearest() {
        assert_eq!(quantise(Format::Q16_16, 0.5 / 65536.0 * 0.99), 0.0);
        assert_eq!(quantise(Format::Q16_16, 1.01 / 65536.0), 1.0 / 65536.0);
        assert_eq!(
            literal(Format::Q16_16, -1.0),
            "zrow::Q16_16::from_bits(-65536)"
        );
        assert_eq!(literal(Format::F32, 0.1f32 as f64), "0.1f32");
    }
}
