//! The model converter ([`zrow_model::convert`], re-exported here), and what the simulator
//! adds to it: [`render_converted`], the converted data drawn as the firmware would draw it.

pub use zrow_model::convert::*;

use crate::model_render::{light, View};
use crate::render::{Format, Image};
use crate::SimError;
use zrow::{Affine, Config, ModelScene, Object, Scalar, Q16_16};

/// The model drawn as the firmware would draw it: the converted data in its format, seen from
/// `view` by model mode's camera and light, with the scan-line method at the host capacities.
pub fn render_converted(
    converted: &Converted,
    view: &View,
    width: u16,
    height: u16,
) -> Result<Image, SimError> {
    match converted.format {
        Format::Q16_16 => render_in::<Q16_16>(converted, view, width, height),
        Format::F32 => render_in::<f32>(converted, view, width, height),
    }
}

fn render_in<N: Scalar + Send + Sync>(
    converted: &Converted,
    view: &View,
    width: u16,
    height: u16,
) -> Result<Image, SimError> {
    let file = converted.report.file.clone();
    let scene_error = |error| SimError::Scene {
        file: file.clone(),
        line: None,
        error,
    };
    view.validate()
        .map_err(|m| SimError::Usage(format!("bad view: {m}")))?;
    let camera = view
        .camera::<N>()
        .ok_or_else(|| scene_error(zrow::Error::BadConfig))?;
    let cfg = Config::model(width, height);
    converted
        .with_mesh::<N, _>(|mesh| {
            let objects = [Object {
                mesh,
                transform: Affine::identity(),
            }];
            let scene = ModelScene {
                objects: &objects,
                camera,
                light: light(),
            };
            let req = zrow::requirements(&scene, &cfg).map_err(scene_error)?;
            crate::render::draw(
                crate::render::Algo::Scanline,
                &scene,
                &cfg,
                &req,
                crate::render::Structure::default,
                scene_error,
            )
        })
        .ok_or_else(|| scene_error(zrow::Error::BadConfig))?
}
