//! Hidden-line drawings: the textbook cube (only the three visible faces' edges, no diagonal, no
//! hidden edge), every method drawing the same facets, the streaming sink against a whole-frame
//! rule, and the typed errors.

#![cfg(feature = "lines")]

mod common;

use common::{every_method, Capture};
use embedded_graphics_core::pixelcolor::{IntoStorage, Rgb565, RgbColor};
use zrow::lines::HiddenLines;
use zrow::shading::Shading;
use zrow::{
    Affine, Camera, Config, Error, Face, FrameBuffer, Light, Mesh, ModelScene, Object, Projection,
    RenderError, Scalar, Scanline, ScreenScene, Vec3, ZBuffer, Q16_16, Q24_8,
};

/// The frame's size.
const S: usize = 64;

/// The unit cube's corner (a, b, c) projected as the textbook figure shows it (isometric, (1,1,1)
/// nearest, (0,0,0) hidden behind it): pixels and depth.
fn corner(a: f64, b: f64, c: f64) -> [f64; 3] {
    [
        32.0 + 18.0 * (a - c),
        32.0 - 20.0 * b + 10.0 * (a + c),
        100.0 - 30.0 * (a + b + c),
    ]
}

/// The cube's corners, index a + 2b + 4c.
fn cube_corners() -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| corner((i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64))
        .collect()
}

/// Its six faces, each a quad cut into two triangles (12 faces; the three at the back are
/// hidden, not culled).
const CUBE: [[u16; 3]; 12] = [
    [0, 1, 3],
    [0, 3, 2], // c = 0
    [4, 5, 7],
    [4, 7, 6], // c = 1
    [0, 2, 6],
    [0, 6, 4], // a = 0
    [1, 3, 7],
    [1, 7, 5], // a = 1
    [0, 1, 5],
    [0, 5, 4], // b = 0
    [2, 3, 7],
    [2, 7, 6], // b = 1
];

/// Faces of one colour and opacity on `triangles`.
fn faces_of(triangles: &[[u16; 3]], color: Rgb565, alpha: u8) -> Vec<Face<'_>> {
    triangles
        .iter()
        .map(|t| Face {
            indices: &t[..],
            color,
            alpha,
        })
        .collect()
}

/// The facets frame of the cube drawn by `m`.
fn cube_facets<N: Scalar>(m: &mut common::Method<N>) -> Capture<N> {
    let vertices: Vec<Vec3<N>> = cube_corners()
        .iter()
        .map(|p| Vec3::from_f32([p[0] as f32, p[1] as f32, p[2] as f32]).unwrap())
        .collect();
    let faces = faces_of(&CUBE, Rgb565::WHITE, 255);
    let scene = ScreenScene {
        mesh: Mesh::new(&vertices, &faces),
    };
    let mut cfg = Config::screen(S as u16, S as u16);
    cfg.shading = Shading::Facets;
    let (cap, _, _) = m
        .scene(&scene, &cfg)
        .unwrap_or_else(|e| panic!("{}: {e:?}", m.name));
    cap
}

/// The hidden-line rule over a whole frame of facet numbers, written independently of the
/// streaming sink: a facet pixel with a 4-neighbour of a smaller number.
fn lines_of(facets: &[u16], w: usize, h: usize) -> Vec<bool> {
    let at = |x: usize, y: usize| facets[y * w + x];
    let mut out = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            let id = at(x, y);
            let mut n = Vec::new();
            if x > 0 {
                n.push(at(x - 1, y));
            }
            if x + 1 < w {
                n.push(at(x + 1, y));
            }
            if y > 0 {
                n.push(at(x, y - 1));
            }
            if y + 1 < h {
                n.push(at(x, y + 1));
            }
            out[y * w + x] = id != 0 && n.iter().any(|&o| o < id);
        }
    }
    out
}

/// Distance from `p` to the segment `a`–`b`.
fn distance(p: [f64; 2], a: [f64; 3], b: [f64; 3]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    let (x, y) = (a[0] + t * dx, a[1] + t * dy);
    ((p[0] - x).powi(2) + (p[1] - y).powi(2)).sqrt()
}

/// The textbook's first figure: the cube's hidden-line drawing has the nine edges of its three
/// visible faces — every line pixel within a pixel of one, every one of them drawn along its
/// length — and nothing along the three hidden edges or the six diagonals, in every method.
fn cube_has_only_the_visible_edges<N: Scalar>() {
    let c = cube_corners();
    let p = |i: usize| c[i];
    // a + 2b + 4c: (1,1,1) = 7 is the near corner; (0,0,0) = 0 the hidden one.
    let visible: [(usize, usize); 9] = [
        (2, 3),
        (3, 7),
        (7, 6),
        (6, 2), // top (b = 1)
        (3, 1),
        (1, 5),
        (5, 7), // right (a = 1)
        (6, 4),
        (4, 5), // left (c = 1)
    ];
    let hidden: [(usize, usize); 9] = [
        (0, 1),
        (0, 2),
        (0, 4),
        (0, 3),
        (0, 6),
        (0, 5),
        (2, 7),
        (1, 7),
        (4, 7),
    ];
    for m in &mut every_method::<N>() {
        let cap = cube_facets(m);
        let facets: Vec<u16> = cap.color.iter().map(|c| c.into_storage()).collect();
        let lines = lines_of(&facets, S, S);
        let drawn = |x: usize, y: usize| lines[y * S + x];
        let near_visible = |q: [f64; 2]| {
            visible
                .iter()
                .map(|&(a, b)| distance(q, p(a), p(b)))
                .fold(f64::MAX, f64::min)
        };
        let mut count = 0;
        for y in 0..S {
            for x in 0..S {
                if drawn(x, y) {
                    count += 1;
                    let d = near_visible([x as f64 + 0.5, y as f64 + 0.5]);
                    assert!(
                        d <= 1.0,
                        "{}: line pixel ({x}, {y}) {d:.2} px from every visible edge",
                        m.name
                    );
                }
            }
        }
        // Along each visible edge, every point has a line pixel within one pixel.
        let line_near = |q: [f64; 2]| {
            let (cx, cy) = (q[0].floor() as i64, q[1].floor() as i64);
            (cy - 1..=cy + 1).any(|y| {
                (cx - 1..=cx + 1).any(|x| {
                    (0..S as i64).contains(&x)
                        && (0..S as i64).contains(&y)
                        && drawn(x as usize, y as usize)
                })
            })
        };
        let along =
            |a: [f64; 3], b: [f64; 3], t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        for &(a, b) in &visible {
            for k in 0..=40 {
                let q = along(p(a), p(b), k as f64 / 40.0);
                assert!(
                    line_near(q),
                    "{}: visible edge {a}-{b} missing at {q:?}",
                    m.name
                );
            }
        }
        // Hidden edges and diagonals: no line pixel near them where they are far enough from
        // a visible edge (3.5 px: the 3 × 3 pixels looked at, plus a line's own pixel).
        for &(a, b) in &hidden {
            for k in 0..=40 {
                let q = along(p(a), p(b), k as f64 / 40.0);
                if near_visible(q) >= 3.5 {
                    assert!(
                        !line_near(q),
                        "{}: hidden edge or diagonal {a}-{b} drawn at {q:?}",
                        m.name
                    );
                }
            }
        }
        // A line 1 px wide has at least one pixel per row or column it spans (less the nine
        // corners two edges share), and not much more.
        let span: usize = visible
            .iter()
            .map(|&(a, b)| (p(a)[0] - p(b)[0]).abs().max((p(a)[1] - p(b)[1]).abs()) as usize)
            .sum();
        assert!(
            (span - 9..=span * 3 / 2).contains(&count),
            "{}: {count} line pixels for edges spanning {span}",
            m.name
        );
    }
}

#[test]
fn textbook_cube_hidden_lines_q16() {
    cube_has_only_the_visible_edges::<Q16_16>();
}

#[test]
fn textbook_cube_hidden_lines_q24() {
    cube_has_only_the_visible_edges::<Q24_8>();
}

#[test]
fn textbook_cube_hidden_lines_f32() {
    cube_has_only_the_visible_edges::<f32>();
}

/// A torus of `rings` × `sides` quads, each cut into two triangles.
fn torus(rings: usize, sides: usize) -> (Vec<[f32; 3]>, Vec<[u16; 3]>) {
    use std::f32::consts::TAU;
    let mut v = Vec::new();
    for i in 0..rings {
        let u = TAU * i as f32 / rings as f32;
        for j in 0..sides {
            let w = TAU * j as f32 / sides as f32;
            let r = 0.7 + 0.3 * w.cos();
            v.push([r * u.cos(), 0.3 * w.sin(), r * u.sin()]);
        }
    }
    let at = |i: usize, j: usize| ((i % rings) * sides + j % sides) as u16;
    let mut t = Vec::new();
    for i in 0..rings {
        for j in 0..sides {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    (v, t)
}

/// The torus (12 × 8 quads, 192 triangles) tilted towards a perspective camera.
fn with_torus<N: Scalar, R>(
    cull: bool,
    draw: impl FnOnce(&ModelScene<'_, N, u16>, &Config) -> R,
) -> R {
    let (v, t) = torus(12, 8);
    let vertices: Vec<Vec3<N>> = v.iter().map(|&p| Vec3::from_f32(p).unwrap()).collect();
    let faces = faces_of(&t, Rgb565::CYAN, 200);
    in_view(&Mesh::new(&vertices, &faces), cull, draw)
}

/// `mesh` tilted towards a perspective camera, drawn as facets.
fn in_view<N: Scalar, R>(
    mesh: &Mesh<'_, N, u16>,
    cull: bool,
    draw: impl FnOnce(&ModelScene<'_, N, u16>, &Config) -> R,
) -> R {
    let objects = [Object {
        mesh,
        transform: Affine::rotate_yx_translate(0.3, 0.9, [0.0, 0.0, 0.0]).unwrap(),
    }];
    let projection = Projection::perspective(50f32.to_radians(), 0.5, 10.0).unwrap();
    let scene = ModelScene {
        objects: &objects,
        camera: Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0], projection).unwrap(),
        light: Light {
            direction: Vec3::from_f32([0.0, 0.0, 1.0]).unwrap(),
            ambient: N::ZERO,
        },
    };
    let mut cfg = Config::model(S as u16, S as u16);
    if !cull {
        cfg.cull = zrow::Cull::None;
    }
    cfg.shading = Shading::Facets;
    draw(&scene, &cfg)
}

/// Every method draws the same facets of the torus (translucent faces drawn opaque: the
/// A-buffer too), culled or not; a quad's two triangles are one facet.
fn every_method_draws_the_same_facets<N: Scalar>() {
    for cull in [true, false] {
        let reference = with_torus::<N, _>(cull, |scene, cfg| {
            let mut cap = Capture::new(S, S);
            Scanline::<N, 64, 1024, 256, 256>::new()
                .render(scene, cfg, &mut cap)
                .unwrap();
            cap
        });
        let ids: std::collections::BTreeSet<u16> = reference
            .color
            .iter()
            .map(|c| c.into_storage())
            .filter(|&i| i != 0)
            .collect();
        assert!(ids.len() > 20, "{} facets visible", ids.len());
        assert!(
            ids.iter().all(|i| (i - 1) % 2 == 0),
            "a quad's second triangle has a facet of its own: {ids:?}"
        );
        for m in &mut every_method::<N>() {
            let (cap, _, _) = with_torus::<N, _>(cull, |scene, cfg| m.scene(scene, cfg))
                .unwrap_or_else(|e| panic!("{}: {e:?}", m.name));
            let differ = cap
                .color
                .iter()
                .zip(&reference.color)
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(
                differ, 0,
                "{} (cull {cull}): {differ} pixels differ from the scan-line's facets",
                m.name
            );
        }
    }
}

#[test]
fn every_method_draws_the_same_facets_q16() {
    every_method_draws_the_same_facets::<Q16_16>();
}

#[test]
fn every_method_draws_the_same_facets_q24() {
    every_method_draws_the_same_facets::<Q24_8>();
}

#[test]
fn every_method_draws_the_same_facets_f32() {
    every_method_draws_the_same_facets::<f32>();
}

/// Facets of a torus with compact (16-bit) positions are the facets of the same positions
/// given in the format: the compact path takes the integers themselves (every length scaled
/// by 2^shift, the tolerance with them), the other converts them first. Each vertex is
/// jittered by a few units so that many quads sit near the coplanarity tolerance: some merge,
/// some split, and a tolerance not scaled with the lengths would move some of them.
fn compact_positions_draw_the_facets_of_their_values<N: Scalar>(shifts: &[u8]) {
    let (v, t) = torus(12, 8);
    let mut seed = 0x2545_f491u32;
    for &shift in shifts {
        let unit = (1u32 << shift) as f32;
        // A few units beyond the format's tolerance (4 LSB, in units of 2^-shift).
        let a = 3 + (8.0 * N::LSB * unit).ceil() as u32;
        let mut jitter = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            (seed % (2 * a + 1)) as i16 - a as i16
        };
        let raw: Vec<[i16; 3]> = v
            .iter()
            .map(|p| p.map(|c| (c * unit).round() as i16 + jitter()))
            .collect();
        let values: Vec<Vec3<N>> = (0..raw.len())
            .map(|i| zrow::Vectors::Compact { raw: &raw, shift }.get(i).unwrap())
            .collect();
        let faces: Vec<Face<'_>> = t.iter().map(|t| Face::new(&t[..], Rgb565::CYAN)).collect();
        let draw = |vertices: zrow::Vectors<'_, N>| {
            let mesh = Mesh::new(&[], &faces).with_positions(vertices);
            in_view(&mesh, true, |scene, cfg| {
                let mut cap = Capture::new(S, S);
                Scanline::<N, 64, 1024, 256, 256>::new()
                    .render(scene, cfg, &mut cap)
                    .unwrap();
                cap.color
            })
        };
        let compact = draw(zrow::Vectors::Compact { raw: &raw, shift });
        let converted = draw(zrow::Vectors::Format(&values));
        let differ = compact
            .iter()
            .zip(&converted)
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differ,
            0,
            "{} shift {shift}: {differ} pixels differ",
            N::NAME
        );
        // Both kinds of quad are on screen: merged (its second triangle drawn in its first's
        // facet) and split (a second triangle, odd face number, drawn as its own facet).
        let ids: std::collections::BTreeSet<u16> = compact
            .iter()
            .map(|c| c.into_storage())
            .filter(|&i| i != 0)
            .collect();
        let split = ids.iter().filter(|&&i| (i - 1) % 2 == 1).count();
        assert!(
            split > 0 && split < ids.len(),
            "{} shift {shift}: {split} of {} facets are split quads",
            N::NAME,
            ids.len()
        );
    }
}

#[test]
fn compact_positions_draw_the_facets_of_their_values_q16() {
    compact_positions_draw_the_facets_of_their_values::<Q16_16>(&[10, 12, 14]);
}

#[test]
fn compact_positions_draw_the_facets_of_their_values_q24() {
    // (Shift 8 is converted exactly; 12 is not, and takes the converted path.)
    compact_positions_draw_the_facets_of_their_values::<Q24_8>(&[8, 12]);
}

#[test]
fn compact_positions_draw_the_facets_of_their_values_f32() {
    compact_positions_draw_the_facets_of_their_values::<f32>(&[12]);
}

/// The sink, fed by a renderer row by row, draws what the whole-frame rule draws from the
/// facets frame (rows held for their lower neighbours, the last one flushed), in the colours
/// asked for, each row once and in order.
/// A strip of 24 quads (48 triangles, each sharing an edge with the one before), flat up to
/// column 12 and folded there: two facets of 24 faces, each longer than the 16 steps a facet
/// is followed back. Face `k` of a run starting at face `r` is drawn as facet
/// `max(r, k − 16)`, read across the middle row (a quad's left pixel is its first triangle,
/// its right pixel its second), in every method, culled or not (the strip is front-facing).
fn long_facets_are_followed_back_sixteen_faces<N: Scalar>() {
    // Column i's top and bottom corners; depth flat, then rising past column 12.
    let z = |i: usize| 10.0 + 3.0 * i.saturating_sub(12) as f32;
    let mut vertices = Vec::new();
    for i in 0..=24 {
        let x = 4.0 + 2.0 * i as f32;
        vertices.push(Vec3::<N>::from_f32([x, 4.0, z(i)]).unwrap());
        vertices.push(Vec3::<N>::from_f32([x, 60.0, z(i)]).unwrap());
    }
    let (top, bottom) = (|i: usize| 2 * i as u16, |i: usize| 2 * i as u16 + 1);
    let triangles: Vec<[u16; 3]> = (0..24)
        .flat_map(|i| {
            [
                [top(i), bottom(i), top(i + 1)],
                [bottom(i), bottom(i + 1), top(i + 1)],
            ]
        })
        .collect();
    let faces = faces_of(&triangles, Rgb565::WHITE, 255);
    let scene = ScreenScene {
        mesh: Mesh::new(&vertices, &faces),
    };
    let facet = |k: usize| {
        let run = if k < 24 { 0 } else { 24 };
        run.max(k.saturating_sub(16)) as u16 + 1
    };
    for cull in [zrow::Cull::None, zrow::Cull::Back] {
        let mut cfg = Config::screen(S as u16, S as u16);
        cfg.shading = Shading::Facets;
        cfg.cull = cull;
        for m in &mut every_method::<N>() {
            let (cap, _, _) = m
                .scene(&scene, &cfg)
                .unwrap_or_else(|e| panic!("{}: {e:?}", m.name));
            let row = &cap.color[32 * S..33 * S];
            let drawn: Vec<u16> = row.iter().map(|c| c.into_storage()).collect();
            for k in 0..48 {
                let x = 4 + 2 * (k / 2) + k % 2;
                assert_eq!(drawn[x], facet(k), "{} ({cull:?}): face {k}", m.name);
            }
        }
    }
}

#[test]
fn long_facets_are_followed_back_sixteen_faces_q16() {
    long_facets_are_followed_back_sixteen_faces::<Q16_16>();
}

#[test]
fn long_facets_are_followed_back_sixteen_faces_f32() {
    long_facets_are_followed_back_sixteen_faces::<f32>();
}

#[test]
fn streaming_sink_matches_the_whole_frame_rule() {
    let facets = with_torus::<Q16_16, _>(false, |scene, cfg| {
        let mut cap = Capture::new(S, S);
        Scanline::<Q16_16, 64, 1024, 256, 256>::new()
            .render(scene, cfg, &mut cap)
            .unwrap();
        cap
    });
    let ids: Vec<u16> = facets.color.iter().map(|c| c.into_storage()).collect();
    let expected = lines_of(&ids, S, S);
    let (line, background) = (Rgb565::YELLOW, Rgb565::new(2, 4, 8));
    // Twice through the same sink: the second frame starts over at row 0.
    let mut pixels = vec![Rgb565::RED; S * S];
    {
        let frame = FrameBuffer::new(&mut pixels, S);
        let mut sink = HiddenLines::<_, S>::new(frame, S as u16, line, background);
        let mut z = Box::new(ZBuffer::<Q16_16, 64, 64>::new());
        for _ in 0..2 {
            with_torus::<Q16_16, _>(false, |scene, cfg| z.render(scene, cfg, &mut sink)).unwrap();
        }
    }
    for (k, (&p, &e)) in pixels.iter().zip(&expected).enumerate() {
        let want = if e { line } else { background };
        assert_eq!(p, want, "pixel ({}, {})", k % S, k / S);
    }
    assert!(expected.iter().filter(|&&e| e).count() > 100);
}

/// Facets on a background that is not black would be read as a facet: refused.
#[test]
fn facets_need_a_black_background() {
    let mut cfg = Config::screen(8, 8);
    cfg.shading = Shading::Facets;
    cfg.background = Rgb565::BLUE;
    let scene = ScreenScene::<Q16_16> {
        mesh: Mesh::new(&[], &[]),
    };
    let mut pixels = [Rgb565::BLACK; 64];
    let r = Scanline::<Q16_16, 8, 8, 2, 2>::new().render(
        &scene,
        &cfg,
        &mut FrameBuffer::new(&mut pixels, 8),
    );
    assert!(
        matches!(r, Err(RenderError::Scene(Error::BadConfig))),
        "{r:?}"
    );
}

/// More facets than 16 bits can name: an error before any row, not two facets sharing a value.
#[test]
fn more_than_65535_faces_are_refused() {
    let q = |x: f32| Vec3::<Q16_16>::from_f32([x, x, 1.0]).unwrap();
    let vertices = [q(-20000.0), q(-20001.0), q(-20002.0)]; // far outside: clipped away
    let tri = [0u16, 1, 2];
    let faces = vec![
        Face {
            indices: &tri[..],
            color: Rgb565::WHITE,
            alpha: 255
        };
        65_536
    ];
    let scene = ScreenScene {
        mesh: Mesh::new(&vertices, &faces),
    };
    let mut cfg = Config::screen(8, 8);
    cfg.shading = Shading::Facets;
    let mut cap = Capture::<Q16_16>::new(8, 8);
    let r = ZBuffer::<Q16_16, 8, 8>::new().render(&scene, &cfg, &mut cap);
    assert!(
        matches!(r, Err(RenderError::Scene(Error::Unsupported { .. }))),
        "{r:?}"
    );
    assert_eq!(cap.rows_received, 0);
    // 65,535 faces are fine.
    let scene = ScreenScene {
        mesh: Mesh::new(&vertices, &faces[..65_535]),
    };
    ZBuffer::<Q16_16, 8, 8>::new()
        .render(&scene, &cfg, &mut cap)
        .unwrap();
}

/// The sink takes any rows a sink of one's own might be handed — out of order, repeated, at
/// the ends of `u16`, wider than its capacity or empty, for frames of any height — without a
/// panic (debug build: no overflow), handing on rows no wider than its capacity and never more
/// rows than it was given.
#[test]
fn the_sink_takes_any_rows_without_panic() {
    struct Count {
        rows: u32,
        widest: usize,
    }
    impl zrow::RowSink<Q16_16> for Count {
        type Error = ();
        fn write_row(&mut self, row: &zrow::Row<'_, Q16_16>) -> Result<(), ()> {
            self.rows += 1;
            self.widest = self.widest.max(row.color.len());
            Ok(())
        }
    }
    let ids: Vec<Rgb565> = (0..20u16)
        .map(|i| Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(i % 3)))
        .collect();
    for height in [0u16, 1, 2, 3, u16::MAX] {
        let mut sink = HiddenLines::<_, 8>::new(
            Count { rows: 0, widest: 0 },
            height,
            Rgb565::WHITE,
            Rgb565::BLACK,
        );
        for (y, w) in [
            (u16::MAX, 20),
            (0, 0),
            (1, 20),
            (2, 3),
            (u16::MAX - 1, 8),
            (u16::MAX, 1),
            (0, 8),
            (1, 8),
            (2, 8),
        ] {
            let row = zrow::Row::<Q16_16> {
                y,
                color: &ids[..w],
                depth: &[],
            };
            zrow::RowSink::write_row(&mut sink, &row).unwrap();
        }
        let count = sink.into_inner();
        assert!(
            count.widest <= 8,
            "height {height}: a row of {}",
            count.widest
        );
        assert!(
            count.rows <= 9,
            "height {height}: {} rows out of 9",
            count.rows
        );
    }
}
