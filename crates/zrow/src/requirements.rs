//! What a scene needs: the capacities to build a renderer with, and the RAM that costs.
//!
//! "Model only what the scene requires": run this on the host (or once at start-up) for the
//! views you will draw, then size [`crate::Scanline`]'s const parameters from it.

use crate::error::Error;
use crate::number::Scalar;
use crate::raster::{setup_into, Config, RasterVertex, SetupPolygon};
use crate::scene::{Scene, VertexBuffer};

/// The capacities a scene needs under one configuration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Requirements {
    /// Polygons after culling and clipping that touch the screen (polygon table).
    pub polygons: u32,
    /// Edges that cross a sample row on screen (edge table).
    pub edges: u32,
    /// Vertex slots of the frame's vertex buffer (the scan-line method's vertex capacity): one
    /// per vertex of every object's mesh, plus the vertices clipping makes and the runs of
    /// polygons with more than [`crate::scene::INDEXED_CORNERS`] corners; 0 for a scene that
    /// lends its vertices ([`crate::SnappedScene`]).
    pub vertices: u32,
    /// Most polygons crossing one row (active list).
    pub active_polygons: u32,
    /// Row width in pixels.
    pub width: u16,
}

impl Requirements {
    /// Most active edges in one row: each active convex polygon has exactly two.
    pub fn active_edges(&self) -> u32 {
        2 * self.active_polygons
    }
    /// Each capacity raised by `percent` %, rounded up, and by at least 1 (the width is
    /// kept): room for the views an animation shows between the ones that were measured.
    ///
    /// ```
    /// let req = zrow::Requirements { polygons: 462, edges: 1316, vertices: 500, active_polygons: 67, width: 240 };
    /// let sized = req.with_margin(10);
    /// assert_eq!((sized.polygons, sized.vertices, sized.active_polygons), (509, 550, 74));
    /// // At least one more; never past u32::MAX.
    /// let edge = zrow::Requirements { polygons: 0, edges: u32::MAX, ..req }.with_margin(10);
    /// assert_eq!((edge.polygons, edge.edges, edge.width), (1, u32::MAX, 240));
    /// ```
    pub const fn with_margin(self, percent: u32) -> Self {
        const fn up(x: u32, percent: u32) -> u32 {
            let extra = (x as u64 * percent as u64).div_ceil(100);
            let extra = if extra == 0 { 1 } else { extra };
            let v = x as u64 + extra;
            if v > u32::MAX as u64 {
                u32::MAX
            } else {
                v as u32
            }
        }
        Requirements {
            polygons: up(self.polygons, percent),
            edges: up(self.edges, percent),
            vertices: up(self.vertices, percent),
            active_polygons: up(self.active_polygons, percent),
            width: self.width,
        }
    }

    /// The larger of two requirements, field by field (for a set of views).
    pub fn max(self, o: Self) -> Self {
        Requirements {
            polygons: self.polygons.max(o.polygons),
            edges: self.edges.max(o.edges),
            vertices: self.vertices.max(o.vertices),
            active_polygons: self.active_polygons.max(o.active_polygons),
            width: self.width.max(o.width),
        }
    }
}

/// Rows counted per pass of [`requirements`] (its counters live on the stack: 1 KiB).
const ROWS_PER_PASS: usize = 256;

/// Measures what `scene` needs under `cfg`, without allocating or asking for scratch: the
/// scene's geometry runs once for frames up to 256 rows tall, once more per further 256 rows.
///
/// For an animation, take the [`Requirements::max`] of the views it will show, add a margin
/// for the views between them ([`Requirements::with_margin`]), and size the renderer from the
/// result with [`scanline_for!`](crate::scanline_for), which takes each capacity from its own
/// field. A converter samples orientations the same way. Measured on the host, the figures go
/// into a `const` for the firmware:
///
/// ```
/// use zrow::{requirements, Affine, Camera, Config, Face, Light, Mesh, ModelScene, Object};
/// use zrow::{scanline_for, Requirements, Scalar, Vec3, Q16_16};
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
/// let q = |x, y, z| Vec3::<Q16_16>::from_f32([x, y, z]).unwrap();
/// let v = [q(-1.0, -1.0, 0.0), q(1.0, -1.0, 0.0), q(0.0, 1.0, 0.0)];
/// let faces = [Face::new(&[0, 1, 2], Rgb565::RED)];
/// let mesh = Mesh::new(&v, &faces);
/// let projection = zrow::Projection::<Q16_16>::perspective(1.0, 0.1, 20.0).unwrap();
/// let camera = Camera::look_at([0.0, 0.0, 4.0], [0.0; 3], [0.0, 1.0, 0.0], projection).unwrap();
/// let light = Light {
///     direction: Vec3::from_f32([0.0, 0.0, 1.0]).unwrap(),
///     ambient: Q16_16::from_f32(0.2).unwrap(),
/// };
/// let cfg = Config::model(64, 64);
/// // Every frame of a turn, one per 0.1 rad.
/// let mut worst = Requirements::default();
/// for k in 0..63 {
///     let transform = Affine::rotate_yx_translate(0.1 * k as f32, 0.0, [0.0; 3]).unwrap();
///     let objects = [Object { mesh: &mesh, transform }];
///     let scene = ModelScene { objects: &objects, camera, light };
///     worst = worst.max(requirements(&scene, &cfg).unwrap());
/// }
/// let sized = worst.with_margin(10);
/// assert!(sized.polygons > worst.polygons && sized.vertices >= 3);
///
/// // What the host printed, as a constant in the firmware: each capacity from its own field.
/// const REQ: Requirements = Requirements {
///     polygons: 2, edges: 4, vertices: 4, active_polygons: 2, width: 64,
/// };
/// type Renderer = scanline_for!(Q16_16, REQ);
/// let renderer = Renderer::new();
/// assert_eq!(Renderer::RAM_BYTES, core::mem::size_of_val(&renderer));
/// ```
///
/// ```
/// use zrow::{requirements, Config, Face, Mesh, ScreenScene, Vec3};
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
/// let v = [Vec3::new(1.0f32, 1.0, 1.0), Vec3::new(9.0, 1.0, 1.0), Vec3::new(1.0, 9.0, 1.0)];
/// let faces = [Face { indices: &[0u16, 1, 2], color: Rgb565::RED, alpha: 255 }];
/// let scene = ScreenScene { mesh: Mesh::new(&v, &faces) };
/// let req = requirements(&scene, &Config::screen(16, 16)).unwrap();
/// assert_eq!((req.polygons, req.edges, req.active_polygons), (1, 2, 1));
/// ```
// Out of line: a sizing call, not a frame's work; inlined, its row passes would weigh on the
// inlining of whatever frame code shares its caller.
#[inline(never)]
pub fn requirements<N: Scalar>(
    scene: &(impl Scene<N> + ?Sized),
    cfg: &Config,
) -> Result<Requirements, Error> {
    requirements_with(scene, cfg, &mut [])
}

/// [`requirements`] with a vertex buffer of `slots` for the geometry, as a renderer lends it:
/// with room for the scene's vertices ([`Requirements::vertices`]) every shared vertex is
/// transformed and projected once per pass instead of once per face corner, which makes
/// measuring many views of a large mesh several times faster (a converter's sampling). The
/// result is the same whatever the number of slots.
///
/// ```
/// use zrow::{requirements, requirements_with, Config, Face, Mesh, ScreenScene, Vec3};
/// use zrow::raster::RasterVertex;
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
/// let v = [Vec3::new(1.0f32, 1.0, 1.0), Vec3::new(9.0, 1.0, 1.0), Vec3::new(1.0, 9.0, 1.0)];
/// let faces = [Face { indices: &[0u16, 1, 2], color: Rgb565::RED, alpha: 255 }];
/// let scene = ScreenScene { mesh: Mesh::new(&v, &faces) };
/// let cfg = Config::screen(16, 16);
/// let mut slots = [RasterVertex::default(); 3];
/// assert_eq!(requirements_with(&scene, &cfg, &mut slots), requirements(&scene, &cfg));
/// ```
#[inline(never)]
pub fn requirements_with<N: Scalar>(
    scene: &(impl Scene<N> + ?Sized),
    cfg: &Config,
    slots: &mut [RasterVertex<N>],
) -> Result<Requirements, Error> {
    cfg.validate(usize::MAX)?;
    let h = cfg.height as usize;
    let mut req = Requirements {
        width: cfg.width,
        ..Requirements::default()
    };
    // Each pass: a difference array over its rows (+1 where a polygon starts, −1 after it
    // ends), with the polygons already open at its first row counted apart.
    let mut rows = [0u32; ROWS_PER_PASS + 1];
    let mut base = 0;
    while base < h {
        let len = (h - base).min(ROWS_PER_PASS);
        rows.fill(0);
        let mut open = 0u32;
        let first_pass = base == 0;
        let mut buf = VertexBuffer::new(&mut *slots);
        let mut sp = SetupPolygon::empty();
        scene.polygons(cfg, &mut buf, &mut |poly| {
            if setup_into(&poly.to_raster()?, cfg, &mut sp)? {
                if first_pass {
                    req.polygons += 1;
                    req.edges += sp.edges.len() as u32;
                }
                // Rows a..b, and this pass's rows base..base + len.
                let (a, b) = (sp.first_row as usize, sp.last_row as usize + 1);
                if a < base + len && b > base {
                    if a < base {
                        open += 1;
                    } else {
                        rows[a - base] = rows[a - base].wrapping_add(1);
                    }
                    if b < base + len {
                        rows[b - base] = rows[b - base].wrapping_sub(1);
                    }
                }
            }
            Ok(())
        })?;
        if first_pass {
            // What a vertex buffer with room would have held (geometry counts it without one).
            req.vertices = buf.needed() as u32;
        }
        let mut running = open;
        for r in &rows[..len] {
            running = running.wrapping_add(*r);
            req.active_polygons = req.active_polygons.max(running);
        }
        base += len;
    }
    Ok(req)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Face, Mesh, ScreenScene, Vec3};
    use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};

    /// Tall frames are counted a pass of rows at a time: a polygon open across a pass boundary
    /// still counts in the next pass, and one that starts in a later pass is found there.
    #[test]
    fn passes_of_rows_count_what_one_pass_would() {
        // Thin triangles side by side over a 1,200-row frame: rows 10..700; 240..=255, which
        // ends just before the second pass; 300..400 and 350..360, where three are open (the
        // first is open across the boundary); and 1150..1190.
        let tri = |x: f32, y0: f32, y1: f32| {
            [
                Vec3::new(x, y0, 1.0),
                Vec3::new(x + 4.0, y0, 1.0),
                Vec3::new(x, y1, 1.0),
            ]
        };
        let mut v = [Vec3::new(0.0f32, 0.0, 0.0); 15];
        for (k, t) in [
            tri(1.0, 10.0, 700.0),
            tri(8.0, 240.0, 256.0),
            tri(16.0, 300.0, 400.0),
            tri(22.0, 350.0, 360.0),
            tri(28.0, 1150.0, 1190.0),
        ]
        .iter()
        .enumerate()
        {
            v[3 * k..3 * k + 3].copy_from_slice(t);
        }
        let idx: [[u16; 3]; 5] = [[0, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11], [12, 13, 14]];
        let faces = idx.each_ref().map(|i| Face::new(i, Rgb565::RED));
        let scene = ScreenScene {
            mesh: Mesh::new(&v, &faces),
        };
        let req = requirements(&scene, &Config::screen(32, 1200)).unwrap();
        assert_eq!((req.polygons, req.edges, req.active_polygons), (5, 10, 3));
        // Only the first two touch a 250-row frame, and they overlap.
        let req = requirements(&scene, &Config::screen(32, 250)).unwrap();
        assert_eq!((req.polygons, req.active_polygons), (2, 2));
    }
}
