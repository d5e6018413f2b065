//! Meshes as a model converter emits them for flash: `u8` face indices and precomputed face
//! normals.
//!
//! - A mesh with `u8` indices renders bit for bit like the same mesh with `u16` indices
//!   (colour and depth, Q16.16 and f32, model and screen mode).
//! - Precomputed normals (computed in f64 from the model, then converted) give the same
//!   coverage and depth bits as normals computed per frame, and colours within 1 LSB per
//!   channel (only the shading's rounding differs).
//! - A mesh of triangles (`Faces::Triangles`: indices and colours, no `Face` list) renders
//!   bit for bit like the same triangles as a list of faces, one colour each or one for all.
//! - A normals slice of the wrong length, a triangle mesh's colours of the wrong length, and
//!   a `u8` index past the vertices, are typed errors raised before any row is sent.

mod common;
use common::*;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::scene::MeshIndex;
use zrow::{
    requirements, Affine, Camera, Config, Error, Face, Faces, Light, Mesh, ModelScene, Object,
    Projection, RenderError, Scalar, ScreenScene, Vec3, Q16_16,
};

/// A model in f64: vertices, triangles (counter-clockwise seen from outside), and the unit
/// outward normal of each triangle computed in f64.
struct Model {
    vertices: Vec<[f64; 3]>,
    tris: Vec<[usize; 3]>,
}

impl Model {
    /// A torus in the xz plane: `ring` × `tube` vertices, two triangles per grid cell.
    fn torus(ring: usize, tube: usize, major: f64, minor: f64) -> Self {
        let tau = std::f64::consts::TAU;
        let mut vertices = Vec::new();
        for i in 0..ring {
            let u = tau * i as f64 / ring as f64;
            for j in 0..tube {
                let v = tau * j as f64 / tube as f64;
                let r = major + minor * v.cos();
                vertices.push([r * u.cos(), minor * v.sin(), r * u.sin()]);
            }
        }
        let at = |i: usize, j: usize| (i % ring) * tube + j % tube;
        let mut tris = Vec::new();
        for i in 0..ring {
            for j in 0..tube {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                tris.push([a, d, c]);
                tris.push([a, c, b]);
            }
        }
        Model { vertices, tris }
    }

    fn normals(&self) -> Vec<[f64; 3]> {
        self.tris
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|k| self.vertices[k]);
                let e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                let e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
                let n = [
                    e1[1] * e2[2] - e1[2] * e2[1],
                    e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0],
                ];
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                [n[0] / len, n[1] / len, n[2] / len]
            })
            .collect()
    }
}

fn vec3<N: Scalar>(v: [f64; 3]) -> Vec3<N> {
    Vec3::from_f32([v[0] as f32, v[1] as f32, v[2] as f32]).expect("fits the format")
}

/// Face colours: a distinct bright colour per face, so shading has room to round.
fn face_color(k: usize) -> Rgb565 {
    Rgb565::new(
        (9 + 7 * k % 23) as u8,
        (20 + 13 * k % 44) as u8,
        (31 - 5 * k % 20) as u8,
    )
}

/// Index lists in type `I` (`None` if an index does not fit).
fn index_lists<I: MeshIndex + TryFrom<usize>>(tris: &[Vec<usize>]) -> Option<Vec<Vec<I>>> {
    tris.iter()
        .map(|t| t.iter().map(|&k| I::try_from(k).ok()).collect())
        .collect()
}

fn faces<I: MeshIndex>(lists: &[Vec<I>]) -> Vec<Face<'_, I>> {
    lists
        .iter()
        .enumerate()
        .map(|(k, l)| Face {
            indices: l,
            color: face_color(k),
            alpha: 255,
        })
        .collect()
}

/// Three placements of the torus: a rotation, a rotation with a non-uniform scale, and a
/// mirror (negative determinant), overlapping on screen.
fn transforms<N: Scalar>() -> [Affine<N>; 3] {
    let rot = Affine::<f32>::rotate_yx_translate(0.5, 0.9, [0.0; 3])
        .unwrap()
        .m;
    let scaled = |s: [f32; 3], t: [f32; 3]| {
        let mut m = [[0.0f32; 4]; 3];
        for r in 0..3 {
            for c in 0..3 {
                m[r][c] = rot[r][c] * s[c];
            }
            m[r][3] = t[r];
        }
        Affine::from_f32(m).unwrap()
    };
    [
        Affine::rotate_yx_translate(0.4, 0.3, [-0.9, 0.1, 0.0]).unwrap(),
        scaled([1.6, 0.5, 0.8], [0.8, 0.3, -0.6]),
        scaled([-1.0, 1.0, 1.0], [0.0, -0.9, 0.7]),
    ]
}

fn cameras<N: Scalar>() -> [Camera<N>; 2] {
    let eye = [0.6, 2.2, 4.0];
    let persp = Camera::perspective(0.9, 0.5, 20.0).unwrap();
    let ortho = Projection::Orthographic {
        half_height: N::from_f32(2.2).unwrap(),
        near: N::from_f32(0.5).unwrap(),
        far: N::from_f32(20.0).unwrap(),
    };
    [
        Camera::look_at(eye, [0.0; 3], [0.0, 1.0, 0.0], persp).unwrap(),
        Camera::look_at(eye, [0.0; 3], [0.0, 1.0, 0.0], ortho).unwrap(),
    ]
}

/// Renders `mesh` placed three times in model mode (Lambert light, some ambient).
fn render_model<N: Scalar, I: MeshIndex>(
    mesh: &Mesh<'_, N, I>,
    camera: Camera<N>,
    cfg: &Config,
) -> Result<Capture<N>, RenderError<()>> {
    let objects = transforms::<N>().map(|transform| Object { mesh, transform });
    let scene = ModelScene {
        objects: &objects,
        camera,
        light: Light {
            direction: Vec3::from_f32([0.4, 0.8, 0.5]).unwrap(),
            ambient: N::from_f32(0.15).unwrap(),
        },
    };
    let mut r = Box::new(Big::<N>::new());
    let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
    r.render(&scene, cfg, &mut cap)?;
    Ok(cap)
}

fn render_screen<N: Scalar, I: MeshIndex>(
    mesh: Mesh<'_, N, I>,
    cfg: &Config,
) -> Result<Capture<N>, RenderError<()>> {
    let mut r = Box::new(Big::<N>::new());
    let mut cap = Capture::new(cfg.width as usize, cfg.height as usize);
    r.render(&ScreenScene { mesh }, cfg, &mut cap)?;
    Ok(cap)
}

/// Depth bits (f32 as f64 bits, so −0 and +0 differ too).
fn depth_bits<N: Scalar>(cap: &Capture<N>) -> Vec<u64> {
    cap.depth.iter().map(|z| z.to_f64().to_bits()).collect()
}

fn assert_same<N: Scalar>(a: &Capture<N>, b: &Capture<N>, what: &str) {
    assert_eq!(a.color, b.color, "{what}: colours differ");
    assert_eq!(depth_bits(a), depth_bits(b), "{what}: depth bits differ");
}

fn model_mode_u8_like_u16<N: Scalar>() {
    let model = Model::torus(16, 10, 1.0, 0.4); // 160 vertices, 320 triangles
    let verts: Vec<Vec3<N>> = model.vertices.iter().map(|&v| vec3(v)).collect();
    let tris: Vec<Vec<usize>> = model.tris.iter().map(|t| t.to_vec()).collect();
    let (l8, l16) = (
        index_lists::<u8>(&tris).unwrap(),
        index_lists::<u16>(&tris).unwrap(),
    );
    let (f8, f16) = (faces(&l8), faces(&l16));
    let normals: Vec<Vec3<N>> = model.normals().into_iter().map(vec3).collect();
    for camera in cameras::<N>() {
        for cfg in [Config::model(96, 80), Config::screen(96, 80)] {
            let a = render_model(&Mesh::new(&verts, &f8), camera, &cfg).unwrap();
            let b = render_model(&Mesh::new(&verts, &f16), camera, &cfg).unwrap();
            assert!(a.drawn() > 2000, "the scene fills the frame: {}", a.drawn());
            assert_same(&a, &b, "model mode");
            let a = render_model(&Mesh::with_normals(&verts, &f8, &normals), camera, &cfg);
            let b = render_model(&Mesh::with_normals(&verts, &f16, &normals), camera, &cfg);
            assert_same(&a.unwrap(), &b.unwrap(), "model mode, precomputed normals");
        }
    }
}

#[test]
fn u8_indices_render_like_u16_in_model_mode_q16_16() {
    model_mode_u8_like_u16::<Q16_16>();
}

#[test]
fn u8_indices_render_like_u16_in_model_mode_f32() {
    model_mode_u8_like_u16::<f32>();
}

fn screen_mode_u8_like_u16<N: Scalar>() {
    let cfg = Config::screen(64, 48);
    for seed in 1..=6u64 {
        let polys = scenes::random(&mut Rng(seed * 7919), 60, 64.0, 48.0);
        // Unused vertices first, so the highest index is 255, the largest a u8 holds.
        let total: usize = polys.polys.iter().map(|p| p.len()).sum();
        let pad = 256 - total;
        let mut verts = vec![Vec3::<N>::from_f32([1.0, 2.0, 3.0]).unwrap(); pad];
        let mut tris = Vec::new();
        for p in &polys.polys {
            tris.push((verts.len()..verts.len() + p.len()).collect::<Vec<_>>());
            verts.extend(p.iter().map(|&v| Vec3::<N>::from_f32(v).unwrap()));
        }
        assert_eq!(verts.len(), 256);
        let (l8, l16) = (
            index_lists::<u8>(&tris).unwrap(),
            index_lists::<u16>(&tris).unwrap(),
        );
        let (f8, f16) = (faces(&l8), faces(&l16));
        let a = render_screen(Mesh::new(&verts, &f8), &cfg).unwrap();
        let b = render_screen(Mesh::new(&verts, &f16), &cfg).unwrap();
        assert!(a.drawn() > 1000, "seed {seed}: {} pixels drawn", a.drawn());
        assert_same(&a, &b, "screen mode");
    }
}

#[test]
fn u8_indices_render_like_u16_in_screen_mode_q16_16() {
    screen_mode_u8_like_u16::<Q16_16>();
}

#[test]
fn u8_indices_render_like_u16_in_screen_mode_f32() {
    screen_mode_u8_like_u16::<f32>();
}

/// Largest per-channel colour difference, and how many pixels differ at all.
fn colour_difference(a: &[Rgb565], b: &[Rgb565]) -> (u8, usize) {
    let mut worst = 0;
    let mut differ = 0;
    for (x, y) in a.iter().zip(b) {
        let d = [
            x.r().abs_diff(y.r()),
            x.g().abs_diff(y.g()),
            x.b().abs_diff(y.b()),
        ];
        worst = worst.max(d.into_iter().max().unwrap());
        differ += (x != y) as usize;
    }
    (worst, differ)
}

/// Returns the pixels whose colour differs, over every camera and cull mode.
fn precomputed_normals_match<N: Scalar>() -> usize {
    let model = Model::torus(16, 10, 1.0, 0.4);
    let verts: Vec<Vec3<N>> = model.vertices.iter().map(|&v| vec3(v)).collect();
    let tris: Vec<Vec<usize>> = model.tris.iter().map(|t| t.to_vec()).collect();
    let lists = index_lists::<u8>(&tris).unwrap();
    let f8 = faces(&lists);
    let normals: Vec<Vec3<N>> = model.normals().into_iter().map(vec3).collect();
    let mut differ = 0;
    for camera in cameras::<N>() {
        for cfg in [Config::model(120, 100), Config::screen(120, 100)] {
            let computed = render_model(&Mesh::new(&verts, &f8), camera, &cfg).unwrap();
            let given =
                render_model(&Mesh::with_normals(&verts, &f8, &normals), camera, &cfg).unwrap();
            assert!(computed.drawn() > 3000, "{} pixels drawn", computed.drawn());
            assert_eq!(
                depth_bits(&computed),
                depth_bits(&given),
                "coverage and depth must not depend on where the normal comes from"
            );
            let (worst, n) = colour_difference(&computed.color, &given.color);
            assert!(worst <= 1, "a channel differs by {worst} LSB");
            differ += n;
        }
    }
    differ
}

#[test]
fn precomputed_normals_match_computed_ones_q16_16() {
    let differ = precomputed_normals_match::<Q16_16>();
    println!("Q16.16: {differ} pixels differ by 1 LSB in a channel");
}

#[test]
fn precomputed_normals_match_computed_ones_f32() {
    let differ = precomputed_normals_match::<f32>();
    println!("f32: {differ} pixels differ by 1 LSB in a channel");
}

/// The normals given are the ones shaded: with every normal pointing at the light each face
/// is fully lit, pointing away it keeps only the ambient part (whatever its real orientation).
#[test]
fn precomputed_normals_are_the_ones_shaded() {
    let model = Model::torus(16, 10, 1.0, 0.4);
    let verts: Vec<Vec3<f32>> = model.vertices.iter().map(|&v| vec3(v)).collect();
    let tris: Vec<Vec<usize>> = model.tris.iter().map(|t| t.to_vec()).collect();
    let lists = index_lists::<u16>(&tris).unwrap();
    let white: Vec<Face<u16>> = lists.iter().map(|l| Face::new(l, Rgb565::WHITE)).collect();
    let mut cfg = Config::model(96, 80);
    cfg.cull = zrow::Cull::None; // the normals would cull half the faces otherwise
    for (n, intensity) in [(1.0, 1.0f32), (-1.0, 0.15)] {
        let normals = vec![Vec3::new(0.0, n, 0.0); white.len()];
        let mesh = Mesh::with_normals(&verts, &white, &normals);
        let objects = [Object {
            mesh: &mesh,
            transform: Affine::identity(),
        }];
        let scene = ModelScene {
            objects: &objects,
            camera: cameras::<f32>()[0],
            light: Light {
                direction: Vec3::new(0.0, 1.0, 0.0),
                ambient: 0.15,
            },
        };
        let mut r = Box::new(Big::<f32>::new());
        let mut cap = Capture::new(96, 80);
        r.render(&scene, &cfg, &mut cap).unwrap();
        let expected = zrow::geometry::shade(Rgb565::WHITE, intensity);
        let drawn: Vec<Rgb565> = cap
            .color
            .iter()
            .copied()
            .filter(|&c| c != Rgb565::BLACK)
            .collect();
        assert!(drawn.len() > 1000, "{} pixels drawn", drawn.len());
        assert!(
            drawn.iter().all(|&c| c == expected),
            "n.y = {n}: {expected:?}"
        );
    }
}

fn triangles_like_faces<N: Scalar>() {
    let model = Model::torus(16, 10, 1.0, 0.4);
    let verts: Vec<Vec3<N>> = model.vertices.iter().map(|&v| vec3(v)).collect();
    let tris: Vec<Vec<usize>> = model.tris.iter().map(|t| t.to_vec()).collect();
    let lists = index_lists::<u16>(&tris).unwrap();
    let triangles: Vec<[u16; 3]> = lists.iter().map(|l| [l[0], l[1], l[2]]).collect();
    let colors: Vec<Rgb565> = (0..lists.len()).map(face_color).collect();
    let list = faces(&lists);
    let one: Vec<Face> = lists.iter().map(|l| Face::new(l, colors[7])).collect();
    let (each, all) = (
        Mesh::triangles(&verts, &triangles, &colors),
        Mesh::triangles(&verts, &triangles, &colors[7..8]),
    );
    assert!(each.faces.iter().eq(list.iter().copied()), "iter");
    assert!((0..=lists.len()).all(|k| each.faces.get(k) == list.get(k).copied()));
    assert!(all.faces.iter().eq(one.iter().copied()), "iter, one colour");
    for camera in cameras::<N>() {
        for cfg in [Config::model(96, 80), Config::screen(96, 80)] {
            let a = render_model(&each, camera, &cfg).unwrap();
            assert!(a.drawn() > 2000, "the scene fills the frame: {}", a.drawn());
            assert_same(
                &a,
                &render_model(&Mesh::new(&verts, &list), camera, &cfg).unwrap(),
                "each",
            );
            let a = render_model(&all, camera, &cfg).unwrap();
            assert_same(
                &a,
                &render_model(&Mesh::new(&verts, &one), camera, &cfg).unwrap(),
                "all",
            );
        }
    }
    let cfg = Config::screen(96, 80);
    let screen: Vec<Vec3<N>> = model
        .vertices
        .iter()
        .map(|v| vec3([48.0 + 30.0 * v[0], 40.0 + 30.0 * v[2], 5.0 + v[1]]))
        .collect();
    let a = render_screen(Mesh::triangles(&screen, &triangles, &colors), &cfg).unwrap();
    assert!(a.drawn() > 2000, "{}", a.drawn());
    assert_same(
        &a,
        &render_screen(Mesh::new(&screen, &list), &cfg).unwrap(),
        "screen",
    );
}

#[test]
fn triangles_render_like_faces_q16_16() {
    triangles_like_faces::<Q16_16>();
}

#[test]
fn triangles_render_like_faces_f32() {
    triangles_like_faces::<f32>();
}

#[test]
fn wrong_colours_length_is_a_typed_error_before_any_row() {
    let model = Model::torus(8, 6, 1.0, 0.4);
    let verts: Vec<Vec3<Q16_16>> = model.vertices.iter().map(|&v| vec3(v)).collect();
    let triangles: Vec<[u8; 3]> = model.tris.iter().map(|t| t.map(|k| k as u8)).collect();
    let colors: Vec<Rgb565> = (0..2 * triangles.len()).map(face_color).collect();
    let n = triangles.len();
    let cfg = Config::model(64, 48);
    for count in [0, 2, n - 1, n + 1] {
        let expected = Error::Colors {
            faces: n as u32,
            colors: count as u32,
        };
        let bad = Mesh::triangles(&verts, &triangles, &colors[..count]);
        assert!(matches!(bad.faces, Faces::Triangles { .. }));
        for camera in cameras::<Q16_16>() {
            let e = render_model(&bad, camera, &cfg).err();
            assert_eq!(e, Some(RenderError::Scene(expected)), "{count} colours");
        }
        let mut cap = Capture::new(64, 48);
        let mut r = Box::new(Big::<Q16_16>::new());
        let e = r.render(&ScreenScene { mesh: bad }, &cfg, &mut cap);
        assert_eq!(e, Err(RenderError::Scene(expected)));
        assert_eq!(cap.rows_received, 0, "no row before the error");
    }
    assert_eq!(
        Error::Colors {
            faces: 3,
            colors: 2
        }
        .to_string(),
        "mesh has 2 colours for 3 triangles: give one per triangle or one for all"
    );
}

#[test]
fn wrong_normals_length_is_a_typed_error_before_any_row() {
    let model = Model::torus(8, 6, 1.0, 0.4);
    let verts: Vec<Vec3<Q16_16>> = model.vertices.iter().map(|&v| vec3(v)).collect();
    let tris: Vec<Vec<usize>> = model.tris.iter().map(|t| t.to_vec()).collect();
    let lists = index_lists::<u8>(&tris).unwrap();
    let f8 = faces(&lists);
    let all: Vec<Vec3<Q16_16>> = model.normals().into_iter().map(vec3).collect();
    let cfg = Config::model(64, 48);
    let camera = cameras::<Q16_16>()[0];
    let nf = f8.len() as u32;
    for count in [1, f8.len() - 1, f8.len() + 1, 2 * f8.len()] {
        let normals: Vec<Vec3<Q16_16>> = all.iter().cycle().take(count).copied().collect();
        let expected = Error::Normals {
            faces: nf,
            normals: count as u32,
        };
        let bad = Mesh::with_normals(&verts, &f8, &normals);
        // Model mode, the bad mesh second: nothing of the good first object is sent either.
        let good = Mesh::new(&verts, &f8);
        let objects = [
            Object {
                mesh: &good,
                transform: Affine::identity(),
            },
            Object {
                mesh: &bad,
                transform: Affine::identity(),
            },
        ];
        let scene = ModelScene {
            objects: &objects,
            camera,
            light: Light {
                direction: Vec3::from_f32([0.0, 1.0, 0.0]).unwrap(),
                ambient: Q16_16::ONE,
            },
        };
        let mut r = Box::new(Big::<Q16_16>::new());
        let mut cap = Capture::new(64, 48);
        assert_eq!(
            r.render(&scene, &cfg, &mut cap),
            Err(RenderError::Scene(expected))
        );
        assert_eq!(cap.rows_received, 0, "no row before the error");
        assert_eq!(requirements(&scene, &cfg), Err(expected));
        // Screen mode ignores normals but rejects a wrong count all the same.
        let mut cap = Capture::new(64, 48);
        let e = r.render(&ScreenScene { mesh: bad }, &cfg, &mut cap);
        assert_eq!(e, Err(RenderError::Scene(expected)));
        assert_eq!(cap.rows_received, 0, "no row before the error");
    }
    assert_eq!(
        Error::Normals {
            faces: 3,
            normals: 2
        }
        .to_string(),
        "mesh has 2 normals for 3 faces: give one per face or none"
    );
}

#[test]
fn u8_index_out_of_range_is_index_out_of_range() {
    let v = [
        Vec3::new(1.0f32, 1.0, 1.0),
        Vec3::new(9.0, 1.0, 1.0),
        Vec3::new(1.0, 9.0, 1.0),
    ];
    let cfg = Config::screen(16, 16);
    for bad in [3u8, 200, 255] {
        let ok = [0u8, 1, 2];
        let wrong = [0u8, bad, 2];
        let f8 = [
            Face {
                indices: &ok[..],
                color: Rgb565::RED,
                alpha: 255,
            },
            Face {
                indices: &wrong[..],
                color: Rgb565::RED,
                alpha: 255,
            },
        ];
        let (ok16, wrong16) = ([0u16, 1, 2], [0u16, bad as u16, 2]);
        let f16 = [
            Face::new(&ok16, Rgb565::RED),
            Face::new(&wrong16, Rgb565::RED),
        ];
        let expected = Err(RenderError::Scene(Error::IndexOutOfRange {
            face: 1,
            index: bad as u32,
        }));
        let mut r = Box::new(Big::<f32>::new());
        let mut cap = Capture::new(16, 16);
        assert_eq!(
            r.render(
                &ScreenScene {
                    mesh: Mesh::new(&v, &f8)
                },
                &cfg,
                &mut cap
            ),
            expected
        );
        assert_eq!(cap.rows_received, 0);
        let mut cap = Capture::new(16, 16);
        assert_eq!(
            r.render(
                &ScreenScene {
                    mesh: Mesh::new(&v, &f16)
                },
                &cfg,
                &mut cap
            ),
            expected
        );
        assert_eq!(cap.rows_received, 0);
        // Model mode too.
        let mesh = Mesh::new(&v, &f8);
        let objects = [Object {
            mesh: &mesh,
            transform: Affine::identity(),
        }];
        let scene = ModelScene {
            objects: &objects,
            camera: cameras::<f32>()[0],
            light: Light {
                direction: Vec3::new(0.0, 1.0, 0.0),
                ambient: 1.0,
            },
        };
        let mut cap = Capture::new(16, 16);
        assert_eq!(r.render(&scene, &Config::model(16, 16), &mut cap), expected);
        assert_eq!(cap.rows_received, 0);
    }
}

#[test]
fn mesh_index_reaches_the_whole_type() {
    assert_eq!(
        (<u8 as MeshIndex>::MAX, <u16 as MeshIndex>::MAX),
        (256, 65536)
    );
    assert_eq!((255u8.index(), 65535u16.index()), (255, 65535));
    // The const constructors work in statics (flash-resident meshes).
    static V: [Vec3<Q16_16>; 3] = [
        Vec3::new(
            Q16_16::from_bits(0),
            Q16_16::from_bits(0),
            Q16_16::from_bits(0),
        ),
        Vec3::new(
            Q16_16::from_bits(1 << 16),
            Q16_16::from_bits(0),
            Q16_16::from_bits(0),
        ),
        Vec3::new(
            Q16_16::from_bits(0),
            Q16_16::from_bits(1 << 16),
            Q16_16::from_bits(0),
        ),
    ];
    static F: [Face<'static, u8>; 1] = [Face {
        indices: &[0, 1, 2],
        color: Rgb565::new(31, 0, 0),
        alpha: 255,
    }];
    static N: [Vec3<Q16_16>; 1] = [Vec3::new(
        Q16_16::from_bits(0),
        Q16_16::from_bits(0),
        Q16_16::from_bits(1 << 16),
    )];
    static M: Mesh<'static, Q16_16, u8> = Mesh::with_normals(&V, &F, &N);
    static M0: Mesh<'static, Q16_16, u8> = Mesh::new(&V, &F);
    assert_eq!((M.normals.len(), M0.normals.len()), (1, 0));
}
