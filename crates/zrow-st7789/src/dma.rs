//! Rows to the panel by DMA, double-buffered, only the rows that changed: the row sink both
//! board firmwares use, over a board's SPI transmit DMA ([`DmaLink`]).
//!
//! While the DMA engine sends row *y* from one buffer, the renderer computes row *y + 1* and
//! [`DmaRows`] encodes it into the other. Each row's 32-bit signature is compared with the one
//! last sent ([`Coherence`]): an unchanged row is skipped; a changed row after a gap first gets
//! the window (CASET once per frame, RASET from this row to the bottom) and RAMWR, which puts
//! the panel's address counter on it; a changed row right after a sent one simply follows. The
//! first frame, and the frame after a row the DMA engine refused, go whole.
//!
//! The few command bytes of a window go straight to the SPI, through [`DmaLink::write`], once
//! the DMA engine and the SPI are idle ([`DmaLink::flush`]): command byte with DC low, then its
//! parameters with DC high.
//!
//! The board gives a [`DmaLink`] (its HAL's DMA transfer of a `&'static mut` buffer) and the
//! DC pin; the panel model checks this sender on the host through a link that feeds the model
//! (`tests/coherence.rs`: 200 frames of each demo scene, and a link that refuses rows).

use crate::coherence::{open_run, Coherence, RowAction};
use crate::rows::encode_row_signed;
use crate::Window;
use embedded_hal::digital::OutputPin;
use zrow::{Row, RowSink};

/// A row buffer the DMA engine reads: `B` bytes in RAM for good.
pub type RowBuf<const B: usize> = &'static mut [u8; B];

/// A board's SPI transmit DMA, as [`DmaRows`] drives it.
pub trait DmaLink<const B: usize> {
    /// Waits until the transfer in flight, if any, has left memory, then starts sending `buf`
    /// and gives back the previous transfer's buffer (`None` before the first). `Err(buf)`:
    /// the engine refused `buf` (its row is lost; the sender sends the next frame whole).
    fn send(&mut self, buf: RowBuf<B>) -> Result<Option<RowBuf<B>>, RowBuf<B>>;

    /// Waits until the transfer in flight, if any, is done and the SPI has shifted out its
    /// last byte.
    fn flush(&mut self);

    /// Writes `bytes` to the SPI without DMA and waits until they are shifted out (called
    /// only after [`DmaLink::flush`]).
    fn write(&mut self, bytes: &[u8]);

    /// A free-running cycle counter, to measure the time spent waiting for the engine
    /// ([`DmaRows::wait_cycles`]); 0 if the board has none.
    fn now(&self) -> u32 {
        0
    }
}

/// The double-buffered, coherent DMA row sink for a window of `H` rows of `B` bytes.
pub struct DmaRows<L, DC, const B: usize, const H: usize> {
    link: L,
    dc: DC,
    window: Window,
    /// The buffer the next row is encoded into.
    spare: Option<RowBuf<B>>,
    /// The second buffer, until the first transfer gives it a turn.
    second: Option<RowBuf<B>>,
    /// The signatures of the rows on the panel (4 bytes a row).
    coherence: Coherence<H>,
    /// Rows sent in the current frame (the others were already on the panel).
    pub rows_sent: u32,
    /// Cycles ([`DmaLink::now`]) spent waiting for the DMA engine or the SPI since the owner
    /// last reset it: the part of sending that rendering did not hide.
    pub wait_cycles: u32,
    /// Rows the DMA engine refused (should stay 0).
    pub dropped: u32,
}

impl<L: DmaLink<B>, DC: OutputPin, const B: usize, const H: usize> DmaRows<L, DC, B, H> {
    /// A sender over `link` with the DC pin and two row buffers, drawing into `window`, whose
    /// rows are `B / 2` pixels wide (the renderer's frame width): fails like
    /// [`crate::CoherentRows::new`] (a window that does not fit the panel or a buffer, or more
    /// rows than `H` signatures).
    pub fn new(
        link: L,
        dc: DC,
        window: Window,
        a: RowBuf<B>,
        b: RowBuf<B>,
    ) -> Result<Self, crate::StreamError> {
        window.check(B)?;
        if (window.height as usize) > H {
            return Err(crate::StreamError::TooFewSignatures {
                height: window.height,
                capacity: u32::try_from(H).unwrap_or(u32::MAX),
            });
        }
        Ok(DmaRows {
            link,
            dc,
            window,
            spare: Some(a),
            second: Some(b),
            coherence: Coherence::new(),
            rows_sent: 0,
            wait_cycles: 0,
            dropped: 0,
        })
    }

    /// Waits until the last row handed over has left (the DMA engine and the SPI idle).
    pub fn flush(&mut self) {
        self.link.flush();
    }

    /// Sends the next frame whole (after anything else wrote to the panel).
    pub fn forget(&mut self) {
        self.coherence.forget();
    }

    /// Opens a run of rows at row `y` (see [`open_run`]); the link is flushed first.
    fn open(&mut self, y: u16, caset: bool) {
        self.link.flush();
        let (link, dc) = (&mut self.link, &mut self.dc);
        let _ = open_run(&self.window, y, caset, |command, params| {
            // One command byte with DC low, then its parameters with DC high, each shifted
            // out completely before DC changes.
            dc.set_low()?;
            link.write(&[command]);
            dc.set_high()?;
            link.write(params);
            Ok::<(), DC::Error>(())
        });
    }
}

impl<N, L: DmaLink<B>, DC: OutputPin, const B: usize, const H: usize> RowSink<N>
    for DmaRows<L, DC, B, H>
{
    type Error = core::convert::Infallible;
    /// The panel takes colours only: the renderer need not write its depth row.
    const WANTS_DEPTH: bool = false;

    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Self::Error> {
        if row.y == 0 {
            self.rows_sent = 0;
        }
        let Some(buf) = self.spare.take() else {
            // A link that kept a buffer (against `DmaLink::send`'s contract): this row is
            // lost, and the next frame goes whole.
            self.dropped += 1;
            self.coherence.forget();
            return Ok(());
        };
        let (_, signature) = encode_row_signed(row.color, buf);
        let action = self.coherence.row_signed(row.y, signature);
        // Before the first transfer nothing is open: always a new run, with its columns.
        let action = match (action, self.second.is_some()) {
            (RowAction::Skip, _) => {
                self.spare = Some(buf);
                return Ok(());
            }
            (_, true) => RowAction::Open { caset: true },
            (action, false) => action,
        };
        let t0 = self.link.now();
        if let RowAction::Open { caset } = action {
            self.open(row.y, caset);
        }
        self.spare = match self.link.send(buf) {
            Ok(previous) => {
                self.rows_sent += 1;
                previous.or_else(|| self.second.take())
            }
            Err(buf) => {
                // The panel misses this row: send the next frame whole.
                self.dropped += 1;
                self.coherence.forget();
                Some(buf)
            }
        };
        self.wait_cycles = self
            .wait_cycles
            .wrapping_add(self.link.now().wrapping_sub(t0));
        Ok(())
    }
}
