//! ST7789 command codes, the power-on sequence as data, and the two ways bytes go out:
//! a command byte with DC low, its parameters (and pixel data) with DC high.

use crate::Error;
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiDevice;

/// No operation.
pub const NOP: u8 = 0x00;
/// Software reset: registers to their defaults; wait 5 ms before the next command and
/// 120 ms before `SLPOUT`.
pub const SWRESET: u8 = 0x01;
/// Sleep in.
pub const SLPIN: u8 = 0x10;
/// Sleep out: wait 5 ms before the next command (120 ms before `SLPIN`).
pub const SLPOUT: u8 = 0x11;
/// Normal display mode on (partial mode off).
pub const NORON: u8 = 0x13;
/// Display inversion off.
pub const INVOFF: u8 = 0x20;
/// Display inversion on: the common IPS modules need it for true colours.
pub const INVON: u8 = 0x21;
/// Display off.
pub const DISPOFF: u8 = 0x28;
/// Display on.
pub const DISPON: u8 = 0x29;
/// Column address set: 4 parameters, XS then XE, each big-endian 16-bit, inclusive.
pub const CASET: u8 = 0x2A;
/// Row address set: 4 parameters, YS then YE, each big-endian 16-bit, inclusive.
pub const RASET: u8 = 0x2B;
/// Memory write: address counters to (XS, YS), then pixel data follows with DC high.
pub const RAMWR: u8 = 0x2C;
/// Memory data access control (orientation, RGB/BGR order): 1 parameter.
pub const MADCTL: u8 = 0x36;
/// Interface pixel format: 1 parameter.
pub const COLMOD: u8 = 0x3A;
/// Memory write continue: pixel data goes on from where the last write stopped.
pub const RAMWRC: u8 = 0x3C;

/// `COLMOD` parameter: 65K-colour RGB interface, 16 bits per pixel on the control interface
/// (RGB565, sent high byte first).
pub const COLMOD_RGB565: u8 = 0x55;
/// `MADCTL` parameter of the default orientation: rows top to bottom, columns left to right,
/// RGB order. With it a 240 × 240 module shows RAM rows 0..240, so its window needs no offset.
pub const MADCTL_DEFAULT: u8 = 0x00;

/// One step of an initialisation sequence: command, its parameters, then a pause in ms.
pub type InitStep = (u8, &'static [u8], u16);

/// The standard ST7789 power-on sequence (see [`init_sequence`]).
pub const INIT_SEQUENCE: &[InitStep] = &[
    (SWRESET, &[], 150),
    (SLPOUT, &[], 10),
    (COLMOD, &[COLMOD_RGB565], 0),
    (MADCTL, &[MADCTL_DEFAULT], 0),
    (INVON, &[], 0),
    (NORON, &[], 0),
    (DISPON, &[], 0),
];

/// The standard ST7789 power-on sequence, as data: software reset (150 ms), sleep out
/// (10 ms), 16-bit pixels (`COLMOD 0x55`), default orientation (`MADCTL 0x00`), inversion on
/// (IPS modules), normal mode, display on.
///
/// It does not drive a reset pin: pulse RST low (≥ 10 µs, then wait 120 ms) before it if the
/// board wires one, or tie RST high and rely on `SWRESET`. Send it with [`init`] (or
/// [`St7789Rows::init`](crate::St7789Rows::init)), or through any other driver.
pub const fn init_sequence() -> &'static [InitStep] {
    INIT_SEQUENCE
}

/// Sends one command: the command byte with DC low, then (if any) its parameters with DC high,
/// each as one SPI write.
pub fn send_command<SPI: SpiDevice, DC: OutputPin>(
    spi: &mut SPI,
    dc: &mut DC,
    command: u8,
    params: &[u8],
) -> Result<(), Error<SPI::Error, DC::Error>> {
    dc.set_low().map_err(Error::Dc)?;
    spi.write(&[command]).map_err(Error::Spi)?;
    if !params.is_empty() {
        dc.set_high().map_err(Error::Dc)?;
        spi.write(params).map_err(Error::Spi)?;
    }
    Ok(())
}

/// Sends [`init_sequence`] with its pauses.
pub fn init<SPI: SpiDevice, DC: OutputPin, D: DelayNs>(
    spi: &mut SPI,
    dc: &mut DC,
    delay: &mut D,
) -> Result<(), Error<SPI::Error, DC::Error>> {
    for &(command, params, ms) in init_sequence() {
        send_command(spi, dc, command, params)?;
        if ms > 0 {
            delay.delay_ms(ms.into());
        }
    }
    Ok(())
}
