//! `--algo auto`: the cheapest exact method chosen from the scene's structure
//! (`zrow_sim::render::choose`), and its picture equal to the scan-line method's.
//!
//! - a closed convex model (cube.obj, icosphere.stl) → cull-only, under every view tried;
//! - a model that hides parts of itself (torus.off) → never cull-only (ordered from the views
//!   tried: its overlapping front faces are far apart in depth);
//! - a screen-space scene of polygons stacked in depth → ordered; interpenetrating → scan-line.

use std::path::Path;
use std::time::Instant;
use zrow_sim::model;
use zrow_sim::model_render::{choose_model, render_model_image, View};
use zrow_sim::off;
use zrow_sim::render::{choose_screen, render_screen, Algo, Format};

const SIZE: u16 = 240;

fn load(name: &str) -> model::LoadedModel {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/models")
        .join(name);
    model::load(&path).unwrap()
}

fn views() -> impl Iterator<Item = View> {
    (0..8).map(|k| View {
        yaw_deg: 45.0 * k as f32 + 10.0,
        pitch_deg: -60.0 + 17.0 * k as f32,
        distance: 2.5 + 0.25 * k as f32,
    })
}

/// `auto` on `model` from each view: the method chosen (both formats), each drawing the
/// scan-line method's picture.
fn model_case(name: &str) -> Vec<Algo> {
    let m = load(name);
    let mut chosen = Vec::new();
    for format in [Format::Q16_16, Format::F32] {
        for view in views() {
            chosen.push(choose_model(&m, &view, SIZE, SIZE, format).unwrap());
            let auto = render_model_image(&m, &view, SIZE, SIZE, Algo::Auto, format).unwrap();
            let scan = render_model_image(&m, &view, SIZE, SIZE, Algo::Scanline, format).unwrap();
            assert!(auto == scan, "{name} {format:?} {view:?}: auto's picture");
        }
    }
    chosen
}

#[test]
fn a_closed_convex_model_needs_culling_alone() {
    assert!(model_case("cube.obj").iter().all(|&a| a == Algo::CullOnly));
}

/// The torus is not convex: never cull-only. Its front faces do overlap (the near side of
/// the ring over the far side of the hole), but where they overlap they are far apart in
/// depth, so from every view tried ordering alone suffices — and the picture equals the
/// scan-line method's.
#[test]
fn a_torus_is_never_culled_alone() {
    let chosen = model_case("torus.off");
    assert!(!chosen.contains(&Algo::CullOnly));
    println!("torus.off, 8 views x 2 formats: auto chose {chosen:?}");
}

/// What auto saves on the convex model (printed, host wall time of this test machine: a
/// rough figure; the emulated bench's `cull-only` lines count instructions).
#[test]
fn report_what_auto_saves_on_the_cube() {
    let m = load("cube.obj");
    let view = View::default();
    let time = |algo| {
        let start = Instant::now();
        for _ in 0..20 {
            render_model_image(&m, &view, SIZE, SIZE, algo, Format::Q16_16).unwrap();
        }
        start.elapsed() / 20
    };
    let (auto, scan) = (time(Algo::Auto), time(Algo::Scanline));
    println!("cube.obj 240x240 Q16.16, host, mean of 20 (thread and buffers included): auto (cull-only) {auto:?}, scanline {scan:?}");
    assert_eq!(
        choose_model(&m, &view, SIZE, SIZE, Format::Q16_16).unwrap(),
        Algo::CullOnly
    );
}

/// Three rectangles stacked in depth (each tilted within its own layer), overlapping.
const LAYERS: &str = "OFF\n12 3 0\n\
    20 20 30\n150 20 32\n150 150 34\n20 150 32\n\
    60 60 20\n200 60 20\n200 200 21\n60 200 21\n\
    100 10 5\n230 10 6\n230 120 7\n100 120 6\n\
    4 0 1 2 3 255 0 0\n4 4 5 6 7 0 255 0\n4 8 9 10 11 0 0 255\n";

#[test]
fn depth_separated_screen_scenes_need_ordering_alone() {
    let scene = off::parse("layers.off", LAYERS.as_bytes()).unwrap();
    for format in [Format::Q16_16, Format::F32] {
        assert_eq!(
            choose_screen(&scene, SIZE, SIZE, format).unwrap(),
            Algo::Ordered
        );
        let auto = render_screen(&scene, SIZE, SIZE, Algo::Auto, format).unwrap();
        let scan = render_screen(&scene, SIZE, SIZE, Algo::Scanline, format).unwrap();
        assert!(auto == scan, "{format:?}");
    }
}

#[test]
fn interpenetrating_screen_scenes_need_the_scan_line_method() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/interpenetrating.off");
    let data = std::fs::read(&path).unwrap();
    let scene = off::parse("interpenetrating.off", &data).unwrap();
    assert_eq!(
        choose_screen(&scene, SIZE, SIZE, Format::Q16_16).unwrap(),
        Algo::Scanline
    );
    let auto = render_screen(&scene, SIZE, SIZE, Algo::Auto, Format::Q16_16).unwrap();
    let scan = render_screen(&scene, SIZE, SIZE, Algo::Scanline, Format::Q16_16).unwrap();
    assert!(auto == scan);
}
