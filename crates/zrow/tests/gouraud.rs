//! Smooth (Gouraud) shading: a sphere against the analytic Lambert value, every method drawing
//! the same smooth frame, and the typed errors around it.

mod common;

use common::{every_method, painters, Capture, Colours};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::scanline::{ram_bytes_gouraud, ram_bytes_uncued};
use zrow::shading::Shading;
use zrow::{
    scanline_for, Affine, Camera, Config, Error, Face, Light, Mesh, ModelScene, Object, Projection,
    RenderError, Requirements, Scalar, Scanline, Vec3, Vectors, Q16_16, Q24_8,
};

/// The frame's size.
const S: u16 = 64;
/// Half the height the orthographic camera sees, world units.
const HALF: f64 = 1.25;
/// The light, towards it (world = view directions: the camera looks down −z from +z): from the
/// front, so that every compared point is lit (n·l ≥ 0.1 where z ≥ 0.35). Gouraud interpolates the vertices'
/// clamped Lambert values, so across the terminator, where `max(0, n·l)` has a kink, it is
/// off by up to the slope times a facet's width (2.4 LSB of green for this sphere lit from
/// the side): that is the method's error, not the arithmetic's.
const LIGHT: [f64; 3] = [0.15, 0.2, 0.97];
const AMBIENT: f64 = 0.2;

/// A unit sphere of `stacks` × `slices` quads cut into triangles (poles: triangles), facing
/// out, its vertex normals its positions.
fn sphere(stacks: usize, slices: usize) -> (Vec<[f64; 3]>, Vec<[u16; 3]>) {
    use std::f64::consts::PI;
    let mut v = vec![[0.0, 1.0, 0.0]];
    for i in 1..stacks {
        let t = PI * i as f64 / stacks as f64;
        for j in 0..slices {
            let p = 2.0 * PI * j as f64 / slices as f64;
            v.push([t.sin() * p.cos(), t.cos(), -t.sin() * p.sin()]);
        }
    }
    v.push([0.0, -1.0, 0.0]);
    let ring = |i: usize, j: usize| (1 + (i - 1) * slices + j % slices) as u16;
    let south = (v.len() - 1) as u16;
    let mut t = Vec::new();
    for j in 0..slices {
        t.push([0, ring(1, j), ring(1, j + 1)]);
        t.push([south, ring(stacks - 1, j + 1), ring(stacks - 1, j)]);
    }
    for i in 1..stacks - 1 {
        for j in 0..slices {
            let (a, b, c, d) = (
                ring(i, j),
                ring(i, j + 1),
                ring(i + 1, j),
                ring(i + 1, j + 1),
            );
            t.push([a, c, d]);
            t.push([a, d, b]);
        }
    }
    (v, t)
}

fn vec3<N: Scalar>(p: [f64; 3]) -> Vec3<N> {
    Vec3::from_f32([p[0] as f32, p[1] as f32, p[2] as f32]).unwrap()
}

/// The camera every test here looks through: orthographic, from +z down −z, [`HALF`] world
/// units above and below the centre.
fn camera<N: Scalar>() -> Camera<N> {
    let projection = Projection::orthographic(HALF as f32, 1.0, 10.0).unwrap();
    Camera::look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], projection).unwrap()
}

/// Draws spheres of `stacks` × `slices` centred at `at` with `draw` (a renderer of the caller's choosing) under `shading`.
fn with_sphere<N: Scalar, R>(
    (stacks, slices): (usize, usize),
    at: &[[f32; 3]],
    shading: Shading,
    normals: bool,
    draw: impl FnOnce(&ModelScene<'_, N, u16>, &Config) -> R,
) -> R {
    let (v, t) = sphere(stacks, slices);
    let vertices: Vec<Vec3<N>> = v.iter().map(|&p| vec3(p)).collect();
    let faces: Vec<Face<'_, u16>> = t
        .iter()
        .map(|t| Face {
            indices: &t[..],
            color: Rgb565::WHITE,
            alpha: 255,
        })
        .collect();
    let mut mesh = Mesh::new(&vertices, &faces);
    if normals {
        mesh = mesh.with_vertex_normals(Vectors::Format(&vertices));
    }
    let objects: Vec<Object<'_, N, u16>> = at
        .iter()
        .map(|&t| Object {
            mesh: &mesh,
            transform: Affine::rotate_yx_translate(0.0, 0.0, t).unwrap(),
        })
        .collect();
    let scene = ModelScene {
        objects: &objects,
        camera: camera(),
        light: Light {
            direction: vec3(LIGHT),
            ambient: N::from_f32(AMBIENT as f32).unwrap(),
        },
    };
    let mut cfg = Config::model(S, S);
    cfg.shading = shading;
    draw(&scene, &cfg)
}

/// The sphere compared with Lambert: 2,208 triangles (facets 7.5° apart).
const FINE: (usize, usize) = (24, 48);
/// The sphere every method draws: 224 triangles, within the capacities of [`every_method`].
const COARSE: (usize, usize) = (8, 16);

type Smooth<N> =
    Scanline<N, 64, 2048, 2048, 256, u16, zrow::scanline::Uncued, [zrow::IntensityPlane<N>; 2048]>;

fn smooth_frame<N: Scalar>(sphere: (usize, usize), at: &[[f32; 3]]) -> Capture<N> {
    smooth_frame_as::<N>(sphere, at, false)
}

fn smooth_frame_as<N: Scalar>(sphere: (usize, usize), at: &[[f32; 3]], dither: bool) -> Capture<N> {
    with_sphere::<N, _>(
        sphere,
        at,
        Shading::Gouraud { dither },
        true,
        |scene, cfg| {
            let mut cap = Capture::new(S as usize, S as usize);
            Box::new(Smooth::<N>::new())
                .as_mut()
                .render(scene, cfg, &mut cap)
                .unwrap();
            cap
        },
    )
}

/// The worst channel error, in LSB of the channel, over the pixels whose sphere point faces
/// the camera (z ≥ 0.5: away from the silhouette, where a ray meets the inscribed mesh far
/// from where it meets the sphere), and how many such pixels there are.
fn against_lambert<N: Scalar>(cap: &Capture<N>) -> (f64, usize) {
    let l = {
        let n = (LIGHT[0] * LIGHT[0] + LIGHT[1] * LIGHT[1] + LIGHT[2] * LIGHT[2]).sqrt();
        [LIGHT[0] / n, LIGHT[1] / n, LIGHT[2] / n]
    };
    let half = S as f64 / 2.0;
    let (mut worst, mut seen) = (0.0f64, 0);
    for j in 0..S as usize {
        for i in 0..S as usize {
            let x = ((i as f64 + 0.5) / half - 1.0) * HALF;
            let y = (1.0 - (j as f64 + 0.5) / half) * HALF;
            let zz = 1.0 - x * x - y * y;
            if zz < 0.5 * 0.5 {
                continue;
            }
            let n = [x, y, zz.sqrt()];
            let lambert = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]).max(0.0);
            let intensity = AMBIENT + (1.0 - AMBIENT) * lambert;
            let c = cap.at(i, j);
            for (got, max) in [(c.r(), 31.0), (c.g(), 63.0), (c.b(), 31.0)] {
                let e = (got as f64 - intensity * max).abs();
                if e > worst && std::env::var("GOURAUD_DEBUG").is_ok() {
                    eprintln!(
                        "({i},{j}) n {n:?} got {got} want {:.3} of {max}",
                        intensity * max
                    );
                }
                worst = worst.max(e);
            }
            seen += 1;
        }
    }
    (worst, seen)
}

#[test]
fn a_smooth_sphere_is_within_one_lsb_of_lambert() {
    let (q16, seen) = against_lambert(&smooth_frame::<Q16_16>(FINE, ONE));
    let (f32_, _) = against_lambert(&smooth_frame::<f32>(FINE, ONE));
    let (q24, _) = against_lambert(&smooth_frame::<Q24_8>(FINE, ONE));
    eprintln!("worst channel error, LSB: Q16.16 {q16:.3}, f32 {f32_:.3}, Q24.8 {q24:.3} over {seen} pixels");
    assert!(seen > 1500, "only {seen} pixels compared");
    for (name, e) in [("Q16.16", q16), ("f32", f32_), ("Q24.8", q24)] {
        assert!(e <= 1.0, "{name}: {e:.3} LSB from Lambert");
    }
    // Flat shading of the same sphere is not: its facets are visible.
    let flat = with_sphere::<Q16_16, _>(FINE, ONE, Shading::Flat, true, |scene, cfg| {
        let mut cap = Capture::new(S as usize, S as usize);
        Box::new(Smooth::<Q16_16>::new())
            .as_mut()
            .render(scene, cfg, &mut cap)
            .unwrap();
        cap
    });
    let (e, _) = against_lambert(&flat);
    assert!(
        e > 2.0,
        "flat shading is {e:.3} LSB from Lambert: the test cannot tell"
    );
}

/// One sphere at the origin.
const ONE: &[[f32; 3]] = &[[0.0; 3]];
/// Three spheres overlapping on screen, at three depths: rows covered more than twice over,
/// which the scan-line method resolves pixel by pixel.
const PILE: &[[f32; 3]] = &[[-0.3, 0.0, 0.0], [0.0, 0.1, -1.0], [0.3, -0.1, 1.0]];

/// Two spheres that meet on screen without piling up: rows where spans overlap are swept, not
/// resolved pixel by pixel. Either in front: the right one's spans open inside the left one's
/// and come in front, or open behind it.
const PAIRS: [&[[f32; 3]]; 2] = [
    &[[-0.45, 0.0, -1.0], [0.45, 0.1, 0.0]],
    &[[-0.45, 0.0, 0.0], [0.45, 0.1, -1.0]],
];

/// The smooth scan-line frame into a sink that reads no depth equals its frame into one that
/// does. Without depths to write, the sweep paints a front's run in one piece past the spans
/// that open behind it; writing depths, it stops at each. In fixed point the shade, stepped
/// exactly, does not depend on where a run starts; f32's does, so it stops there too.
#[test]
fn a_smooth_frame_is_the_same_painted_ahead() {
    fn check<N: Scalar>() {
        for (pair, dither) in PAIRS.into_iter().flat_map(|p| [(p, false), (p, true)]) {
            let with_depth = smooth_frame_as::<N>((5, 10), pair, dither);
            let shading = Shading::Gouraud { dither };
            let (colours, stats) =
                with_sphere::<N, _>((5, 10), pair, shading, true, |scene, cfg| {
                    let mut colours = Colours(Vec::new());
                    let mut r = Box::new(Smooth::<N>::new());
                    let stats = r.as_mut().render(scene, cfg, &mut colours).unwrap();
                    (colours, stats)
                });
            assert!(stats.front_changes > 20, "{}: rows are swept", N::NAME);
            let s = S as usize;
            let differ = (colours.0.iter().enumerate())
                .filter(|&(k, &c)| c != with_depth.at(k % s, k / s))
                .count();
            assert_eq!(differ, 0, "{} (dither {dither}): pixels differ", N::NAME);
        }
    }
    check::<Q16_16>();
    check::<Q24_8>();
    check::<f32>();
}

/// Every method draws the same smooth frame, bit for bit, dithered or not, in each fixed-point
/// format (the painters, exact only without overlap, draw one sphere).
fn every_method_draws_the_same<N: Scalar>() {
    for dither in [false, true] {
        for m in &mut painters::<N>() {
            same_as_scanline(m, ONE, dither);
        }
        for m in &mut every_method::<N>() {
            same_as_scanline(m, ONE, dither);
            same_as_scanline(m, PILE, dither);
        }
    }
}

/// `m` draws the spheres at `at` as the scan-line method does (each of 224 triangles, or of
/// 80 when there are several: within the capacities of [`every_method`]).
fn same_as_scanline<N: Scalar>(m: &mut common::Method<N>, at: &[[f32; 3]], dither: bool) {
    let sphere = if at.len() > 1 { (5, 10) } else { COARSE };
    let reference = smooth_frame_as::<N>(sphere, at, dither);
    {
        if m.name == "scanline" {
            return; // Flat: refuses (tested below)
        }
        let (cap, _, _) = with_sphere::<N, _>(
            sphere,
            at,
            Shading::Gouraud { dither },
            true,
            |scene, cfg| m.scene(scene, cfg),
        )
        .unwrap_or_else(|e| panic!("{}: {e:?}", m.name));
        let differ = (0..S as usize)
            .flat_map(|j| (0..S as usize).map(move |i| (i, j)))
            .filter(|&(i, j)| cap.at(i, j) != reference.at(i, j))
            .count();
        let spheres = at.len();
        assert_eq!(
            differ, 0,
            "{} ({spheres} spheres, dither {dither}): {differ} pixels differ from the scan-line frame",
            m.name
        );
    }
}

#[test]
fn every_method_draws_the_same_smooth_frame_q16() {
    every_method_draws_the_same::<Q16_16>();
}

#[test]
fn every_method_draws_the_same_smooth_frame_q24() {
    every_method_draws_the_same::<Q24_8>();
}

#[test]
fn smooth_shading_without_vertex_normals_is_flat() {
    let draw = |shading| {
        with_sphere::<Q16_16, _>(FINE, ONE, shading, false, |scene, cfg| {
            let mut cap = Capture::new(S as usize, S as usize);
            Box::new(Smooth::<Q16_16>::new())
                .as_mut()
                .render(scene, cfg, &mut cap)
                .unwrap();
            cap.color
        })
    };
    assert_eq!(
        draw(Shading::Gouraud { dither: false }),
        draw(Shading::Flat)
    );
}

#[test]
fn a_flat_scanline_refuses_a_smooth_frame_before_any_row() {
    let (result, rows) = with_sphere::<Q16_16, _>(
        FINE,
        ONE,
        Shading::Gouraud { dither: false },
        true,
        |scene, cfg| {
            let mut cap = Capture::new(S as usize, S as usize);
            let r = Box::new(Scanline::<Q16_16, 64, 1024, 1024, 256>::new())
                .as_mut()
                .render(scene, cfg, &mut cap);
            (r.map(|_| ()), cap.drawn())
        },
    );
    assert!(
        matches!(result, Err(RenderError::Scene(Error::Unsupported { .. }))),
        "{result:?}"
    );
    assert_eq!(rows, 0);
}

#[test]
fn vertex_normals_of_the_wrong_count_are_a_typed_error() {
    let v = [Vec3::<Q16_16>::from_f32([0.0, 0.0, 0.0]).unwrap(); 3];
    let faces = [Face {
        indices: &[0u16, 1, 2][..],
        color: Rgb565::WHITE,
        alpha: 255,
    }];
    let mesh = Mesh::new(&v, &faces).with_vertex_normals(Vectors::Format(&v[..2]));
    let objects = [Object {
        mesh: &mesh,
        transform: Affine::identity(),
    }];
    let scene = ModelScene {
        objects: &objects,
        camera: camera(),
        light: Light {
            direction: vec3([0.0, 0.0, 1.0]),
            ambient: Q16_16::ONE,
        },
    };
    let mut cap = Capture::new(8, 8);
    let r =
        Box::new(Smooth::<Q16_16>::new())
            .as_mut()
            .render(&scene, &Config::model(8, 8), &mut cap);
    assert_eq!(
        r.map(|_| ()),
        Err(RenderError::Scene(Error::VertexNormals {
            vertices: 3,
            normals: 2
        }))
    );
}

#[test]
fn the_smooth_renderer_is_the_uncued_one_and_a_plane_per_polygon() {
    const REQ: Requirements = Requirements {
        polygons: 100,
        edges: 300,
        vertices: 60,
        active_polygons: 12,
        width: 64,
    };
    type R = scanline_for!(Q16_16, REQ, gouraud);
    let planes = 100 * core::mem::size_of::<zrow::IntensityPlane<Q16_16>>();
    assert_eq!(planes, 2400); // the levels' plane (20 B) and the dither flag
    assert_eq!(
        ram_bytes_gouraud::<Q16_16>(&REQ),
        ram_bytes_uncued::<Q16_16>(&REQ) + planes
    );
    // The formula is the struct, up to the bytes that align its tables.
    let real = R::RAM_BYTES;
    let formula = ram_bytes_gouraud::<Q16_16>(&REQ);
    assert!(
        real >= formula && real - formula < 32,
        "{real} vs {formula}"
    );
}

/// Ordered dithering: over each 4 × 4 block a channel averages its exact value `c·level/255`
/// within 1/16 of a step (rounding alone is off by up to half a step), never passes `c`, and
/// leaves the full and zero levels exact.
#[test]
fn dithering_averages_the_exact_channel() {
    use zrow::raster::{shade_level, shade_level_dithered};
    let (mut worst_dither, mut worst_round) = (0.0f64, 0.0f64);
    for ch in 0..=63u8 {
        let c = Rgb565::new(ch.min(31), ch, 31 - ch.min(31));
        for level in 0..=255u8 {
            let mut sum = [0u32; 3];
            for y in 0..4 {
                for x in 0..4 {
                    let d = shade_level_dithered(c, level, x, y);
                    let pairs = [(d.r(), c.r()), (d.g(), c.g()), (d.b(), c.b())];
                    for (s, (v, max)) in sum.iter_mut().zip(pairs) {
                        assert!(v <= max, "channel {v} passes {max}");
                        *s += v as u32;
                    }
                    if level == 255 || level == 0 {
                        assert_eq!(d, shade_level(c, level));
                    }
                }
            }
            let r = shade_level(c, level);
            let channels = [(c.r(), r.r()), (c.g(), r.g()), (c.b(), r.b())];
            for (s, (full, rounded)) in sum.iter().zip(channels) {
                let exact = full as f64 * level as f64 / 255.0;
                worst_dither = worst_dither.max((*s as f64 / 16.0 - exact).abs());
                worst_round = worst_round.max((rounded as f64 - exact).abs());
            }
        }
    }
    eprintln!("4x4 block mean from the exact channel: dithered {worst_dither:.4}, rounded {worst_round:.4} LSB");
    assert!(worst_dither <= 1.0 / 16.0, "{worst_dither}");
    assert!(
        worst_round > 0.45,
        "rounding alone is as close: the test cannot tell"
    );
}

/// Vertex normals at the extremes (zero, huge, tiny; in f32 also infinite and not a number)
/// draw in every method without a panic: the sphere comes out, its faces lit as the format
/// can (a normal that cannot be lit is unlit, a plane that cannot be fitted leaves the face
/// flat), never an error.
fn extreme_normals_draw<N: Scalar>(extremes: &[f32]) {
    let (v, t) = sphere(6, 12);
    let vertices: Vec<Vec3<N>> = v.iter().map(|&p| vec3(p)).collect();
    let normals: Vec<Vec3<N>> = (0..v.len())
        .map(|k| {
            let e = |j: usize| extremes[(3 * k + j) % extremes.len()];
            Vec3::new(
                N::from_f32(e(0)).unwrap_or(N::MAX),
                N::from_f32(e(1)).unwrap_or(N::MAX),
                N::from_f32(e(2)).unwrap_or(N::ZERO),
            )
        })
        .collect();
    let faces: Vec<Face<'_, u16>> = t
        .iter()
        .map(|t| Face {
            indices: &t[..],
            color: Rgb565::WHITE,
            alpha: 255,
        })
        .collect();
    let mesh = Mesh::new(&vertices, &faces).with_vertex_normals(Vectors::Format(&normals));
    let objects = [Object {
        mesh: &mesh,
        transform: Affine::identity(),
    }];
    let scene = ModelScene {
        objects: &objects,
        camera: camera(),
        light: Light {
            direction: vec3(LIGHT),
            ambient: N::from_f32(AMBIENT as f32).unwrap(),
        },
    };
    for dither in [false, true] {
        let mut cfg = Config::model(S, S);
        cfg.shading = Shading::Gouraud { dither };
        let mut cap = Capture::new(S as usize, S as usize);
        Box::new(Smooth::<N>::new())
            .as_mut()
            .render(&scene, &cfg, &mut cap)
            .unwrap();
        assert!(
            cap.drawn() > 500,
            "{}: only {} pixels drawn",
            N::NAME,
            cap.drawn()
        );
        for m in every_method::<N>()
            .iter_mut()
            .chain(painters::<N>().iter_mut())
        {
            if m.name == "scanline" {
                continue; // Flat: refuses (tested above); the smooth one drew it
            }
            let (r, _) = m.outcome(&scene, &cfg);
            r.unwrap_or_else(|e| panic!("{} {}: {e:?}", N::NAME, m.name));
        }
    }
}

#[test]
fn extreme_vertex_normals_draw_in_every_method() {
    let fixed = [0.0, 1.0e4, -1.0e4, 1.0e-6, -0.5, 32767.0, -32768.0];
    extreme_normals_draw::<Q16_16>(&fixed);
    extreme_normals_draw::<Q24_8>(&fixed);
    extreme_normals_draw::<f32>(&[
        0.0,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        1.0e30,
        -1.0e-30,
        f32::MAX,
        f32::MIN_POSITIVE,
    ]);
}
