//! Screen-space rendering of a parsed OFF scene with one of zrow's methods.
//!
//! The scene goes to zrow as a [`zrow::ScreenScene`]: vertices are pixels (x right, y down),
//! z is depth (smaller is nearer), each face keeps its own colour. [`zrow::requirements()`]
//! measures the tables the scene needs first; a scene that fits the host's fixed capacities
//! ([`HOST_WIDTH`], [`HOST_POLYGONS`], [`HOST_EDGES`], [`HOST_ACTIVE`]) is then drawn into an
//! in-memory [`Image`], one finished row at a time.
//!
//! The renderer keeps all its tables inline (that is what lets it live in a microcontroller's
//! static RAM), which at these capacities is a couple of megabytes: more than a test thread's
//! stack. It is therefore built and run on a thread of its own with a stack sized from
//! [`HostScanline::RAM_BYTES`].

use crate::off::OffScene;
use crate::SimError;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use zrow::Scanline;
use zrow::{Config, Face, FrameBuffer, Mesh, RenderError, Renderer, Requirements, Scalar};
use zrow::{Cull, Scene, ScreenScene, Table, Q16_16};

/// Widest frame the host renders (zrow's largest viewport).
pub const HOST_WIDTH: usize = zrow::raster::MAX_VIEWPORT as usize;
/// Polygon-table capacity of the host renderer.
pub const HOST_POLYGONS: usize = 16384;
/// Edge-table capacity of the host renderer.
pub const HOST_EDGES: usize = 49152;
/// Active-list capacity of the host renderer (polygons crossing one row).
pub const HOST_ACTIVE: usize = 4096;

/// Pieces (polygons plus split parts) the host's depth-sort and BSP can hold.
pub const HOST_PIECES: usize = 65000;
/// Deepest BSP tree the host builds.
pub const HOST_BSP_DEPTH: usize = 16384;

/// The scan-line renderer at the host's capacities, drawing every shading (the affine cue's
/// per-edge state, an intensity plane per polygon).
pub type HostScanline<N> = Scanline<
    N,
    HOST_WIDTH,
    HOST_EDGES,
    HOST_POLYGONS,
    HOST_ACTIVE,
    u16,
    [zrow::scanline::EdgeCue<N>; HOST_ACTIVE],
    [zrow::IntensityPlane<N>; HOST_POLYGONS],
>;
/// The z-buffer at the host's largest frame.
pub type HostZBuffer<N> = zrow::ZBuffer<N, HOST_WIDTH, HOST_WIDTH>;
/// Depth-sort at the host's capacities.
pub type HostDepthSort<N> =
    zrow::depthsort::DepthSort<N, HOST_WIDTH, HOST_POLYGONS, HOST_EDGES, HOST_PIECES>;
/// Translucent fragments in one row the host's A-buffer can hold.
pub const HOST_FRAGMENTS: usize = 1 << 16;
/// The A-buffer at the host's capacities.
pub type HostABuffer<N> =
    zrow::abuffer::ABuffer<N, HOST_WIDTH, HOST_POLYGONS, HOST_EDGES, HOST_FRAGMENTS>;
/// Rows per band of the host's tiled z-buffer and Warnock (a band of 16 rows, as on the MCU).
pub const HOST_BAND: usize = 16;
/// The tiled 16-bit z-buffer at the host's capacities.
pub type HostTiled<N> = zrow::tiled::Tiled<N, HOST_WIDTH, HOST_BAND, HOST_POLYGONS, HOST_EDGES>;
/// Warnock's list room: every polygon reaching one band, `log2(16) + 2` times.
pub const HOST_WARNOCK_LIST: usize = HOST_POLYGONS * 6;
/// Warnock at the host's capacities.
pub type HostWarnock<N> =
    zrow::warnock::Warnock<N, HOST_WIDTH, HOST_BAND, HOST_POLYGONS, HOST_EDGES, HOST_WARNOCK_LIST>;
/// Back-face culling alone at the host's capacities (`auto`'s choice for a convex solid).
pub type HostCullOnly<N> = zrow::cullonly::CullOnly<N, HOST_WIDTH, HOST_POLYGONS, HOST_EDGES>;
/// Ordering alone at the host's capacities (`auto`'s choice for depth-separated polygons).
pub type HostOrdered<N> = zrow::ordered::Ordered<N, HOST_WIDTH, HOST_POLYGONS, HOST_EDGES>;
/// The BSP tree at the host's capacities.
pub type HostBsp<N> =
    zrow::bsp::Bsp<N, HOST_WIDTH, HOST_POLYGONS, HOST_EDGES, HOST_PIECES, HOST_BSP_DEPTH>;

/// A hidden-surface method, by its `--algo` name (`docs/conventions.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Algo {
    /// The scan-line method (`zrow::Scanline`).
    Scanline,
    /// The z-buffer (`zrow::ZBuffer`).
    ZBuffer,
    /// The tiled 16-bit z-buffer (`zrow::tiled::Tiled`): exact where depths differ by more
    /// than one 16-bit step of the frame's depth range.
    Tiled,
    /// Depth-sort (`zrow::depthsort::DepthSort`).
    DepthSort,
    /// Warnock's area subdivision (`zrow::warnock::Warnock`).
    Warnock,
    /// The BSP tree (`zrow::bsp::Bsp`).
    Bsp,
    /// Transparency, A-buffer style (`zrow::abuffer::ABuffer`): blends translucent faces
    /// (OFF alpha below 255) over the opaque surface; with every face opaque it is exact.
    ABuffer,
    /// The cheapest exact method for the scene ([`choose`]).
    Auto,
    /// Back-face culling alone (`zrow::cullonly::CullOnly`): only as `auto`'s choice for one
    /// closed convex solid (not an `--algo` name: it is not exact on other scenes).
    CullOnly,
    /// Ordering alone (`zrow::ordered::Ordered`): only as `auto`'s choice where polygons
    /// overlapping on screen never overlap in depth.
    Ordered,
}

impl Algo {
    /// Every accepted method with its name, in the order `--help` lists them.
    pub const ALL: &'static [(&'static str, Algo)] = &[
        ("scanline", Algo::Scanline),
        ("zbuffer", Algo::ZBuffer),
        ("tiled", Algo::Tiled),
        ("depth-sort", Algo::DepthSort),
        ("warnock", Algo::Warnock),
        ("bsp", Algo::Bsp),
        ("abuffer", Algo::ABuffer),
        ("auto", Algo::Auto),
    ];

    /// The method called `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().find(|(n, _)| *n == name).map(|&(_, a)| a)
    }

    /// Its `--algo` name (`auto`'s own choices: their renderers' names).
    pub fn name(self) -> &'static str {
        match self {
            Algo::CullOnly => "cull-only",
            Algo::Ordered => "ordered",
            _ => Self::ALL
                .iter()
                .find(|&&(_, a)| a == self)
                .map_or("?", |&(n, _)| n),
        }
    }

    /// The accepted names, comma-separated (for messages).
    pub fn names() -> String {
        join_names(Self::ALL)
    }
}

/// The names of a name table, comma-separated.
fn join_names<T>(all: &[(&str, T)]) -> String {
    all.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
}

pub use zrow_model::Format;

/// A rendered frame in Rgb565, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u16,
    /// Height in pixels.
    pub height: u16,
    /// `width × height` pixels, top row first.
    pub pixels: Vec<Rgb565>,
}

impl Image {
    /// The pixel at (x, y).
    pub fn pixel(&self, x: u16, y: u16) -> Option<Rgb565> {
        (x < self.width)
            .then(|| {
                self.pixels
                    .get(y as usize * self.width as usize + x as usize)
            })
            .flatten()
            .copied()
    }

    /// The pixels as 8-bit RGB triples (see [`rgb565_to_rgb8`]).
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|&c| rgb565_to_rgb8(c))
            .collect()
    }
}

/// Rgb565 to 8-bit RGB, rounding to nearest: `r8 = (r5·255 + 15) / 31`, `g8 = (g6·255 + 31)
/// / 63`, `b8` like `r8`. Full scale maps to 255 and zero to 0.
pub fn rgb565_to_rgb8(c: Rgb565) -> [u8; 3] {
    let scale = |v: u8, max: u32| ((v as u32 * 255 + max / 2) / max) as u8;
    [scale(c.r(), 31), scale(c.g(), 63), scale(c.b(), 31)]
}

/// Renders `scene` in screen-space mode at `width × height` pixels (each 1..=2048).
///
/// Errors: a vertex that does not fit `format` (named by its line), a face zrow rejects (named
/// by the face's line), a scene that needs more than the host capacities.
pub fn render_screen(
    scene: &OffScene,
    width: u16,
    height: u16,
    algo: Algo,
    format: Format,
) -> Result<Image, SimError> {
    match format {
        Format::Q16_16 => screen::<Q16_16>(scene, width, height, algo),
        Format::F32 => screen::<f32>(scene, width, height, algo),
    }
}

/// Measures what `scene` needs at this size in format `N` (checks every face on the way).
pub fn measure<N: Scalar>(
    scene: &OffScene,
    width: u16,
    height: u16,
) -> Result<Requirements, SimError> {
    let vertices = scene.vertices_in::<N>()?;
    let faces = faces(scene);
    let screen = screen_scene(&vertices, &faces);
    let cfg = Config::screen(width, height);
    zrow::requirements(&screen, &cfg).map_err(|e| core_error(scene, e))
}

fn faces(scene: &OffScene) -> Vec<Face<'_, u32>> {
    scene
        .faces
        .iter()
        .map(|f| Face {
            indices: &f.indices,
            color: f.rgb565(),
            alpha: f.alpha,
        })
        .collect()
}

fn screen_scene<'a, N>(
    vertices: &'a [zrow::Vec3<N>],
    faces: &'a [Face<'a, u32>],
) -> ScreenScene<'a, N, u32> {
    ScreenScene {
        mesh: Mesh::new(vertices, faces),
    }
}

/// A zrow error, blamed on the line of the face it names.
fn core_error(scene: &OffScene, error: zrow::Error) -> SimError {
    SimError::Scene {
        file: scene.file.clone(),
        line: error.face().and_then(|f| scene.face_line(f)),
        error,
    }
}

/// Checks measured requirements against the host capacities.
pub(crate) fn check_capacity(req: &Requirements) -> Result<(), zrow::Error> {
    for (table, needed, capacity) in [
        (Table::Polygons, req.polygons, HOST_POLYGONS),
        (Table::Edges, req.edges, HOST_EDGES),
        // The scan-line method's vertex buffer (its `V`).
        (Table::Vertices, req.vertices, HOST_EDGES),
        (Table::ActivePolygons, req.active_polygons, HOST_ACTIVE),
        (Table::RowWidth, req.width as u32, HOST_WIDTH),
    ] {
        if needed as usize > capacity {
            return Err(zrow::Error::Capacity {
                table,
                needed,
                capacity: capacity as u32,
            });
        }
    }
    Ok(())
}

fn screen<N: Scalar + Send + Sync>(
    scene: &OffScene,
    width: u16,
    height: u16,
    algo: Algo,
) -> Result<Image, SimError> {
    with_screen::<N, _>(scene, width, height, |screen, cfg, req| {
        draw(algo, screen, cfg, req, Structure::default, |e| {
            core_error(scene, e)
        })
    })
}

/// The method `auto` chooses for `scene` at this size in `format` ([`choose`]: screen-space
/// scenes are not culled, so cull-only never applies; ordered where its check passes).
pub fn choose_screen(
    scene: &OffScene,
    width: u16,
    height: u16,
    format: Format,
) -> Result<Algo, SimError> {
    fn run<N: Scalar + Send + Sync>(s: &OffScene, w: u16, h: u16) -> Result<Algo, SimError> {
        with_screen::<N, _>(s, w, h, |screen, cfg, req| {
            resolve(Algo::Auto, screen, cfg, req, Structure::default).map_err(|e| core_error(s, e))
        })
    }
    match format {
        Format::Q16_16 => run::<Q16_16>(scene, width, height),
        Format::F32 => run::<f32>(scene, width, height),
    }
}

/// Measures `scene` at this size in format `N`, then calls `f` with it as a zrow screen-space
/// scene, and what it measured.
fn with_screen<N: Scalar + Send + Sync, T>(
    scene: &OffScene,
    width: u16,
    height: u16,
    f: impl FnOnce(&ScreenScene<'_, N, u32>, &Config, &Requirements) -> Result<T, SimError>,
) -> Result<T, SimError> {
    let req = measure::<N>(scene, width, height)?;
    let vertices = scene.vertices_in::<N>()?;
    let faces = faces(scene);
    f(
        &screen_scene(&vertices, &faces),
        &Config::screen(width, height),
        &req,
    )
}

/// What a scene's structure allows, for [`choose`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Structure {
    /// The scene is one closed convex solid (`zrow_sim::structure::closed_convex`, the core's rule).
    pub closed_convex: bool,
}

/// `auto`'s rule: the cheapest method that is exact for this scene, from its structure.
///
/// 1. One closed convex solid drawn with back faces culled: **cull-only** — no depth test at
///    all (its front faces never overlap on screen).
/// 2. Polygons that overlap on screen never overlap in depth (checked exactly on this frame's
///    polygons, `zrow::ordered::Ordered::exact_for`): **ordered** — a sort, no depth test.
/// 3. Otherwise the **scan-line** method.
///
/// A static scene of several separate convex solids is drawn exactly by a precomputed BSP
/// order over the objects (`zrow::bsporder`, no depth test); `zrow-sim`'s scenes are one model
/// each, so `auto` here never meets one (the core's tests do). Runs the check on a thread
/// with room for the host's polygon table. Errors are the scene's, as a render would give.
pub fn choose<N: Scalar + Send + Sync, S: Scene<N> + Sync>(
    scene: &S,
    cfg: &Config,
    structure: Structure,
) -> Result<Algo, zrow::Error> {
    if structure.closed_convex && cfg.cull == Cull::Back {
        return Ok(Algo::CullOnly);
    }
    let ordered = on_big_stack(HostOrdered::<N>::RAM_BYTES, || {
        let mut check = HostOrdered::<N>::default();
        check.exact_for(scene, cfg)
    })
    .map_err(|_| zrow::Error::BadConfig)??;
    Ok(if ordered {
        Algo::Ordered
    } else {
        Algo::Scanline
    })
}

/// Runs `f` on a thread whose stack holds a renderer of `bytes` (three copies, as an
/// unoptimised build may make while constructing it) and the work's own frames.
pub(crate) fn on_big_stack<T: Send>(
    bytes: usize,
    f: impl FnOnce() -> T + Send,
) -> Result<T, SimError> {
    std::thread::scope(|s| {
        let worker = std::thread::Builder::new()
            .name("zrow-render".into())
            .stack_size(3 * bytes + (4 << 20))
            .spawn_scoped(s, f)
            .map_err(SimError::Thread)?;
        Ok(worker
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
    })
}

/// Draws `scene` with method `algo` into a new [`Image`], on a thread of its own (see the
/// module doc); `req` is what the scene measured ([`zrow::requirements()`]), `blame` turns a
/// zrow error into the caller's message. A scene that fits the host capacities is drawn in
/// one pass; a larger one band by band ([`crate::bands`]), which any size fits. `auto` is
/// resolved by [`choose`] with the scene's structure, asked for only then (the closed-convex
/// check reads the whole mesh); for a scene beyond the host capacities, whose polygons the
/// ordered check cannot hold, `auto` is cull-only or the scan-line method.
pub(crate) fn draw<N: Scalar + Send + Sync, S: Scene<N> + Sync>(
    algo: Algo,
    scene: &S,
    cfg: &Config,
    req: &Requirements,
    structure: impl FnOnce() -> Structure,
    blame: impl Fn(zrow::Error) -> SimError,
) -> Result<Image, SimError> {
    let algo = resolve::<N, S>(algo, scene, cfg, req, structure).map_err(&blame)?;
    if check_capacity(req).is_err() {
        let slots = req.vertices as usize;
        return crate::bands::draw(
            algo,
            scene,
            cfg,
            slots,
            crate::bands::BAND_POLYGONS,
            crate::bands::BAND_CORNERS,
            blame,
        );
    }
    match algo {
        Algo::Scanline | Algo::Auto => draw_with::<N, S, HostScanline<N>>(scene, cfg, blame),
        Algo::CullOnly => draw_with::<N, S, HostCullOnly<N>>(scene, cfg, blame),
        Algo::Ordered => draw_with::<N, S, HostOrdered<N>>(scene, cfg, blame),
        Algo::ZBuffer => draw_with::<N, S, HostZBuffer<N>>(scene, cfg, blame),
        Algo::Tiled => draw_with::<N, S, HostTiled<N>>(scene, cfg, blame),
        Algo::Warnock => draw_with::<N, S, HostWarnock<N>>(scene, cfg, blame),
        Algo::DepthSort => draw_with::<N, S, HostDepthSort<N>>(scene, cfg, blame),
        Algo::Bsp => draw_with::<N, S, HostBsp<N>>(scene, cfg, blame),
        Algo::ABuffer => draw_with::<N, S, HostABuffer<N>>(scene, cfg, blame),
    }
}

/// `algo`, with `auto` resolved as [`draw`] resolves it.
pub(crate) fn resolve<N: Scalar + Send + Sync, S: Scene<N> + Sync>(
    algo: Algo,
    scene: &S,
    cfg: &Config,
    req: &Requirements,
    structure: impl FnOnce() -> Structure,
) -> Result<Algo, zrow::Error> {
    let fits = check_capacity(req).is_ok();
    Ok(match algo {
        Algo::Auto if fits => choose::<N, S>(scene, cfg, structure())?,
        Algo::Auto if structure().closed_convex && cfg.cull == Cull::Back => Algo::CullOnly,
        Algo::Auto => Algo::Scanline,
        a => a,
    })
}

/// [`draw`] with one method's type.
fn draw_with<N: Scalar + Send + Sync, S: Scene<N> + Sync, R: Renderer<N> + Default>(
    scene: &S,
    cfg: &Config,
    blame: impl FnOnce(zrow::Error) -> SimError,
) -> Result<Image, SimError> {
    let (width, height) = (cfg.width, cfg.height);
    let mut pixels = vec![Rgb565::BLACK; width as usize * height as usize];
    let mut frame = FrameBuffer::new(&mut pixels, width as usize);
    let result = on_big_stack(R::RAM_BYTES, || {
        let mut renderer = R::default();
        renderer.render(scene, cfg, &mut frame).map(|_| ())
    })?
    .map_err(|e| match e {
        RenderError::Scene(e) => blame(e),
        RenderError::Sink(never) => match never {},
    });
    result?;
    Ok(Image {
        width,
        height,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::off::parse;

    #[test]
    fn rgb565_round_trips_through_rgb8() {
        assert_eq!(rgb565_to_rgb8(Rgb565::WHITE), [255; 3]);
        assert_eq!(rgb565_to_rgb8(Rgb565::BLACK), [0; 3]);
        assert_eq!(rgb565_to_rgb8(Rgb565::new(16, 32, 1)), [132, 130, 8]);
        for r in 0..32u8 {
            for g in 0..64u8 {
                let c = Rgb565::new(r, g, 31 - r);
                assert_eq!(crate::off::rgb8_to_rgb565(rgb565_to_rgb8(c)), c);
            }
        }
    }

    #[test]
    fn names_round_trip() {
        for &(n, a) in Algo::ALL {
            assert_eq!(Algo::from_name(n), Some(a));
            assert_eq!(a.name(), n);
        }
        for &(n, f) in Format::ALL {
            assert_eq!(Format::from_name(n), Some(f));
            assert_eq!(f.name(), n);
        }
        assert_eq!(Algo::from_name("painter"), None);
    }

    const SEED002: &str = "OFF\n6 2 0\n0 0 6\n6 0 0\n0 6 0\n2 0 6\n6 0 6\n4 4 0\n\
                           3 0 1 2 255 0 0\n3 3 4 5 0 255 0\n";

    #[test]
    fn seed_002_s1_is_in_front_at_3_1() {
        let scene = parse("seed002.off", SEED002.as_bytes()).unwrap();
        for format in [Format::Q16_16, Format::F32] {
            let img = render_screen(&scene, 8, 8, Algo::Scanline, format).unwrap();
            // Pixel (3, 1)'s centre is (3.5, 1.5): inside both, s1 (red) nearer.
            assert_eq!(img.pixel(3, 1), Some(Rgb565::RED), "{format:?}");
            assert_eq!(img.pixel(4, 2), Some(Rgb565::GREEN), "{format:?}");
            assert_eq!(img.pixel(7, 7), Some(Rgb565::BLACK), "{format:?}");
        }
    }

    /// `--algo abuffer` blends a face whose OFF colour carries an alpha; every other method
    /// draws it opaque.
    #[test]
    fn abuffer_blends_the_off_alpha() {
        let text = "OFF\n8 2 0\n0 0 2\n8 0 2\n8 8 2\n0 8 2\n2 2 1\n6 2 1\n6 6 1\n2 6 1\n\
                    4 0 1 2 3 255 0 0\n4 4 5 6 7 0 0 255 128\n";
        let scene = parse("alpha.off", text.as_bytes()).unwrap();
        let blended = render_screen(&scene, 8, 8, Algo::ABuffer, Format::Q16_16).unwrap();
        let opaque = render_screen(&scene, 8, 8, Algo::Scanline, Format::Q16_16).unwrap();
        // Blue at alpha 128 over red: (31·127 + 127)/255 = 15 red, (31·128 + 127)/255 = 16 blue.
        assert_eq!(blended.pixel(4, 4), Some(Rgb565::new(15, 0, 16)));
        assert_eq!(opaque.pixel(4, 4), Some(Rgb565::BLUE));
        assert_eq!(blended.pixel(0, 0), Some(Rgb565::RED));
    }

    #[test]
    fn measures_the_scene() {
        let scene = parse("seed002.off", SEED002.as_bytes()).unwrap();
        let req = measure::<Q16_16>(&scene, 8, 8).unwrap();
        assert_eq!((req.polygons, req.active_polygons), (2, 2));
    }

    #[test]
    fn a_scene_beyond_the_host_capacities_is_a_typed_error() {
        // HOST_ACTIVE + 1 thin triangles, all crossing row 0.
        let n = HOST_ACTIVE + 1;
        let mut text = format!("OFF\n{} {n} 0\n", 3 * n);
        for k in 0..n {
            let x = (k % 200) as f32;
            text += &format!("{x} 0 1\n{} 0 1\n{x} 4 1\n", x + 1.0);
        }
        for k in 0..n {
            text += &format!("3 {} {} {}\n", 3 * k, 3 * k + 1, 3 * k + 2);
        }
        let scene = parse("many.off", text.as_bytes()).unwrap();
        let e = render_screen(&scene, 240, 8, Algo::Scanline, Format::Q16_16).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "many.off: active list holds {HOST_ACTIVE} but this scene needs {n}: raise that capacity (the renderer's const parameter A to at least {n})"
            )
        );
    }

    #[test]
    fn core_errors_name_the_face_line() {
        // A non-convex quad on line 8 (after a comment line).
        let text = "OFF\n4 1 0\n0 0 0\n10 0 0\n2 2 0\n0 10 0\n# bow tie\n4 0 2 1 3\n";
        let scene = parse("bad.off", text.as_bytes()).unwrap();
        let e = render_screen(&scene, 16, 16, Algo::Scanline, Format::Q16_16).unwrap_err();
        assert_eq!(e.to_string(), "bad.off:8: face 0: not convex");
    }
}
