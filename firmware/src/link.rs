//! The F411's SPI transmit DMA as the demo's row sink drives it (`zrow_st7789::dma::DmaLink`):
//! SPI1 TX on DMA2 stream 3, channel 3, through stm32f4xx-hal's double-buffering `Transfer`.
//!
//! The HAL's DMA `Tx` half keeps the SPI for good, so the few command bytes of a window are
//! written straight to SPI1's data register, once the DMA stream and the SPI are idle.

use cortex_m::peripheral::DWT;
use stm32f4xx_hal::dma::{config::DmaConfig, DMAError, MemoryToPeripheral, Stream3, Transfer};
use stm32f4xx_hal::pac::{self, DMA2, SPI1};
use stm32f4xx_hal::spi::Tx;
use zrow_demo::ROW_BYTES;
use zrow_st7789::dma::{DmaLink, RowBuf};

type SpiDma = Transfer<Stream3<DMA2>, 3, Tx<SPI1>, MemoryToPeripheral, RowBuf<ROW_BYTES>>;

/// SPI1 TX by DMA2 stream 3.
pub struct Link(State);

enum State {
    /// Before the first row.
    Idle(Stream3<DMA2>, Tx<SPI1>),
    /// A transfer has been started (it may still be running); it holds its buffer.
    Running(SpiDma),
    /// Only while switching between the two.
    Switching,
}

impl Link {
    /// Takes DMA2 stream 3 and the SPI's DMA half.
    pub fn new(stream: Stream3<DMA2>, tx: Tx<SPI1>) -> Self {
        Link(State::Idle(stream, tx))
    }
}

impl DmaLink<ROW_BYTES> for Link {
    fn send(
        &mut self,
        buf: RowBuf<ROW_BYTES>,
    ) -> Result<Option<RowBuf<ROW_BYTES>>, RowBuf<ROW_BYTES>> {
        let (state, result) = match core::mem::replace(&mut self.0, State::Switching) {
            State::Idle(stream, tx) => {
                let config = DmaConfig::default()
                    .memory_increment(true)
                    .fifo_enable(true);
                let mut t = Transfer::init_memory_to_peripheral(stream, tx, buf, None, config);
                t.start(|_| {});
                (State::Running(t), Ok(None))
            }
            State::Running(mut t) => {
                t.wait(); // the previous row has left memory
                let result = match t.next_transfer(buf) {
                    Ok((old, _)) => Ok(Some(old)),
                    Err(
                        DMAError::NotReady(b) | DMAError::SmallBuffer(b) | DMAError::Overrun(b),
                    ) => Err(b),
                };
                (State::Running(t), result)
            }
            State::Switching => (State::Switching, Err(buf)),
        };
        self.0 = state;
        result
    }

    fn flush(&mut self) {
        if let State::Running(t) = &mut self.0 {
            t.wait();
        }
        wait_spi_idle();
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            write_byte(b);
        }
        wait_spi_idle();
    }

    fn now(&self) -> u32 {
        DWT::cycle_count()
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
