//! zrow on an STM32F103C8 "Blue Pill" (Cortex-M3, 72 MHz, no FPU, 20 KB of RAM, 64 KB of
//! flash) driving a 240×240 ST7789 over SPI1.
//!
//! The same demo as the F411 (`zrow_demo`): the panel is initialised with mipidsi, then rows
//! stream by DMA (DMA1 channel 3) from two row buffers, only the rows that changed since the
//! last frame (`zrow_st7789::dma`, over this board's link in `link`). No frame buffer could
//! fit here: a 240×240 RGB565 frame is 112.5 KB.
//!
//! It shows the demo scenes that fit its RAM: the interlocked rings and the cube (the
//! 1,000-triangle torus's renderer would leave the stack too little room; README, "The Blue
//! Pill", has the figures).
//!
//! Wiring (README): SCK PA5, MOSI PA7, CS PA4, DC PA3, RST PA2, backlight PA1 — the F411's.
#![no_std]
#![no_main]

mod link;

use cortex_m_rt::entry;
use defmt_rtt as _;
use static_cell::ConstStaticCell;
use stm32f1xx_hal::{
    pac,
    prelude::*,
    rcc,
    spi::{Mode, Phase, Polarity},
};
use zrow::Q16_16;

/// System clock.
const SYSCLK_HZ: u32 = 72_000_000;
/// The demo scenes this board shows (those its RAM holds).
const SCENES: [zrow_demo::Show; 2] = [zrow_demo::INTERLOCKED, zrow_demo::CUBE];
/// The renderer, sized to those scenes: what the interlocked scene needs at most over a turn
/// (it needs more of everything than the cube), plus 5 % (`zrow_scenes::DEMO_MEASURED_EACH`,
/// checked by `crates/zrow-scenes/tests/demos.rs`).
type Renderer = zrow::scanline_for!(
    Q16_16,
    zrow_scenes::DEMO_MEASURED_EACH[0].with_margin(5),
    display
);

static RENDERER: ConstStaticCell<Renderer> = ConstStaticCell::new(Renderer::new());

#[entry]
fn main() -> ! {
    let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), cortex_m::Peripherals::take()) else {
        panic!("peripherals taken twice");
    };
    let mut flash = dp.FLASH.constrain();
    // 8 MHz crystal, PLL to 72 MHz; SPI1 sits on APB2 (72 MHz), its fastest clock 36 MHz.
    let mut rcc = dp.RCC.freeze(
        rcc::Config::hse(8.MHz()).sysclk(72.MHz()).pclk1(36.MHz()),
        &mut flash.acr,
    );
    cp.DCB.enable_trace();
    cp.DWT.enable_cycle_counter();
    let mut delay = cp.SYST.delay(&rcc.clocks);

    let mut gpioa = dp.GPIOA.split(&mut rcc);
    let mut cs = gpioa.pa4.into_push_pull_output(&mut gpioa.crl);
    let mut dc = gpioa.pa3.into_push_pull_output(&mut gpioa.crl);
    let rst = gpioa.pa2.into_push_pull_output(&mut gpioa.crl);
    let mut backlight = gpioa.pa1.into_push_pull_output(&mut gpioa.crl);
    // Mode 3 works for modules with and without a CS pin.
    let mode = Mode {
        polarity: Polarity::IdleHigh,
        phase: Phase::CaptureOnSecondTransition,
    };
    let mut spi = dp.SPI1.spi(
        (Some(gpioa.pa5), pac::SPI1::NoMiso, Some(gpioa.pa7)),
        mode,
        36.MHz(),
        &mut rcc,
    );

    zrow_demo::init_panel(&mut spi, &mut cs, &mut dc, rst, &mut delay);
    // CS stays low from here on: the row sink owns the bus.
    cs.set_low();
    backlight.set_high();

    let dma = dp.DMA1.split(&mut rcc);
    let link = link::Link::new(spi.with_tx_dma(dma.3));
    let mut rows = zrow_demo::rows(link, dc);
    zrow_demo::run(RENDERER.take(), &mut rows, &SCENES, SYSCLK_HZ)
}
