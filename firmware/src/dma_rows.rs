//! Rows to the ST7789 by DMA, double-buffered: while the DMA engine sends row y from one
//! buffer, the renderer computes row y + 1 and this sink encodes it into the other.
//!
//! Only the rows that changed since the last frame are sent (frame coherence on the wire,
//! `zrow_st7789::coherence`): the panel keeps its own memory. Each row's 32-bit signature is
//! compared with the one last sent; an unchanged row is skipped, a changed row after a gap
//! first gets the window (CASET once per frame, RASET from this row to the bottom) and RAMWR,
//! which puts the panel's address counter on it, and a changed row right after a sent one
//! simply follows. The first frame, and the frame after a DMA error, go whole.
//!
//! The HAL's DMA `Tx` half keeps the SPI for good, so those few command bytes are written
//! straight to SPI1's data register, DC low for a command and high for its parameters, once
//! the DMA stream and the SPI are idle. The bytes and commands are `zrow-st7789`'s, whose
//! panel model checks this protocol (`crates/zrow-st7789/tests/coherence.rs` drives a sender
//! built like this one over 200 frames of each demo scene).

use core::convert::Infallible;
use cortex_m::peripheral::DWT;
use embedded_hal::digital::OutputPin;
use stm32f4xx_hal::dma::{config::DmaConfig, MemoryToPeripheral, Stream3, Transfer};
use stm32f4xx_hal::pac::{self, DMA2, SPI1};
use stm32f4xx_hal::spi::Tx;
use zrow::{Row, RowSink};
use zrow_st7789::coherence::{open_run, Coherence, RowAction};
use zrow_st7789::{encode_row_signed, Window};

/// Bytes in one row (240 RGB565 pixels).
pub const ROW_BYTES: usize = 480;
/// A row buffer in RAM the DMA engine can read.
pub type RowBuf = &'static mut [u8; ROW_BYTES];
type SpiDma = Transfer<Stream3<DMA2>, 3, Tx<SPI1>, MemoryToPeripheral, RowBuf>;

enum State {
    /// Before the first row: the parts of a transfer and both buffers.
    Idle(Stream3<DMA2>, Tx<SPI1>, RowBuf, RowBuf),
    /// A transfer has been started (and may still be running); the other buffer is free.
    Running(SpiDma, RowBuf),
    /// Only while switching between the two.
    Switching,
}

/// The panel window the demo draws into.
const WINDOW: Window = Window::new(240, 240);

/// The DMA row sink.
pub struct DmaRows<DC> {
    state: State,
    dc: DC,
    /// The signatures of the rows on the panel (960 bytes).
    coherence: Coherence<240>,
    /// Rows sent in the current frame (the others were already on the panel).
    pub rows_sent: u32,
    /// Cycles spent waiting for the DMA engine or the SPI since the last reset: the part of
    /// sending that rendering did not hide.
    pub wait_cycles: u32,
    /// Rows the DMA engine refused (should stay 0).
    pub dropped: u32,
}

impl<DC: OutputPin> DmaRows<DC> {
    /// Takes DMA2 stream 3 (SPI1 TX, channel 3), the SPI's DMA half, the DC pin and two row
    /// buffers.
    pub fn new(stream: Stream3<DMA2>, tx: Tx<SPI1>, dc: DC, a: RowBuf, b: RowBuf) -> Self {
        DmaRows {
            state: State::Idle(stream, tx, a, b),
            dc,
            coherence: Coherence::new(),
            rows_sent: 0,
            wait_cycles: 0,
            dropped: 0,
        }
    }

    /// Opens a run of rows at row `y` (see `open_run`); the SPI must be idle (it is: callers
    /// wait first).
    fn open(&mut self, y: u16, caset: bool) {
        let _ = open_run(&WINDOW, y, caset, |c, p| -> Result<(), Infallible> {
            self.command(c, p);
            Ok(())
        });
    }

    /// One command byte with DC low, then its parameters with DC high, each shifted out
    /// completely before DC changes.
    fn command(&mut self, command: u8, params: &[u8]) {
        let _ = self.dc.set_low();
        write_byte(command);
        wait_spi_idle();
        let _ = self.dc.set_high();
        for &p in params {
            write_byte(p);
        }
        wait_spi_idle();
    }
}

/// Writes one byte to SPI1 once its transmit buffer is free.
fn write_byte(byte: u8) {
    // SAFETY: status polls and data-register writes of SPI1 while its DMA stream is idle
    // (every transfer has completed): nothing else touches SPI1 now.
    let spi = unsafe { &*pac::SPI1::ptr() };
    while spi.sr().read().txe().bit_is_clear() {}
    spi.dr().write(|w| unsafe { w.dr().bits(byte as u16) });
}

/// Waits until SPI1 has shifted out everything written to it.
fn wait_spi_idle() {
    // SAFETY: read-only status polls of SPI1.
    let spi = unsafe { &*pac::SPI1::ptr() };
    while spi.sr().read().txe().bit_is_clear() {}
    while spi.sr().read().bsy().bit_is_set() {}
}

impl<N, DC: OutputPin> RowSink<N> for DmaRows<DC> {
    type Error = Infallible;
    /// The panel takes colours only: the renderer need not write its depth row.
    const WANTS_DEPTH: bool = false;

    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Infallible> {
        if row.y == 0 {
            self.rows_sent = 0;
        }
        let mut waited = 0u32;
        self.state = match core::mem::replace(&mut self.state, State::Switching) {
            State::Idle(stream, tx, a, b) => {
                let (_, signature) = encode_row_signed(row.color, a);
                match self.coherence.row_signed(row.y, signature) {
                    RowAction::Skip => State::Idle(stream, tx, a, b),
                    // Nothing is open before the first transfer: always a new run.
                    RowAction::Continue | RowAction::Open { .. } => {
                        wait_spi_idle();
                        self.open(row.y, true);
                        let mut t = Transfer::init_memory_to_peripheral(
                            stream,
                            tx,
                            a,
                            None,
                            DmaConfig::default()
                                .memory_increment(true)
                                .fifo_enable(true),
                        );
                        t.start(|_| {});
                        self.rows_sent += 1;
                        State::Running(t, b)
                    }
                }
            }
            State::Running(mut t, spare) => {
                let (_, signature) = encode_row_signed(row.color, spare);
                let action = self.coherence.row_signed(row.y, signature);
                if action == RowAction::Skip {
                    State::Running(t, spare)
                } else {
                    let t0 = DWT::cycle_count();
                    t.wait(); // the previous row has left memory
                    if let RowAction::Open { caset } = action {
                        wait_spi_idle(); // ... and the SPI
                        self.open(row.y, caset);
                    }
                    waited = DWT::cycle_count().wrapping_sub(t0);
                    match t.next_transfer(spare) {
                        Ok((old, _)) => {
                            self.rows_sent += 1;
                            State::Running(t, old)
                        }
                        Err(e) => {
                            // The panel misses this row: send the next frame whole.
                            self.dropped += 1;
                            self.coherence.forget();
                            let buf = match e {
                                stm32f4xx_hal::dma::DMAError::NotReady(b)
                                | stm32f4xx_hal::dma::DMAError::SmallBuffer(b)
                                | stm32f4xx_hal::dma::DMAError::Overrun(b) => b,
                            };
                            State::Running(t, buf)
                        }
                    }
                }
            }
            State::Switching => State::Switching,
        };
        self.wait_cycles = self.wait_cycles.wrapping_add(waited);
        Ok(())
    }
}
