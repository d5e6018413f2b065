//! The row sink: the address window set once per frame, then one SPI write per row of
//! big-endian RGB565 bytes; and [`encode_row`], the same encoding as a pure function for
//! firmware that sends rows by DMA from two buffers of its own.

use crate::coherence::Signature;
use crate::command;
use crate::{Error, StreamError};
use embedded_graphics_core::pixelcolor::{IntoStorage, Rgb565};
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiDevice;
use zrow::{Row, RowSink};

/// Columns of the ST7789's frame memory (in the default orientation, `MADCTL 0x00`).
pub const PANEL_WIDTH: u16 = 240;
/// Rows of the ST7789's frame memory (in the default orientation, `MADCTL 0x00`).
pub const PANEL_HEIGHT: u16 = 320;

/// Bytes one row of `width` pixels takes on the wire (2 per pixel): the least line-buffer
/// capacity `B` for [`St7789Rows`].
pub const fn line_bytes(width: u16) -> usize {
    2 * width as usize
}

/// Where the frame goes in the panel's 240 × 320 RAM: `width` × `height` pixels starting at
/// column `x_offset`, row `y_offset`.
///
/// Offsets depend on the module and the orientation, because the glass shows only part of
/// the RAM. In the default orientation (`MADCTL 0x00`, what [`init_sequence`] sets):
///
/// - 240 × 240 modules show columns 0..240, rows 0..240: no offsets (`Window::new(240, 240)`).
///   Turned 180° (`MADCTL 0xC0`) they show rows 80..320 instead: `y_offset` 80.
/// - 240 × 320 modules show the whole RAM: no offsets.
/// - Smaller glass is usually centred, e.g. 135 × 240 modules: `x_offset` 52, `y_offset` 40;
///   240 × 280: `y_offset` 20. Check the module's documentation.
///
/// [`init_sequence`]: crate::init_sequence
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Window {
    /// Width in pixels (the rows' length).
    pub width: u16,
    /// Height in pixels (the number of rows).
    pub height: u16,
    /// First RAM column.
    pub x_offset: u16,
    /// First RAM row.
    pub y_offset: u16,
}

impl Window {
    /// A `width` × `height` window at the RAM's top-left corner.
    pub const fn new(width: u16, height: u16) -> Self {
        Window {
            width,
            height,
            x_offset: 0,
            y_offset: 0,
        }
    }

    /// The same window moved to RAM column `x_offset`, row `y_offset`.
    pub const fn with_offset(self, x_offset: u16, y_offset: u16) -> Self {
        Window {
            x_offset,
            y_offset,
            ..self
        }
    }

    /// Checks that the window is not empty, fits the panel RAM, and that a line buffer of
    /// `buffer_bytes` holds one of its rows. A `const fn`, so firmware can check at compile
    /// time: `const _: () = assert!(WINDOW.check(480).is_ok());`.
    pub const fn check(&self, buffer_bytes: usize) -> Result<(), StreamError> {
        if self.width == 0
            || self.height == 0
            || self.x_offset as u32 + self.width as u32 > PANEL_WIDTH as u32
            || self.y_offset as u32 + self.height as u32 > PANEL_HEIGHT as u32
        {
            return Err(StreamError::BadWindow);
        }
        let needed = line_bytes(self.width);
        if buffer_bytes < needed {
            return Err(StreamError::BufferTooSmall {
                needed: needed as u32,
                capacity: if buffer_bytes > u32::MAX as usize {
                    u32::MAX
                } else {
                    buffer_bytes as u32
                },
            });
        }
        Ok(())
    }

    /// `CASET` parameters: first and last column, big-endian, inclusive.
    pub const fn caset(&self) -> [u8; 4] {
        span(self.x_offset, self.width)
    }

    /// `RASET` parameters: first and last row, big-endian, inclusive.
    pub const fn raset(&self) -> [u8; 4] {
        span(self.y_offset, self.height)
    }

    /// `RASET` parameters from the window's row `row` (the last row if `row` is past it) to
    /// its last row: what a sender of changed rows only sets before a run
    /// ([`crate::coherence`]).
    ///
    /// ```
    /// use zrow_st7789::Window;
    /// let w = Window::new(240, 240).with_offset(0, 80);
    /// assert_eq!(w.raset_from(10), [0, 90, 1, 63]); // RAM rows 90..=319
    /// ```
    pub const fn raset_from(&self, row: u16) -> [u8; 4] {
        let row = if row < self.height {
            row
        } else {
            self.height.saturating_sub(1)
        };
        span(self.y_offset.wrapping_add(row), self.height - row)
    }
}

/// Start and inclusive end of `len` addresses from `start`, as the ST7789 takes them.
const fn span(start: u16, len: u16) -> [u8; 4] {
    let end = start.wrapping_add(len).wrapping_sub(1);
    let [s0, s1] = start.to_be_bytes();
    let [e0, e1] = end.to_be_bytes();
    [s0, s1, e0, e1]
}

/// Encodes pixels as the ST7789 takes them in 16-bit mode: RGB565, high byte first.
///
/// Writes as many whole pixels as fit in `out` and returns the bytes written (2 per pixel):
/// `2 * row.len()` when `out` is large enough. A pure function, so a firmware can encode
/// the next row into one buffer while DMA sends the other.
///
/// ```
/// use embedded_graphics_core::pixelcolor::Rgb565;
/// let mut out = [0u8; 4];
/// let n = zrow_st7789::encode_row(&[Rgb565::new(31, 0, 0), Rgb565::new(0, 0, 31)], &mut out);
/// assert_eq!((n, out), (4, [0xF8, 0x00, 0x00, 0x1F]));
/// ```
pub fn encode_row(row: &[Rgb565], out: &mut [u8]) -> usize {
    encode_with(row, out, |_| {})
}

/// [`encode_row`] and the row's [`row_signature`](crate::coherence::row_signature) of the bytes
/// written, in one pass (what a sender of changed rows only needs; cheaper than encoding, then
/// reading the bytes again to sign them).
///
/// ```
/// use embedded_graphics_core::pixelcolor::Rgb565;
/// use zrow_st7789::{coherence::row_signature, encode_row_signed};
/// let row = [Rgb565::new(31, 0, 0), Rgb565::new(0, 63, 0), Rgb565::new(0, 0, 31)];
/// let mut out = [0u8; 6];
/// let (n, signature) = encode_row_signed(&row, &mut out);
/// assert_eq!((n, signature), (6, row_signature(&out)));
/// ```
// Out of line, so that its loop has the core's registers to itself: inlined into the
// firmware's run loop, how many it got depended on the renderer's code around it (a change
// there once cost it the signature's constant, reloaded every two words: +0.03 M cycles a
// frame on the emulated F411, `bash emu/board/run.sh`).
#[inline(never)]
pub fn encode_row_signed(row: &[Rgb565], out: &mut [u8]) -> (usize, u32) {
    let n = row.len().min(out.len() / 2);
    let mut signature = Signature::new(2 * n);
    encode_with(row, out, |word| signature.mix(word));
    (2 * n, signature.finish())
}

/// Encodes as many whole pixels of `row` as fit in `out`, two a word, handing each word (the
/// bytes as a little-endian `u32`, a last lone pixel padded with zeros) to `word`.
#[inline(always)]
fn encode_with(row: &[Rgb565], out: &mut [u8], mut word: impl FnMut(u32)) -> usize {
    let n = row.len().min(out.len() / 2);
    let (row, out) = (&row[..n], &mut out[..2 * n]);
    // Two pixels a word: both byte-swapped at once (one `rev16` on a Cortex-M); two words an
    // iteration (fewer loop steps, and the signature's constant stays in a register).
    let swap = |p: &[Rgb565]| {
        let x = u32::from(p[0].into_storage()) | u32::from(p[1].into_storage()) << 16;
        ((x & 0x00FF_00FF) << 8) | ((x >> 8) & 0x00FF_00FF)
    };
    let mut quads = row.chunks_exact(4);
    let mut eights = out.chunks_exact_mut(8);
    // Tested at the bottom (a `for` over the zip, out of line, became a loop tested at the
    // top with its body predicated: 19 instructions a step against 13).
    if let (Some(mut p), Some(mut w)) = (quads.next(), eights.next()) {
        loop {
            let (a, b) = (swap(&p[..2]), swap(&p[2..]));
            w[..4].copy_from_slice(&a.to_le_bytes());
            w[4..].copy_from_slice(&b.to_le_bytes());
            word(a);
            word(b);
            match (quads.next(), eights.next()) {
                (Some(np), Some(nw)) => (p, w) = (np, nw),
                _ => break,
            }
        }
    }
    let (row, out) = (quads.remainder(), eights.into_remainder());
    let mut pairs = row.chunks_exact(2);
    let mut words = out.chunks_exact_mut(4);
    for (p, w) in (&mut pairs).zip(&mut words) {
        let x = swap(p);
        w.copy_from_slice(&x.to_le_bytes());
        word(x);
    }
    if let ([px], last) = (pairs.remainder(), words.into_remainder()) {
        let bytes = px.into_storage().to_be_bytes();
        last.copy_from_slice(&bytes);
        word(u32::from_le_bytes([bytes[0], bytes[1], 0, 0]));
    }
    2 * n
}

/// Streams zrow rows to an ST7789 over an SPI device and a DC pin.
///
/// - `SPI`: an [`SpiDevice`] (it owns chip select; wrap a HAL's bus in
///   `embedded_hal_bus::spi::ExclusiveDevice`);
/// - `DC`: the data/command pin, low for command bytes, high for parameters and pixels;
/// - `B`: the line buffer's capacity in bytes, at least [`line_bytes`]`(width)`.
///
/// Per frame: [`begin_frame`](Self::begin_frame) sets the window and opens `RAMWR`; the
/// renderer then hands over rows `0..height` in order through [`RowSink::write_row`], each
/// sent as one SPI write. After the last row the frame is closed; the next frame starts
/// with `begin_frame` again. After any error, start again with `begin_frame`.
pub struct St7789Rows<SPI, DC, const B: usize> {
    pub(crate) spi: SPI,
    pub(crate) dc: DC,
    pub(crate) window: Window,
    /// The row due next, `None` outside a frame.
    pub(crate) next_row: Option<u16>,
    pub(crate) line: [u8; B],
}

impl<SPI, DC, const B: usize> St7789Rows<SPI, DC, B> {
    /// A sink for `window`; sends nothing yet. Fails if the window does not fit the panel
    /// or `B` is below [`line_bytes`]`(window.width)` (see [`Window::check`]).
    pub fn new(spi: SPI, dc: DC, window: Window) -> Result<Self, StreamError> {
        window.check(B)?;
        Ok(St7789Rows {
            spi,
            dc,
            window,
            next_row: None,
            line: [0; B],
        })
    }

    /// The window rows go to.
    pub fn window(&self) -> Window {
        self.window
    }

    /// The row due next, or `None` outside a frame (before `begin_frame`, after the last row).
    pub fn next_row(&self) -> Option<u16> {
        self.next_row
    }

    /// Gives back the SPI device and the DC pin (for DMA, or another driver).
    pub fn release(self) -> (SPI, DC) {
        (self.spi, self.dc)
    }
}

impl<SPI: SpiDevice, DC: OutputPin, const B: usize> St7789Rows<SPI, DC, B> {
    /// Sends the power-on sequence ([`crate::init_sequence`]) with its pauses.
    pub fn init(&mut self, delay: &mut impl DelayNs) -> Result<(), Error<SPI::Error, DC::Error>> {
        command::init(&mut self.spi, &mut self.dc, delay)
    }

    /// Sends one command and its parameters (see [`crate::send_command`]). Closes the frame
    /// in progress: the panel leaves `RAMWR` at any command.
    pub fn command(
        &mut self,
        command: u8,
        params: &[u8],
    ) -> Result<(), Error<SPI::Error, DC::Error>> {
        self.next_row = None;
        command::send_command(&mut self.spi, &mut self.dc, command, params)
    }

    /// Starts a frame: `CASET` and `RASET` with the window, then `RAMWR`. The panel's
    /// address counter is then at the window's top-left pixel, and row 0 is due.
    pub fn begin_frame(&mut self) -> Result<(), Error<SPI::Error, DC::Error>> {
        self.next_row = None;
        let (spi, dc) = (&mut self.spi, &mut self.dc);
        crate::coherence::open_run(&self.window, 0, true, |c, p| {
            command::send_command(spi, dc, c, p)
        })?;
        self.next_row = Some(0);
        Ok(())
    }
}

impl<N, SPI: SpiDevice, DC: OutputPin, const B: usize> RowSink<N> for St7789Rows<SPI, DC, B> {
    type Error = Error<SPI::Error, DC::Error>;
    /// The panel takes colours only: the renderer need not write its depth row.
    const WANTS_DEPTH: bool = false;

    /// Checks the row's place and length, encodes it big-endian into the line buffer and
    /// sends it with DC high in one SPI write.
    fn write_row(&mut self, row: &Row<'_, N>) -> Result<(), Self::Error> {
        let n = self.take_row(row)?;
        self.dc.set_high().map_err(Error::Dc)?;
        self.spi.write(&self.line[..n]).map_err(Error::Spi)?;
        self.row_done();
        Ok(())
    }
}

impl<SPI, DC, const B: usize> St7789Rows<SPI, DC, B> {
    /// Checks that `row` is the one due and as wide as the window, encodes it into the line
    /// buffer: the bytes to send are `line[..n]`. [`Self::row_done`] moves on once it is sent.
    pub(crate) fn take_row<N>(&mut self, row: &Row<'_, N>) -> Result<usize, StreamError> {
        self.check_row(row)?;
        // `new` checked B >= 2 * width, so the whole row fits.
        Ok(encode_row(row.color, &mut self.line))
    }

    /// Checks that `row` is the one due and as wide as the window.
    fn check_row<N>(&self, row: &Row<'_, N>) -> Result<(), StreamError> {
        let expected = self.next_row.ok_or(StreamError::NoFrame)?;
        if row.y != expected {
            return Err(StreamError::OutOfOrder {
                expected,
                got: row.y,
            });
        }
        let width = self.window.width;
        if row.color.len() != width as usize {
            return Err(StreamError::WrongLength {
                expected: width,
                got: u32::try_from(row.color.len()).unwrap_or(u32::MAX),
            });
        }
        Ok(())
    }

    /// [`Self::take_row`], with the row's signature computed while encoding.
    pub(crate) fn take_row_signed<N>(
        &mut self,
        row: &Row<'_, N>,
    ) -> Result<(usize, u32), StreamError> {
        self.check_row(row)?;
        Ok(encode_row_signed(row.color, &mut self.line))
    }

    /// The row due has been dealt with: the next one is due (none after the window's last).
    pub(crate) fn row_done(&mut self) {
        self.next_row = self
            .next_row
            .and_then(|r| (r + 1 < self.window.height).then_some(r + 1));
    }
}
