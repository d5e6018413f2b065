//! The exact reference: the preset scenes rebuilt in `f64` with exact trigonometry and no
//! snapping, each pixel centre classified per face with the dEQP three-state rule.
//!
//! Geometry follows `crates/zrow-scenes` (objects, transforms, camera, light) and
//! `crates/zrow/src/geometry.rs` (view transform, back-face test on the first vertex, Lambert
//! shading, projection, depth mapping) step by step, in `f64` (`std`'s correctly rounded
//! trigonometry). A pixel is FULL for a face when its centre lies inside the face by more than
//! `tolerance` pixels, NONE when outside by more than that, PARTIAL otherwise: snapping moves
//! each vertex by at most half a sub-pixel per axis, so an edge by at most 2^-S·√2/2 px,
//! and `tolerance` = 2^-S px covers it with margin (dEQP's "each vertex rounded both ways").

use zrow::geometry::DEPTH_RANGE;
use zrow::shading::DepthCue;
use zrow::{Face, Mesh};
use zrow_scenes::{EYE, FOV_Y, LIGHT, MODEL_TURN, NEAR_FAR};

/// A 3 × 4 affine transform in `f64`.
#[derive(Clone, Copy, Debug)]
pub struct Aff(pub [[f64; 4]; 3]);

impl Aff {
    /// `zrow::Affine::rotate_yx_translate` with exact sines and cosines.
    pub fn rotate_yx_translate(yaw: f64, pitch: f64, t: [f64; 3]) -> Aff {
        let (sy, cy) = yaw.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        Aff([
            [cy, 0.0, sy, t[0]],
            [sp * sy, cp, -sp * cy, t[1]],
            [-cp * sy, sp, cp * cy, t[2]],
        ])
    }
    /// `self ∘ o`.
    pub fn then_after(&self, o: &Aff) -> Aff {
        let mut m = [[0.0; 4]; 3];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, e) in row.iter_mut().enumerate() {
                *e = (0..3).map(|k| self.0[r][k] * o.0[k][c]).sum::<f64>()
                    + if c == 3 { self.0[r][3] } else { 0.0 };
            }
        }
        Aff(m)
    }
    /// Applies to a point.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let r = |k: usize| {
            self.0[k][0] * p[0] + self.0[k][1] * p[1] + self.0[k][2] * p[2] + self.0[k][3]
        };
        [r(0), r(1), r(2)]
    }
    /// Applies the linear part.
    pub fn apply_dir(&self, p: [f64; 3]) -> [f64; 3] {
        let r = |k: usize| self.0[k][0] * p[0] + self.0[k][1] * p[1] + self.0[k][2] * p[2];
        [r(0), r(1), r(2)]
    }
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(crate) fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// The camera of `zrow_scenes::camera_with`, exactly: view transform, focal length, near, far.
pub struct Cam {
    /// World → view.
    pub view: Aff,
    /// cot(fov/2).
    pub focal: f64,
    /// Near plane.
    pub near: f64,
    /// Far plane.
    pub far: f64,
}

impl Cam {
    /// The model scenes' camera.
    pub fn scenes() -> Cam {
        Self::look_at(
            EYE.map(f64::from),
            [0.0; 3],
            FOV_Y as f64,
            NEAR_FAR.map(f64::from),
        )
    }
    /// A look-at camera, y up.
    pub fn look_at(eye: [f64; 3], target: [f64; 3], fov: f64, nf: [f64; 2]) -> Cam {
        let back = unit(sub(eye, target));
        let right = unit(cross([0.0, 1.0, 0.0], back));
        let up = cross(back, right);
        let row = |a: [f64; 3]| [a[0], a[1], a[2], -dot(a, eye)];
        Cam {
            view: Aff([row(right), row(up), row(back)]),
            focal: 1.0 / (fov * 0.5).tan(),
            near: nf[0],
            far: nf[1],
        }
    }
}

/// One front face on screen.
pub struct ScreenFace {
    /// Face number in the scene (objects in order, faces in order), as the core counts.
    pub number: u32,
    /// Vertices in pixels.
    pub xy: Vec<[f64; 2]>,
    /// 1/w as an affine function of the pixel position: `a·x + b·y + c`.
    pub inv_w: [f64; 3],
    /// Lit colour channels before rounding (r 0..31, g 0..63, b 0..31).
    pub lit: [f64; 3],
}

/// A scene as the reference sees it.
pub struct RefScene {
    /// Front faces.
    pub faces: Vec<ScreenFace>,
    /// Camera near and far.
    pub near_far: [f64; 2],
    /// Frame size.
    pub size: usize,
}

/// An object: a mesh (in `f32`, the scenes' source data) and its transform.
pub struct Obj<'a> {
    /// Mesh.
    pub mesh: Mesh<'a, f32>,
    /// Model → world.
    pub transform: Aff,
}

/// The objects of a preset scene (`zrow_scenes::PRESET_SCENES`) at angle 0.
pub fn objects(name: &str) -> Option<Vec<Obj<'static>>> {
    let mesh = |n: &str| zrow_scenes::mesh::<f32>(n);
    let t = |yaw: f64, pitch: f64, t: [f64; 3]| Aff::rotate_yx_translate(yaw, pitch, t);
    Some(match name {
        "cube" | "mesh1k" => vec![Obj {
            mesh: mesh(name)?,
            transform: t(MODEL_TURN.0 as f64, MODEL_TURN.1 as f64, [0.0; 3]),
        }],
        // zrow_scenes' `interlocked` at angle 0.
        "interlocked" => {
            let g = zrow_scenes::INTERLOCKED_SCALE as f64;
            let grow = Aff([[g, 0.0, 0.0, 0.0], [0.0, g, 0.0, 0.0], [0.0, 0.0, g, 0.0]]);
            let spin = grow.then_after(&t(0.0, 0.3, [0.0; 3]));
            vec![
                Obj {
                    mesh: mesh("ring-warm")?,
                    transform: spin.then_after(&t(0.0, 0.0, [-0.35, 0.0, 0.0])),
                },
                Obj {
                    mesh: mesh("ring-cool")?,
                    transform: spin.then_after(&t(
                        0.0,
                        std::f64::consts::FRAC_PI_2,
                        [0.35, 0.0, 0.0],
                    )),
                },
                Obj {
                    mesh: mesh("cube-plain")?,
                    transform: spin.then_after(&t(0.0, 0.6, [0.0; 3])),
                },
            ]
        }
        _ => return None,
    })
}

fn channels(f: &Face<'_, u16>) -> [f64; 3] {
    use embedded_graphics_core::pixelcolor::RgbColor;
    [f.color.r() as f64, f.color.g() as f64, f.color.b() as f64]
}

/// Projects the objects' front faces for a `size`² frame (geometry.rs, exactly).
pub fn build(objs: &[Obj<'_>], cam: &Cam, light: ([f64; 3], f64), size: usize) -> RefScene {
    let (w_px, h_px) = (size as f64, size as f64);
    let (sx, sy) = (cam.focal * h_px / w_px, cam.focal);
    let (cx, cy) = (w_px * 0.5, h_px * 0.5);
    let l = unit(cam.view.apply_dir(light.0));
    let mut faces = vec![];
    let mut number = 0u32;
    for o in objs {
        let mv = cam.view.then_after(&o.transform);
        for face in o.mesh.faces {
            let this = number;
            number += 1;
            let v: Vec<[f64; 3]> = face
                .indices
                .iter()
                .map(|&i| {
                    let p = o
                        .mesh
                        .vertices
                        .get(i as usize)
                        .expect("a standard scene's index");
                    mv.apply([p.x as f64, p.y as f64, p.z as f64])
                })
                .collect();
            let n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
            if dot(n, v[0]) >= 0.0 {
                continue; // back face (backface.rs: normal · view ≥ 0)
            }
            assert!(
                v.iter().all(|p| -p[2] > cam.near),
                "preset scenes lie beyond the near plane"
            );
            let lambert = (dot(n, l) / dot(n, n).sqrt()).max(0.0);
            let intensity = light.1 + (1.0 - light.1) * lambert;
            let lit = channels(&face).map(|c| c * intensity);
            let xy: Vec<[f64; 2]> = v
                .iter()
                .map(|p| {
                    let w = -p[2];
                    [cx + p[0] * sx / w * cx, cy - p[1] * sy / w * cy]
                })
                .collect();
            // 1/w is affine in screen space: the plane through three vertices.
            let q: Vec<[f64; 3]> = (0..3)
                .map(|k| [xy[k][0], xy[k][1], -1.0 / v[k][2]])
                .collect();
            let nrm = cross(sub(q[1], q[0]), sub(q[2], q[0]));
            let (a, b) = (-nrm[0] / nrm[2], -nrm[1] / nrm[2]);
            let c = q[0][2] - a * q[0][0] - b * q[0][1];
            faces.push(ScreenFace {
                number: this,
                xy,
                inv_w: [a, b, c],
                lit,
            });
        }
    }
    RefScene {
        faces,
        near_far: [cam.near, cam.far],
        size,
    }
}

/// The dEQP state of a pixel for one face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum State {
    /// Outside by more than the tolerance.
    None,
    /// Within the tolerance of an edge: either answer is right.
    Partial,
    /// Inside by more than the tolerance.
    Full,
}

impl ScreenFace {
    /// Signed distance of `p` inside the face (positive inside), in pixels.
    pub fn inside_by(&self, p: [f64; 2]) -> f64 {
        let n = self.xy.len();
        let area: f64 = (0..n)
            .map(|k| {
                let (a, b) = (self.xy[k], self.xy[(k + 1) % n]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum();
        let s = area.signum();
        (0..n)
            .map(|k| {
                let (a, b) = (self.xy[k], self.xy[(k + 1) % n]);
                let e = [b[0] - a[0], b[1] - a[1]];
                s * (e[0] * (p[1] - a[1]) - e[1] * (p[0] - a[0])) / e[0].hypot(e[1])
            })
            .fold(f64::INFINITY, f64::min)
    }
    /// The state of pixel (i, j).
    pub fn state(&self, i: usize, j: usize, tolerance: f64) -> State {
        let d = self.inside_by([i as f64 + 0.5, j as f64 + 0.5]);
        if d > tolerance {
            State::Full
        } else if d < -tolerance {
            State::None
        } else {
            State::Partial
        }
    }
    /// View distance at pixel (i, j)'s centre.
    pub fn w(&self, i: usize, j: usize) -> f64 {
        let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
        1.0 / (self.inv_w[0] * x + self.inv_w[1] * y + self.inv_w[2])
    }
}

/// The reference at one pixel.
#[derive(Clone, Copy, Debug)]
pub struct Pixel {
    /// The nearest face whose polygon contains the centre (index into `faces`), if any.
    pub face: Option<usize>,
    /// Its state here.
    pub state: State,
    /// The best state of any face here (the union's coverage).
    pub union: State,
    /// Its view distance here.
    pub w: f64,
}

/// Classifies every pixel.
pub fn pixels(scene: &RefScene, tolerance: f64) -> Vec<Pixel> {
    let n = scene.size;
    let mut out = vec![
        Pixel {
            face: None,
            state: State::None,
            union: State::None,
            w: f64::INFINITY,
        };
        n * n
    ];
    for (k, f) in scene.faces.iter().enumerate() {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in &f.xy {
            (x0, x1, y0, y1) = (x0.min(p[0]), x1.max(p[0]), y0.min(p[1]), y1.max(p[1]));
        }
        let clampi = |v: f64| (v.max(0.0) as usize).min(n);
        for j in clampi(y0 - 2.0)..clampi(y1 + 2.0) {
            for i in clampi(x0 - 2.0)..clampi(x1 + 2.0) {
                let st = f.state(i, j, tolerance);
                let px = &mut out[j * n + i];
                px.union = px.union.max(st);
                if f.inside_by([i as f64 + 0.5, j as f64 + 0.5]) >= 0.0 {
                    let w = f.w(i, j);
                    if w < px.w {
                        (px.face, px.state, px.w) = (Some(k), st, w);
                    }
                }
            }
        }
    }
    out
}

/// The stored depth of view distance `w` under a depth mapping (geometry.rs).
pub fn depth_of(w: f64, near_far: [f64; 2], linear_w: bool) -> f64 {
    let [n, f] = near_far;
    let r = DEPTH_RANGE as f64;
    if linear_w {
        r * (w - n) / (f - n)
    } else {
        r * f / (f - n) * (1.0 - n / w)
    }
}

/// The depth-cue factor at `w` (shading.rs, exactly).
pub fn cue(c: &DepthCue, w: f64) -> f64 {
    let t = ((w - c.near as f64) / (c.far as f64 - c.near as f64)).clamp(0.0, 1.0);
    1.0 - (1.0 - c.floor as f64) * t
}

/// The scenes' light in `f64`.
pub fn light() -> ([f64; 3], f64) {
    (LIGHT.0.map(f64::from), LIGHT.1 as f64)
}
