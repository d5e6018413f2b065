//! Scene builders for the frame benchmark.
//!
//! Meshes are generated in `f32`, checked (faces counter-clockwise seen from outside), then
//! converted to the renderer's number format with `Vec3::<N>::from_f32`, so every scene exists
//! in both `Q16_16` and `f32` from one generic builder.

use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{
    Affine, Camera, Config, Face, Light, Mesh, ModelScene, Object, Scalar, Scene, ScreenScene, Vec3,
};

/// Owned mesh data in format `N`; [`MeshData::faces`] borrows it as `zrow` faces.
pub struct MeshData<N> {
    pub vertices: Vec<Vec3<N>>,
    pub polygons: Vec<(Vec<u16>, Rgb565)>,
}

impl<N: Scalar> MeshData<N> {
    fn from_f32(vertices: &[[f32; 3]], polygons: Vec<(Vec<u16>, Rgb565)>) -> Self {
        assert!(
            vertices.len() <= u16::MAX as usize,
            "too many vertices for u16 indices"
        );
        let vertices = vertices
            .iter()
            .map(|&v| Vec3::<N>::from_f32(v).expect("vertex not representable in format"))
            .collect();
        MeshData { vertices, polygons }
    }

    /// The faces, borrowing this mesh's index lists.
    pub fn faces(&self) -> Vec<Face<'_>> {
        self.polygons
            .iter()
            .map(|(indices, color)| Face {
                indices,
                color: *color,
            })
            .collect()
    }
}

type V = [f32; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: V, b: V) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Asserts every face is counter-clockwise seen from outside: its normal points away from
/// `inside(centroid)`, a point inside the solid near the face.
fn assert_outward(vertices: &[V], polygons: &[(Vec<u16>, Rgb565)], inside: impl Fn(V) -> V) {
    for (no, (idx, _)) in polygons.iter().enumerate() {
        let p = |k: usize| vertices[idx[k] as usize];
        let normal = cross(sub(p(1), p(0)), sub(p(2), p(0)));
        let n = idx.len() as f32;
        let mut c = [0.0f32; 3];
        for &i in idx {
            for (ck, vk) in c.iter_mut().zip(vertices[i as usize]) {
                *ck += vk / n;
            }
        }
        assert!(
            dot(normal, sub(c, inside(c))) > 0.0,
            "face {no} is not counter-clockwise seen from outside"
        );
    }
}

/// The unit cube centred on the origin: 6 quads, one colour each.
pub fn cube<N: Scalar>() -> MeshData<N> {
    // Corner i is (x, y, z) = bits (0, 1, 2) of i, shifted to -0.5..0.5.
    let vertices: Vec<V> = (0..8)
        .map(|i| {
            let c = |bit: u32| ((i >> bit) & 1) as f32 - 0.5;
            [c(0), c(1), c(2)]
        })
        .collect();
    let quads: [([u16; 4], Rgb565); 6] = [
        ([1, 3, 7, 5], Rgb565::RED),     // +x
        ([0, 4, 6, 2], Rgb565::CYAN),    // -x
        ([2, 6, 7, 3], Rgb565::GREEN),   // +y
        ([0, 1, 5, 4], Rgb565::MAGENTA), // -y
        ([4, 5, 7, 6], Rgb565::BLUE),    // +z
        ([0, 2, 3, 1], Rgb565::YELLOW),  // -z
    ];
    let polygons: Vec<_> = quads.iter().map(|(q, c)| (q.to_vec(), *c)).collect();
    assert_outward(&vertices, &polygons, |_| [0.0; 3]);
    MeshData::from_f32(&vertices, polygons)
}

/// A closed torus around the y axis: `ring` segments around the axis, `tube` segments round
/// the tube, two triangles per quad (`2 · ring · tube` faces).
pub fn torus<N: Scalar>(ring: usize, tube: usize, major: f32, minor: f32) -> MeshData<N> {
    use std::f32::consts::TAU;
    let mut vertices = Vec::with_capacity(ring * tube);
    for i in 0..ring {
        let u = TAU * i as f32 / ring as f32;
        for j in 0..tube {
            let v = TAU * j as f32 / tube as f32;
            let r = major + minor * v.cos();
            vertices.push([r * u.cos(), minor * v.sin(), r * u.sin()]);
        }
    }
    let palette = [
        Rgb565::new(31, 40, 8),
        Rgb565::new(8, 48, 28),
        Rgb565::new(24, 24, 31),
    ];
    let at = |i: usize, j: usize| ((i % ring) * tube + j % tube) as u16;
    let mut polygons = Vec::with_capacity(2 * ring * tube);
    for i in 0..ring {
        for j in 0..tube {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            let color = palette[(i + j) % palette.len()];
            polygons.push((vec![a, b, c], color));
            polygons.push((vec![a, c, d], color));
        }
    }
    // Inside the solid: the point of the tube's core circle nearest the face.
    assert_outward(&vertices, &polygons, |c| {
        let l = (c[0] * c[0] + c[2] * c[2]).sqrt();
        [major * c[0] / l, 0.0, major * c[2] / l]
    });
    MeshData::from_f32(&vertices, polygons)
}

/// A tiny deterministic RNG (Marsaglia's xorshift32).
pub struct XorShift32(u32);

impl XorShift32 {
    pub fn new(seed: u32) -> Self {
        XorShift32(seed.max(1))
    }
    pub fn next_u32(&mut self) -> u32 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.0 = x;
        x
    }
    /// Uniform in `0.0..1.0` (24 random bits).
    pub fn unit(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 / (1u32 << 24) as f32
    }
}

/// `count` random screen-space triangles: x in `0..width`, y in `0..height`, depth in
/// `0..max_depth`, random non-black colours. Either winding (screen scenes are not culled).
pub fn random_triangles<N: Scalar>(
    count: usize,
    width: f32,
    height: f32,
    max_depth: f32,
    seed: u32,
) -> MeshData<N> {
    let mut rng = XorShift32::new(seed);
    let mut vertices = Vec::with_capacity(3 * count);
    let mut polygons = Vec::with_capacity(count);
    for t in 0..count {
        for _ in 0..3 {
            vertices.push([
                rng.unit() * width,
                rng.unit() * height,
                rng.unit() * max_depth,
            ]);
        }
        // Never the black background: set the low bit of every channel.
        let color = Rgb565::from(RawU16::new(rng.next_u32() as u16 | 0x0821));
        let k = (3 * t) as u16;
        polygons.push((vec![k, k + 1, k + 2], color));
    }
    MeshData::from_f32(&vertices, polygons)
}

/// The benchmark camera: from (2.5, 1.8, 3.2) at the origin, 60° vertical field of view,
/// near 0.1, far 20.
pub fn camera<N: Scalar>() -> Camera<N> {
    let projection =
        Camera::<N>::perspective(60f32.to_radians(), 0.1, 20.0).expect("projection fits format");
    Camera::look_at([2.5, 1.8, 3.2], [0.0; 3], [0.0, 1.0, 0.0], projection)
        .expect("camera fits format")
}

/// A directional light from above, right and front, with ambient 0.2.
pub fn light<N: Scalar>() -> Light<N> {
    Light {
        direction: Vec3::from_f32([0.4, 1.0, 0.7]).expect("light fits format"),
        ambient: N::from_f32(0.2).expect("ambient fits format"),
    }
}

/// A small rotation about the origin.
pub fn tilt<N: Scalar>() -> Affine<N> {
    Affine::rotate_yx_translate(0.35, 0.2, [0.0; 3]).expect("transform fits format")
}

/// The standard scenes by name: `cube`, `mesh1k` (model mode, benchmark camera and light) and
/// `random400` (screen space), each at 240×240. Calls `f` with the scene, its configuration
/// and its face count; `None` for an unknown name.
pub fn with_scene<N: Scalar, R>(
    name: &str,
    f: impl FnOnce(&dyn Scene<N>, &Config, usize) -> R,
) -> Option<R> {
    let data = match name {
        "cube" => cube::<N>(),
        "mesh1k" => torus::<N>(25, 20, 1.0, 0.4),
        "random400" => random_triangles::<N>(400, 240.0, 240.0, 100.0, 0x2545_f491),
        _ => return None,
    };
    let faces = data.faces();
    let mesh = Mesh {
        vertices: &data.vertices,
        faces: &faces,
    };
    if name == "random400" {
        return Some(f(
            &ScreenScene { mesh },
            &Config::screen(240, 240),
            faces.len(),
        ));
    }
    let objects = [Object {
        mesh: &mesh,
        transform: tilt(),
    }];
    let scene = ModelScene {
        objects: &objects,
        camera: camera(),
        light: light(),
    };
    Some(f(&scene, &Config::model(240, 240), faces.len()))
}

/// The standard scenes' names, in report order.
pub const NAMES: [&str; 3] = ["cube", "mesh1k", "random400"];
