//! The demo both board firmwares run: the simulator's demo scenes (`zrow_scenes::with_demo`,
//! const data in flash) turning in Q16.16, each for [`FRAMES_PER_SCENE`] frames, drawn by the
//! board's renderer into the board's DMA row sink (`zrow_st7789::dma::DmaRows`); every 32
//! frames a defmt log line with the cycles of the last frame (render, SPI wait, rows sent,
//! frames per second). Each board gives its renderer (sized to the scenes it shows), its DMA
//! link, its clock and its list of scenes; everything else is here, once.
#![no_std]

use cortex_m::peripheral::DWT;
use embedded_hal::digital::OutputPin;
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::{interface::SpiInterface, models::ST7789, options::ColorInversion, Builder};
use static_cell::ConstStaticCell;
use zrow::{Config, Renderer, Scene, Q16_16};
use zrow_st7789::dma::{DmaLink, DmaRows};

/// Bytes in one row (240 RGB565 pixels).
pub const ROW_BYTES: usize = 480;
/// Rows in a frame.
pub const ROWS: usize = 240;
/// The panel window the demo draws into: a 240×240 module.
pub const WINDOW: zrow_st7789::Window = zrow_st7789::Window::new(240, 240);

/// The DMA row sink of a demo board.
pub type Rows<L, DC> = DmaRows<L, DC, ROW_BYTES, ROWS>;

static ROW_A: ConstStaticCell<[u8; ROW_BYTES]> = ConstStaticCell::new([0; ROW_BYTES]);
static ROW_B: ConstStaticCell<[u8; ROW_BYTES]> = ConstStaticCell::new([0; ROW_BYTES]);

/// The board's row sink over its DMA `link` and DC pin, drawing into [`WINDOW`] from the demo's
/// two row buffers (statics, zeroed in `.bss`). Call it once: the buffers are handed out once
/// (a second call panics). Inlined into the board's `main`: called out of line, it changed
/// how `main` was inlined and cost the F411 image 5 KB of flash (measured).
#[inline(always)]
pub fn rows<L: DmaLink<ROW_BYTES>, DC: OutputPin>(link: L, dc: DC) -> Rows<L, DC> {
    match Rows::new(link, dc, WINDOW, ROW_A.take(), ROW_B.take()) {
        Ok(rows) => rows,
        Err(_) => panic!("the window does not fit the row buffers"),
    }
}

/// What draws one frame of a scene: calls its argument with the scene turned by the angle
/// (radians) and its configuration; `None` if the scene cannot be built.
pub type Draw = fn(f32, &mut dyn FnMut(&dyn Scene<Q16_16>, &Config)) -> Option<()>;

/// A demo scene a board shows: its name (for the log) and what draws it. A board lists only
/// the scenes it shows, so only their meshes are linked.
#[derive(Clone, Copy)]
pub struct Show {
    /// The scene's name in `zrow_scenes::DEMOS`.
    pub name: &'static str,
    /// One of `zrow_scenes::demo`'s functions.
    pub draw: Draw,
}

/// The interlocked rings and cube.
pub const INTERLOCKED: Show = Show {
    name: "interlocked",
    draw: |angle, f| zrow_scenes::demo::interlocked(angle, |s, c, _| f(s, c)),
};
/// The cube.
pub const CUBE: Show = Show {
    name: "cube",
    draw: |angle, f| zrow_scenes::demo::cube(angle, |s, c, _| f(s, c)),
};
/// The 1,000-triangle torus.
pub const MESH1K: Show = Show {
    name: "mesh1k",
    draw: |angle, f| zrow_scenes::demo::mesh1k(angle, |s, c, _| f(s, c)),
};
/// Every demo scene, in the simulator's order (`zrow_scenes::DEMOS`).
pub const ALL: [Show; 3] = [INTERLOCKED, CUBE, MESH1K];

/// Frames per demo scene. A static read at every frame, so a debugger, or the
/// board-in-the-loop test (`emu/board`), can shorten the scenes without another build.
#[no_mangle]
pub static FRAMES_PER_SCENE: u32 = 256;

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

/// Initialises a 240×240 ST7789 module (colours inverted, as these modules want) with mipidsi, through borrows so the SPI and pins come back
/// afterwards. Out of line, so the driver's state leaves the stack before the demo runs.
#[inline(never)]
pub fn init_panel<SPI, CS, DC, RST>(
    spi: &mut SPI,
    cs: &mut CS,
    dc: &mut DC,
    rst: RST,
    delay: &mut impl embedded_hal::delay::DelayNs,
) where
    SPI: embedded_hal::spi::SpiBus,
    CS: embedded_hal::digital::OutputPin<Error = core::convert::Infallible>,
    DC: embedded_hal::digital::OutputPin,
    RST: embedded_hal::digital::OutputPin,
{
    let Ok(device) = ExclusiveDevice::new_no_delay(spi, cs);
    let mut buffer = [0u8; 64];
    let interface = SpiInterface::new(device, dc, &mut buffer);
    if Builder::new(ST7789, interface)
        .display_size(240, 240)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(delay)
        .is_err()
    {
        defmt::error!("ST7789 init failed");
    }
}

/// Shows `scenes` in turn forever, each [`FRAMES_PER_SCENE`]
/// frames, turning 0.03 rad a frame (`zrow_scenes::board_angle`). `sysclk_hz` converts the cycle counts of the log (DWT's
/// cycle counter, which the board enables) to frames per second. A frame the renderer refuses
/// (a capacity error) is logged and not sent: the panel keeps its last frame.
pub fn run<R, L, DC>(renderer: &mut R, rows: &mut Rows<L, DC>, scenes: &[Show], sysclk_hz: u32) -> !
where
    R: Renderer<Q16_16>,
    L: DmaLink<ROW_BYTES>,
    DC: OutputPin,
{
    defmt::info!("zrow: renderer {} bytes of RAM, DMA rows", R::RAM_BYTES);
    let mut frame = 0u32;
    loop {
        // SAFETY: a plain read of an immutable static (volatile: a debugger may change it).
        let per_scene = unsafe { core::ptr::read_volatile(&FRAMES_PER_SCENE) }.max(1);
        let Some(show) = scenes.get((frame / per_scene) as usize % scenes.len().max(1)) else {
            defmt::error!("no scenes to show");
            loop {
                cortex_m::asm::wfi();
            }
        };
        let (name, angle) = (show.name, zrow_scenes::board_angle(frame));
        rows.wait_cycles = 0;
        let t0 = DWT::cycle_count();
        let mut result = None;
        let built = (show.draw)(angle, &mut |scene, cfg| {
            result = Some(renderer.render(scene, cfg, rows));
        });
        let cycles = DWT::cycle_count().wrapping_sub(t0);
        match result.filter(|_| built.is_some()) {
            Some(Ok(stats)) if frame.is_multiple_of(32) => defmt::info!(
                "{=str}: {} polygons, render {} cyc, SPI wait {} cyc, {} of 240 rows sent, {} fps",
                name,
                stats.polygons,
                cycles.wrapping_sub(rows.wait_cycles),
                rows.wait_cycles,
                rows.rows_sent,
                sysclk_hz / cycles.max(1)
            ),
            Some(Ok(_)) => {}
            Some(Err(e)) => defmt::error!("{=str}: {}", name, e),
            None => defmt::error!("no scene {=str}", name),
        }
        zrow_frame_done(frame);
        frame = frame.wrapping_add(1);
    }
}
