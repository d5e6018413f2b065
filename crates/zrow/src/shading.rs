//! Depth cueing: intensity falling with distance, interpolated affinely or
//! perspective-correctly — the intensity knob of the presets.
//!
//! A face keeps its flat (Lambert) colour; with [`Shading::DepthCue`](crate::shading::Shading::DepthCue) each pixel's colour is
//! scaled by a factor that falls linearly with the view distance w, from 1 at `near` to `floor`
//! at `far` (clamped outside). The factor is an attribute that varies across a polygon, so how
//! it is interpolated matters:
//!
//! - [`Interpolation::PerspectiveCorrect`](crate::shading::Interpolation::PerspectiveCorrect): the factor is computed at every pixel from the
//!   pixel's own w. Under the default depth mapping stored depth is affine in 1/w, so
//!   w = k·near / (k − z) follows from the visible depth alone: one division per pixel, done on
//!   the finished row ([`Cue::shade_row`](crate::shading::Cue::shade_row)), which is why every method supports it. It is exact
//!   (up to the format's rounding) — the same as interpolating factor/w and 1/w and dividing.
//! - [`Interpolation::Affine`](crate::shading::Interpolation::Affine): Gouraud's incremental scheme — the factor is exact where each
//!   edge first and last crosses a sample row, stepped linearly down the edges and across each
//!   span in screen space. No division per pixel, but w is not linear in screen space, so a
//!   polygon receding in depth gets the wrong intensity in between (too dark or too light by
//!   up to a few percent for the faces of an ordinary scene). Only the scan-line method walks
//!   edges, so only it offers this; the others return [`Error::Unsupported`](crate::Error::Unsupported).
//!
//! Under [`crate::geometry::DepthMapping::LinearW`] the stored depth is itself interpolated
//! affinely, so "perspective-correct" then inherits its error.

use crate::error::Error;
use crate::geometry::{shade, ViewDepth};
use crate::number::Scalar;
use crate::raster::Config;
use crate::scene::Scene;
use embedded_graphics_core::pixelcolor::Rgb565;

/// How a face's intensity varies ([`Config::shading`]).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Shading {
    /// One colour per face.
    #[default]
    Flat,
    /// Intensity falls with distance.
    DepthCue(DepthCue),
    /// Smooth (Gouraud 1971; Foley & van Dam §16.2.4): each vertex lit with its own normal
    /// ([`crate::Mesh::vertex_normals`]), the intensity interpolated linearly across each
    /// polygon in screen space as an exact plane, like depth (see [`crate::scene::IntensityPlane`]). A mesh
    /// without vertex normals is drawn flat. Every method draws it, with the same bits.
    Gouraud {
        /// Ordered dithering (a 4 × 4 Bayer matrix) where each channel is cut to Rgb565's 5
        /// or 6 bits, so that a slow gradient does not band: the channel's fraction decides,
        /// pixel by pixel, whether it rounds up, so that a 4 × 4 block averages the exact value.
        dither: bool,
    },
    /// Facets instead of colours, for hidden-line drawings ([`crate::lines`]): every polygon
    /// is drawn opaque, unlit, in the raw Rgb565 value `facet + 1` (0 is the background, so
    /// [`Config::background`](crate::Config::background) must be black), where `facet` is the
    /// scene number (objects in order, faces in order) of the first face of its facet. Faces
    /// listed one after the other that share an edge and lie in one plane (within 0.06°: a
    /// polygon split into triangles) are one facet, so that the diagonals inside a flat quad
    /// are not edges. The visibility is every method's own, unchanged: a frame of facets is a
    /// map of which surface is visible at each pixel, and [`crate::lines::HiddenLines`]
    /// turns it into lines, 1 px wide, where the visible facet changes. A scene of more than
    /// 65,535 faces is refused ([`Error::Unsupported`]) rather
    /// than drawn with two facets sharing a value. Needs the `lines` feature (default).
    #[cfg(feature = "lines")]
    Facets,
}

/// Depth-cue parameters: the factor is 1 at w ≤ `near`, `floor` at w ≥ `far`, linear between.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthCue {
    /// View distance where dimming starts.
    pub near: f32,
    /// View distance where the factor reaches `floor`.
    pub far: f32,
    /// The factor at and beyond `far`, 0..=1.
    pub floor: f32,
    /// Affine or perspective-correct.
    pub interpolation: Interpolation,
}

/// How an attribute is interpolated across a polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// Linearly in screen space (Gouraud): cheap, wrong where depth recedes.
    Affine,
    /// From each pixel's own distance: one division per pixel, exact.
    PerspectiveCorrect,
}

impl Shading {
    /// Whether vertices are lit one by one ([`Shading::Gouraud`]).
    pub const fn is_smooth(&self) -> bool {
        matches!(self, Shading::Gouraud { .. })
    }

    /// Whether polygons are drawn as facets for hidden lines ([`Shading::Facets`]; never
    /// without the `lines` feature).
    pub const fn is_facets(&self) -> bool {
        #[cfg(feature = "lines")]
        return matches!(self, Shading::Facets);
        #[cfg(not(feature = "lines"))]
        false
    }

    /// Finite parameters, `near < far`, `floor` in 0..=1.
    pub(crate) fn is_valid(&self) -> bool {
        match *self {
            Shading::Flat | Shading::Gouraud { .. } => true,
            #[cfg(feature = "lines")]
            Shading::Facets => true,
            Shading::DepthCue(c) => {
                c.near.is_finite()
                    && c.far.is_finite()
                    && c.near < c.far
                    && (0.0..=1.0).contains(&c.floor)
            }
        }
    }
}

/// A frame's depth cue in the renderer's format: stored depth → w → factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cue<N> {
    view: ViewDepth<N>,
    near: N,
    /// 1 / (far − near).
    inv_span: N,
    /// 1 − floor.
    drop: N,
    /// How the method must interpolate the factor.
    pub interpolation: Interpolation,
}

impl<N: Scalar> Cue<N> {
    /// A cue of all-zero bits that shades nothing: the placeholder of a renderer that keeps
    /// its cue beside a flag, so that the renderer built in a `static` is all zero and lands
    /// in `.bss` instead of being copied from flash (an `Option` of a cue is not all zero).
    pub(crate) const UNSET: Cue<N> = Cue {
        view: ViewDepth::InverseW {
            k: N::ZERO,
            k_near: N::ZERO,
        },
        near: N::ZERO,
        inv_span: N::ZERO,
        drop: N::ZERO,
        interpolation: Interpolation::Affine,
    };

    /// The cue for one frame, or `None` for flat shading (or a scene without distances).
    /// [`Error::BadConfig`] if a parameter does not fit the format.
    pub fn for_frame(
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
    ) -> Result<Option<Self>, Error> {
        let Shading::DepthCue(c) = cfg.shading else {
            return Ok(None);
        };
        let Some(view) = scene.view_depth(cfg) else {
            return Ok(None);
        };
        let num = |v: f32| N::from_f32(v).ok_or(Error::BadConfig);
        Ok(Some(Cue {
            view,
            near: num(c.near)?,
            inv_span: num(1.0 / (c.far - c.near))?,
            drop: num(1.0 - c.floor)?,
            interpolation: c.interpolation,
        }))
    }

    /// [`Cue::for_frame`] for a method that shades finished rows only: affine interpolation
    /// is [`Error::Unsupported`] there.
    pub fn for_rows(scene: &(impl Scene<N> + ?Sized), cfg: &Config) -> Result<Option<Self>, Error> {
        let cue = Self::for_frame(scene, cfg)?;
        if cue.is_some_and(|c| c.interpolation == Interpolation::Affine) {
            return Err(Error::Unsupported {
                feature: "affine depth-cue interpolation (scan-line only)",
            });
        }
        Ok(cue)
    }

    /// The factor at view distance `w`, clamped to `floor..=1`.
    pub fn of_w(&self, w: N) -> N {
        let t = w.sub(self.near).mul(self.inv_span);
        let t = if t < N::ZERO {
            N::ZERO
        } else if t > N::ONE {
            N::ONE
        } else {
            t
        };
        N::ONE.sub(self.drop.mul(t))
    }

    /// The factor at stored depth `z`.
    pub fn at_depth(&self, z: N) -> N {
        self.of_w(self.view.w(z))
    }

    /// Scales every drawn pixel of a finished row by the factor at its depth (perspective-
    /// correct; background pixels, at the format's maximum depth, are left alone).
    pub fn shade_row(&self, depth: &[N], colours: &mut [Rgb565]) {
        for (c, &z) in colours.iter_mut().zip(depth) {
            if z != N::MAX {
                *c = shade(*c, self.at_depth(z));
            }
        }
    }

    /// [`Cue::shade_row`] if the cue is perspective-correct (the row pass); nothing otherwise.
    pub fn shade_row_if_perspective(cue: &Option<Self>, depth: &[N], colours: &mut [Rgb565]) {
        if let Some(c) = cue.filter(|c| c.interpolation == Interpolation::PerspectiveCorrect) {
            c.shade_row(depth, colours);
        }
    }
}
