//! Smooth shading and hidden lines on the torus (`mesh1k`), measured like the presets: the
//! emulated Cortex-M4's instructions (zrow-scenes' `mesh1k-smooth`, `mesh1k-dither` and
//! `mesh1k-lines` frames of `emu/run.sh m4`), host time, RAM, and the error against an exact
//! `f64` reference:
//!
//! - **Gouraud** (dithered or not): at every pixel where the reference's nearest face covers
//!   the centre unambiguously (FULL) and the frame shows that face, each Rgb565 channel
//!   against the face's colour times the intensity Gouraud interpolates there — the vertices
//!   lit in `f64` with their own normals (`ambient + (1 − ambient)·max(0, n̂·l̂)`), linearly in
//!   screen space over the unsnapped projected triangle.
//! - **Hidden lines**: the reference's facets (its nearest face per pixel, faces merged as
//!   `zrow::shading::Shading::Facets` says: listed one after the other, sharing an edge, in one
//!   plane), turned into lines by the same rule as `zrow::lines::HiddenLines`; a reference line
//!   pixel with no drawn line pixel within one pixel (its 3 × 3 block) is **missing**, a drawn
//!   one with no reference line pixel within one pixel is **extra**.

use crate::reference::{self, cross, dot, sub, unit, Aff, Cam, RefScene, State};
use crate::render::{draw, face_of, median, Capture, Frame, IdScene, SIZE};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use std::collections::BTreeMap;
use std::time::Duration;
use zrow::lines::HiddenLines;
use zrow::scanline::Uncued;
use zrow::shading::Shading;
use zrow::{IntensityPlane, Renderer, Scalar, Scanline, Scene, Q16_16};

/// What a row measured.
pub enum Error {
    /// Gouraud: largest and mean channel error (LSB), pixels over 1 LSB, pixels compared.
    Intensity {
        max: f64,
        mean: f64,
        over_one: u32,
        pixels: u32,
    },
    /// Hidden lines: line pixels in the reference and drawn, missing and extra (beyond 1 px).
    Lines {
        reference: u32,
        drawn: u32,
        missing: u32,
        extra: u32,
    },
}

/// One row of the table.
pub struct Row {
    /// What is drawn.
    pub name: &'static str,
    /// The emu scene it is measured on.
    pub scene: &'static str,
    /// Number format.
    pub format: &'static str,
    /// Emulated M4 instructions and `ram=` bytes, if the bench ran.
    pub m4: Option<(u64, u64)>,
    /// Median host time per frame.
    pub host: Duration,
    /// Against the reference.
    pub error: Error,
}

/// The smooth-shading renderer: intensity planes, no affine-cue state.
type Smooth<N> = Scanline<N, SIZE, 3072, 1024, 512, u16, Uncued, [IntensityPlane<N>; 1024]>;
/// The flat renderer (facets, and the ID render).
type Flat<N> = Scanline<N, SIZE, 3072, 1024, 512>;

/// `(instructions, ram)` of the bench's `method=scanline` frames, by (scene, format).
pub fn bench(text: &str) -> BTreeMap<(String, String), (u64, u64)> {
    let mut out = BTreeMap::new();
    for line in text.lines().filter(|l| l.starts_with("method=scanline ")) {
        let field = |key: &str| {
            line.split_whitespace()
                .find_map(|kv| kv.strip_prefix(key)?.strip_prefix('='))
        };
        if let (Some(s), Some(f), Some(i), Some(r)) = (
            field("scene"),
            field("format"),
            field("instructions").and_then(|i| i.parse().ok()),
            field("ram").and_then(|r| r.parse().ok()),
        ) {
            out.insert((s.to_string(), f.to_string()), (i, r));
        }
    }
    out
}

/// Every row, in format `N`.
fn rows_in<N: zrow_scenes::Format>(
    counts: &BTreeMap<(String, String), (u64, u64)>,
    time_for: Duration,
) -> Result<Vec<Row>, String> {
    let (scene, pixels) = crate::measure::reference_of("mesh1k", 8).ok_or("no reference")?;
    let m4 = |s: &str| counts.get(&(s.to_string(), N::NAME.to_string())).copied();
    let mut rows = vec![];
    for (name, s) in [
        ("gouraud", "mesh1k-smooth"),
        ("gouraud + dither", "mesh1k-dither"),
    ] {
        let mut r = Box::new(Smooth::<N>::new());
        let mut flat = Box::new(Flat::<N>::new());
        let run = zrow_scenes::with_scene::<N, _>(s, 0.0, |sc, cfg, _| {
            let frame = draw(&mut *r, sc, cfg, SIZE)?;
            let ids_cfg = zrow::Config {
                shading: Shading::Flat,
                ..*cfg
            };
            let ids = draw(&mut *flat, &IdScene(sc), &ids_cfg, SIZE)?;
            let host = median(time_for, || draw(&mut *r, sc, cfg, SIZE).map(|_| ()))?;
            Ok::<_, String>((frame, ids, host))
        })
        .ok_or(format!("no scene {s}"))??;
        let (frame, ids, host) = run;
        rows.push(Row {
            name,
            scene: s,
            format: N::NAME,
            m4: m4(s),
            host,
            error: gouraud_error(&scene, &pixels, &frame, &ids)?,
        });
    }
    let mut r = Box::new(Flat::<N>::new());
    let run = zrow_scenes::with_scene::<N, _>("mesh1k-lines", 0.0, |sc, cfg, _| {
        let lines = draw_lines(&mut *r, sc, cfg)?;
        let host = median(time_for, || draw_lines(&mut *r, sc, cfg).map(|_| ()))?;
        Ok::<_, String>((lines, host))
    })
    .ok_or("no scene mesh1k-lines")??;
    let (lines, host) = run;
    rows.push(Row {
        name: "hidden lines",
        scene: "mesh1k-lines",
        format: N::NAME,
        m4: m4("mesh1k-lines"),
        host,
        error: lines_error(&scene, &pixels, &lines)?,
    });
    Ok(rows)
}

/// Every row: Q16.16, then f32.
pub fn rows(text: &str, time_for: Duration) -> Result<Vec<Row>, String> {
    let counts = bench(text);
    let mut out = rows_in::<Q16_16>(&counts, time_for)?;
    out.extend(rows_in::<f32>(&counts, time_for)?);
    Ok(out)
}

/// A frame of facets through the hidden-line sink: which pixels are on a line.
fn draw_lines<N: Scalar, R: Renderer<N>>(
    r: &mut R,
    scene: &dyn Scene<N>,
    cfg: &zrow::Config,
) -> Result<Vec<bool>, String> {
    let mut frame = Frame {
        colour: vec![Rgb565::BLACK; SIZE * SIZE],
        depth: vec![f64::INFINITY; SIZE * SIZE],
    };
    let sink = Capture(&mut frame);
    let mut lines = Box::new(HiddenLines::<_, SIZE>::new(
        sink,
        SIZE as u16,
        Rgb565::WHITE,
        Rgb565::BLACK,
    ));
    r.render(scene, cfg, &mut *lines)
        .map_err(|e| format!("{e:?}"))?;
    drop(lines);
    Ok(frame.colour.iter().map(|&c| c == Rgb565::WHITE).collect())
}

/// One triangle of the torus: model-space corners, their vertex normals, its colour's
/// channels, its vertex indices.
type Triangle = ([[f64; 3]; 3], [[f64; 3]; 3], [f64; 3], [usize; 3]);

/// The torus's faces in the reference's order, and its transform.
struct Model {
    faces: Vec<Triangle>,
    transform: Aff,
}

fn model() -> Result<Model, String> {
    let mesh = zrow_scenes::mesh::<f32>("mesh1k-smooth").ok_or("no mesh1k-smooth")?;
    let objs = reference::objects("mesh1k").ok_or("no mesh1k")?;
    let v = |i: usize, normals: bool| -> Result<[f64; 3], String> {
        let p = match normals {
            true => mesh.vertex_normals.get(i),
            false => mesh.vertices.get(i),
        }
        .ok_or("an index out of range")?;
        Ok([p.x as f64, p.y as f64, p.z as f64])
    };
    let mut faces = vec![];
    for f in mesh.faces {
        let i: Vec<usize> = f.indices.iter().map(|&i| i as usize).collect();
        let &[a, b, c] = &i[..] else {
            return Err("mesh1k is triangles".into());
        };
        let c3 = [f.color.r() as f64, f.color.g() as f64, f.color.b() as f64];
        faces.push((
            [v(a, false)?, v(b, false)?, v(c, false)?],
            [v(a, true)?, v(b, true)?, v(c, true)?],
            c3,
            [a, b, c],
        ));
    }
    Ok(Model {
        faces,
        transform: objs[0].transform,
    })
}

/// Gouraud's error: channels against the interpolated exact intensity.
fn gouraud_error(
    scene: &RefScene,
    pixels: &[reference::Pixel],
    frame: &Frame,
    ids: &Frame,
) -> Result<Error, String> {
    let m = model()?;
    let cam = Cam::scenes();
    let mv = cam.view.then_after(&m.transform);
    let (dir, ambient) = reference::light();
    let l = unit(cam.view.apply_dir(dir));
    let lit = |n: [f64; 3]| ambient + (1.0 - ambient) * dot(unit(mv.apply_dir(n)), l).max(0.0);
    let (mut max, mut sum, mut over_one, mut count) = (0.0f64, 0.0, 0u32, 0u32);
    for (k, px) in pixels.iter().enumerate() {
        let (Some(rf), State::Full) = (px.face, px.state) else {
            continue;
        };
        let face = &scene.faces[rf];
        if face_of(ids.colour[k]) != Some(face.number) {
            continue; // another surface drawn: the presets table counts those
        }
        let (_, normals, colour, _) = m.faces[face.number as usize];
        let (x, y) = ((k % SIZE) as f64 + 0.5, (k / SIZE) as f64 + 0.5);
        let [a, b, c] = [face.xy[0], face.xy[1], face.xy[2]];
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let lb = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / det;
        let lc = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / det;
        let i = (1.0 - lb - lc) * lit(normals[0]) + lb * lit(normals[1]) + lc * lit(normals[2]);
        let got = frame.colour[k];
        let mut worst: f64 = 0.0;
        for (g, c) in [got.r(), got.g(), got.b()].into_iter().zip(colour) {
            let d = (g as f64 - c * i).abs();
            worst = worst.max(d);
            sum += d;
        }
        max = max.max(worst);
        over_one += (worst > 1.0) as u32;
        count += 1;
    }
    Ok(Error::Intensity {
        max,
        mean: sum / (3 * count.max(1)) as f64,
        over_one,
        pixels: count,
    })
}

/// Whether face `k` continues face `k − 1`'s facet: a shared edge, the same side, and `k`'s
/// third corner in `k − 1`'s plane within 10⁻³ of its distance (exact maths, the source data).
fn continues(m: &Model, k: usize) -> bool {
    let (Some(prev), Some(face)) = (k.checked_sub(1).map(|p| &m.faces[p]), m.faces.get(k)) else {
        return false;
    };
    let shared: Vec<usize> = face
        .3
        .iter()
        .copied()
        .filter(|i| prev.3.contains(i))
        .collect();
    if shared.len() != 2 {
        return false;
    }
    let normal = |p: &[[f64; 3]; 3]| unit(cross(sub(p[1], p[0]), sub(p[2], p[0])));
    let (n, other) = (normal(&prev.0), normal(&face.0));
    let third = (0..3).find(|&j| !shared.contains(&face.3[j])).unwrap_or(0);
    let d = sub(face.0[third], prev.0[0]);
    dot(n, other) > 0.0 && dot(n, d).abs() <= 1e-3 * dot(d, d).sqrt()
}

/// Hidden lines: the reference's facets as lines, against the drawn ones.
fn lines_error(
    scene: &RefScene,
    pixels: &[reference::Pixel],
    drawn: &[bool],
) -> Result<Error, String> {
    let m = model()?;
    let mut facet = vec![0u32; m.faces.len()];
    for k in 0..m.faces.len() {
        facet[k] = if continues(&m, k) {
            facet[k - 1]
        } else {
            k as u32
        };
    }
    let ids: Vec<u32> = pixels
        .iter()
        .map(|p| {
            p.face
                .map_or(0, |f| facet[scene.faces[f].number as usize] + 1)
        })
        .collect();
    let n = SIZE as i64;
    let at = |v: &[u32], x: i64, y: i64| {
        ((0..n).contains(&x) && (0..n).contains(&y)).then(|| v[(y * n + x) as usize])
    };
    let reference: Vec<bool> = (0..n * n)
        .map(|k| {
            let (x, y) = (k % n, k / n);
            let id = ids[k as usize];
            id != 0
                && [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
                    .iter()
                    .any(|&(i, j)| at(&ids, i, j).is_some_and(|o| o < id))
        })
        .collect();
    let near = |v: &[bool], k: i64| {
        let (x, y) = (k % n, k / n);
        (y - 1..=y + 1).any(|j| {
            (x - 1..=x + 1)
                .any(|i| (0..n).contains(&i) && (0..n).contains(&j) && v[(j * n + i) as usize])
        })
    };
    let count = |v: &[bool]| v.iter().filter(|&&b| b).count() as u32;
    Ok(Error::Lines {
        reference: count(&reference),
        drawn: count(drawn),
        missing: (0..n * n)
            .filter(|&k| reference[k as usize] && !near(drawn, k))
            .count() as u32,
        extra: (0..n * n)
            .filter(|&k| drawn[k as usize] && !near(&reference, k))
            .count() as u32,
    })
}

/// The section of `docs/presets/presets.md`.
pub fn report(rows: &[Row]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "\n## Smooth shading and hidden lines (mesh1k)\n");
    let _ = writeln!(
        s,
        "The torus at 240 × 240 from the bench's view, without a depth cue, drawn by the \
         scan-line method: smooth shaded (`Shading::Gouraud`, dithered or not; \
         `scanline_for!(N, REQ, gouraud)`) and as a hidden-line drawing (`Shading::Facets` \
         through `lines::HiddenLines`). M4: the bench's `mesh1k-smooth`, `mesh1k-dither` and \
         `mesh1k-lines` frames (instructions, not cycles; the flat frame is `mesh1k`); RAM: \
         their `ram=` (the renderer at the frame's requirements, the hidden-line sink's rows \
         included). Error against an exact f64 reference: Gouraud's channels at every pixel \
         showing the reference's FULL face, against its colour times the intensity \
         interpolated in screen space between its vertices lit in f64 (dithering trades a \
         pixel's error for its 4 × 4 block's: the block averages the exact value); hidden \
         lines against the same rule applied to the reference's facets, a pixel of slack \
         either way.\n"
    );
    let _ = writeln!(
        s,
        "| drawing | format | M4 instr./frame | host µs/frame | RAM (B) | error against the f64 reference |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for r in rows {
        let err = match r.error {
            Error::Intensity {
                max,
                mean,
                over_one,
                pixels,
            } => format!(
                "intensity max {max:.2} / mean {mean:.3} LSB; {over_one} of {pixels} pixels over 1 LSB"
            ),
            Error::Lines {
                reference,
                drawn,
                missing,
                extra,
            } => format!(
                "line pixels {drawn} drawn / {reference} in the reference; missing {missing}, extra {extra}"
            ),
        };
        let _ = writeln!(
            s,
            "| {} (`{}`) | {} | {} | {:.0} | {} | {} |",
            r.name,
            r.scene,
            r.format,
            r.m4.map_or("—".into(), |(i, _)| format!("{:.2} M", i as f64 / 1e6)),
            r.host.as_secs_f64() * 1e6,
            r.m4.map_or("—".into(), |(_, b)| b.to_string()),
            err
        );
    }
    s
}
