//! What a scene needs: the capacities to build a renderer with, and the RAM that costs.
//!
//! "Model only what the scene requires": run this on the host (or once at start-up) for the
//! views you will draw, then size [`crate::Scanline`]'s const parameters from it.

use crate::error::Error;
use crate::number::Scalar;
use crate::raster::{setup, Config};
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
    /// polygons with more than [`crate::scene::INDEXED_CORNERS`] corners.
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

/// Measures what `scene` needs under `cfg`. `rows` is scratch, at least `cfg.height + 1` long
/// (one counter per row); shorter scratch is [`Error::BadConfig`].
///
/// ```
/// use zrow::{requirements, Config, Face, Mesh, ScreenScene, Vec3};
/// use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
/// let v = [Vec3::new(1.0f32, 1.0, 1.0), Vec3::new(9.0, 1.0, 1.0), Vec3::new(1.0, 9.0, 1.0)];
/// let faces = [Face { indices: &[0u16, 1, 2], color: Rgb565::RED, alpha: 255 }];
/// let scene = ScreenScene { mesh: Mesh::new(&v, &faces) };
/// let mut rows = [0u32; 17];
/// let req = requirements(&scene, &Config::screen(16, 16), &mut rows).unwrap();
/// assert_eq!((req.polygons, req.edges, req.active_polygons), (1, 2, 1));
/// ```
pub fn requirements<N: Scalar>(
    scene: &(impl Scene<N> + ?Sized),
    cfg: &Config,
    rows: &mut [u32],
) -> Result<Requirements, Error> {
    cfg.validate(usize::MAX)?;
    let h = cfg.height as usize;
    let rows = rows.get_mut(..=h).ok_or(Error::BadConfig)?;
    rows.fill(0);
    let mut req = Requirements {
        width: cfg.width,
        ..Requirements::default()
    };
    let mut buf = VertexBuffer::new(&mut []);
    scene.polygons(cfg, &mut buf, &mut |poly| {
        if let Some(sp) = setup(&poly.to_raster(), cfg)? {
            req.polygons += 1;
            req.edges += sp.edges.len() as u32;
            let (a, b) = (sp.first_row as usize, sp.last_row as usize + 1);
            rows[a] = rows[a].wrapping_add(1);
            rows[b] = rows[b].wrapping_sub(1);
        }
        Ok(())
    })?;
    // What a vertex buffer with room would have held (geometry counts it without one).
    req.vertices = buf.needed() as u32;
    let mut running = 0u32;
    for r in rows.iter() {
        running = running.wrapping_add(*r);
        req.active_polygons = req.active_polygons.max(running);
    }
    Ok(req)
}
