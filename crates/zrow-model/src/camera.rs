//! Model mode's camera and light, shared by the simulator (`zrow-sim render-model`, the
//! window) and the converter, which measures a model as model mode shows it.
//!
//! Models are normalised into the unit sphere ([`crate::model`]), so one camera setup suits
//! every model: the eye sits `distance` from the origin at a [`View`]'s yaw and pitch and looks
//! at the origin (y up), perspective with a [`FOV_Y_DEG`] vertical field of view, near plane
//! [`NEAR`], far plane [`FAR`]. The light is directional and fixed in the world, coming from
//! the upper front right ([`LIGHT_DIRECTION`]), with ambient [`AMBIENT`].

use zrow::{Camera, Light, Scalar, Vec3};

/// Vertical field of view, degrees.
pub const FOV_Y_DEG: f32 = 60.0;
/// Near plane distance.
pub const NEAR: f32 = 0.1;
/// Far plane distance.
pub const FAR: f32 = 20.0;
/// Direction towards the light in world space: up, towards the default eye, to the right.
pub const LIGHT_DIRECTION: [f32; 3] = [0.6, 1.0, 0.8];
/// Fraction of a face's colour that faces turned away from the light keep.
pub const AMBIENT: f32 = 0.2;
/// Largest pitch magnitude, degrees (the camera's up is +y, so it cannot look straight down).
pub const MAX_PITCH_DEG: f32 = 89.0;

/// Where the orbiting camera is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Rotation about the vertical axis, degrees: 0 looks from +z, 90 from +x.
    pub yaw_deg: f32,
    /// Elevation, degrees, in −[`MAX_PITCH_DEG`]..=[`MAX_PITCH_DEG`]: positive looks down
    /// from above.
    pub pitch_deg: f32,
    /// Distance of the eye from the origin (the model fits the unit sphere), in
    /// (0, [`FAR`]).
    pub distance: f32,
}

impl Default for View {
    /// Yaw 30°, pitch 20°, distance 3.
    fn default() -> Self {
        View {
            yaw_deg: 30.0,
            pitch_deg: 20.0,
            distance: 3.0,
        }
    }
}

impl View {
    /// The eye position.
    pub fn eye(&self) -> [f32; 3] {
        let (yaw, pitch) = (self.yaw_deg.to_radians(), self.pitch_deg.to_radians());
        let d = self.distance;
        [
            d * pitch.cos() * yaw.sin(),
            d * pitch.sin(),
            d * pitch.cos() * yaw.cos(),
        ]
    }

    /// Checks the ranges documented on the fields; the message says which is wrong.
    pub fn validate(&self) -> Result<(), String> {
        if !self.yaw_deg.is_finite() {
            return Err(format!("yaw {} is not finite", self.yaw_deg));
        }
        if self.pitch_deg.is_nan() || self.pitch_deg.abs() > MAX_PITCH_DEG {
            return Err(format!(
                "pitch {} is outside -{MAX_PITCH_DEG}..={MAX_PITCH_DEG} degrees",
                self.pitch_deg
            ));
        }
        if self.distance.is_nan() || self.distance <= 0.0 || self.distance >= FAR {
            return Err(format!(
                "distance {} is outside the open interval (0, {FAR})",
                self.distance
            ));
        }
        Ok(())
    }

    /// The camera for this view in format `N` (`None`: a bad view, see [`View::validate`]).
    pub fn camera<N: Scalar>(&self) -> Option<Camera<N>> {
        self.validate().ok()?;
        let projection = Camera::<N>::perspective(FOV_Y_DEG.to_radians(), NEAR, FAR)?;
        Camera::look_at(self.eye(), [0.0; 3], [0.0, 1.0, 0.0], projection)
    }
}

/// The model-mode light in format `N`.
pub fn light<N: Scalar>() -> Light<N> {
    Light {
        direction: Vec3::from_f32(LIGHT_DIRECTION).unwrap_or_default(),
        ambient: N::from_f32(AMBIENT).unwrap_or(N::ZERO),
    }
}
