//! Host time per frame of the scan-line renderer at 240×240, in Q16.16 and f32.
//!
//! Scenes (the shared `zrow-scenes` crate):
//! - `cube`: the unit cube, 6 quads, model mode, perspective camera, one light;
//! - `mesh1k`: a closed torus of 1,000 triangles (25 × 20 segments), same camera;
//! - `random400`: 400 random screen-space triangles (overlapping, intersecting).
//!
//! Before timing, each scene and format is rendered once to check that it draws (more than
//! `MIN_DRAWN` non-background pixels) and to print one line of figures:
//!
//! `scene=NAME format=FMT tris=T polygons=P edges=E max_active=A front_changes=C crossings=X
//! ram_used=BYTES ram_struct=BYTES`
//!
//! `ram_used` is `zrow::scanline::ram_bytes` (tables at exactly the required sizes plus two
//! rows); `ram_struct` is `Scanline::RAM_BYTES` of the benchmark's instantiation below.
//!
//! Run: `cargo bench -p zrow --bench frame`.

use criterion::measurement::WallTime;
use criterion::{
    criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, SamplingMode,
};
use embedded_graphics_core::pixelcolor::{IntoStorage, Rgb565};
use std::convert::Infallible;
use std::hint::black_box;
use std::time::{Duration, Instant};
use zrow::scanline::ram_bytes;
use zrow::{requirements, Config, Row, RowSink, Scalar, Scanline, Scene, Q16_16};

/// Renderer capacities: row width, vertex buffer, polygon table, active list.
const W: usize = 240;
const V: usize = 6144;
const P: usize = 2048;
const A: usize = 512;
/// A frame drawing fewer non-background pixels than this is treated as broken.
const MIN_DRAWN: usize = 1000;
/// Criterion settings: short, so the whole bench runs in well under a minute.
const MEASUREMENT: Duration = Duration::from_secs(3);
const SAMPLES: usize = 20;

type Renderer<N> = Scanline<N, W, V, P, A>;

/// Discards rows but keeps them observable: every row goes through `black_box` and a few of
/// its pixels are folded into `acc`, so the optimizer cannot drop the work.
#[derive(Default)]
struct ProbeSink {
    acc: u32,
}

impl<N> RowSink<N> for ProbeSink {
    type Error = Infallible;
    /// A display's sink: colours only.
    const WANTS_DEPTH: bool = false;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Infallible> {
        let px = black_box(row.color);
        let n = px.len();
        let raw = |x: usize| u32::from(px[x].into_storage());
        self.acc = self.acc.rotate_left(5) ^ raw(0) ^ raw(n / 2) ^ raw(n - 1) ^ u32::from(row.y);
        Ok(())
    }
}

/// Counts rows and non-background pixels (setup only, not timed).
struct CountSink {
    background: Rgb565,
    rows: usize,
    drawn: usize,
}

impl<N> RowSink<N> for CountSink {
    type Error = Infallible;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Infallible> {
        self.rows += 1;
        self.drawn += row.color.iter().filter(|&&c| c != self.background).count();
        Ok(())
    }
}

/// Checks and describes one scene in one format, then times `render` on it.
fn measure<N: Scalar>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    tris: usize,
    scene: &dyn Scene<N>,
    cfg: &Config,
) {
    let req = requirements(scene, cfg).expect("requirements");
    assert!(
        req.polygons as usize <= P
            && req.vertices as usize <= V
            && req.active_polygons as usize <= A,
        "{name}/{}: {req:?} exceeds the capacities P={P} V={V} A={A}",
        N::NAME
    );

    let mut renderer: Box<Renderer<N>> = Box::new(Scanline::new());
    let mut count = CountSink {
        background: cfg.background,
        rows: 0,
        drawn: 0,
    };
    let started = Instant::now();
    let stats = renderer.render(scene, cfg, &mut count).expect("render");
    let once = started.elapsed();
    assert_eq!(count.rows, cfg.height as usize, "{name}/{}: rows", N::NAME);
    assert!(
        count.drawn > MIN_DRAWN,
        "{name}/{}: only {} non-background pixels drawn",
        N::NAME,
        count.drawn
    );
    assert_eq!(
        (stats.polygons, stats.edges, stats.max_active),
        (req.polygons, req.edges, req.active_polygons),
        "{name}/{}: FrameStats disagree with requirements",
        N::NAME
    );

    println!(
        "scene={name} format={} tris={tris} polygons={} edges={} max_active={} \
         front_changes={} crossings={} ram_used={} ram_struct={}",
        N::NAME,
        req.polygons,
        req.edges,
        req.active_polygons,
        stats.front_changes,
        stats.crossings,
        ram_bytes::<N>(&req),
        Renderer::<N>::RAM_BYTES,
    );

    // Linear sampling runs d·(1 + 2 + … + SAMPLES) iterations with d ≥ 1; where d = 1 would
    // come near the measurement time (slow frames), use flat sampling instead.
    let linear = once * (SAMPLES * (SAMPLES + 1) / 2) as u32;
    group.sampling_mode(if 2 * linear > MEASUREMENT {
        SamplingMode::Flat
    } else {
        SamplingMode::Linear
    });
    let mut sink = ProbeSink::default();
    group.bench_function(BenchmarkId::new(name, N::NAME), |b| {
        b.iter(|| renderer.render(scene, cfg, &mut sink).expect("render"))
    });
    black_box(sink.acc);
}

fn scenes_in<N: zrow_scenes::Format>(group: &mut BenchmarkGroup<'_, WallTime>) {
    for name in zrow_scenes::NAMES {
        zrow_scenes::with_scene::<N, _>(name, 0.0, |scene, cfg, tris| {
            measure(group, name, tris, scene, cfg)
        });
    }
}

fn frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame");
    group
        .measurement_time(MEASUREMENT)
        .warm_up_time(Duration::from_secs(1))
        .sample_size(SAMPLES);
    scenes_in::<Q16_16>(&mut group);
    scenes_in::<f32>(&mut group);
    group.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
