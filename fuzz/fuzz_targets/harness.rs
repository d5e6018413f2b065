//! The fuzz harness, shared by the libFuzzer target (`render.rs`, nightly, coverage-guided) and
//! the stable fixed-seed run (`crates/zrow/tests/fuzz_stable.rs`, in `cargo test` and CI).
//!
//! Any bytes → a scene (screen or model mode, Q16.16 or f32, any bit pattern for positions,
//! camera and transform, out-of-range indices, faces of 0..12 vertices, any alpha, flat,
//! smooth shaded with any vertex normals, or as facets for hidden lines) → every
//! method at small capacities. The contract checked: no panic; rows arrive top to bottom, each
//! once, all of them on success and none on error (nothing drawn is corrupted).

use embedded_graphics_core::pixelcolor::Rgb565;
use zrow::lines::HiddenLines;
use zrow::{
    abuffer::ABuffer, bsp::Bsp, cullonly::CullOnly, depthsort::DepthSort, ordered::Ordered,
    tiled::Tiled, warnock::Warnock, Affine, Camera, Config, Cull, Face, IntensityPlane, Light,
    Mesh, ModelScene, Object, Projection, Renderer, Row, RowSink, Scalar, Scanline, Scene,
    ScreenScene, Vec3, Vectors, ZBuffer, Q16_16,
};

/// Reads the input front to back; zeros once it runs out.
struct Bytes<'a>(&'a [u8]);
impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        let (b, rest) = self.0.split_first().map_or((0, &[][..]), |(b, r)| (*b, r));
        self.0 = rest;
        b
    }
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
}

/// Checks the row contract; reads depth if `DEPTH` (else, as a display's sink, colours only).
struct Sink<const DEPTH: bool> {
    height: u16,
    next: u16,
}
impl<N, const DEPTH: bool> RowSink<N> for Sink<DEPTH> {
    type Error = ();
    const WANTS_DEPTH: bool = DEPTH;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
        assert_eq!(row.y, self.next, "rows top to bottom, each once");
        assert!(row.y < self.height, "no row past the frame");
        let depths = if DEPTH { row.color.len() } else { 0 };
        assert_eq!(row.depth.len(), depths);
        self.next += 1;
        Ok(())
    }
}

/// How far one input got: renders that succeeded, and those that drew a polygon.
#[derive(Clone, Copy, Debug, Default)]
pub struct Reach {
    pub ok: u32,
    pub drew: u32,
}

fn run<N: Scalar, R: Renderer<N>>(
    r: &mut R,
    scene: &impl Scene<N>,
    cfg: &Config,
    reach: &mut Reach,
) {
    run_into::<N, R, true>(r, scene, cfg, reach)
}

/// [`run`] into a sink that reads depth if `DEPTH`.
fn run_into<N: Scalar, R: Renderer<N>, const DEPTH: bool>(
    r: &mut R,
    scene: &impl Scene<N>,
    cfg: &Config,
    reach: &mut Reach,
) {
    let mut sink = Sink::<DEPTH> {
        height: cfg.height,
        next: 0,
    };
    match r.render(scene, cfg, &mut sink) {
        Ok(stats) => {
            assert_eq!(sink.next, cfg.height, "{}: every row on success", R::NAME);
            reach.ok += 1;
            reach.drew += (stats.polygons > 0) as u32;
        }
        Err(_) => assert_eq!(sink.next, 0, "{}: no row before an error", R::NAME),
    }
}

/// A frame of facets through the hidden-line sink: the same row contract (its rows carry no
/// depth), every row once on success, none on error.
fn lines<N: Scalar>(scene: &impl Scene<N>, cfg: &Config) {
    struct Lines {
        next: u16,
    }
    impl<N> RowSink<N> for Lines {
        type Error = ();
        fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), ()> {
            assert_eq!(
                row.y, self.next,
                "hidden lines: rows top to bottom, each once"
            );
            assert!(row.depth.is_empty());
            self.next += 1;
            Ok(())
        }
    }
    let (white, black) = (Rgb565::new(31, 63, 31), Rgb565::new(0, 0, 0));
    let mut sink = HiddenLines::<_, 64>::new(Lines { next: 0 }, cfg.height, white, black);
    let drawn = Scanline::<N, 64, 64, 16, 16>::new().render(scene, cfg, &mut sink);
    let rows = sink.into_inner().next;
    match drawn {
        Ok(_) => assert_eq!(rows, cfg.height, "hidden lines: every row on success"),
        Err(_) => assert_eq!(rows, 0, "hidden lines: no row before an error"),
    }
}

fn every_method<N: Scalar>(scene: &impl Scene<N>, cfg: &Config) -> Reach {
    let r = &mut Reach::default();
    run(&mut Scanline::<N, 64, 64, 16, 16>::new(), scene, cfg, r);
    // Smooth shading's scan-line renderer (the flat one above refuses a smooth frame).
    type Smooth<N> =
        Scanline<N, 64, 64, 16, 16, u16, zrow::scanline::Uncued, [IntensityPlane<N>; 16]>;
    run(&mut Smooth::<N>::new(), scene, cfg, r);
    // A display's renderer (no depth row, 12-bit slots) into a sink that takes colours only.
    run_into::<N, _, false>(
        &mut zrow::scanline::Display::<N, 64, 64, 16, 16>::new(),
        scene,
        cfg,
        r,
    );
    if cfg.shading.is_facets() {
        lines(scene, cfg);
    }
    run(&mut ZBuffer::<N, 64, 64>::new(), scene, cfg, r);
    run(&mut Tiled::<N, 64, 8, 16, 64>::new(), scene, cfg, r);
    run(&mut DepthSort::<N, 64, 16, 64, 256>::new(), scene, cfg, r);
    run(&mut Warnock::<N, 64, 16, 16, 64, 96>::new(), scene, cfg, r);
    run(&mut Bsp::<N, 64, 16, 64, 256, 64>::new(), scene, cfg, r);
    run(&mut ABuffer::<N, 64, 16, 64, 64>::new(), scene, cfg, r);
    run(&mut CullOnly::<N, 64, 16, 64>::new(), scene, cfg, r);
    let mut ordered = Ordered::<N, 64, 16, 64>::new();
    let _ = ordered.exact_for(scene, cfg);
    run(&mut ordered, scene, cfg, r);
    *r
}

fn value<N: Scalar>(b: &mut Bytes<'_>, q16: bool) -> N {
    let bits = b.u32();
    let v = if q16 {
        Q16_16::from_bits(bits as i32).to_f32()
    } else {
        f32::from_bits(bits)
    };
    // Any f32 the format holds; others (NaN, ∞, out of range) become a format extreme.
    N::from_f32(v).unwrap_or(if bits & 1 == 0 { N::MAX } else { N::ZERO })
}

fn scene<N: Scalar>(data: &[u8], q16: bool) -> Reach {
    let mut b = Bytes(data);
    let mode = b.u8();
    let mut cfg = Config {
        width: 1 + (b.u8() % 64) as u16,
        height: 1 + (b.u8() % 64) as u16,
        subpixel_bits: b.u8() % 10, // 0 and 9 are invalid on purpose
        cull: if mode & 2 == 0 {
            Cull::None
        } else {
            Cull::Back
        },
        ..Config::screen(1, 1)
    };
    let nv = (b.u8() % 17) as usize;
    let vertices: Vec<Vec3<N>> = (0..nv)
        .map(|_| Vec3::new(value(&mut b, q16), value(&mut b, q16), value(&mut b, q16)))
        .collect();
    let nf = (b.u8() % 9) as usize;
    let indices: Vec<Vec<u16>> = (0..nf)
        .map(|_| {
            let n = (b.u8() % 13) as usize;
            (0..n).map(|_| (b.u8() % 20) as u16).collect()
        })
        .collect();
    let faces: Vec<Face> = indices
        .iter()
        .map(|i| {
            Face::translucent(
                i,
                Rgb565::new(b.u8() & 31, b.u8() & 63, b.u8() & 31),
                b.u8(),
            )
        })
        .collect();
    let mesh = Mesh::new(&vertices, &faces);
    if mode & 1 == 0 {
        // Mode bit 3 in screen mode: facets, for hidden lines.
        if mode & 8 != 0 {
            cfg.shading = zrow::shading::Shading::Facets;
        }
        every_method::<N>(&ScreenScene { mesh }, &cfg)
    } else {
        let f = |b: &mut Bytes<'_>| f32::from_bits(b.u32());
        let projection = if mode & 4 == 0 {
            let Some(p) = Camera::<N>::perspective(f(&mut b), f(&mut b), f(&mut b)) else {
                return Reach::default();
            };
            p
        } else {
            // Any values, unchecked: the renderer must refuse bad ones itself.
            Projection::Orthographic {
                half_height: value(&mut b, q16),
                near: value(&mut b, q16),
                far: value(&mut b, q16),
            }
        };
        let eye = [f(&mut b), f(&mut b), f(&mut b)];
        let Some(camera) = Camera::look_at(eye, [0.0; 3], [0.0, 1.0, 0.0], projection) else {
            return Reach::default();
        };
        let mut m = [[0f32; 4]; 3];
        for r in &mut m {
            for c in r.iter_mut() {
                *c = f(&mut b);
            }
        }
        let Some(transform) = Affine::from_f32(m) else {
            return Reach::default();
        };
        let light = Light {
            direction: Vec3::new(value(&mut b, q16), value(&mut b, q16), value(&mut b, q16)),
            ambient: value(&mut b, q16),
        };
        // Mode bit 3: smooth shading (bit 4: dithered), a normal per vertex from the bytes
        // after the light (read last, so the layout before stays as it was).
        let normals: Vec<Vec3<N>> = match mode & 8 {
            0 => Vec::new(),
            _ => (0..nv)
                .map(|_| Vec3::new(value(&mut b, q16), value(&mut b, q16), value(&mut b, q16)))
                .collect(),
        };
        let mesh = mesh.with_vertex_normals(Vectors::Format(&normals));
        let objects = [Object {
            mesh: &mesh,
            transform,
        }];
        match mode & 24 {
            0 => {}
            // Bit 4 alone: facets, for hidden lines.
            16 => cfg.shading = zrow::shading::Shading::Facets,
            _ => {
                cfg.shading = zrow::shading::Shading::Gouraud {
                    dither: mode & 16 != 0,
                }
            }
        }
        let scene = ModelScene {
            objects: &objects,
            camera,
            light,
        };
        every_method::<N>(&scene, &cfg)
    }
}

/// Runs one input: its first byte picks the number format (even: Q16.16, odd: f32), the rest
/// builds the scene. Panics if the contract above breaks; else says how far the input got.
pub fn check(data: &[u8]) -> Reach {
    match data.first() {
        Some(f) if f & 1 == 0 => scene::<Q16_16>(&data[1..], true),
        Some(_) => scene::<f32>(&data[1..], false),
        None => Reach::default(),
    }
}
