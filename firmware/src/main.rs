//! zrow on an STM32F411 "Black Pill" driving a 240×240 ST7789 over SPI1.
//!
//! The panel is initialised with mipidsi; after that rows stream by DMA: a row leaves from one
//! of two buffers while the renderer computes the next row into the other, and only the rows
//! that changed since the last frame are sent, consecutive ones under one window
//! (`zrow_st7789::dma`, over this board's DMA link in `link`).
//!
//! The demo (`zrow_demo`, shared with the Blue Pill) shows the simulator's scenes: two linked
//! rings pierced by a cube, the cube, and the 1,000-triangle torus, turning, in Q16.16. Every
//! 32 frames it logs, through defmt, the cycles of the last frame (DWT CYCCNT at 100 MHz):
//! render, SPI wait (sending that rendering did not hide), the rows sent, and frames per
//! second.
//!
//! Wiring (README): SCK PA5, MOSI PA7, CS PA4, DC PA3, RST PA2, backlight PA1.
#![no_std]
#![no_main]

mod link;

use cortex_m_rt::entry;
use defmt_rtt as _;
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
type Renderer = zrow::scanline_for!(Q16_16, zrow_scenes::DEMO_REQUIREMENTS, display);

static RENDERER: ConstStaticCell<Renderer> = ConstStaticCell::new(Renderer::new());

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

    zrow_demo::init_panel(&mut spi, &mut cs, &mut dc, rst, &mut delay);
    // CS stays low from here on: the row sink owns the bus.
    cs.set_low();
    backlight.set_high();

    let streams = StreamsTuple::new(dp.DMA2, &mut rcc);
    let link = link::Link::new(streams.3, spi.use_dma().tx());
    let mut rows = zrow_demo::rows(link, dc);
    zrow_demo::run(RENDERER.take(), &mut rows, &zrow_demo::ALL, SYSCLK_HZ)
}
