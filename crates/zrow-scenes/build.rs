//! Generates the standard meshes as const Rust data (`$OUT_DIR/meshes.rs`), once, on the
//! build host: the model meshes' positions (cube, torus, ring) as compact 16-bit integers at
//! 2^-14, one table for every number format; the screen-space scenes' positions in every
//! number format (f32, and Q16.16 and Q24.8 bits rounded to the nearest LSB); faces as static
//! index slices with colours. Every generated face is
//! checked to be counter-clockwise seen from outside (the culling convention). The
//! screen-space scenes (`random400`, and `foley100`/`foley2500` from zrow-compare's generator,
//! included by path) are drawn without culling.

use std::fmt::Write as _;

// The comparison scene's generator (Foley & van Dam's Table 15.3, crates/zrow-compare), shared
// by path so the emulated bench draws the same surfaces as zrow-compare's host run.
#[path = "../zrow-compare/src/surfaces.rs"]
#[allow(dead_code)]
mod surfaces;

type V = [f32; 3];

/// The model meshes' compact positions are integers at 2^-SHIFT (`zrow_scenes::MODEL_SHIFT`).
const SHIFT: u32 = 14;

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

struct MeshGen {
    vertices: Vec<V>,
    faces: Vec<(Vec<u16>, (u8, u8, u8))>,
}

impl MeshGen {
    /// Checks that each face's normal points away from `inside(centroid)`.
    fn assert_outward(&self, inside: impl Fn(V) -> V) {
        for (no, (idx, _)) in self.faces.iter().enumerate() {
            let p = |k: usize| self.vertices[idx[k] as usize];
            let normal = cross(sub(p(1), p(0)), sub(p(2), p(0)));
            let mut c = [0.0f32; 3];
            for &i in idx {
                for (ck, vk) in c.iter_mut().zip(self.vertices[i as usize]) {
                    *ck += vk / idx.len() as f32;
                }
            }
            assert!(
                dot(normal, sub(c, inside(c))) > 0.0,
                "face {no} is not outward"
            );
        }
    }

    fn emit(&self, out: &mut String, name: &str) {
        let n = self.vertices.len();
        writeln!(out, "pub(crate) static {name}_F32: [Vec3<f32>; {n}] = [").unwrap();
        for v in &self.vertices {
            writeln!(
                out,
                "    Vec3::new({:?}f32, {:?}f32, {:?}f32),",
                v[0], v[1], v[2]
            )
            .unwrap();
        }
        writeln!(out, "];").unwrap();
        // Each fixed format: its type, its fractional bits (rounded to the nearest LSB).
        for (ty, frac) in [("Q16_16", 16), ("Q24_8", 8)] {
            let (int, point) = (32 - frac, frac);
            writeln!(
                out,
                "/// {int}.{point} fixed point, rounded to nearest from the f32 positions."
            )
            .unwrap();
            writeln!(out, "pub(crate) static {name}_{ty}: [Vec3<{ty}>; {n}] = [").unwrap();
            let q = |x: f32| fixed_bits(x, frac, name, ty);
            for v in &self.vertices {
                writeln!(
                    out,
                    "    Vec3::new({ty}::from_bits({}), {ty}::from_bits({}), {ty}::from_bits({})),",
                    q(v[0]),
                    q(v[1]),
                    q(v[2])
                )
                .unwrap();
            }
            writeln!(out, "];").unwrap();
        }
        self.emit_faces(out, name);
    }

    /// The positions snapped to the sub-pixel grid of `bits` bits, in every format, to the
    /// bits `zrow::raster::RasterVertex::snapped` gives (`tests/formats.rs` checks them):
    /// what a `zrow::SnappedScene` lends the renderer.
    fn emit_snapped(&self, out: &mut String, name: &str, bits: u32) {
        let n = self.vertices.len();
        // f32: x·2^bits, exact, rounded half up (the floor of t + 0.5 in f32 below 2^23).
        let snap_f32 = |x: f32| {
            let t = x * (1u32 << bits) as f32;
            assert!(t.abs() < 8_388_608.0, "{name}: {x} beyond the grid");
            (t + 0.5).floor() as i32
        };
        writeln!(
            out,
            "/// Snapped to {bits} sub-pixel bits.\n\
             pub(crate) static {name}_SNAPPED_F32: [RasterVertex<f32>; {n}] = ["
        )
        .unwrap();
        for v in &self.vertices {
            let (x, y) = (snap_f32(v[0]), snap_f32(v[1]));
            writeln!(
                out,
                "    RasterVertex {{ x: {x}, y: {y}, z: {:?}f32 }},",
                v[2]
            )
            .unwrap();
        }
        writeln!(out, "];").unwrap();
        // Fixed point: the format's bits rounded half up to `bits` fractional bits.
        for (ty, frac) in [("Q16_16", 16), ("Q24_8", 8)] {
            let shift = frac - bits.min(frac);
            let snap = |raw: i32| match shift {
                0 => raw,
                _ => ((raw as i64 + (1 << (shift - 1))) >> shift) as i32,
            };
            writeln!(
                out,
                "/// Snapped to {bits} sub-pixel bits.\n\
                 pub(crate) static {name}_SNAPPED_{ty}: [RasterVertex<{ty}>; {n}] = ["
            )
            .unwrap();
            for v in &self.vertices {
                let q = |x: f32| fixed_bits(x, frac, name, ty);
                let (x, y, z) = (snap(q(v[0])), snap(q(v[1])), q(v[2]));
                writeln!(
                    out,
                    "    RasterVertex {{ x: {x}, y: {y}, z: {ty}::from_bits({z}) }},"
                )
                .unwrap();
            }
            writeln!(out, "];").unwrap();
        }
    }

    /// Vectors as compact 16-bit integers at 2^-`SHIFT` (`zrow::Vectors::Compact`, 6
    /// bytes a vertex in every format), rounded to nearest, then the faces.
    fn emit_compact(&self, out: &mut String, name: &str) {
        let n = self.vertices.len();
        writeln!(out, "pub(crate) static {name}_I16: [[i16; 3]; {n}] = [").unwrap();
        let q = |x: f32| {
            let v = (x as f64 * (1u32 << SHIFT) as f64).round();
            assert!(
                v.abs() < 32768.0,
                "{name}: {x} does not fit 16 bits at 2^-{SHIFT}"
            );
            v as i16
        };
        for v in &self.vertices {
            writeln!(out, "    [{}, {}, {}],", q(v[0]), q(v[1]), q(v[2])).unwrap();
        }
        writeln!(out, "];").unwrap();
        self.emit_faces(out, name);
    }

    fn emit_faces(&self, out: &mut String, name: &str) {
        let f = self.faces.len();
        if self.triangles() {
            // Triangles: their indices and one colour each (zrow::Faces::Triangles), 8 bytes a
            // face instead of a zrow::Face's 12 and its indices' 6.
            writeln!(
                out,
                "pub(crate) static {name}_TRIANGLES: [[u16; 3]; {f}] = ["
            )
            .unwrap();
            for (idx, _) in &self.faces {
                writeln!(out, "    {idx:?},").unwrap();
            }
            writeln!(out, "];").unwrap();
            writeln!(out, "pub(crate) static {name}_COLORS: [Rgb565; {f}] = [").unwrap();
            for (_, (r, g, b)) in &self.faces {
                writeln!(out, "    Rgb565::new({r}, {g}, {b}),").unwrap();
            }
            writeln!(out, "];").unwrap();
            return;
        }
        writeln!(
            out,
            "pub(crate) static {name}_FACES: [Face<'static>; {f}] = ["
        )
        .unwrap();
        for (idx, (r, g, b)) in &self.faces {
            writeln!(
                out,
                "    Face {{ indices: &{idx:?}, color: Rgb565::new({r}, {g}, {b}), alpha: 255 }},"
            )
            .unwrap();
        }
        writeln!(out, "];").unwrap();
    }

    /// Whether every face is a triangle (emitted as zrow::Faces::Triangles).
    fn triangles(&self) -> bool {
        self.faces.iter().all(|(idx, _)| idx.len() == 3)
    }
}

impl MeshGen {
    /// The faces alone, every one in `color`, as `static {name}: [Face; n]` (an object drawn in
    /// one colour over the same vertices).
    fn emit_faces_in(&self, out: &mut String, name: &str, (r, g, b): (u8, u8, u8)) {
        if self.triangles() {
            // The same triangles (`{mesh}_TRIANGLES`) in one colour: the colour alone.
            writeln!(
                out,
                "pub(crate) static {name}: [Rgb565; 1] = [Rgb565::new({r}, {g}, {b})];"
            )
            .unwrap();
            return;
        }
        let f = self.faces.len();
        writeln!(out, "pub(crate) static {name}: [Face<'static>; {f}] = [").unwrap();
        for (idx, _) in &self.faces {
            writeln!(
                out,
                "    Face {{ indices: &{idx:?}, color: Rgb565::new({r}, {g}, {b}), alpha: 255 }},"
            )
            .unwrap();
        }
        writeln!(out, "];").unwrap();
    }
}

/// The unit cube centred on the origin: 6 quads, one colour each (Rgb565 channel values).
fn cube() -> MeshGen {
    let vertices = (0..8)
        .map(|i: u32| {
            let c = |bit: u32| ((i >> bit) & 1) as f32 - 0.5;
            [c(0), c(1), c(2)]
        })
        .collect();
    let quads: [([u16; 4], (u8, u8, u8)); 6] = [
        ([1, 3, 7, 5], (31, 0, 0)),  // +x red
        ([0, 4, 6, 2], (0, 63, 31)), // -x cyan
        ([2, 6, 7, 3], (0, 63, 0)),  // +y green
        ([0, 1, 5, 4], (31, 0, 31)), // -y magenta
        ([4, 5, 7, 6], (0, 0, 31)),  // +z blue
        ([0, 2, 3, 1], (31, 63, 0)), // -z yellow
    ];
    let m = MeshGen {
        vertices,
        faces: quads.iter().map(|(q, c)| (q.to_vec(), *c)).collect(),
    };
    m.assert_outward(|_| [0.0; 3]);
    m
}

/// A closed torus about the y axis, `ring` × `tube` quads as two triangles each.
fn torus(ring: usize, tube: usize, major: f32, minor: f32) -> MeshGen {
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
    let palette = [(31, 40, 8), (8, 48, 28), (24, 24, 31)];
    let at = |i: usize, j: usize| ((i % ring) * tube + j % tube) as u16;
    let mut faces = Vec::with_capacity(2 * ring * tube);
    for i in 0..ring {
        for j in 0..tube {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            let color = palette[(i + j) % palette.len()];
            faces.push((vec![a, b, c], color));
            faces.push((vec![a, c, d], color));
        }
    }
    let m = MeshGen { vertices, faces };
    m.assert_outward(|c| {
        let l = (c[0] * c[0] + c[2] * c[2]).sqrt();
        [major * c[0] / l, 0.0, major * c[2] / l]
    });
    m
}

/// The unit outward normals of [`torus`]'s vertices, in the same order: the surface's own,
/// `(cos v cos u, sin v, cos v sin u)`, at 2^-SHIFT (smooth shading's `mesh1k-smooth`).
fn emit_torus_normals(out: &mut String, name: &str, ring: usize, tube: usize) {
    use std::f64::consts::TAU;
    writeln!(
        out,
        "pub(crate) static {name}_NORMALS_I16: [[i16; 3]; {}] = [",
        ring * tube
    )
    .unwrap();
    let q = |x: f64| (x * (1u32 << SHIFT) as f64).round() as i16;
    for i in 0..ring {
        let u = TAU * i as f64 / ring as f64;
        for j in 0..tube {
            let v = TAU * j as f64 / tube as f64;
            let n = [v.cos() * u.cos(), v.sin(), v.cos() * u.sin()];
            writeln!(out, "    [{}, {}, {}],", q(n[0]), q(n[1]), q(n[2])).unwrap();
        }
    }
    writeln!(out, "];").unwrap();
}

/// `count` random screen-space triangles (x, y in 0..size, depth 0..max_depth), random
/// non-black colours; Marsaglia's xorshift32.
fn random_triangles(count: usize, size: f32, max_depth: f32, seed: u32) -> MeshGen {
    let mut s = seed.max(1);
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        s
    };
    let mut vertices = Vec::with_capacity(3 * count);
    let mut faces = Vec::with_capacity(count);
    for t in 0..count {
        for _ in 0..3 {
            let mut unit = || (next() >> 8) as f32 / (1u32 << 24) as f32;
            vertices.push([unit() * size, unit() * size, unit() * max_depth]);
        }
        let raw = next() as u16 | 0x0821; // never black: low bit of each channel set
        let color = ((raw >> 11) as u8, ((raw >> 5) & 63) as u8, (raw & 31) as u8);
        let k = (3 * t) as u16;
        faces.push((vec![k, k + 1, k + 2], color));
    }
    MeshGen { vertices, faces }
}

/// `x` in the fixed-point format `ty` of `frac` fractional bits, rounded to nearest: its bits.
fn fixed_bits(x: f32, frac: u32, name: &str, ty: &str) -> i32 {
    let v = ((x as f64) * (1u64 << frac) as f64).round();
    assert!(v.abs() < 2f64.powi(31), "{name}: {x} does not fit {ty}");
    v as i32
}

/// The comparison scene at `polygons` triangles for a 240 × 240 screen (screen space).
fn foley(polygons: usize) -> MeshGen {
    let s = surfaces::foley_scene(polygons, 240.0).expect("a Table 15.3 polygon count");
    MeshGen {
        vertices: s.vertices,
        faces: s.faces.into_iter().map(|(t, c)| (t.to_vec(), c)).collect(),
    }
}

fn main() {
    let mut out = String::from("// Generated by build.rs: do not edit.\n");
    let cube = cube();
    cube.emit_compact(&mut out, "CUBE");
    torus(25, 20, 1.0, 0.4).emit_compact(&mut out, "TORUS");
    emit_torus_normals(&mut out, "TORUS", 25, 20);
    let ring = torus(16, 8, 0.7, 0.25);
    ring.emit_compact(&mut out, "RING");
    // The interlocked demo: one lit colour per object.
    ring.emit_faces_in(&mut out, "RING_WARM_COLOR", (31, 38, 6));
    ring.emit_faces_in(&mut out, "RING_COOL_COLOR", (6, 44, 30));
    cube.emit_faces_in(&mut out, "CUBE_PLAIN_FACES", (29, 58, 26));
    let random400 = random_triangles(400, 240.0, 100.0, 0x2545_f491);
    random400.emit(&mut out, "RANDOM400");
    // Drawn as a snapped scene at `Config::screen`'s 8 sub-pixel bits (`with_scene`).
    random400.emit_snapped(&mut out, "RANDOM400", 8);
    foley(100).emit(&mut out, "FOLEY100");
    foley(2_500).emit(&mut out, "FOLEY2500");
    let path = std::path::Path::new(&std::env::var("OUT_DIR").unwrap()).join("meshes.rs");
    std::fs::write(path, out).unwrap();
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=../zrow-compare/src/surfaces.rs");
}
