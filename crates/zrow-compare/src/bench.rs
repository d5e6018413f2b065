//! The methods compared, how each is timed, checked and sized.
//!
//! [`methods`] is the list: one line per method. Each runs on a thread of its own with a
//! stack big enough to build it (the renderers keep every table inline, megabytes at these
//! capacities), renders every scene once into a frame (kept for the pixel check against the
//! z-buffer), then times further renders.

use crate::surfaces::Surfaces;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use std::time::{Duration, Instant};
use zrow::abuffer::ABuffer;
use zrow::bsp::Bsp;
use zrow::depthsort::DepthSort;
use zrow::{tiled::Tiled, warnock::Warnock};
use zrow::{Config, Face, FrameBuffer, FrameStats, Mesh, Renderer, Requirements, Scene};
use zrow::{Scanline, ScreenScene, Vec3, ZBuffer, Q16_16};

/// Host frame width and height (Foley's era: 512 × 512).
pub const SIZE: usize = 512;
/// Polygon capacity: the largest scene.
const P: usize = 60_000;
/// Edge capacity, and the scan-line's vertex slots: three per triangle.
const E: usize = 3 * P;
/// Active-list capacity (scan-line): polygons crossing one row, with room to spare.
const A: usize = 8_192;
/// Piece capacity (depth-sort, BSP): the most their `u16` indices allow.
const Q: usize = 65_534;
/// BSP tree depth bound.
const D: usize = 65_534;
/// Warnock's list capacity: one band of `SIZE` rows (the whole screen, so the seed's full
/// quadtree) reached by `P` polygons needs `P·(log2(SIZE) + 2)` entries.
const L: usize = P * (SIZE.ilog2() as usize + 2);

/// Every method compared, in the order the table lists them: ONE line per method. The first
/// argument is its RAM formula (see [`ram`]), `None` for "RAM_BYTES as built".
pub fn methods() -> Vec<Method> {
    vec![
        method::<DepthSort<Q16_16, SIZE, P, E, Q>>(Some(ram::depthsort)),
        method::<ZBuffer<Q16_16, SIZE, SIZE>>(Some(ram::zbuffer)),
        method::<Scanline<Q16_16, SIZE, E, P, A, u32>>(Some(ram::scanline)),
        method::<Bsp<Q16_16, SIZE, P, E, Q, D>>(Some(ram::bsp)),
        method::<ABuffer<Q16_16, SIZE, P, E, 16>>(Some(ram::abuffer)),
        method::<Tiled<Q16_16, SIZE, 16, P, E>>(Some(ram::tiled)),
        method::<Warnock<Q16_16, SIZE, SIZE, P, E, L>>(Some(ram::warnock)),
    ]
}

/// What a scene needs, for the RAM formulas.
#[derive(Clone, Copy, Debug)]
pub struct Need {
    /// Frame width and height.
    pub width: usize,
    /// Frame height.
    pub height: usize,
    /// [`zrow::requirements()`] of the scene.
    pub req: Requirements,
    /// Pieces the method made (polygons plus the parts splitting made: depth-sort, BSP).
    pub pieces: usize,
}

/// RAM formulas: bytes each method needs with every capacity sized to the scene.
pub mod ram {
    use super::{Need, D, SIZE};
    use zrow::{abuffer::ABuffer, bsp::Bsp, depthsort::DepthSort, Q16_16};
    use zrow::{tiled::Tiled, warnock::Warnock};

    /// `zrow::scanline::ram_bytes` (its tables at the sizes required, plus two rows).
    pub fn scanline(n: &Need) -> usize {
        zrow::scanline::ram_bytes::<Q16_16>(&n.req)
    }
    /// `ZBuffer::<Q16_16, W, H>::RAM_BYTES` = `W·H·(4 + 2)`: a depth and a colour per pixel.
    pub fn zbuffer(n: &Need) -> usize {
        n.width * n.height * (core::mem::size_of::<Q16_16>() + 2)
    }
    /// `DepthSort::<Q16_16, W, P, E, Q>::RAM_BYTES` at W = width, P = polygons, E = edges,
    /// Q = pieces, from the struct's size at small capacities (it is linear in each; padding
    /// may add up to 8 bytes).
    pub fn depthsort(n: &Need) -> usize {
        type T<const W: usize, const P: usize, const E: usize, const Q: usize> =
            DepthSort<Q16_16, W, P, E, Q>;
        let base = T::<1, 1, 1, 1>::RAM_BYTES;
        let slope = [
            T::<65, 1, 1, 1>::RAM_BYTES - base,
            T::<1, 65, 1, 1>::RAM_BYTES - base,
            T::<1, 1, 65, 1>::RAM_BYTES - base,
            T::<1, 1, 1, 65>::RAM_BYTES - base,
        ];
        linear(base, slope, n, 0)
    }
    /// `Bsp::<Q16_16, W, P, E, Q, D>::RAM_BYTES` as [`depthsort`], with the tree-depth bound D
    /// as built (65,534: its two stacks take 10 bytes an entry).
    pub fn bsp(n: &Need) -> usize {
        type T<const W: usize, const P: usize, const E: usize, const Q: usize, const D: usize> =
            Bsp<Q16_16, W, P, E, Q, D>;
        let base = T::<1, 1, 1, 1, 1>::RAM_BYTES;
        let slope = [
            T::<65, 1, 1, 1, 1>::RAM_BYTES - base,
            T::<1, 65, 1, 1, 1>::RAM_BYTES - base,
            T::<1, 1, 65, 1, 1>::RAM_BYTES - base,
            T::<1, 1, 1, 65, 1>::RAM_BYTES - base,
        ];
        let depth = (T::<1, 1, 1, 1, 65>::RAM_BYTES - base) * (D - 1) / 64;
        linear(base, slope, n, depth)
    }
    /// `ABuffer::<Q16_16, W, P, E, F>::RAM_BYTES` as [`depthsort`], with room for one
    /// translucent fragment (the scenes are opaque: none is made).
    pub fn abuffer(n: &Need) -> usize {
        type T<const W: usize, const P: usize, const E: usize> = ABuffer<Q16_16, W, P, E, 1>;
        let base = T::<1, 1, 1>::RAM_BYTES;
        let slope = [
            T::<65, 1, 1>::RAM_BYTES - base,
            T::<1, 65, 1>::RAM_BYTES - base,
            T::<1, 1, 65>::RAM_BYTES - base,
            0,
        ];
        linear(base, slope, n, 0)
    }
    /// `Tiled::<Q16_16, W, 16, P, E>::RAM_BYTES` as [`depthsort`] (bands of 16 rows).
    pub fn tiled(n: &Need) -> usize {
        type T<const W: usize, const P: usize, const E: usize> = Tiled<Q16_16, W, 16, P, E>;
        let base = T::<1, 1, 1>::RAM_BYTES;
        let slope = [
            T::<65, 1, 1>::RAM_BYTES - base,
            T::<1, 65, 1>::RAM_BYTES - base,
            T::<1, 1, 65>::RAM_BYTES - base,
            0,
        ];
        linear(base, slope, n, 0)
    }
    /// `Warnock::<Q16_16, W, SIZE, P, E, L>::RAM_BYTES` as [`depthsort`] (one band of
    /// `SIZE` rows: the seed's quadtree over the whole screen), with the list capacity the
    /// scene needs, `L = polygons·(log2(SIZE) + 2)` (every polygon reaches the one band).
    pub fn warnock(n: &Need) -> usize {
        type T<const W: usize, const P: usize, const E: usize, const L: usize> =
            Warnock<Q16_16, W, SIZE, P, E, L>;
        let base = T::<1, 1, 1, 1>::RAM_BYTES;
        let slope = [
            T::<65, 1, 1, 1>::RAM_BYTES - base,
            T::<1, 65, 1, 1>::RAM_BYTES - base,
            T::<1, 1, 65, 1>::RAM_BYTES - base,
            0,
        ];
        let list = n.req.polygons as usize * (SIZE.ilog2() as usize + 2);
        let entries = (T::<1, 1, 1, 65>::RAM_BYTES - base) * list.saturating_sub(1) / 64;
        linear(base, slope, n, entries)
    }
    fn linear(base: usize, slope: [usize; 4], n: &Need, extra: usize) -> usize {
        let (p, e) = (n.req.polygons as usize, n.req.edges as usize);
        let caps = [n.width, p.max(1), e.max(1), n.pieces.max(1)];
        base + extra
            + caps
                .iter()
                .zip(slope)
                .map(|(&c, s)| (c - 1) * s / 64)
                .sum::<usize>()
    }
}

/// One method: its name, RAM as built, RAM formula and runner.
pub struct Method {
    /// `Renderer::NAME`.
    pub name: &'static str,
    /// `Renderer::RAM_BYTES` at this program's capacities.
    pub built: usize,
    /// Bytes needed at capacities sized for a scene, if the method has a formula.
    pub ram: Option<fn(&Need) -> usize>,
    run: fn(&[Surfaces], &Budget) -> Vec<Outcome>,
}

impl Method {
    /// Renders and times every scene.
    pub fn run(&self, scenes: &[Surfaces], budget: &Budget) -> Vec<Outcome> {
        (self.run)(scenes, budget)
    }
}

/// How long to time each frame.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// At least this many timed runs (unless one run exceeds `slow`)...
    pub min_runs: usize,
    /// ... at most this many...
    pub max_runs: usize,
    /// ... stopping once they add up to this.
    pub target: Duration,
    /// A first frame slower than this is timed once (that run is the figure).
    pub slow: Duration,
}

/// One method on one scene.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The frame, or the error's text.
    pub frame: Result<Vec<Rgb565>, String>,
    /// The first render's statistics.
    pub stats: FrameStats,
    /// Median render time.
    pub median: Duration,
    /// Timed renders.
    pub runs: usize,
}

/// The list entry for renderer `R`.
fn method<R: Renderer<Q16_16> + Default + 'static>(ram: Option<fn(&Need) -> usize>) -> Method {
    Method {
        name: R::NAME,
        built: R::RAM_BYTES,
        ram,
        run: run::<R>,
    }
}

/// The scene as zrow sees it: Q16.16 vertices and faces borrowing `s`'s indices.
pub fn with_screen<T>(s: &Surfaces, f: impl FnOnce(&ScreenScene<'_, Q16_16>) -> T) -> T {
    let vertices: Vec<Vec3<Q16_16>> = s
        .vertices
        .iter()
        .map(|v| Vec3::from_f32(*v).expect("scene positions fit Q16.16"))
        .collect();
    let faces: Vec<Face<'_>> = s
        .faces
        .iter()
        .map(|(idx, (r, g, b))| Face::new(idx, Rgb565::new(*r, *g, *b)))
        .collect();
    let mesh = Mesh::new(&vertices, &faces);
    f(&ScreenScene { mesh })
}

/// The frame configuration: [`SIZE`] × [`SIZE`], screen space.
pub fn config() -> Config {
    Config::screen(SIZE as u16, SIZE as u16)
}

/// Builds `R` on a thread whose stack can hold it (as host-sim does), renders every scene.
fn run<R: Renderer<Q16_16> + Default + 'static>(
    scenes: &[Surfaces],
    budget: &Budget,
) -> Vec<Outcome> {
    let stack = 2 * R::RAM_BYTES + (16 << 20);
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name(R::NAME.into())
            .stack_size(stack)
            .spawn_scoped(scope, || {
                // Built inside the big stack: `Box::new` may build the value on the stack first.
                let mut renderer = Box::new(R::default());
                scenes
                    .iter()
                    .map(|s| with_screen(s, |scene| time(&mut *renderer, scene, budget)))
                    .collect()
            })
            .expect("spawn the renderer's thread")
            .join()
            .expect("the renderer's thread panicked")
    })
}

fn time<R: Renderer<Q16_16>>(r: &mut R, scene: &impl Scene<Q16_16>, b: &Budget) -> Outcome {
    let cfg = config();
    let mut pixels = vec![Rgb565::BLACK; SIZE * SIZE];
    let start = Instant::now();
    let first = r.render(scene, &cfg, &mut FrameBuffer::new(&mut pixels, SIZE));
    let first_time = start.elapsed();
    let stats = match first {
        Ok(s) => s,
        Err(e) => {
            return Outcome {
                frame: Err(format!("{e:?}")),
                stats: FrameStats::default(),
                median: first_time,
                runs: 0,
            }
        }
    };
    let mut times = vec![];
    if first_time >= b.slow {
        times.push(first_time);
    } else {
        let mut scratch = vec![Rgb565::BLACK; SIZE * SIZE];
        let mut total = Duration::ZERO;
        while times.len() < b.max_runs && (times.len() < b.min_runs || total < b.target) {
            let start = Instant::now();
            let _ = r.render(scene, &cfg, &mut FrameBuffer::new(&mut scratch, SIZE));
            let t = start.elapsed();
            times.push(t);
            total += t;
        }
    }
    times.sort();
    Outcome {
        frame: Ok(pixels),
        stats,
        median: times[times.len() / 2],
        runs: times.len(),
    }
}
