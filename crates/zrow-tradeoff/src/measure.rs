//! The measurements: errors of a preset's frame against the reference, watertightness on a
//! fan, and the depth-resolution threshold.

use crate::reference::{self, Cam, Pixel, RefScene, State};
use crate::render::{self, Build, Rendered};
use embedded_graphics_core::pixelcolor::RgbColor;
use zrow::geometry::DepthMapping;
use zrow::presets::{DepthStore, Format, Preset};
use zrow::shading::Shading;
use zrow::{
    Camera, Config, Face, Light, Mesh, ModelScene, Object, Scalar, Scene, ScreenScene, Vec3,
};
use zrow_scenes::{FOV_Y, PRESET_CUE};

/// Errors of one frame.
#[derive(Clone, Copy, Debug, Default)]
pub struct Errors {
    /// FULL pixels (some face covers the centre unambiguously) left as background.
    pub missing: u32,
    /// NONE pixels (no face near the centre) drawn.
    pub extra: u32,
    /// Pixels where the nearest face is FULL, another face is drawn, and that face is not
    /// PARTIAL there.
    pub wrong_surface: u32,
    /// Largest depth error at right-surface FULL pixels, in the depth format's LSB.
    pub depth_max_lsb: f64,
    /// Mean of the same.
    pub depth_mean_lsb: f64,
    /// Largest intensity error (any channel, in that channel's LSB) at right-surface FULL pixels.
    pub intensity_max: f64,
    /// Mean of the same (over pixels and channels).
    pub intensity_mean: f64,
    /// Pixels whose intensity is off by more than 2 LSB in some channel.
    pub intensity_bad: u32,
}

impl Errors {
    /// Pixels in error of any kind (for the plot).
    pub fn pixels(&self) -> u32 {
        self.missing + self.extra + self.wrong_surface + self.intensity_bad
    }
}

/// The depth LSB of a format at stored depth `z`.
pub fn depth_lsb(format: Format, z: f64) -> f64 {
    match format {
        Format::Q16_16 => 2f64.powi(-16),
        Format::Q24_8 => 2f64.powi(-8),
        Format::F32 => 2f64.powi((z.max(f64::MIN_POSITIVE)).log2().floor() as i32 - 23),
    }
}

/// Compares a preset's frame with the reference.
pub fn errors(p: &Preset, scene: &RefScene, refp: &[Pixel], got: &Rendered) -> Errors {
    let n = scene.size;
    let tol = 2f64.powi(-(p.subpixel_bits as i32));
    let mut e = Errors::default();
    let (mut dsum, mut isum, mut count) = (0.0, 0.0, 0u64);
    let by_number = |num: u32| scene.faces.iter().position(|f| f.number == num);
    for j in 0..n {
        for i in 0..n {
            let k = j * n + i;
            let (r, id) = (refp[k], got.ids[k]);
            match (r.union, id) {
                (State::Full, None) => e.missing += 1,
                (State::None, Some(_)) => e.extra += 1,
                _ => {}
            }
            let (Some(rf), Some(gnum)) = (r.face, id) else {
                continue;
            };
            if r.state != State::Full {
                continue;
            }
            let face = &scene.faces[rf];
            if face.number != gnum {
                let drawn = by_number(gnum).map(|g| scene.faces[g].state(i, j, tol));
                if drawn != Some(State::Partial) {
                    e.wrong_surface += 1;
                }
                continue;
            }
            // Right surface: depth and intensity.
            let z_exact =
                reference::depth_of(r.w, scene.near_far, p.depth == DepthMapping::LinearW);
            let z = got.frame.depth[k];
            let lsb = depth_lsb(p.format, z_exact);
            let dz = ((z - z_exact) / lsb).abs();
            e.depth_max_lsb = e.depth_max_lsb.max(dz);
            dsum += dz;
            let c = reference::cue(&PRESET_CUE, r.w);
            let px = got.frame.colour[k];
            let gotc = [px.r() as f64, px.g() as f64, px.b() as f64];
            let mut worst: f64 = 0.0;
            for (g, lit) in gotc.iter().zip(face.lit) {
                let d = (g - lit * c).abs();
                worst = worst.max(d);
                isum += d;
            }
            e.intensity_max = e.intensity_max.max(worst);
            if worst > 2.0 {
                e.intensity_bad += 1;
            }
            count += 1;
        }
    }
    if count > 0 {
        e.depth_mean_lsb = dsum / count as f64;
        e.intensity_mean = isum / (3 * count) as f64;
    }
    e
}

/// A simple deterministic generator (xorshift64*).
pub struct Rng(pub u64);
impl Rng {
    /// Uniform in `0..1`.
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// One triangle of a fan, alone, in screen space.
struct FanTriangle {
    tri: [[f64; 2]; 3],
}

impl Build for FanTriangle {
    fn build<N: Scalar>(&self, f: &mut dyn FnMut(&dyn Scene<N>)) {
        let v: Vec<Vec3<N>> = self
            .tri
            .iter()
            .filter_map(|p| Vec3::from_f32([p[0] as f32, p[1] as f32, 1.0]))
            .collect();
        let faces = [Face::new(
            &[0, 1, 2],
            embedded_graphics_core::pixelcolor::Rgb565::WHITE,
        )];
        f(&ScreenScene {
            mesh: Mesh::new(&v, &faces),
        });
    }
}

/// Watertightness (`docs/extremes.md` item 4): a fan of `n` triangles round a centre, perimeter steps
/// random, each triangle drawn alone. Returns (pixels drawn twice or more, FULL pixels of the
/// fan not drawn, NONE pixels drawn).
pub fn fan(p: &Preset, n: usize, seed: u64) -> Result<(u32, u32, u32), String> {
    const S: usize = 64;
    let mut rng = Rng(seed);
    let c = [31.3 + rng.next(), 32.1 + rng.next()];
    let mut angles: Vec<f64> = (0..n).map(|_| 0.2 + rng.next()).collect();
    let total: f64 = angles.iter().sum();
    let mut a = 0.0;
    for x in angles.iter_mut() {
        a += *x / total * std::f64::consts::TAU;
        *x = a;
    }
    let rim: Vec<[f64; 2]> = angles
        .iter()
        .map(|t| [c[0] + 27.0 * t.cos(), c[1] + 27.0 * t.sin()])
        .collect();
    let mut count = vec![0u32; S * S];
    let mut cfg = Config::screen(S as u16, S as u16);
    cfg.subpixel_bits = p.subpixel_bits;
    for k in 0..n {
        let tri = [c, rim[k], rim[(k + 1) % n]];
        let fr = render::run_ids(p, &FanTriangle { tri }, &cfg, S)?;
        for (cnt, px) in count.iter_mut().zip(&fr.colour) {
            *cnt += render::face_of(*px).is_some() as u32;
        }
    }
    let poly = reference::ScreenFace {
        number: 0,
        xy: rim.clone(),
        inv_w: [0.0, 0.0, 1.0],
        lit: [0.0; 3],
    };
    let tol = 2f64.powi(-(p.subpixel_bits as i32));
    let (mut twice, mut holes, mut extra) = (0, 0, 0);
    for j in 0..S {
        for i in 0..S {
            let k = count[j * S + i];
            twice += (k >= 2) as u32;
            match poly.state(i, j, tol) {
                State::Full => holes += (k == 0) as u32,
                State::None => extra += (k > 0) as u32,
                State::Partial => {}
            }
        }
    }
    Ok((twice, holes, extra))
}

/// Two parallel squares facing the eye, `delta` apart (the far one first in the scene, so it
/// wins ties), and a small far square that stretches the frame's depth range to w = 15.
struct Planes {
    delta: f64,
    preset: Preset,
}

/// Depth of the near square.
pub const PLANE_W: f64 = 5.0;
/// Depth of the small far square.
pub const FAR_W: f64 = 15.0;

impl Build for Planes {
    fn build<N: Scalar>(&self, f: &mut dyn FnMut(&dyn Scene<N>)) {
        let sq = |h: f64, w: f64, x0: f64, y0: f64| {
            [
                [x0 - h, y0 - h, -w],
                [x0 + h, y0 - h, -w],
                [x0 + h, y0 + h, -w],
                [x0 - h, y0 + h, -w],
            ]
        };
        let mut pts = vec![];
        pts.extend(sq(2.5, PLANE_W + self.delta, 0.0, 0.0));
        pts.extend(sq(1.5, PLANE_W, 0.0, 0.0));
        pts.extend(sq(0.75, FAR_W, 3.75, 3.75));
        let v: Vec<Vec3<N>> = pts
            .iter()
            .filter_map(|p| Vec3::from_f32([p[0] as f32, p[1] as f32, p[2] as f32]))
            .collect();
        let white = embedded_graphics_core::pixelcolor::Rgb565::WHITE;
        let faces = [
            Face::new(&[0, 1, 2, 3], white),
            Face::new(&[4, 5, 6, 7], white),
            Face::new(&[8, 9, 10, 11], white),
        ];
        let mesh = Mesh::new(&v, &faces);
        let objects = [Object {
            mesh: &mesh,
            transform: zrow::Affine::identity(),
        }];
        let nf = zrow_scenes::NEAR_FAR;
        let Some(projection) = Camera::<N>::perspective_with(self.preset.math, FOV_Y, nf[0], nf[1])
        else {
            return;
        };
        let Some(camera) = Camera::look_at([0.0; 3], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0], projection)
        else {
            return;
        };
        let Some(light) = Vec3::from_f32([0.0, 0.0, 1.0]) else {
            return;
        };
        f(&ModelScene {
            objects: &objects,
            camera,
            light: Light {
                direction: light,
                ambient: N::ONE,
            },
        });
    }
}

/// The depth-resolution threshold (`docs/extremes.md` item 17) of a preset.
pub struct Threshold {
    /// Δw from the format's depth LSB and the mapping's slope at w = [`PLANE_W`].
    pub theory: f64,
    /// The smallest Δ swept above which the near square wins at every pixel it covers.
    pub measured: f64,
    /// The vertex coordinate quantum at w = 5 (fixed formats cannot place a plane closer).
    pub coordinate_lsb: f64,
}

/// Measures the threshold: Δ swept from theory/16 to theory·16 in half-octaves.
pub fn threshold(p: &Preset) -> Result<Threshold, String> {
    let [n, f] = zrow_scenes::NEAR_FAR.map(f64::from);
    let linear = p.depth == DepthMapping::LinearW;
    let z = |w: f64| reference::depth_of(w, [n, f], linear);
    let slope = (z(PLANE_W + 1e-6) - z(PLANE_W - 1e-6)) / 2e-6;
    let lsb = match p.store {
        DepthStore::Row32 => depth_lsb(p.format, z(PLANE_W)),
        // 16 bits over the frame's depth range: the near square to the far one.
        DepthStore::Tile16 => (z(FAR_W) - z(PLANE_W)) / 65535.0,
    };
    let theory = lsb / slope;
    let coordinate_lsb = match p.format {
        Format::Q16_16 => 2f64.powi(-16),
        Format::Q24_8 => 2f64.powi(-8),
        Format::F32 => 2f64.powi(PLANE_W.log2().floor() as i32 - 23),
    };
    let mut cfg = p.config(
        Config::model(render::SIZE as u16, render::SIZE as u16),
        PRESET_CUE,
    );
    cfg.shading = Shading::Flat;
    let cam = Cam::look_at([0.0; 3], [0.0, 0.0, -1.0], FOV_Y as f64, [n, f]);
    let half = 1.5 / PLANE_W * cam.focal * render::SIZE as f64 / 2.0;
    let c = render::SIZE as f64 / 2.0;
    let mut clean_from: Option<f64> = None;
    for k in -8..=8 {
        let delta = theory * 2f64.powf(k as f64 / 2.0);
        let fr = render::run_ids(p, &Planes { delta, preset: *p }, &cfg, render::SIZE)?;
        let s = render::SIZE;
        let mut wrong = 0;
        for j in 0..s {
            for i in 0..s {
                let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                if (x - c).abs() < half - 2.0 && (y - c).abs() < half - 2.0 {
                    wrong += (render::face_of(fr.colour[j * s + i]) != Some(1)) as u32;
                }
            }
        }
        if wrong == 0 {
            clean_from.get_or_insert(delta);
        } else {
            clean_from = None;
        }
    }
    let measured = clean_from.unwrap_or(f64::NAN);
    Ok(Threshold {
        theory,
        measured,
        coordinate_lsb,
    })
}

/// The reference of a preset scene, and its pixels for sub-pixel bits `s`.
pub fn reference_of(name: &str, s: u8) -> Option<(RefScene, Vec<Pixel>)> {
    let objs = reference::objects(name)?;
    let scene = reference::build(&objs, &Cam::scenes(), reference::light(), render::SIZE);
    let px = reference::pixels(&scene, 2f64.powi(-(s as i32)));
    Some((scene, px))
}
