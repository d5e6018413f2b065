//! A lit cube pierced by a pyramid, turning, drawn by the scan-line method with a camera and a
//! light — the program a new user writes first, in both number formats:
//!
//! ```sh
//! cargo run -p zrow --example lit_scene
//! ```
//!
//! It sizes the renderer from the scene (`zrow::requirements` over the frames it will draw),
//! draws 24 frames into a frame buffer, and checks what a user would look at: both objects
//! show, lit faces differ in brightness, the pyramid pierces the cube (the visible surface
//! changes where they cross), and Q16.16 and f32 agree on nearly every pixel. It exits non-zero
//! if any of that fails (CI runs it).

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{
    requirements, Affine, Camera, Config, Face, FrameBuffer, Light, Mesh, ModelScene, Object,
    Projection, Requirements, Scalar, Scanline, Vec3, Q16_16,
};

const SIZE: u16 = 120;
const FRAMES: usize = 24;

/// A unit cube (corners at ±0.5) and a square pyramid (base 1.2 wide at y = −0.9, apex at
/// y = 0.9), so the pyramid's tip comes out of the cube's top.
const CUBE: [[f32; 3]; 8] = [
    [-0.5, -0.5, -0.5],
    [0.5, -0.5, -0.5],
    [0.5, 0.5, -0.5],
    [-0.5, 0.5, -0.5],
    [-0.5, -0.5, 0.5],
    [0.5, -0.5, 0.5],
    [0.5, 0.5, 0.5],
    [-0.5, 0.5, 0.5],
];
/// Counter-clockwise seen from outside (the front faces a back-face cull keeps).
const CUBE_FACES: [[u16; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [2, 3, 7, 6],
    [1, 2, 6, 5],
    [0, 4, 7, 3],
];
const PYRAMID: [[f32; 3]; 5] = [
    [-0.6, -0.9, -0.6],
    [0.6, -0.9, -0.6],
    [0.6, -0.9, 0.6],
    [-0.6, -0.9, 0.6],
    [0.0, 0.9, 0.0],
];
const PYRAMID_FACES: [[u16; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 3],
    [0, 4, 1],
    [1, 4, 2],
    [2, 4, 3],
    [3, 4, 0],
];

/// Big enough for this scene from any angle (checked against `requirements` before drawing).
type Renderer<N> = Scanline<N, { SIZE as usize }, 64, 32, 16>;

struct Frame {
    pixels: Vec<Rgb565>,
    stats: zrow::FrameStats,
}

fn draw<N: Scalar>() -> Vec<Frame> {
    let v = |p: &[[f32; 3]]| -> Vec<Vec3<N>> {
        p.iter().map(|c| Vec3::from_f32(*c).unwrap()).collect()
    };
    let (cube_v, pyr_v) = (v(&CUBE), v(&PYRAMID));
    let cube_f: Vec<Face> = CUBE_FACES
        .iter()
        .map(|f| Face::new(f, Rgb565::new(31, 40, 6)))
        .collect();
    let pyr_f: Vec<Face> = PYRAMID_FACES
        .iter()
        .map(|f| Face::new(f, Rgb565::new(6, 44, 31)))
        .collect();
    let (cube, pyramid) = (Mesh::new(&cube_v, &cube_f), Mesh::new(&pyr_v, &pyr_f));
    let projection = Projection::<N>::perspective(1.0, 0.1, 20.0).unwrap();
    let camera = Camera::look_at([1.8, 1.4, 2.6], [0.0; 3], [0.0, 1.0, 0.0], projection).unwrap();
    let light = Light {
        direction: Vec3::from_f32([0.4, 1.0, 0.7]).unwrap(),
        ambient: N::from_f32(0.2).unwrap(),
    };
    let cfg = Config::model(SIZE, SIZE);
    let scene_at = |k: usize, f: &mut dyn FnMut(&ModelScene<'_, N>)| {
        let turn = k as f32 * core::f32::consts::TAU / FRAMES as f32;
        let objects = [
            Object {
                mesh: &cube,
                transform: Affine::rotate_yx_translate(turn, 0.3, [0.0; 3]).unwrap(),
            },
            Object {
                mesh: &pyramid,
                transform: Affine::rotate_yx_translate(-turn, 0.0, [0.0; 3]).unwrap(),
            },
        ];
        f(&ModelScene {
            objects: &objects,
            camera,
            light,
        });
    };

    // What the scene needs over the frames drawn, against the renderer's capacities.
    let mut need = Requirements::default();
    for k in 0..FRAMES {
        scene_at(k, &mut |s| {
            need = need.max(requirements(s, &cfg).unwrap());
        });
    }
    assert!(
        need.vertices <= 64 && need.polygons <= 32 && need.active_polygons <= 16,
        "the renderer is too small for {need:?}"
    );
    println!(
        "{}: needs {need:?}: {} bytes at exactly that ({} as built)",
        N::NAME,
        zrow::scanline::ram_bytes::<N>(&need),
        Renderer::<N>::RAM_BYTES
    );

    let mut renderer = Box::new(Renderer::<N>::new());
    let mut frames = Vec::new();
    for k in 0..FRAMES {
        let mut pixels = vec![Rgb565::BLACK; SIZE as usize * SIZE as usize];
        let mut stats = None;
        scene_at(k, &mut |s| {
            let mut fb = FrameBuffer::new(&mut pixels, SIZE as usize);
            stats = Some(renderer.render(s, &cfg, &mut fb).unwrap());
        });
        frames.push(Frame {
            pixels,
            stats: stats.unwrap(),
        });
    }
    frames
}

/// Whether a colour is one of the cube's shades (red dominant) or the pyramid's (blue).
fn is_cube(c: Rgb565) -> bool {
    c.r() > c.b() && c != Rgb565::BLACK
}
fn is_pyramid(c: Rgb565) -> bool {
    c.b() > c.r() && c != Rgb565::BLACK
}

fn main() {
    let q16 = draw::<Q16_16>();
    let f32s = draw::<f32>();
    let mut differ_worst = 0.0f64;
    for (k, (a, b)) in q16.iter().zip(&f32s).enumerate() {
        let cube = a.pixels.iter().filter(|&&c| is_cube(c)).count();
        let pyramid = a.pixels.iter().filter(|&&c| is_pyramid(c)).count();
        let mut shades: Vec<Rgb565> = a.pixels.iter().copied().filter(|&c| is_cube(c)).collect();
        shades.sort_by_key(|c| (c.r(), c.g(), c.b()));
        shades.dedup();
        let differ = a
            .pixels
            .iter()
            .zip(&b.pixels)
            .filter(|(x, y)| x != y)
            .count();
        let share = differ as f64 / a.pixels.len() as f64;
        differ_worst = differ_worst.max(share);
        if k % 5 == 0 {
            println!(
                "frame {k:2}: {cube:5} cube px, {pyramid:5} pyramid px, {} cube shades, {} polygons, {} front changes, {} crossings; Q16.16 vs f32: {differ} px differ",
                shades.len(),
                a.stats.polygons,
                a.stats.front_changes,
                a.stats.crossings
            );
        }
        assert!(cube > 500 && pyramid > 200, "frame {k}: both objects show");
        assert!(
            shades.len() >= 2,
            "frame {k}: the light shades the cube's faces differently"
        );
    }
    // Interpenetration: somewhere the visible surface changes where the two cross.
    assert!(
        q16.iter().any(|f| f.stats.crossings > 0),
        "the pyramid pierces the cube"
    );
    // The formats round differently only along edges and crossings.
    assert!(
        differ_worst < 0.02,
        "Q16.16 and f32 differ on {differ_worst:.3} of a frame"
    );
    println!(
        "{FRAMES} frames in Q16.16 and f32: both objects lit in every frame; formats differ on at most {:.2} % of a frame",
        differ_worst * 100.0
    );
}
