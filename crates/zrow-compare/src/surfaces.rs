//! The comparison scene: the same four surfaces tessellated into 100, 2,500 or 60,000
//! triangles, in screen space.
//!
//! Sutherland, Sproull & Schumacker (1974), whose estimates Foley & van Dam's Table 15.3
//! reprints, grew the polygon count by tessellating the same scene finer: the picture and its
//! depth complexity stay about the same while the polygons get smaller. This scene does the
//! same with two tilted tori, overlapping on screen, and two wavy sheets that cut through both
//! tori and through each other (so every method meets intersections, not just overlaps):
//!
//! | polygons | each torus (ring × tube quads) | each sheet (quads) |
//! |---|---|---|
//! | 100 | 4 × 4 → 32 triangles | 3 × 3 → 18 |
//! | 2,500 | 20 × 20 → 800 | 15 × 15 → 450 |
//! | 60,000 | 100 × 96 → 19,200 | 75 × 72 → 10,800 |
//!
//! (two of each: 2·32 + 2·18 = 100, 2·800 + 2·450 = 2,500, 2·19,200 + 2·10,800 = 60,000).
//! The surfaces are defined in a unit cube (x right, y down, z depth, smaller nearer) and
//! scaled to `size` pixels; depth spans about `0..size`. Positions are rounded to 1/256 pixel
//! (x, y: the snapping grid's 8 sub-pixel bits) and 1/1024 (z), so the f32 and Q16.16 versions
//! of a scene are exactly the same numbers. Each face is coloured by its surface and shaded by
//! a fixed light on its normal (screen-space mode draws colours as they are).
//!
//! This file has no dependencies: `crates/zrow-scenes/build.rs` includes it by path to
//! generate the 240×240 versions as flash-resident consts for the emulated Cortex-M4, so the
//! host and the emulator draw the same scene.

use std::f64::consts::TAU;

/// The polygon counts of Foley & van Dam's Table 15.3.
pub const POLYGONS: [usize; 3] = [100, 2_500, 60_000];

/// A screen-space triangle mesh: positions in pixels (x, y) and depth (z), triangles with an
/// Rgb565 colour as `(r5, g6, b5)`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Surfaces {
    /// Vertex positions, `[x, y, z]`.
    pub vertices: Vec<[f32; 3]>,
    /// Triangles (vertex indices) and colours.
    pub faces: Vec<([u16; 3], (u8, u8, u8))>,
}

/// Grid sizes for a polygon count: (torus ring, torus tube, sheet u, sheet v) in quads.
fn grids(polygons: usize) -> Option<(usize, usize, usize, usize)> {
    match polygons {
        100 => Some((4, 4, 3, 3)),
        2_500 => Some((20, 20, 15, 15)),
        60_000 => Some((100, 96, 75, 72)),
        _ => None,
    }
}

type P = [f64; 3];

/// Rotation about x by `a`, then about y by `b`.
fn rotate(p: P, a: f64, b: f64) -> P {
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (x, y, z) = (p[0], p[1] * ca - p[2] * sa, p[1] * sa + p[2] * ca);
    [x * cb + z * sb, y, -x * sb + z * cb]
}

impl Surfaces {
    /// Adds a `nu × nv` grid of quads over a parametric surface, two triangles each;
    /// `closed_u`/`closed_v` wrap the grid (a torus wraps both ways, a sheet neither).
    fn grid(
        &mut self,
        (nu, nv): (usize, usize),
        (closed_u, closed_v): (bool, bool),
        rgb: [f64; 3],
        at: impl Fn(f64, f64) -> P,
        size: f64,
    ) {
        let cols_u = if closed_u { nu } else { nu + 1 };
        let cols_v = if closed_v { nv } else { nv + 1 };
        let base = self.vertices.len();
        let mut pos = Vec::with_capacity(cols_u * cols_v);
        for i in 0..cols_u {
            for j in 0..cols_v {
                let p = at(i as f64 / nu as f64, j as f64 / nv as f64);
                pos.push(p);
                // x, y to 1/256 pixel, z to 1/1024: exact in f32 and in Q16.16.
                let q = |v: f64, k: f64| ((v * size * k).round() / k) as f32;
                self.vertices
                    .push([q(p[0], 256.0), q(p[1], 256.0), q(p[2], 1024.0)]);
            }
        }
        let index = |i: usize, j: usize| (i % cols_u) * cols_v + j % cols_v;
        for i in 0..nu {
            for j in 0..nv {
                let quad = [
                    index(i, j),
                    index(i, j + 1),
                    index(i + 1, j + 1),
                    index(i + 1, j),
                ];
                for tri in [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]] {
                    let colour = shade(rgb, tri.map(|k| pos[k]));
                    let idx = tri.map(|k| (base + k) as u16);
                    self.faces.push((idx, colour));
                }
            }
        }
    }
}

/// Lambert shading (two-sided) of a triangle under a fixed light, to Rgb565 channels.
fn shade(rgb: [f64; 3], t: [P; 3]) -> (u8, u8, u8) {
    let (a, b) = (
        [t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]],
        [t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]],
    );
    let n = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-12);
    let light = [-0.4, -0.6, -0.69]; // from the upper left, towards the scene (unit length)
    let lambert = ((n[0] * light[0] + n[1] * light[1] + n[2] * light[2]) / len).abs();
    let k = 0.3 + 0.7 * lambert;
    let c = |v: f64, max: f64| ((v * k * max).round().clamp(1.0, max)) as u8;
    (c(rgb[0], 31.0), c(rgb[1], 63.0), c(rgb[2], 31.0))
}

/// The comparison scene at `polygons` ∈ [`POLYGONS`] triangles for a `size × size` screen;
/// `None` for another count.
pub fn foley_scene(polygons: usize, size: f32) -> Option<Surfaces> {
    let (ring, tube, su, sv) = grids(polygons)?;
    let size = size as f64;
    let mut s = Surfaces::default();
    // Two tori, tilted differently, overlapping on screen.
    let torus = |c: P, tilt: (f64, f64)| {
        move |u: f64, v: f64| {
            let (major, minor) = (0.24, 0.085);
            let (su, cu) = (TAU * u).sin_cos();
            let (sv, cv) = (TAU * v).sin_cos();
            let r = major + minor * cv;
            let p = rotate([r * cu, minor * sv, r * su], tilt.0, tilt.1);
            [c[0] + p[0], c[1] + p[1], c[2] + p[2]]
        }
    };
    let t1 = torus([0.37, 0.40, 0.5], (1.05, 0.35));
    let t2 = torus([0.63, 0.60, 0.5], (0.25, 1.2));
    s.grid((ring, tube), (true, true), [1.0, 0.55, 0.2], t1, size);
    s.grid((ring, tube), (true, true), [0.3, 0.6, 1.0], t2, size);
    // Two wavy sheets, tilted in depth opposite ways, crossing the tori and each other.
    let sheet1 = |u: f64, v: f64| {
        let (x, y) = (0.04 + 0.92 * u, 0.06 + 0.88 * v);
        let z = 0.5 + 0.35 * (x - 0.5) + 0.06 * (TAU * 1.5 * y).sin() * (TAU * 0.5 * x).cos();
        [x, y, z]
    };
    let sheet2 = |u: f64, v: f64| {
        let (x, y) = (0.12 + 0.80 * u, 0.14 + 0.76 * v);
        let z = 0.5 - 0.3 * (y - 0.5) + 0.07 * (TAU * 1.25 * x).sin();
        [x, y, z]
    };
    s.grid((su, sv), (false, false), [0.35, 0.95, 0.35], sheet1, size);
    s.grid((su, sv), (false, false), [0.95, 0.35, 0.85], sheet2, size);
    debug_assert_eq!(s.faces.len(), polygons);
    Some(s)
}
