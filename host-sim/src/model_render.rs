//! Model-mode rendering: a [`LoadedModel`] seen by a camera orbiting the origin, under one
//! fixed light.
//!
//! The model is already normalised into the unit sphere ([`crate::model`]), so one camera
//! setup suits every model: the eye sits `distance` from the origin at a [`View`]'s yaw and
//! pitch and looks at the origin (y up), perspective with a [`FOV_Y_DEG`] vertical field of
//! view, near plane [`NEAR`], far plane [`FAR`]. The light is directional and fixed in the
//! world, coming from the upper front right ([`LIGHT_DIRECTION`]), with ambient [`AMBIENT`].
//! Faces are flat shaded, or smooth shaded ([`zrow::shading::Shading::Gouraud`]) when the
//! model has vertex normals ([`LoadedModel::smoothed`]), and back faces culled
//! ([`zrow::Config::model`]).
//!
//! Rendering goes the same way as [`crate::render`]: [`zrow::requirements()`] measures the view
//! first, a model that needs more than the host capacities is an error naming the capacity
//! and what it needs, and the frame is drawn by [`crate::render::HostScanline`] on a thread of
//! its own.

use crate::model::{LoadedModel, ModelError};
use crate::render::{draw, resolve, Algo, Format, Image, Structure};
use crate::structure::closed_convex;
use crate::SimError;
use zrow::pixelcolor::RgbColor;
use zrow::shading::Shading;
use zrow::{Affine, Config, Cull, ModelScene, Object, Requirements, Rgb565, Scalar};
use zrow::{Scene, Q16_16};

pub use zrow_model::camera::{
    light, View, AMBIENT, FAR, FOV_Y_DEG, LIGHT_DIRECTION, MAX_PITCH_DEG, NEAR,
};

/// Renders `model` from `view` at `width × height` pixels (each 1..=2048) with the chosen
/// method and number format. This is the one call the command line and the simulator window
/// share: it converts the model (errors name the vertex's line), measures the view against
/// the host capacities, then draws on a render thread.
///
/// Errors: a bad view ([`SimError::Usage`], see [`View::validate`]), a position that does not
/// fit the format or a face zrow rejects ([`SimError::Model`], naming the line or triangle), a
/// view that needs more than a host capacity or a size outside 1..=2048 ([`SimError::Scene`]
/// with zrow's [`zrow::Error::Capacity`], naming the table and what it needs, or
/// [`zrow::Error::BadConfig`]).
///
/// ```
/// use zrow_sim::model::{parse, ModelFormat};
/// use zrow_sim::model_render::{render_model_image, View};
/// use zrow_sim::render::{Algo, Format};
/// let obj = b"v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n"; // faces the default camera
/// let model = parse("tri.obj", ModelFormat::Obj, obj, ".".as_ref()).unwrap();
/// let image =
///     render_model_image(&model, &View::default(), 32, 32, Algo::Scanline, Format::Q16_16).unwrap();
/// assert_ne!(image.to_rgb8()[3 * (16 * 32 + 16)], 0); // the centre is lit
/// ```
pub fn render_model_image(
    model: &LoadedModel,
    view: &View,
    width: u16,
    height: u16,
    algo: Algo,
    format: Format,
) -> Result<Image, SimError> {
    let cull = Config::model(width, height).cull;
    render_model_culled(model, view, (width, height), algo, format, cull).map(|(image, _)| image)
}

/// Measures what `model` needs from `view` at this size in format `N`.
pub fn measure_model<N: Scalar>(
    model: &LoadedModel,
    view: &View,
    width: u16,
    height: u16,
) -> Result<Requirements, SimError> {
    with_scene::<N, _>(model, view, width, height, |scene, cfg| {
        measure(model, scene, cfg)
    })?
}

fn measure<N: Scalar>(
    model: &LoadedModel,
    scene: &dyn Scene<N>,
    cfg: &Config,
) -> Result<Requirements, SimError> {
    zrow::requirements(scene, cfg).map_err(|e| blame(model, e))
}

/// Builds the scene (the model at the origin, the orbit camera, the fixed light) and calls `f`
/// with it and a `width × height` model-mode configuration.
pub(crate) fn with_scene<N: Scalar, R>(
    model: &LoadedModel,
    view: &View,
    width: u16,
    height: u16,
    f: impl FnOnce(&ModelScene<'_, N, u32>, &Config) -> R,
) -> Result<R, SimError> {
    view.validate()
        .map_err(|m| SimError::Usage(format!("bad view: {m}")))?;
    let camera = view.camera::<N>().ok_or_else(|| {
        SimError::Usage(format!(
            "bad view: the camera does not fit the {} number format",
            N::NAME
        ))
    })?;
    let mut cfg = Config::model(width, height);
    if !model.vertex_normals.is_empty() {
        cfg.shading = zrow::shading::Shading::Gouraud { dither: false };
    }
    model.with_mesh::<N, _>(|mesh| {
        let objects = [Object {
            mesh,
            transform: Affine::identity(),
        }];
        let scene = ModelScene {
            objects: &objects,
            camera,
            light: light(),
        };
        f(&scene, &cfg)
    })
}

fn model_image<N: Scalar + Send + Sync>(
    model: &LoadedModel,
    view: &View,
    width: u16,
    height: u16,
    algo: Algo,
    cull: Cull,
    shading: Option<Shading>,
) -> Result<(Image, Requirements), SimError> {
    with_scene::<N, _>(model, view, width, height, |scene, cfg| {
        let shading = shading.unwrap_or(cfg.shading);
        let cfg = &Config {
            cull,
            shading,
            ..*cfg
        };
        let req = measure(model, scene, cfg)?;
        let image = draw(
            algo,
            scene,
            cfg,
            &req,
            || structure(scene),
            |e| blame(model, e),
        )?;
        Ok((image, req))
    })?
}

/// [`render_model_image`] with culling `cull` (the window's toggle; model mode culls back
/// faces), also returning what the view measured. Renderers are sized to the model as
/// [`render_model_image`]'s are, so any model draws (the window's fixed renderers fall back
/// to this for a model beyond them).
pub fn render_model_culled(
    model: &LoadedModel,
    view: &View,
    (width, height): (u16, u16),
    algo: Algo,
    format: Format,
    cull: Cull,
) -> Result<(Image, Requirements), SimError> {
    match format {
        Format::Q16_16 => model_image::<Q16_16>(model, view, width, height, algo, cull, None),
        Format::F32 => model_image::<f32>(model, view, width, height, algo, cull, None),
    }
}

/// How `render-model` draws a model: its shaded surfaces, a hidden-line drawing (its visible
/// edges in [`INK`] on [`PAPER`]), or the surfaces with their visible edges over them in
/// [`OUTLINE_INK`] (`--lines hidden|outline`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Lines {
    /// Shaded surfaces only.
    #[default]
    Off,
    /// Visible edges only.
    Hidden,
    /// Shaded surfaces and their visible edges.
    Outline,
}

impl Lines {
    /// The names `--lines` accepts.
    pub const ALL: &'static [(&'static str, Lines)] =
        &[("hidden", Lines::Hidden), ("outline", Lines::Outline)];
}

/// A hidden-line drawing's lines.
pub const INK: Rgb565 = Rgb565::BLACK;
/// A hidden-line drawing's background.
pub const PAPER: Rgb565 = Rgb565::WHITE;
/// The lines over the surfaces of an outline drawing.
pub const OUTLINE_INK: Rgb565 = Rgb565::WHITE;

/// How `render-model` draws beyond the model and the view: lines or not, dithering or not.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Style {
    /// Shaded, a hidden-line drawing or an outline drawing.
    pub lines: Lines,
    /// Smooth shading dithered (`--dither`; a model with vertex normals only).
    pub dither: bool,
}

impl From<Lines> for Style {
    fn from(lines: Lines) -> Style {
        Style {
            lines,
            dither: false,
        }
    }
}

/// [`render_model_image`] in a [`Style`] (or just [`Lines`]): the visible edges come from a
/// frame of facets ([`zrow::shading::Shading::Facets`]) drawn by the same method, turned into
/// lines 1 px wide by [`zrow::lines::HiddenLines`] (an edge is drawn where one of the surfaces
/// it separates is visible; the diagonal inside a flat quad is not an edge). An outline
/// drawing draws the shaded frame too. With `dither`, a model with vertex normals is drawn
/// smooth shaded and dithered ([`zrow::shading::Shading::Gouraud`]).
pub fn render_model_lines(
    model: &LoadedModel,
    view: &View,
    (width, height): (u16, u16),
    algo: Algo,
    format: Format,
    style: impl Into<Style>,
) -> Result<Image, SimError> {
    let Style { lines, dither } = style.into();
    let cull = Config::model(width, height).cull;
    let draw = |shading| match format {
        Format::Q16_16 => model_image::<Q16_16>(model, view, width, height, algo, cull, shading),
        Format::F32 => model_image::<f32>(model, view, width, height, algo, cull, shading),
    };
    let smooth =
        (dither && !model.vertex_normals.is_empty()).then_some(Shading::Gouraud { dither: true });
    let shaded = || draw(smooth).map(|(image, _)| image);
    if lines == Lines::Off {
        return shaded();
    }
    let (facets, _) = draw(Some(Shading::Facets))?;
    let edges = hidden_lines(&facets);
    let mut image = match lines {
        Lines::Outline => shaded()?,
        _ => Image {
            pixels: vec![PAPER; facets.pixels.len()],
            ..facets
        },
    };
    let ink = if lines == Lines::Outline {
        OUTLINE_INK
    } else {
        INK
    };
    for (p, _) in image.pixels.iter_mut().zip(&edges).filter(|(_, &e)| e) {
        *p = ink;
    }
    Ok(image)
}

/// Which pixels of a frame of facets are on a visible edge: the frame's rows through zrow's
/// [`zrow::lines::HiddenLines`], top to bottom, as the MCU streams them.
pub fn hidden_lines(facets: &Image) -> Vec<bool> {
    use zrow::lines::HiddenLines;
    use zrow::{FrameBuffer, Row, RowSink};
    let w = facets.width as usize;
    let mut out = vec![Rgb565::BLACK; facets.pixels.len()];
    let frame = FrameBuffer::new(&mut out, w);
    let mut lines = Box::new(HiddenLines::<_, { crate::render::HOST_WIDTH }>::new(
        frame,
        facets.height,
        Rgb565::WHITE,
        Rgb565::BLACK,
    ));
    for (y, row) in facets.pixels.chunks(w.max(1)).enumerate() {
        let row = Row::<f32> {
            y: y as u16,
            color: row,
            depth: &[],
        };
        let Ok(()) = lines.write_row(&row);
    }
    drop(lines);
    out.iter().map(|&c| c == Rgb565::WHITE).collect()
}

/// The scene's structure: one object whose mesh is a closed convex solid?
fn structure<N: Scalar>(scene: &ModelScene<'_, N, u32>) -> Structure {
    Structure {
        closed_convex: scene
            .objects
            .iter()
            .map(|o| closed_convex(o.mesh))
            .eq([true]),
    }
}

/// The method `auto` chooses for `model` seen from `view` ([`crate::render::choose`]: cull-only for a
/// closed convex model, ordered where its check passes, else the scan-line method).
pub fn choose_model(
    model: &LoadedModel,
    view: &View,
    width: u16,
    height: u16,
    format: Format,
) -> Result<Algo, SimError> {
    fn run<N: Scalar + Send + Sync>(
        m: &LoadedModel,
        v: &View,
        w: u16,
        h: u16,
    ) -> Result<Algo, SimError> {
        with_scene::<N, _>(m, v, w, h, |scene, cfg| {
            let req = measure(m, scene, cfg)?;
            resolve(Algo::Auto, scene, cfg, &req, || structure(scene)).map_err(|e| blame(m, e))
        })?
    }
    match format {
        Format::Q16_16 => run::<Q16_16>(model, view, width, height),
        Format::F32 => run::<f32>(model, view, width, height),
    }
}

/// A zrow error, blamed on the line (or triangle) of the face it names.
fn blame(model: &LoadedModel, error: zrow::Error) -> SimError {
    use zrow::Error::*;
    match error {
        IndexOutOfRange { face, .. }
        | TooFewVertices { face }
        | TooManyVertices { face }
        | NonFinite { face }
        | NotConvex { face } => SimError::Model(ModelError {
            file: model.file.clone(),
            at: model.face_origin(face),
            message: error.to_string(),
        }),
        _ => SimError::Scene {
            file: model.file.clone(),
            line: None,
            error,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_eye_is_front_right_above() {
        let e = View::default().eye();
        assert!(e[0] > 0.0 && e[1] > 0.0 && e[2] > 0.0, "{e:?}");
        let len = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
        assert!((len - 3.0).abs() < 1e-5);
    }

    #[test]
    fn bad_views_say_what_is_wrong() {
        let bad = |v: View| v.validate().unwrap_err();
        let v = View::default();
        assert!(bad(View {
            pitch_deg: 90.0,
            ..v
        })
        .contains("pitch 90"));
        assert!(bad(View { distance: 0.0, ..v }).contains("distance 0"));
        assert!(bad(View {
            yaw_deg: f32::NAN,
            ..v
        })
        .contains("yaw"));
        assert!(v.camera::<Q16_16>().is_some());
    }
}
