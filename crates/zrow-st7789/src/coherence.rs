//! Frame coherence on the wire: only the rows that changed since the last frame are sent.
//!
//! The ST7789 keeps its own frame memory, so a row equal to the one the panel already shows
//! need not cross the SPI again. [`Coherence`] keeps a 32-bit signature of each row last sent
//! (4 bytes a row: 960 bytes for 240 rows) and tells the sender, row by row, what to do
//! ([`RowAction`]): skip an unchanged row; send a changed row that follows a sent one (the
//! panel's address counter is already there); or, for a changed row after a gap, first set
//! `RASET` from this row to the window's last ([`Window::raset_from`]) and send `RAMWR`, so
//! consecutive changed rows share one address window. The window keeps ending at the bottom:
//! the sender never needs to know how long a run of changed rows is, and the next command
//! ends it. `CASET` (the whole width) goes before the first run of each frame.
//!
//! Columns are not narrowed: a signature says that a row changed, not where, and a row of a
//! turning object usually changes over most of its covered width anyway.
//!
//! Everything is sent when nothing is known of the panel's memory: the first frame, and the
//! frame after [`Coherence::forget`], which a sender calls on any send error and whenever
//! something else wrote to the panel (another driver, a new window, a reset).
//!
//! [`row_signature`] mixes the row's bytes 32 bits at a time through a bijection, so a row
//! whose bytes changed within one aligned 4-byte word (two pixels) always gets a new
//! signature; a wider change keeps the old one with a chance of about 2^-32 per changed row,
//! and such a row would stay stale on the panel until it changes again. A refresh period
//! ([`Coherence::with_refresh`]) bounds that: every so many frames are sent whole.
//!
//! [`CoherentRows`] is the blocking row sink built on it; firmware that
//! sends rows by DMA uses [`Coherence`] directly (see the repository's `firmware/`).
//!
//! [`Window::raset_from`]: crate::Window::raset_from

use crate::command::{self, CASET, RAMWR, RASET};
use crate::{Error, St7789Rows, StreamError, Window};
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiDevice;
use zrow::{Row, RowSink};

/// What to send for one row, as [`Coherence::row`] decides it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RowAction {
    /// The panel already shows this row: send nothing.
    Skip,
    /// The row follows the last row sent: send its bytes (DC high) in the open `RAMWR`.
    Continue,
    /// A changed row after a gap (or the frame's first): send `CASET` with the window's
    /// columns if `caset`, then `RASET` from this row to the window's last
    /// ([`Window::raset_from`](crate::Window::raset_from)), `RAMWR`, and the row's bytes.
    Open {
        /// Whether `CASET` must go first (the first run of a frame).
        caset: bool,
    },
}

/// Sends, through `send(command, parameters)`, what opens a run of rows at the window's row
/// `row`: `CASET` with the window's columns if `caset`, `RASET` from `row` to the window's
/// last row, then `RAMWR` (the panel's address counter goes to the run's first pixel). Stops
/// at the first error. [`CoherentRows`] sends [`RowAction::Open`] with it; a DMA firmware
/// calls it with its own command writer.
///
/// ```
/// use zrow_st7789::coherence::open_run;
/// use zrow_st7789::{command, Window};
/// let mut sent = Vec::new();
/// open_run(&Window::new(240, 240), 100, true, |c, p| -> Result<(), ()> {
///     sent.push((c, p.to_vec()));
///     Ok(())
/// })
/// .unwrap();
/// assert_eq!(sent, [
///     (command::CASET, vec![0, 0, 0, 239]),
///     (command::RASET, vec![0, 100, 0, 239]),
///     (command::RAMWR, vec![]),
/// ]);
/// ```
pub fn open_run<E>(
    window: &Window,
    row: u16,
    caset: bool,
    mut send: impl FnMut(u8, &[u8]) -> Result<(), E>,
) -> Result<(), E> {
    if caset {
        send(CASET, &window.caset())?;
    }
    send(RASET, &window.raset_from(row))?;
    send(RAMWR, &[])
}

/// The signature of one encoded row: its bytes mixed four at a time (little-endian words, a
/// short last word padded with zeros) by `h ← (rotl(h, 5) ⊕ w) · 0x9E3779B1`, then
/// scrambled once more. Each step is a bijection of `h` for a given word and of the word for
/// a given `h`, so two rows that differ within a single aligned word never share a signature.
///
/// ```
/// use zrow_st7789::coherence::row_signature;
/// let a = [0u8; 480];
/// let mut b = a;
/// b[101] = 1;
/// assert_ne!(row_signature(&a), row_signature(&b));
/// ```
pub fn row_signature(bytes: &[u8]) -> u32 {
    let mut h = Signature::new(bytes.len());
    let mut words = bytes.chunks_exact(4);
    for w in &mut words {
        h.mix(u32::from_le_bytes([w[0], w[1], w[2], w[3]]));
    }
    let rest = words.remainder();
    if !rest.is_empty() {
        let mut w = [0u8; 4];
        w[..rest.len()].copy_from_slice(rest);
        h.mix(u32::from_le_bytes(w));
    }
    h.finish()
}

/// [`row_signature`] as it goes: started with the row's length in bytes, fed its bytes as
/// little-endian words (a short last word padded with zeros), finished once. Lets
/// [`crate::encode_row_signed`] sign a row while encoding it, in the same pass.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Signature(u32);

impl Signature {
    #[inline]
    pub(crate) fn new(len: usize) -> Self {
        Signature(len as u32)
    }

    #[inline]
    pub(crate) fn mix(&mut self, word: u32) {
        const K: u32 = 0x9E37_79B1;
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(K);
    }

    /// Murmur3's finaliser: spreads every bit of the state over the result (a bijection too).
    #[inline]
    pub(crate) fn finish(self) -> u32 {
        let mut h = self.0;
        h ^= h >> 16;
        h = h.wrapping_mul(0x85EB_CA6B);
        h ^= h >> 13;
        h = h.wrapping_mul(0xC2B2_AE35);
        h ^ (h >> 16)
    }
}

/// The signatures of the rows last sent to the panel, for `H` rows at most (the window's
/// height), and the decision per row. See the module documentation.
///
/// ```
/// use zrow_st7789::coherence::{Coherence, RowAction};
/// let mut c = Coherence::<3>::new();
/// let (a, b) = ([1u8; 8], [2u8; 8]);
/// // The first frame: everything, in one run.
/// assert_eq!(c.row(0, &a), RowAction::Open { caset: true });
/// assert_eq!(c.row(1, &a), RowAction::Continue);
/// assert_eq!(c.row(2, &a), RowAction::Continue);
/// // The next frame: only row 1 changed.
/// assert_eq!(c.row(0, &a), RowAction::Skip);
/// assert_eq!(c.row(1, &b), RowAction::Open { caset: true });
/// assert_eq!(c.row(2, &a), RowAction::Skip);
/// ```
#[derive(Clone, Debug)]
pub struct Coherence<const H: usize> {
    signatures: [u32; H],
    /// Whether `signatures` describe what the panel shows.
    known: bool,
    /// Whether every row of the current frame is sent.
    whole: bool,
    /// The row the open `RAMWR` would write next, if one is open in this frame.
    next: Option<u16>,
    /// Whether `CASET` has gone in this frame.
    caset_sent: bool,
    /// Send a whole frame every `refresh` frames (0: never).
    refresh: u16,
    /// Frames since the last whole one.
    since_whole: u16,
}

impl<const H: usize> Default for Coherence<H> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const H: usize> Coherence<H> {
    /// Nothing known of the panel yet (the first frame is sent whole); no refresh period.
    /// A `const fn`, so it can initialise a `static` (zeroed, in `.bss`).
    pub const fn new() -> Self {
        Coherence {
            signatures: [0; H],
            known: false,
            whole: true,
            next: None,
            caset_sent: false,
            refresh: 0,
            since_whole: 0,
        }
    }

    /// The same, with every `frames`-th frame sent whole (0: never), which bounds how long a
    /// row whose change kept its signature (a chance of about 2^-32) can stay stale.
    pub const fn with_refresh(frames: u16) -> Self {
        let mut c = Self::new();
        c.refresh = frames;
        c
    }

    /// Forgets what the panel shows: the rest of this frame and the next frame are sent
    /// whole. Call it after any send error, and when something else has written to the panel
    /// or changed its address window.
    pub fn forget(&mut self) {
        self.known = false;
        self.whole = true;
        self.next = None;
        self.caset_sent = false;
    }

    /// Whether the current frame is being sent whole (the first, after [`Self::forget`], or
    /// a refresh).
    pub fn sending_whole(&self) -> bool {
        self.whole
    }

    /// Decides what to send for row `y` of the frame, whose encoded bytes are `bytes`, and
    /// records its signature as sent. Row 0 starts a frame; rows come top to bottom. A row
    /// past `H` is always sent, with its own window (`Open`): nothing is recorded for it.
    /// If sending what this returns fails, call [`Self::forget`].
    pub fn row(&mut self, y: u16, bytes: &[u8]) -> RowAction {
        self.row_signed(y, row_signature(bytes))
    }

    /// [`Self::row`] for a row whose signature is already known: [`row_signature`] of its
    /// encoded bytes, as [`crate::encode_row_signed`] gives it in the encoding pass.
    pub fn row_signed(&mut self, y: u16, signature: u32) -> RowAction {
        if y == 0 {
            self.since_whole = self.since_whole.wrapping_add(1);
            let refresh = self.refresh != 0 && self.since_whole >= self.refresh;
            self.whole = !self.known || refresh;
            if self.whole {
                self.since_whole = 0;
            }
            self.known = true;
            self.next = None;
            self.caset_sent = false;
        }
        let changed = match self.signatures.get_mut(y as usize) {
            Some(s) => {
                let changed = self.whole || *s != signature;
                *s = signature;
                changed
            }
            None => true,
        };
        if !changed {
            self.next = None;
            return RowAction::Skip;
        }
        let action = if self.next == Some(y) && (y as usize) < H {
            RowAction::Continue
        } else {
            RowAction::Open {
                caset: !self.caset_sent,
            }
        };
        self.caset_sent = true;
        self.next = y.checked_add(1);
        action
    }
}

/// The blocking row sink that sends only the rows that changed ([`Coherence`] over an
/// [`St7789Rows`]): the same wiring, window and line buffer `B`; `H` signatures, at least the
/// window's height (240 rows: 960 bytes).
///
/// Per frame: [`begin_frame`](Self::begin_frame) (it sends nothing), then rows `0..height`
/// through [`RowSink::write_row`]. A row equal to the one the panel shows is not sent; a run of
/// changed rows is sent under one `RASET`/`RAMWR`. The first frame, and the frame after any
/// error or [`command`](Self::command), are sent whole.
///
/// ```
/// use zrow_st7789::mock::MockBus;
/// use zrow_st7789::{CoherentRows, Window};
/// let bus = MockBus::new();
/// let mut rows =
///     CoherentRows::<_, _, 480, 240>::new(bus.spi(), bus.dc(), Window::new(240, 240)).unwrap();
/// rows.init(&mut bus.delay()).unwrap();
/// ```
pub struct CoherentRows<SPI, DC, const B: usize, const H: usize> {
    rows: St7789Rows<SPI, DC, B>,
    coherence: Coherence<H>,
    sent: u16,
}

impl<SPI, DC, const B: usize, const H: usize> CoherentRows<SPI, DC, B, H> {
    /// A sink for `window`; sends nothing yet. Fails like [`St7789Rows::new`], or with
    /// [`StreamError::TooFewSignatures`] if `H` is below the window's height.
    pub fn new(spi: SPI, dc: DC, window: Window) -> Result<Self, StreamError> {
        if (window.height as usize) > H {
            return Err(StreamError::TooFewSignatures {
                height: window.height,
                capacity: u32::try_from(H).unwrap_or(u32::MAX),
            });
        }
        Ok(CoherentRows {
            rows: St7789Rows::new(spi, dc, window)?,
            coherence: Coherence::new(),
            sent: 0,
        })
    }

    /// The same sink, sending every `frames`-th frame whole (see [`Coherence::with_refresh`]).
    pub fn with_refresh(mut self, frames: u16) -> Self {
        self.coherence = Coherence::with_refresh(frames);
        self
    }

    /// The window rows go to.
    pub fn window(&self) -> Window {
        self.rows.window()
    }

    /// Rows sent so far in the current frame (the rest were already on the panel).
    pub fn rows_sent(&self) -> u16 {
        self.sent
    }

    /// The next frame goes whole (see [`Coherence::forget`]): call it if something else wrote
    /// to the panel.
    pub fn forget(&mut self) {
        self.coherence.forget();
    }

    /// Starts a frame: row 0 is due. Sends nothing.
    pub fn begin_frame(&mut self) {
        self.rows.next_row = Some(0);
        self.sent = 0;
    }

    /// Gives back the SPI device and the DC pin.
    pub fn release(self) -> (SPI, DC) {
        self.rows.release()
    }
}

impl<SPI: SpiDevice, DC: OutputPin, const B: usize, const H: usize> CoherentRows<SPI, DC, B, H> {
    /// Sends the power-on sequence ([`crate::init_sequence`]) with its pauses; the next frame
    /// goes whole.
    pub fn init(&mut self, delay: &mut impl DelayNs) -> Result<(), Error<SPI::Error, DC::Error>> {
        self.coherence.forget();
        self.rows.init(delay)
    }

    /// Sends one command (see [`St7789Rows::command`]); the next frame goes whole.
    pub fn command(
        &mut self,
        command: u8,
        params: &[u8],
    ) -> Result<(), Error<SPI::Error, DC::Error>> {
        self.coherence.forget();
        self.rows.command(command, params)
    }

    fn send(&mut self, action: RowAction, n: usize) -> Result<(), Error<SPI::Error, DC::Error>> {
        let r = &mut self.rows;
        if let RowAction::Open { caset } = action {
            let (spi, dc) = (&mut r.spi, &mut r.dc);
            open_run(&r.window, r.next_row.unwrap_or(0), caset, |c, p| {
                command::send_command(spi, dc, c, p)
            })?;
        }
        r.dc.set_high().map_err(Error::Dc)?;
        r.spi.write(&r.line[..n]).map_err(Error::Spi)
    }
}

impl<N, SPI: SpiDevice, DC: OutputPin, const B: usize, const H: usize> RowSink<N>
    for CoherentRows<SPI, DC, B, H>
{
    type Error = Error<SPI::Error, DC::Error>;
    /// The panel takes colours only: the renderer need not write its depth row.
    const WANTS_DEPTH: bool = false;

    /// Checks the row's place and length, encodes it, and sends it only if it changed (with
    /// the window first after a gap). On a bus error the next frame goes whole.
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Self::Error> {
        let (n, signature) = self.rows.take_row_signed(row)?;
        let action = self.coherence.row_signed(row.y, signature);
        if action != RowAction::Skip {
            if let Err(e) = self.send(action, n) {
                self.coherence.forget();
                return Err(e);
            }
            self.sent += 1;
        }
        self.rows.row_done();
        Ok(())
    }
}
