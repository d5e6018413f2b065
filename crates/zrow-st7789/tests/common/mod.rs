//! Test support: scenes from f32 triangles, and one render through both the core's
//! `FrameBuffer` and `St7789Rows` over the mock bus into the panel model.
#![allow(dead_code)]

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zrow::{Config, Face, FrameBuffer, Mesh, Scalar, Scanline, Scene, ScreenScene, Vec3};
use zrow_st7789::mock::{MockBus, Write};
use zrow_st7789::{line_bytes, St7789Rows, Window};

/// Host capacities big enough for every test scene (standard scenes included).
pub type Big<N> = Scanline<N, 240, 4096, 1024, 512>;

/// Line buffer for the widest window.
pub const B: usize = line_bytes(240);

/// Screen-space polygons in f32 with a colour each.
pub struct Polys(pub Vec<(Vec<[f32; 3]>, Rgb565)>);

impl Polys {
    /// Calls `f` with the polygons as a zrow screen-space scene in format `N`.
    pub fn with_scene<N: Scalar, R>(&self, f: impl FnOnce(&ScreenScene<'_, N>) -> R) -> R {
        let mut vertices = Vec::new();
        let mut indices: Vec<Vec<u16>> = Vec::new();
        for (poly, _) in &self.0 {
            indices.push(
                poly.iter()
                    .map(|v| {
                        vertices.push(Vec3::<N>::from_f32(*v).expect("vertex fits the format"));
                        (vertices.len() - 1) as u16
                    })
                    .collect(),
            );
        }
        let faces: Vec<Face> = indices
            .iter()
            .zip(&self.0)
            .map(|(i, (_, color))| Face {
                indices: i,
                color: *color,
                alpha: 255,
            })
            .collect();
        f(&ScreenScene {
            mesh: Mesh::new(&vertices, &faces),
        })
    }
}

/// Two overlapping triangles (the 6-pixel example of `crates/zrow/tests/seeds.rs`), scaled
/// to `w` × `h`.
pub fn seed_pair(w: u16, h: u16) -> Polys {
    let (sx, sy) = (w as f32 / 6.0, h as f32 / 6.0);
    let p = |x: f32, y: f32, z: f32| [x * sx + 0.5, y * sy + 0.5, z];
    Polys(vec![
        (
            vec![p(0.0, 0.0, 6.0), p(6.0, 0.0, 0.0), p(0.0, 6.0, 0.0)],
            Rgb565::RED,
        ),
        (
            vec![p(2.0, 0.0, 6.0), p(6.0, 0.0, 6.0), p(4.0, 4.0, 0.0)],
            Rgb565::GREEN,
        ),
    ])
}

/// Several overlapping triangles (some interpenetrating, some sharing edges) and a quad, in
/// distinct colours, spread over `w` × `h` and partly off screen.
pub fn overlapping(w: u16, h: u16) -> Polys {
    let (w, h) = (w as f32, h as f32);
    let p = |x: f32, y: f32, z: f32| [x * w, y * h, z];
    let c = |r, g, b| Rgb565::new(r, g, b);
    Polys(vec![
        (
            vec![p(0.05, 0.1, 5.0), p(0.9, 0.2, 1.0), p(0.3, 0.95, 9.0)],
            c(31, 0, 0),
        ),
        (
            vec![p(0.1, 0.8, 2.0), p(0.5, 0.05, 8.0), p(0.95, 0.85, 2.0)],
            c(0, 63, 0),
        ),
        (
            vec![p(-0.2, 0.4, 4.0), p(0.7, 0.3, 4.0), p(0.6, 0.7, 4.0)],
            c(0, 0, 31),
        ),
        // Two triangles sharing an edge (the fill rule: no gap, no double cover).
        (
            vec![p(0.2, 0.2, 3.0), p(0.8, 0.5, 3.0), p(0.2, 0.8, 3.0)],
            c(31, 63, 0),
        ),
        (
            vec![p(0.8, 0.5, 3.5), p(1.2, 0.9, 3.5), p(0.2, 0.8, 3.5)],
            c(0, 63, 31),
        ),
        // A quad leaning through the others.
        (
            vec![
                p(0.35, 0.35, 0.5),
                p(0.75, 0.4, 9.5),
                p(0.7, 0.75, 9.5),
                p(0.4, 0.7, 0.5),
            ],
            c(17, 9, 23),
        ),
        (
            vec![p(0.45, -0.1, 0.2), p(1.1, 0.1, 0.2), p(0.6, 0.3, 0.2)],
            c(31, 32, 16),
        ),
    ])
}

/// The same scene rendered twice: into a `FrameBuffer` and into the panel model through
/// `St7789Rows` (after the power-on sequence). Returns the bus for inspection.
pub struct Both {
    pub frame: Vec<Rgb565>,
    pub bus: MockBus,
    pub window: Window,
}

pub fn render_both<N: Scalar>(
    scene: &(impl Scene<N> + ?Sized),
    cfg: &Config,
    window: Window,
) -> Both {
    assert_eq!((cfg.width, cfg.height), (window.width, window.height));
    let mut renderer = Box::new(Big::<N>::new());
    let mut frame = vec![Rgb565::BLACK; cfg.width as usize * cfg.height as usize];
    renderer
        .render(
            scene,
            cfg,
            &mut FrameBuffer::new(&mut frame, cfg.width as usize),
        )
        .expect("frame buffer render");

    let bus = MockBus::new();
    let mut panel = St7789Rows::<_, _, B>::new(bus.spi(), bus.dc(), window).unwrap();
    panel.init(&mut bus.delay()).unwrap();
    bus.clear_writes();
    panel.begin_frame().unwrap();
    renderer
        .render(scene, cfg, &mut panel)
        .expect("panel render");
    assert_eq!(panel.next_row(), None, "the frame is complete");
    Both { frame, bus, window }
}

impl Both {
    /// Checks the model's window equals the frame buffer bit for bit, every window pixel
    /// was written exactly once, nothing outside it was, and the stream was clean.
    pub fn check(&self) {
        let model = self.bus.model();
        assert_eq!(model.errors(), &[], "protocol errors");
        let got = model.read_window(&self.window);
        let w = self.window.width as usize;
        for (i, (g, f)) in got.iter().zip(&self.frame).enumerate() {
            assert_eq!(g, f, "pixel ({}, {}) of the window", i % w, i / w);
        }
        assert_eq!(got.len(), self.frame.len());
        let mut written = 0u64;
        for y in 0..zrow_st7789::PANEL_HEIGHT {
            for x in 0..zrow_st7789::PANEL_WIDTH {
                let n = model.writes_at(x, y);
                let inside = (self.window.x_offset..self.window.x_offset + self.window.width)
                    .contains(&x)
                    && (self.window.y_offset..self.window.y_offset + self.window.height)
                        .contains(&y);
                assert_eq!(n, inside as u32, "writes at RAM ({x}, {y})");
                written += n as u64;
            }
        }
        assert_eq!(written, self.frame.len() as u64);
        // The window once (CASET, RASET with 4 parameters each, RAMWR), then one data write a row.
        let mut expect = vec![
            Write {
                dc_high: false,
                len: 1,
            },
            Write {
                dc_high: true,
                len: 4,
            },
            Write {
                dc_high: false,
                len: 1,
            },
            Write {
                dc_high: true,
                len: 4,
            },
            Write {
                dc_high: false,
                len: 1,
            },
        ];
        expect.extend((0..self.window.height).map(|_| Write {
            dc_high: true,
            len: line_bytes(self.window.width),
        }));
        assert_eq!(self.bus.writes(), expect);
    }

    /// Pixels that are not the background.
    pub fn drawn(&self) -> usize {
        self.frame.iter().filter(|&&c| c != Rgb565::BLACK).count()
    }

    /// Distinct colours in the frame.
    pub fn colours(&self) -> usize {
        let mut c: Vec<Rgb565> = self.frame.clone();
        c.sort_by_key(|p| zrow_scenes::raw(*p));
        c.dedup();
        c.len()
    }
}
