//! zrow's standard scenes as const data: the same scenes on the host, in the simulator, in the
//! emulated Cortex-M benches and on the board.
//!
//! Meshes are generated once by `build.rs` and compiled in as `static` arrays, so on a
//! microcontroller they stay in flash: positions in every number format — f32, [`Q16_16`] and
//! [`Q24_8`], the fixed ones rounded to the nearest LSB (the [`Format`] trait picks the right
//! array) — and faces as static index slices with a colour each.
//!
//! | name | mode | faces |
//! |---|---|---|
//! | `cube` | model: the unit cube, 6 quads, one colour each | 6 |
//! | `mesh1k` | model: a closed torus, 25 × 20 quads as triangles | 1,000 |
//! | `random400` | screen space: 400 random triangles, depth 0..100, intersecting; snapped ([`zrow::SnappedScene`]) | 400 |
//!
//! Comparison scenes ([`FOLEY`], for Foley & van Dam's Table 15.3 on the emulated Cortex-M4:
//! `crates/zrow-compare`, `emu/`): `foley100` and `foley2500`, screen space — two tilted tori
//! and two wavy sheets cutting through them and each other, tessellated into 100 and 2,500
//! triangles by zrow-compare's generator (`crates/zrow-compare/src/surfaces.rs`, included by
//! `build.rs`), at 240 × 240. Positions are on a 1/256-pixel grid (depth 1/1024), so their f32
//! and Q16.16 versions are the same numbers; Q24.8 keeps x and y exactly and rounds depth to
//! the nearest 1/256.
//!
//! Demo scenes ([`DEMOS`], for the simulator window and the board): `interlocked` — two
//! 256-triangle rings linked through each other and a cube piercing both, turning, so hidden
//! surfaces change every frame — then `cube` and `mesh1k`.
//!
//! Model scenes share one camera (from (2.5, 1.8, 3.2) at the origin, 60° field of view, near
//! 0.1, far 20) and one light (towards (0.4, 1, 0.7), ambient 0.2).
//!
//! ```
//! use zrow::{FrameBuffer, Q16_16, Scanline};
//! use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
//! let mut pixels = vec![Rgb565::BLACK; 240 * 240];
//! let mut renderer = Box::new(Scanline::<Q16_16, 240, 256, 64, 64>::new());
//! let faces = zrow_scenes::with_scene::<Q16_16, _>("cube", 0.0, |scene, cfg, faces| {
//!     renderer.render(scene, cfg, &mut FrameBuffer::new(&mut pixels, 240)).unwrap();
//!     faces
//! });
//! assert_eq!(faces, Some(6));
//! assert!(pixels.iter().any(|&p| p != Rgb565::BLACK));
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

use embedded_graphics_core::pixelcolor::Rgb565;
use zrow::presets::Preset;
use zrow::raster::RasterVertex;
use zrow::shading::{DepthCue, Interpolation};
use zrow::{
    Affine, Camera, Config, Face, Faces, Light, MathLib, Mesh, ModelScene, Object, Scalar, Scene,
    ScreenScene, SnappedScene, Vec3, Vectors, Q16_16, Q24_8,
};

mod meshes {
    #![allow(clippy::all)]
    use super::*;
    include!(concat!(env!("OUT_DIR"), "/meshes.rs"));
}

/// The scenes' names, in report order.
pub const NAMES: [&str; 3] = ["cube", "mesh1k", "random400"];

/// The comparison scenes (Foley & van Dam's Table 15.3 at 100 and 2,500 polygons), screen space.
pub const FOLEY: [&str; 2] = ["foley100", "foley2500"];

/// The demo scenes, in the order the simulator and the board show them.
pub const DEMOS: [&str; 3] = ["interlocked", "cube", "mesh1k"];

/// How far a board's demo turns a frame, radians.
pub const BOARD_STEP: f32 = 0.03;
/// Frames after which a board's demo angle starts again from 0: 1,885 steps are nine turns
/// and 0.0012 rad, so the wrap does not show, and the angle stays small (an `f32` frame count
/// times the step would lose its precision after 2^24 frames, four days at 50 fps).
pub const BOARD_PERIOD: u32 = 1_885;

/// The angle a board's demo draws frame `frame` at.
pub fn board_angle(frame: u32) -> f32 {
    (frame % BOARD_PERIOD) as f32 * BOARD_STEP
}

/// What each demo scene needs at most (Q16.16, 240×240, [`with_demo`]), measured over 2,048
/// angles of a turn and the board's first 3,000 frames (0.03 rad each), in the order of
/// [`DEMOS`] (`tests/demos.rs` measures them again). A board that shows some of the demos
/// sizes its renderer to those.
pub const DEMO_MEASURED_EACH: [zrow::Requirements; 3] = [
    zrow::Requirements {
        polygons: 253,
        edges: 744,
        vertices: 264,
        active_polygons: 57,
        width: SIZE,
    },
    zrow::Requirements {
        polygons: 3,
        edges: 12,
        vertices: 8,
        active_polygons: 3,
        width: SIZE,
    },
    zrow::Requirements {
        polygons: 463,
        edges: 1316,
        vertices: 500,
        active_polygons: 67,
        width: SIZE,
    },
];

/// What the demo scenes need at most, all of them: mesh1k's 463 polygons, 500 vertices and 67
/// active polygons, the most of each.
pub const DEMO_MEASURED: zrow::Requirements = DEMO_MEASURED_EACH[2];

/// The board's renderer capacities: [`DEMO_MEASURED`] plus 5 % for the angles between the
/// measured ones (`zrow::scanline_for!(Q16_16, DEMO_REQUIREMENTS)`).
pub const DEMO_REQUIREMENTS: zrow::Requirements = DEMO_MEASURED.with_margin(5);

/// Frame size of every standard scene.
pub const SIZE: u16 = 240;

/// The model meshes' (cube, torus, ring) positions are compact 16-bit integers at
/// 2^-`MODEL_SHIFT` (`zrow::Vectors::Compact`): one table for every number format, 6 bytes a
/// vertex, exact in every format (a multiple of 2^-14 is one of Q16.16 and of f32; Q24.8
/// rounds it to its 2^-8).
pub const MODEL_SHIFT: u8 = 14;

/// Compact positions at [`MODEL_SHIFT`].
const fn compact<N>(raw: &'static [[i16; 3]]) -> Vectors<'static, N> {
    Vectors::Compact {
        raw,
        shift: MODEL_SHIFT,
    }
}

/// The cube's faces over its compact positions.
fn cube_with<N>(faces: &'static [Face<'static>]) -> Mesh<'static, N> {
    Mesh::new(&[], faces).with_positions(compact(&meshes::CUBE_I16))
}

/// Triangles over compact positions.
fn compact_triangles<N>(
    raw: &'static [[i16; 3]],
    indices: &'static [[u16; 3]],
    colors: &'static [Rgb565],
) -> Mesh<'static, N> {
    Mesh::triangles(&[], indices, colors).with_positions(compact(raw))
}

/// A number format the screen-space scenes exist in: each has its own const positions (the
/// model meshes' compact positions serve every format).
pub trait Format: Scalar {
    /// Random triangles' positions (screen space).
    fn random400() -> &'static [Vec3<Self>];
    /// [`Format::random400`] snapped to 8 sub-pixel bits (`zrow::raster::RasterVertex::snapped`,
    /// `Config::screen`'s grid): what [`with_scene`] draws `random400` from, as a
    /// [`SnappedScene`].
    fn random400_snapped() -> &'static [RasterVertex<Self>];
    /// The 100-triangle comparison scene's positions (screen space).
    fn foley100() -> &'static [Vec3<Self>];
    /// The 2,500-triangle comparison scene's positions (screen space).
    fn foley2500() -> &'static [Vec3<Self>];
}

impl Format for f32 {
    fn random400() -> &'static [Vec3<f32>] {
        &meshes::RANDOM400_F32
    }
    fn random400_snapped() -> &'static [RasterVertex<f32>] {
        &meshes::RANDOM400_SNAPPED_F32
    }
    fn foley100() -> &'static [Vec3<f32>] {
        &meshes::FOLEY100_F32
    }
    fn foley2500() -> &'static [Vec3<f32>] {
        &meshes::FOLEY2500_F32
    }
}

impl Format for Q16_16 {
    fn random400() -> &'static [Vec3<Q16_16>] {
        &meshes::RANDOM400_Q16_16
    }
    fn random400_snapped() -> &'static [RasterVertex<Q16_16>] {
        &meshes::RANDOM400_SNAPPED_Q16_16
    }
    fn foley100() -> &'static [Vec3<Q16_16>] {
        &meshes::FOLEY100_Q16_16
    }
    fn foley2500() -> &'static [Vec3<Q16_16>] {
        &meshes::FOLEY2500_Q16_16
    }
}

impl Format for Q24_8 {
    fn random400() -> &'static [Vec3<Q24_8>] {
        &meshes::RANDOM400_Q24_8
    }
    fn random400_snapped() -> &'static [RasterVertex<Q24_8>] {
        &meshes::RANDOM400_SNAPPED_Q24_8
    }
    fn foley100() -> &'static [Vec3<Q24_8>] {
        &meshes::FOLEY100_Q24_8
    }
    fn foley2500() -> &'static [Vec3<Q24_8>] {
        &meshes::FOLEY2500_Q24_8
    }
}

/// The mesh of a standard scene, borrowed from flash.
pub fn mesh<N: Format>(name: &str) -> Option<Mesh<'static, N>> {
    use meshes::*;
    let triangles = Mesh::triangles;
    Some(match name {
        "cube" => cube_with(&CUBE_FACES),
        "mesh1k" | "mesh1k-lines" => compact_triangles(&TORUS_I16, &TORUS_TRIANGLES, &TORUS_COLORS),
        // The torus with its surface normals at the vertices, for smooth shading.
        "mesh1k-smooth" | "mesh1k-dither" => {
            compact_triangles(&TORUS_I16, &TORUS_TRIANGLES, &TORUS_COLORS)
                .with_vertex_normals(compact(&TORUS_NORMALS_I16))
        }
        "random400" => triangles(N::random400(), &RANDOM400_TRIANGLES, &RANDOM400_COLORS),
        "foley100" => triangles(N::foley100(), &FOLEY100_TRIANGLES, &FOLEY100_COLORS),
        "foley2500" => triangles(N::foley2500(), &FOLEY2500_TRIANGLES, &FOLEY2500_COLORS),
        "ring" => compact_triangles(&RING_I16, &RING_TRIANGLES, &RING_COLORS),
        // The interlocked demo's objects: one colour each.
        "ring-warm" => compact_triangles(&RING_I16, &RING_TRIANGLES, &RING_WARM_COLOR),
        "ring-cool" => compact_triangles(&RING_I16, &RING_TRIANGLES, &RING_COOL_COLOR),
        "cube-plain" => cube_with(&CUBE_PLAIN_FACES),
        _ => return None,
    })
}

/// The model scenes' eye (looking at the origin, y up).
pub const EYE: [f32; 3] = [2.5, 1.8, 3.2];
/// The model scenes' vertical field of view, radians.
pub const FOV_Y: f32 = 60.0 * core::f32::consts::PI / 180.0;
/// The model scenes' near and far planes.
pub const NEAR_FAR: [f32; 2] = [0.1, 20.0];
/// Towards the model scenes' light, and its ambient fraction.
pub const LIGHT: ([f32; 3], f32) = ([0.4, 1.0, 0.7], 0.2);
/// How a model scene (`cube`, `mesh1k`) is turned: yaw `MODEL_TURN.0 + angle`, pitch
/// `MODEL_TURN.1`.
pub const MODEL_TURN: (f32, f32) = (0.35, 0.2);

/// The model scenes' camera (`MathLib::Libm`: tangent by libm in f32, from exact integer
/// sines in fixed point).
pub fn camera<N: Scalar>() -> Option<Camera<N>> {
    camera_with(MathLib::Libm)
}

/// The model scenes' camera, its tangent from `math`.
pub fn camera_with<N: Scalar>(math: MathLib) -> Option<Camera<N>> {
    let projection = Camera::<N>::perspective_with(math, FOV_Y, NEAR_FAR[0], NEAR_FAR[1])?;
    Camera::look_at(EYE, [0.0; 3], [0.0, 1.0, 0.0], projection)
}

/// The scenes the presets are measured on (`crates/zrow-tradeoff`, `emu/`).
pub const PRESET_SCENES: [&str; 3] = ["cube", "mesh1k", "interlocked"];

/// The depth cue of the preset measurements: full intensity up to 3 units from the eye, 0.2
/// from 6 on (the model scenes' objects lie about 3.4 to 5.5 from the eye).
pub const PRESET_CUE: DepthCue = DepthCue {
    near: 3.0,
    far: 6.0,
    floor: 0.2,
    interpolation: Interpolation::PerspectiveCorrect,
};

/// Calls `f` with a model scene as `preset` draws it: built with the preset's maths, its
/// configuration from [`Preset::config`] with [`PRESET_CUE`]. `None` for an unknown name.
pub fn with_preset_scene<N: Format, R>(
    name: &str,
    preset: &Preset,
    f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
) -> Option<R> {
    with_scene_math(name, 0.0, preset.math, |scene, cfg, faces| {
        f(scene, &preset.config(*cfg, PRESET_CUE), faces)
    })
}

/// The model scenes' light.
pub fn light<N: Scalar>() -> Option<Light<N>> {
    Some(Light {
        direction: Vec3::from_f32([0.4, 1.0, 0.7])?,
        ambient: N::from_f32(0.2)?,
    })
}

/// The smooth-shaded scenes: `mesh1k-smooth`, the torus with its surface normals at the
/// vertices, configured for [`zrow::shading::Shading::Gouraud`] (a renderer that keeps
/// intensity planes draws it: `zrow::scanline_for!(N, REQ, gouraud)`), and `mesh1k-dither`,
/// the same dithered.
pub const SMOOTH: [&str; 2] = ["mesh1k-smooth", "mesh1k-dither"];

/// The hidden-line scenes (the `lines` feature): `mesh1k-lines`, the torus configured for
/// [`zrow::shading::Shading::Facets`], to be drawn into a `zrow::lines::HiddenLines` sink.
pub const LINES: [&str; 1] = ["mesh1k-lines"];

/// Calls `f` with the named scene, its configuration (240×240) and its face count; `None` for
/// an unknown name. `angle` (radians) turns model scenes about the vertical axis. Names: the
/// standard scenes ([`NAMES`]), the demos ([`DEMOS`]), the comparison scenes ([`FOLEY`]), the
/// smooth-shaded ones ([`SMOOTH`]) and, with the `lines` feature, the hidden-line ones
/// ([`LINES`]).
pub fn with_scene<N: Format, R>(
    name: &str,
    angle: f32,
    f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
) -> Option<R> {
    with_scene_math(name, angle, MathLib::Libm, f)
}

/// [`with_scene`] with the model scenes' trig from `math`.
pub fn with_scene_math<N: Format, R>(
    name: &str,
    angle: f32,
    math: MathLib,
    f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
) -> Option<R> {
    if name == "interlocked" {
        return interlocked(angle, math, f);
    }
    if name == "random400" {
        // Its vertices lent to the renderer, snapped: a scan-line renderer keeps no copy.
        let scene = SnappedScene {
            vertices: N::random400_snapped(),
            faces: Faces::Triangles {
                indices: &meshes::RANDOM400_TRIANGLES,
                colors: &meshes::RANDOM400_COLORS,
            },
            subpixel_bits: 8,
        };
        return Some(f(&scene, &Config::screen(SIZE, SIZE), scene.faces.len()));
    }
    let mesh = mesh::<N>(name)?;
    let faces = mesh.faces.len();
    if FOLEY.contains(&name) {
        return Some(f(&ScreenScene { mesh }, &Config::screen(SIZE, SIZE), faces));
    }
    #[cfg(feature = "lines")]
    if LINES.contains(&name) {
        return model(mesh, angle, math, |scene, cfg, faces| {
            let cfg = Config {
                shading: zrow::shading::Shading::Facets,
                ..*cfg
            };
            f(scene, &cfg, faces)
        });
    }
    if SMOOTH.contains(&name) {
        return model(mesh, angle, math, |scene, cfg, faces| {
            let cfg = Config {
                shading: zrow::shading::Shading::Gouraud {
                    dither: name == "mesh1k-dither",
                },
                ..*cfg
            };
            f(scene, &cfg, faces)
        });
    }
    model(mesh, angle, math, f)
}

/// [`with_scene`] for the demo scenes ([`DEMOS`]) alone, with `MathLib::Libm`: a program that
/// shows only these (the board's demo) links only their meshes, not the comparison scenes'
/// (which [`with_scene`]'s lookup by name keeps in flash). `None` for another name.
pub fn with_demo<N: Format, R>(
    name: &str,
    angle: f32,
    f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
) -> Option<R> {
    match name {
        "interlocked" => demo::interlocked(angle, f),
        "cube" => demo::cube(angle, f),
        "mesh1k" => demo::mesh1k(angle, f),
        _ => None,
    }
}

/// The demo scenes one function each, as [`with_demo`] draws them: a program that shows some
/// of them (a board with little flash) links only those functions' meshes.
pub mod demo {
    use super::*;

    /// The interlocked rings and cube (`"interlocked"`).
    pub fn interlocked<N: Format, R>(
        angle: f32,
        f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
    ) -> Option<R> {
        super::interlocked(angle, MathLib::Libm, f)
    }

    /// The cube (`"cube"`).
    pub fn cube<N: Format, R>(
        angle: f32,
        f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
    ) -> Option<R> {
        let mesh = cube_with(&meshes::CUBE_FACES);
        model(mesh, angle, MathLib::Libm, f)
    }

    /// The 1,000-triangle torus (`"mesh1k"`).
    pub fn mesh1k<N: Format, R>(
        angle: f32,
        f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
    ) -> Option<R> {
        let mesh = compact_triangles(
            &meshes::TORUS_I16,
            &meshes::TORUS_TRIANGLES,
            &meshes::TORUS_COLORS,
        );
        model(mesh, angle, MathLib::Libm, f)
    }
}

/// A model scene of one mesh, turned by `angle`, as the standard camera and light see it.
fn model<N: Format, R>(
    mesh: Mesh<'static, N>,
    angle: f32,
    math: MathLib,
    f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
) -> Option<R> {
    let faces = mesh.faces.len();
    let objects = [Object {
        mesh: &mesh,
        transform: Affine::rotate_yx_translate_with(
            math,
            MODEL_TURN.0 + angle,
            MODEL_TURN.1,
            [0.0; 3],
        )?,
    }];
    let scene = ModelScene {
        objects: &objects,
        camera: camera_with(math)?,
        light: light()?,
    };
    Some(f(&scene, &Config::model(SIZE, SIZE), faces))
}

/// Two rings linked through each other and a cube through both, turning by `angle`: one lit
/// colour per object (a warm ring, a cool ring, a pale cube), scaled by [`INTERLOCKED_SCALE`]
/// to fill most of the view.
fn interlocked<N: Format, R>(
    angle: f32,
    math: MathLib,
    f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
) -> Option<R> {
    let warm = compact_triangles(
        &meshes::RING_I16,
        &meshes::RING_TRIANGLES,
        &meshes::RING_WARM_COLOR,
    );
    let cool = compact_triangles(
        &meshes::RING_I16,
        &meshes::RING_TRIANGLES,
        &meshes::RING_COOL_COLOR,
    );
    let cube = cube_with(&meshes::CUBE_PLAIN_FACES);
    let [a, b, c] = interlocked_turns::<N>(angle, math)?;
    let objects = [
        Object {
            mesh: &warm,
            transform: a,
        },
        Object {
            mesh: &cool,
            transform: b,
        },
        Object {
            mesh: &cube,
            transform: c,
        },
    ];
    let scene = ModelScene {
        objects: &objects,
        camera: camera_with(math)?,
        light: light()?,
    };
    let faces = warm.faces.len() + cool.faces.len() + cube.faces.len();
    Some(f(&scene, &Config::model(SIZE, SIZE), faces))
}

/// The interlocked objects' placements at `angle`: ring A lies flat, ring B stands up through
/// A's hole, the cube sits where they cross. Out of line, so the temporaries of composing them
/// leave the stack before the frame is drawn (a board with 20 KB of RAM counts them).
#[inline(never)]
fn interlocked_turns<N: Format>(angle: f32, math: MathLib) -> Option<[Affine<N>; 3]> {
    let turn =
        |yaw: f32, pitch: f32, t: [f32; 3]| Affine::rotate_yx_translate_with(math, yaw, pitch, t);
    let s = INTERLOCKED_SCALE;
    let grow = Affine::from_f32([[s, 0.0, 0.0, 0.0], [0.0, s, 0.0, 0.0], [0.0, 0.0, s, 0.0]])?;
    let spin = grow.then_after(&turn(angle, 0.3, [0.0; 3])?);
    Some([
        spin.then_after(&turn(0.0, 0.0, [-0.35, 0.0, 0.0])?),
        spin.then_after(&turn(0.0, core::f32::consts::FRAC_PI_2, [0.35, 0.0, 0.0])?),
        spin.then_after(&turn(2.0 * angle, 0.6, [0.0, 0.0, 0.0])?),
    ])
}

/// How much the interlocked demo is scaled up (its rings are 1.9 units across): to fill most
/// of the 240 × 240 view from the model scenes' camera.
pub const INTERLOCKED_SCALE: f32 = 1.5;

/// The colour of `Rgb565` pixels as the little-endian `u16` words the frame hash reads.
pub fn raw(c: Rgb565) -> u16 {
    use embedded_graphics_core::pixelcolor::IntoStorage;
    c.into_storage()
}

/// FNV-1a 64 over pixels as little-endian `u16`: the frame hash the emulated benches and the
/// host compare.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameHash(pub u64);

impl Default for FrameHash {
    fn default() -> Self {
        FrameHash(0xcbf2_9ce4_8422_2325)
    }
}

impl FrameHash {
    /// Adds pixels. Out of line, so that every frame the emulated bench counts hashes with the
    /// same code as the hash it measures alone and subtracts (inlined, its loop's unrolling
    /// followed whatever else the caller inlined).
    #[inline(never)]
    pub fn add(&mut self, pixels: &[Rgb565]) {
        for &p in pixels {
            for b in raw(p).to_le_bytes() {
                self.0 = (self.0 ^ b as u64).wrapping_mul(0x100_0000_01b3);
            }
        }
    }
}

impl<N> zrow::RowSink<N> for FrameHash {
    type Error = core::convert::Infallible;
    /// Colours only.
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &zrow::Row<'_, N>) -> Result<(), Self::Error> {
        self.add(row.color);
        Ok(())
    }
}
