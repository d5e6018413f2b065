//! Named configurations: the speed–accuracy trade, one knob at a time.
//!
//! A preset fixes every choice that trades speed or memory for accuracy:
//!
//! | knob | cheap | accurate |
//! |---|---|---|
//! | number format ([`Format`](crate::presets::Format)) | [`Format::Q24_8`](crate::presets::Format::Q24_8) (depth LSB 1/256) | [`Format::Q16_16`](crate::presets::Format::Q16_16), [`Format::F32`](crate::presets::Format::F32) |
//! | sub-pixel bits ([`Config::subpixel_bits`](crate::Config::subpixel_bits)) | 4 | 8 |
//! | depth store ([`DepthStore`](crate::presets::DepthStore)) | 16-bit tiles ([`crate::tiled`]) | 32-bit row ([`crate::Scanline`]) |
//! | depth mapping ([`DepthMapping`](crate::geometry::DepthMapping)) | linear in w | affine in 1/w |
//! | trig, square roots and f32 transforms ([`MathLib`](crate::math::MathLib)) | micromath, plain f32 sums | libm, compensated f32 sums |
//! | intensity ([`Interpolation`](crate::shading::Interpolation)) | affine | perspective-correct |
//!
//! The format and the depth store are types (pick the renderer type the preset names); the
//! rest is [`Preset::config`](crate::presets::Preset::config). `cargo run --release -p zrow-tradeoff -- --out docs/presets`
//! measures every preset's cost (host time, emulated Cortex-M4 instructions) and error
//! against an exact reference, and writes the table and plot the README links
//! (`docs/presets/presets.md`).
//!
//! ```
//! use zrow::presets::{by_name, Format};
//! use zrow::shading::{DepthCue, Interpolation};
//! let p = by_name("q16-affine").unwrap();
//! assert_eq!(p.format, Format::Q16_16);
//! let cue = DepthCue { near: 3.0, far: 6.0, floor: 0.2, interpolation: Interpolation::PerspectiveCorrect };
//! let cfg = p.config(zrow::Config::model(240, 240), cue);
//! assert_eq!(cfg.subpixel_bits, 8);
//! ```

use crate::geometry::DepthMapping;
use crate::math::MathLib;
use crate::raster::Config;
use crate::shading::{DepthCue, Interpolation, Shading};

/// The number format of a preset (a type parameter of the renderer).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// [`crate::Q16_16`]: 16.16 fixed point.
    Q16_16,
    /// [`crate::Q24_8`]: 24.8 fixed point (depth to 1/256 over 0..256).
    Q24_8,
    /// `f32` (needs an FPU to be fast).
    F32,
}

/// Where depth is kept while visibility is resolved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthStore {
    /// One row of depths in the format ([`crate::Scanline`]): exact plane comparisons.
    Row32,
    /// Bands of 16-bit depths over the frame's depth range ([`crate::tiled::Tiled`]).
    Tile16,
}

/// One named configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    /// Name (used on the command line and in the docs).
    pub name: &'static str,
    /// What it is for.
    pub summary: &'static str,
    /// Number format.
    pub format: Format,
    /// Sub-pixel bits.
    pub subpixel_bits: u8,
    /// Depth store (renderer).
    pub store: DepthStore,
    /// Depth mapping under perspective.
    pub depth: DepthMapping,
    /// Trig and square roots.
    pub math: MathLib,
    /// How the depth cue is interpolated.
    pub intensity: Interpolation,
}

impl Preset {
    /// `base` with this preset's sub-pixel bits, depth mapping, maths and a depth cue with
    /// `cue`'s range and this preset's interpolation.
    pub fn config(&self, base: Config, cue: DepthCue) -> Config {
        let mut cfg = base;
        cfg.subpixel_bits = self.subpixel_bits;
        cfg.depth = self.depth;
        cfg.math = self.math;
        cfg.shading = Shading::DepthCue(DepthCue {
            interpolation: self.intensity,
            ..cue
        });
        cfg
    }
}

const BASE: Preset = Preset {
    name: "q16",
    summary: "the default: Q16.16, 8 sub-pixel bits, 32-bit depth row affine in 1/w, libm, perspective-correct intensity",
    format: Format::Q16_16,
    subpixel_bits: 8,
    store: DepthStore::Row32,
    depth: DepthMapping::InverseW,
    math: MathLib::Libm,
    intensity: Interpolation::PerspectiveCorrect,
};

/// Every preset: the default, one knob changed at a time, and the all-cheap and all-accurate
/// ends.
pub const PRESETS: [Preset; 10] = [
    Preset {
        name: "f32",
        summary: "the accurate end: f32 throughout (needs an FPU), otherwise as q16",
        format: Format::F32,
        ..BASE
    },
    BASE,
    Preset {
        name: "q16-affine",
        summary: "q16 with affine (Gouraud) intensity: no division per pixel",
        intensity: Interpolation::Affine,
        ..BASE
    },
    Preset {
        name: "q16-micromath",
        summary: "q16 with micromath's trig and square roots",
        math: MathLib::Micromath,
        ..BASE
    },
    Preset {
        name: "q16-s4",
        summary: "q16 with 4 sub-pixel bits (vertices snapped to 1/16 pixel)",
        subpixel_bits: 4,
        ..BASE
    },
    Preset {
        name: "q16-linear-w",
        summary: "q16 storing depth linear in w, interpolated in screen space",
        depth: DepthMapping::LinearW,
        ..BASE
    },
    Preset {
        name: "q16-tile16",
        summary: "q16 resolved in 16-bit depth tiles over the frame's depth range",
        store: DepthStore::Tile16,
        ..BASE
    },
    Preset {
        name: "q24.8",
        summary: "Q24.8: depth to 1/256 of a unit over 0..256 (a 16-bit depth in a 32-bit word)",
        format: Format::Q24_8,
        ..BASE
    },
    Preset {
        name: "q16-fast",
        summary: "the cheap end in Q16.16: 4 sub-pixel bits, micromath, affine intensity",
        subpixel_bits: 4,
        math: MathLib::Micromath,
        intensity: Interpolation::Affine,
        ..BASE
    },
    Preset {
        name: "f32-fast",
        summary: "f32 with 4 sub-pixel bits, micromath, affine intensity",
        format: Format::F32,
        subpixel_bits: 4,
        math: MathLib::Micromath,
        intensity: Interpolation::Affine,
        ..BASE
    },
];

/// The preset called `name`.
pub fn by_name(name: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.name == name)
}
