//! zrow on an STM32F411 "Black Pill" driving a 240×240 ST7789 over SPI1.
//!
//! The panel is initialised with mipidsi; after that the firmware streams rows itself: a row
//! leaves by DMA from one of two buffers while the renderer computes the next row into the
//! other, and only the rows that changed since the last frame are sent, consecutive ones under
//! one window (see `dma_rows`).
//!
//! The demo shows the simulator's scenes (`zrow_scenes::DEMOS`, const data in flash): two
//! linked rings pierced by a cube, the cube, and the 1,000-triangle torus, turning, in Q16.16. Every 32 frames it logs, through
//! defmt, the cycles of the last frame (DWT CYCCNT at 100 MHz): render, SPI wait (sending that
//! rendering did not hide), the rows sent, and frames per second.
//!
//! Wiring (README): SCK PA5, MOSI PA7, CS PA4, DC PA3, RST PA2, backlight PA1.
#![no_std]
#![no_main]

mod dma_rows;

use cortex_m::peripheral::DWT;
use cortex_m_rt::entry;
use defmt_rtt as _;
use dma_rows::{DmaRows, ROW_BYTES};
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
use static_cell::ConstStaticCell;
use stm32f4xx_hal::{
    dma::StreamsTuple,
    gpio::Speed,
    pac,
    prelude::*,
    rcc,
    spi::{Mode, Phase, Polarity},
};
use zrow::Q16_16;

/// System clock.
const SYSCLK_HZ: u32 = 100_000_000;
/// The renderer, sized to the demo scenes: what they need at most over a turn plus 5 %
/// (`zrow_scenes::DEMO_REQUIREMENTS`, measured with `zrow::requirements`; the torus needs 463
/// polygons, 500 vertices, 67 active; `crates/zrow-scenes/tests/demos.rs` checks it).
type Renderer = zrow::scanline_for!(Q16_16, zrow_scenes::DEMO_REQUIREMENTS);

static RENDERER: ConstStaticCell<Renderer> = ConstStaticCell::new(Renderer::new());
static ROW_A: ConstStaticCell<[u8; ROW_BYTES]> = ConstStaticCell::new([0; ROW_BYTES]);
static ROW_B: ConstStaticCell<[u8; ROW_BYTES]> = ConstStaticCell::new([0; ROW_BYTES]);

/// Frames per demo scene (the simulator's demos, `zrow_scenes::DEMOS`). A static read at
/// every frame, so a debugger, or the board-in-the-loop test (`emu/board`), can shorten the
/// scenes without another build.
#[no_mangle]
static FRAMES_PER_SCENE: u32 = 256;

/// Called after every frame with its number, once its last row is handed to the DMA engine:
/// a place for a debugger's breakpoint, and the frame marker of the board-in-the-loop test.
/// Does nothing.
#[no_mangle]
#[inline(never)]
pub extern "C" fn zrow_frame_done(frame: u32) {
    core::hint::black_box(frame);
}

/// A panic (none is expected: the core reports bad input as errors) logs where it happened
/// and stops on a fault. Only the location is logged: the message would pull in `core::fmt`,
/// several kilobytes of flash.
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    cortex_m::interrupt::disable();
    match info.location() {
        Some(at) => defmt::error!("panic at {=str}:{=u32}", at.file(), at.line()),
        None => defmt::error!("panic"),
    }
    cortex_m::asm::udf()
}

#[entry]
fn main() -> ! {
    let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        panic!("peripherals taken twice");
    };
    let mut rcc = dp.RCC.freeze(rcc::Config::hse(25.MHz()).sysclk(100.MHz()));
    cp.DCB.enable_trace();
    cp.DWT.enable_cycle_counter();
    let mut delay = cp.SYST.delay(&rcc.clocks);

    let gpioa = dp.GPIOA.split(&mut rcc);
    let sck = gpioa.pa5.into_alternate().speed(Speed::VeryHigh);
    let mosi = gpioa.pa7.into_alternate().speed(Speed::VeryHigh);
    let mut cs = gpioa.pa4.into_push_pull_output();
    let mut dc = gpioa.pa3.into_push_pull_output();
    let rst = gpioa.pa2.into_push_pull_output();
    let mut backlight = gpioa.pa1.into_push_pull_output();
    // Mode 3 works for modules with and without a CS pin; 50 MHz is SPI1's fastest (APB2/2).
    let mode = Mode {
        polarity: Polarity::IdleHigh,
        phase: Phase::CaptureOnSecondTransition,
    };
    let mut spi = dp.SPI1.spi(
        (Some(sck), pac::SPI1::NoMiso, Some(mosi)),
        mode,
        50.MHz(),
        &mut rcc,
    );

    // Panel initialisation with mipidsi, through borrows so the SPI comes back afterwards.
    {
        let Ok(device) = ExclusiveDevice::new_no_delay(&mut spi, &mut cs);
        let mut buffer = [0u8; 64];
        let interface = SpiInterface::new(device, &mut dc, &mut buffer);
        if Builder::new(ST7789, interface)
            .display_size(240, 240)
            .invert_colors(ColorInversion::Inverted)
            .reset_pin(rst)
            .init(&mut delay)
            .is_err()
        {
            defmt::error!("ST7789 init failed");
        }
    }
    // CS stays low from here on: the row sink owns the bus.
    cs.set_low();
    backlight.set_high();

    let streams = StreamsTuple::new(dp.DMA2, &mut rcc);
    let mut rows = DmaRows::new(
        streams.3,
        spi.use_dma().tx(),
        dc,
        ROW_A.take(),
        ROW_B.take(),
    );
    let renderer = RENDERER.take();
    defmt::info!(
        "zrow: renderer {} bytes of RAM; SPI1 50 MHz, DMA rows",
        Renderer::RAM_BYTES
    );

    let mut frame = 0u32;
    loop {
        let demos = zrow_scenes::DEMOS;
        // SAFETY: a plain read of an immutable static (volatile: a debugger may change it).
        let per_scene = unsafe { core::ptr::read_volatile(&FRAMES_PER_SCENE) }.max(1);
        let name = demos[(frame / per_scene) as usize % demos.len()];
        let angle = frame as f32 * 0.03;
        rows.wait_cycles = 0;
        let t0 = DWT::cycle_count();
        let result = zrow_scenes::with_demo::<Q16_16, _>(name, angle, |scene, cfg, _| {
            renderer.render(scene, cfg, &mut rows)
        });
        let cycles = DWT::cycle_count().wrapping_sub(t0);
        match result {
            Some(Ok(stats)) if frame.is_multiple_of(32) => defmt::info!(
                "{=str}: {} polygons, render {} cyc, SPI wait {} cyc, {} of 240 rows sent, {} fps",
                name,
                stats.polygons,
                cycles.wrapping_sub(rows.wait_cycles),
                rows.wait_cycles,
                rows.rows_sent,
                SYSCLK_HZ / cycles.max(1)
            ),
            Some(Ok(_)) => {}
            Some(Err(e)) => defmt::error!("{=str}: {}", name, e),
            None => defmt::error!("no scene {=str}", name),
        }
        zrow_frame_done(frame);
        frame = frame.wrapping_add(1);
    }
}
