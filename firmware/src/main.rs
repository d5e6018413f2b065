//! zrow on an STM32F411 "Black Pill" — skeleton.
//!
//! Renders the demo cube with the same core as the host, one row at a time, into a sink that
//! checksums the rows, and logs the frame's statistics through defmt. The ST7789 driver (SPI,
//! DMA row streaming) and DWT cycle counts are the firmware issue's work; the sink is where the
//! display goes.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use defmt_rtt as _;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use panic_probe as _;
use zrow::{
    Affine, Camera, Config, Face, Light, Mesh, ModelScene, Object, Q16_16, Row, RowSink,
    Scanline, Vec3,
};

/// Sums the rows so the work is observable (stand-in for the display).
struct Checksum(u32);

impl<N> RowSink<N> for Checksum {
    type Error = core::convert::Infallible;
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Self::Error> {
        for c in row.intensity {
            self.0 = self.0.rotate_left(5) ^ u32::from(c.r() ^ c.g() ^ c.b());
        }
        Ok(())
    }
}

const fn q(v: i32) -> Q16_16 {
    Q16_16::from_bits(v << 16) // 16.16 fixed point
}

static CUBE_VERTICES: [Vec3<Q16_16>; 8] = {
    let mut v = [Vec3::new(q(0), q(0), q(0)); 8];
    let mut i = 0;
    while i < 8 {
        v[i] = Vec3::new(
            q((i & 1) as i32 * 2 - 1),
            q(((i >> 1) & 1) as i32 * 2 - 1),
            q(((i >> 2) & 1) as i32 * 2 - 1),
        );
        i += 1;
    }
    v
};

static CUBE_FACES: [Face<'static>; 6] = [
    Face { indices: &[1, 3, 7, 5], color: Rgb565::RED },
    Face { indices: &[0, 4, 6, 2], color: Rgb565::GREEN },
    Face { indices: &[2, 6, 7, 3], color: Rgb565::BLUE },
    Face { indices: &[0, 1, 5, 4], color: Rgb565::YELLOW },
    Face { indices: &[4, 5, 7, 6], color: Rgb565::CYAN },
    Face { indices: &[0, 2, 3, 1], color: Rgb565::MAGENTA },
];

#[entry]
fn main() -> ! {
    let mesh = Mesh { vertices: &CUBE_VERTICES, faces: &CUBE_FACES };
    let mut renderer = Scanline::<Q16_16, 240, 8, 32, 8>::new();
    defmt::info!("zrow: renderer RAM {} bytes", Scanline::<Q16_16, 240, 8, 32, 8>::RAM_BYTES);
    let cfg = Config::model(240, 240);
    let mut angle = 0.0f32;
    loop {
        let Some(transform) = Affine::rotate_yx_translate(angle, 0.4, [0.0, 0.0, 0.0]) else {
            continue;
        };
        let objects = [Object { mesh: &mesh, transform }];
        let (Some(projection), Some(direction)) = (
            Camera::perspective(1.0, 0.1, 20.0),
            Vec3::from_f32([0.3, 1.0, 0.6]),
        ) else {
            continue;
        };
        let Some(camera) = Camera::look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], projection)
        else {
            continue;
        };
        let scene = ModelScene {
            objects: &objects,
            camera,
            light: Light { direction, ambient: q(1) / 5 },
        };
        let mut sink = Checksum(0);
        match renderer.render(&scene, &cfg, &mut sink) {
            Ok(stats) => defmt::info!(
                "frame: {} polygons, {} edges, max active {}, checksum {=u32:x}",
                stats.polygons,
                stats.edges,
                stats.max_active,
                sink.0
            ),
            Err(_) => defmt::error!("frame failed"),
        }
        angle += 0.05;
    }
}
