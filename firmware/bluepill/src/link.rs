//! The F103's SPI transmit DMA as the demo's row sink drives it (`zrow_st7789::dma::DmaLink`):
//! SPI1 TX on DMA1 channel 3, through stm32f1xx-hal's one-shot `Transfer` (it gives back the
//! buffer and the channel when waited for; the next row starts a new one).
//!
//! The HAL's `SpiTxDma` keeps the SPI, so the few command bytes of a window are written
//! straight to SPI1's data register, once the DMA channel and the SPI are idle.

use cortex_m::peripheral::DWT;
use stm32f1xx_hal::dma::{Transfer, WriteDma, R};
use stm32f1xx_hal::pac;
use stm32f1xx_hal::spi::Spi1TxDma;
use zrow_demo::ROW_BYTES;
use zrow_st7789::dma::{DmaLink, RowBuf};

/// SPI1 TX by DMA1 channel 3.
pub struct Link(State);

enum State {
    /// No transfer since the last wait; the last transfer's buffer, if any.
    Idle(Spi1TxDma, Option<RowBuf<ROW_BYTES>>),
    /// A transfer has been started (it may still be running).
    Running(Transfer<R, RowBuf<ROW_BYTES>, Spi1TxDma>),
    /// Only while switching between the two.
    Switching,
}

impl Link {
    /// Takes the SPI with its DMA channel.
    pub fn new(tx: Spi1TxDma) -> Self {
        Link(State::Idle(tx, None))
    }

    /// Waits for the transfer in flight, if any.
    fn wait(&mut self) {
        self.0 = match core::mem::replace(&mut self.0, State::Switching) {
            State::Running(t) => {
                let (buf, tx) = t.wait();
                State::Idle(tx, Some(buf))
            }
            other => other,
        };
    }
}

impl DmaLink<ROW_BYTES> for Link {
    fn send(
        &mut self,
        buf: RowBuf<ROW_BYTES>,
    ) -> Result<Option<RowBuf<ROW_BYTES>>, RowBuf<ROW_BYTES>> {
        self.wait(); // the previous row has left memory
        match core::mem::replace(&mut self.0, State::Switching) {
            State::Idle(tx, previous) => {
                self.0 = State::Running(tx.write(buf));
                Ok(previous)
            }
            other => {
                self.0 = other;
                Err(buf)
            }
        }
    }

    fn flush(&mut self) {
        self.wait();
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
    // SAFETY: status polls and data-register writes of SPI1 while its DMA channel is idle
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
