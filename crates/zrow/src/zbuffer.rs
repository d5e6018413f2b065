//! The z-buffer (depth-buffer) method (Catmull 1974; Foley, van Dam, Feiner & Hughes §15.4).
//!
//! The algorithm: two buffers the size of the frame, `depth[x][y]` set to the maximum
//! and `intensity[x][y]` to the background; scan-convert each polygon in any order and, at
//! each pixel it covers, compute its depth z and keep the pixel where `z < depth[x][y]`.
//! Depth moves incrementally: `z − A/C` one pixel right, `z + (A/m + B)/C` one row down.
//!
//! Here every polygon is streamed from the scene straight into the buffers — nothing is
//! stored per polygon — and its rows come from the exact edge walk shared by every method
//! ([`crate::polygons::walk_edges`]); depth starts each span from the polygon's plane and
//! steps by `dzdx`, the same bits as the scan-line method in Q16.16. The test is a strict
//! `<`, and polygons arrive in scene order, so a tie goes to the polygon first in the scene
//! (README, Conventions).
//!
//! A sink that reads depth is told each pixel's depth from the visible polygon's exact plane
//! ([`Scalar::exact_plane`]), kept in a third buffer as pixels are won (the `exact-depth`
//! feature); the test itself is on the stepped depths, as in every method.
//!
//! Rows leave top to bottom, but only once the whole frame is drawn: the method needs the
//! whole frame in RAM, `W·H·(size_of::<N>() + 2)` bytes ([`ZBuffer::RAM_BYTES`]) — 345,600
//! bytes for 240×240 in Q16.16 (576,000 with the `exact-depth` feature's third buffer), more
//! than an STM32F411 has. It is the host reference and
//! the method for small screens; [`crate::tiled`] is its MCU form.

use crate::error::{Error, RenderError, Table};
use crate::method::{FrameStats, Renderer};
use crate::number::Scalar;
use crate::polygons::walk_edges;
#[cfg(feature = "exact-depth")]
use crate::raster::exact_plane;
use crate::raster::{color_at, setup_into, Config, SetupPolygon};
use crate::scene::{Scene, VertexBuffer};
use crate::sink::{Row, RowSink};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};

/// The z-buffer renderer: `W`×`H` depths and colours (the largest frame it can draw).
pub struct ZBuffer<N, const W: usize, const H: usize> {
    depth: [[N; W]; H],
    intensity: [[Rgb565; W]; H],
    /// Each pixel's depth as a sink that reads depth is told it: the visible polygon's exact
    /// plane ([`Scalar::exact_plane`]), written as it wins the test on `depth`
    /// (`exact-depth` feature).
    #[cfg(feature = "exact-depth")]
    exact: [[N; W]; H],
}

impl<N: Scalar, const W: usize, const H: usize> Default for ZBuffer<N, W, H> {
    fn default() -> Self {
        Self::new()
    }
}

impl<N: Scalar, const W: usize, const H: usize> ZBuffer<N, W, H> {
    /// Bytes of RAM the renderer occupies (both buffers).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// An empty renderer (all zero, so a `static` one sits in `.bss`).
    pub const fn new() -> Self {
        ZBuffer {
            depth: [[N::ZERO; W]; H],
            intensity: [[Rgb565::BLACK; W]; H],
            #[cfg(feature = "exact-depth")]
            exact: [[N::ZERO; W]; H],
        }
    }

    /// Renders `scene` and sends its rows, top to bottom, to `sink`.
    pub fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        cfg.validate(W)?;
        if cfg.height as usize > H {
            return Err(Error::Capacity {
                table: Table::FrameBuffer,
                needed: cfg.height as u32,
                capacity: H as u32,
            }
            .into());
        }
        let cue = crate::shading::Cue::for_rows(scene, cfg)?;
        let (w, h) = (cfg.width as usize, cfg.height as usize);
        for row in &mut self.depth[..h] {
            row[..w].fill(N::MAX);
        }
        for row in &mut self.intensity[..h] {
            row[..w].fill(cfg.background);
        }
        #[cfg(feature = "exact-depth")]
        if K::WANTS_DEPTH {
            for row in &mut self.exact[..h] {
                row[..w].fill(N::MAX);
            }
        }
        let mut stats = FrameStats::default();
        let s = cfg.subpixel_bits as u32;
        let (depth, intensity) = (&mut self.depth, &mut self.intensity);
        #[cfg(feature = "exact-depth")]
        let exact = &mut self.exact;
        let mut buf = VertexBuffer::new(&mut []);
        // Set up in place, polygon after polygon (no edge table moved by value).
        let mut sp = SetupPolygon::empty();
        scene.polygons(cfg, &mut buf, &mut |poly| {
            let raster = poly.to_raster()?;
            if !setup_into(&raster, cfg, &mut sp)? {
                return Ok(());
            }
            #[cfg(feature = "exact-depth")]
            let fine = match K::WANTS_DEPTH {
                true => exact_plane(&raster, cfg),
                false => None,
            };
            stats.polygons += 1;
            stats.edges += sp.edges.len() as u32;
            let (first, last) = (sp.first_row as i32, sp.last_row as i32);
            // (In registers for the rows: `sp` is the closure's, behind a reference.)
            let (plane, c) = (sp.plane, sp.color);
            walk_edges(&sp.edges, s, first, last, |y, xl, xr| {
                let (x0, x1) = (xl.max(0), xr.min(w as i32));
                if x0 < x1 {
                    let (zrow, crow) = (&mut depth[y as usize], &mut intensity[y as usize]);
                    let z = plane.at(x0, y);
                    let dzdx = plane.dzdx;
                    #[cfg(feature = "exact-depth")]
                    if let Some(e) = &fine {
                        // A sink that reads depth: each pixel won gets the exact depth too.
                        let erow = &mut exact[y as usize];
                        let color = |x| color_at(c, poly.intensity.as_ref(), x, y);
                        test_span(zrow, crow, z, dzdx, x0, x1, |x| {
                            erow[x as usize] = N::exact_at(e, x, y);
                            color(x)
                        });
                        return true;
                    }
                    // The loop twice: flat, one colour; smooth, the colour at each pixel.
                    match poly.intensity.as_ref() {
                        None => test_span(zrow, crow, z, dzdx, x0, x1, |_| c),
                        Some(i) => {
                            test_span(zrow, crow, z, dzdx, x0, x1, |x| color_at(c, Some(i), x, y))
                        }
                    }
                }
                true
            });
            Ok(())
        })?;
        for y in 0..h {
            crate::shading::Cue::shade_row_if_perspective(
                &cue,
                &self.depth[y][..w],
                &mut self.intensity[y][..w],
            );
            sink.write_row(&Row {
                y: y as u16,
                color: &self.intensity[y][..w],
                #[cfg(feature = "exact-depth")]
                depth: match K::WANTS_DEPTH {
                    true => &self.exact[y][..w],
                    false => &self.depth[y][..w],
                },
                #[cfg(not(feature = "exact-depth"))]
                depth: &self.depth[y][..w],
            })
            .map_err(RenderError::Sink)?;
        }
        Ok(stats)
    }
}

impl<N: Scalar, const W: usize, const H: usize> Renderer<N> for ZBuffer<N, W, H> {
    const NAME: &'static str = "zbuffer";
    const RAM_BYTES: usize = Self::RAM_BYTES;
    fn render<K: RowSink<N>>(
        &mut self,
        scene: &(impl Scene<N> + ?Sized),
        cfg: &Config,
        sink: &mut K,
    ) -> Result<FrameStats, RenderError<K::Error>> {
        ZBuffer::render(self, scene, cfg, sink)
    }
}

/// Depth-tests columns `x0..x1` of a row (in range) against a polygon whose depth at `x0` is
/// `z`, stepping `dzdx`: each pixel it is nearer at gets its depth and `color(x)`.
#[inline(always)]
fn test_span<N: Scalar>(
    zrow: &mut [N],
    crow: &mut [Rgb565],
    mut z: N,
    dzdx: N,
    x0: i32,
    x1: i32,
    mut color: impl FnMut(i32) -> Rgb565,
) {
    for x in x0 as usize..x1 as usize {
        if z < zrow[x] {
            zrow[x] = z;
            crow[x] = color(x as i32);
        }
        z = z.step(dzdx, 1);
    }
}
