//! A host-side model of the ST7789 (feature `model`): it decodes the (DC level, bytes) stream
//! a driver sends into register state and a 240 × 320 frame of [`Rgb565`] pixels, and records
//! every protocol mistake instead of guessing.
//!
//! What it follows from the datasheet:
//!
//! - A byte with DC low is a command; bytes with DC high are its parameters, or pixel data
//!   after `RAMWR`/`RAMWRC`. Any command ends the previous one.
//! - `CASET`/`RASET` take 4 parameters (start and inclusive end, big-endian 16-bit) and
//!   apply once all 4 have come; start > end or an end outside the RAM is refused.
//! - `RAMWR` puts the address counter at (XS, YS). Each pixel advances the column; past XE
//!   the column returns to XS and the row advances; past YE the row returns to YS. Data may
//!   come in any number of SPI writes (a pixel may even be split between two).
//! - `COLMOD` must select 16-bit pixels on the control interface (bits 2..0 = `101`, as in
//!   `0x55`); pixels arrive high byte first. `MADCTL` is modelled for the default orientation
//!   `0x00` only; any other value is recorded as an error.
//! - `SWRESET` restores the register defaults (window 240 × 320, `MADCTL 0x00`, `COLMOD 0x66`,
//!   sleeping, display off, inversion off, normal mode) but keeps the RAM. With the clock fed
//!   by the mock delay, the model checks the waits: 5 ms after `SWRESET`/`SLPOUT`/`SLPIN`
//!   before any command, 120 ms after `SWRESET`/`SLPOUT`/`SLPIN` before `SLPOUT`/`SLPIN`.

use crate::command::*;
use crate::rows::{PANEL_HEIGHT, PANEL_WIDTH};
use crate::Window;
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use std::vec;
use std::vec::Vec;

const MS: u64 = 1_000_000;

/// A protocol mistake the model saw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ModelError {
    /// A command byte the model does not know.
    UnknownCommand(u8),
    /// `command` was ended by the next command with `got` of its `needed` parameters: send
    /// them all.
    MissingParams {
        /// The command.
        command: u8,
        /// Parameters received.
        got: usize,
        /// Parameters it takes.
        needed: usize,
    },
    /// Data bytes beyond what `command` takes (or for a command that takes none).
    ExtraData {
        /// The command.
        command: u8,
    },
    /// Data bytes before any command.
    DataWithoutCommand,
    /// `CASET`/`RASET` with start > end or an end outside the RAM: the window was not changed.
    BadAddress {
        /// The command.
        command: u8,
    },
    /// A `MADCTL` value other than the default orientation `0x00`.
    UnsupportedMadctl(u8),
    /// A `COLMOD` value that does not select 16-bit pixels.
    UnsupportedColmod(u8),
    /// Pixel data while `COLMOD` is not 16-bit (the data was dropped).
    PixelsNot16Bit {
        /// The `COLMOD` value in force.
        colmod: u8,
    },
    /// Pixel data ended on half a pixel, cut off by `command`.
    HalfPixel {
        /// The command that cut it.
        command: u8,
    },
    /// `command` came `wait_ns` too early after `SWRESET`/`SLPOUT`/`SLPIN`.
    TooSoon {
        /// The command.
        command: u8,
        /// How much longer it should have waited.
        wait_ns: u64,
    },
}

/// The ST7789 model. See the module documentation.
#[derive(Clone, Debug)]
pub struct St7789Model {
    ram: Vec<Rgb565>,
    writes: Vec<u32>,
    caset: (u16, u16),
    raset: (u16, u16),
    madctl: u8,
    colmod: u8,
    sleeping: bool,
    display_on: bool,
    inverted: bool,
    normal_mode: bool,
    /// The command whose parameters or data are coming.
    command: Option<u8>,
    params: Vec<u8>,
    col: u16,
    row: u16,
    half_pixel: Option<u8>,
    now_ns: u64,
    ready_at_ns: u64,
    sleep_toggle_at_ns: u64,
    commands: Vec<u8>,
    errors: Vec<ModelError>,
    wire_bytes: u64,
}

impl Default for St7789Model {
    fn default() -> Self {
        Self::new()
    }
}

/// Parameters a command takes (pixel data not counted).
fn param_count(command: u8) -> Option<usize> {
    Some(match command {
        CASET | RASET => 4,
        MADCTL | COLMOD => 1,
        NOP | SWRESET | SLPIN | SLPOUT | NORON | INVOFF | INVON | DISPOFF | DISPON | RAMWR
        | RAMWRC => 0,
        _ => return None,
    })
}

fn is_16_bit(colmod: u8) -> bool {
    colmod & 0x07 == 0b101
}

impl St7789Model {
    /// A panel just powered on: registers at their defaults, RAM all black, clock at 0.
    pub fn new() -> Self {
        let n = PANEL_WIDTH as usize * PANEL_HEIGHT as usize;
        let mut m = St7789Model {
            ram: vec![Rgb565::BLACK; n],
            writes: vec![0; n],
            caset: (0, 0),
            raset: (0, 0),
            madctl: 0,
            colmod: 0,
            sleeping: true,
            display_on: false,
            inverted: false,
            normal_mode: true,
            command: None,
            params: Vec::new(),
            col: 0,
            row: 0,
            half_pixel: None,
            now_ns: 0,
            ready_at_ns: 0,
            sleep_toggle_at_ns: 0,
            commands: Vec::new(),
            errors: Vec::new(),
            wire_bytes: 0,
        };
        m.reset_registers();
        m
    }

    fn reset_registers(&mut self) {
        self.caset = (0, PANEL_WIDTH - 1);
        self.raset = (0, PANEL_HEIGHT - 1);
        self.madctl = 0x00;
        self.colmod = 0x66;
        self.sleeping = true;
        self.display_on = false;
        self.inverted = false;
        self.normal_mode = true;
    }

    /// Takes one SPI write: `bytes` sent while DC was high (`dc_high`) or low.
    pub fn feed(&mut self, dc_high: bool, bytes: &[u8]) {
        self.wire_bytes = self.wire_bytes.saturating_add(bytes.len() as u64);
        if dc_high {
            self.data(bytes);
        } else {
            for &b in bytes {
                self.begin_command(b);
            }
        }
    }

    /// Bytes received so far, commands, parameters and pixels together: what crossed the
    /// wire (each takes 8 SPI clocks).
    pub fn wire_bytes(&self) -> u64 {
        self.wire_bytes
    }

    /// Lets `ns` nanoseconds pass (the mock delay calls this).
    pub fn advance_ns(&mut self, ns: u64) {
        self.now_ns = self.now_ns.saturating_add(ns);
    }

    fn begin_command(&mut self, command: u8) {
        self.end_command();
        self.commands.push(command);
        if self.now_ns < self.ready_at_ns {
            self.errors.push(ModelError::TooSoon {
                command,
                wait_ns: self.ready_at_ns - self.now_ns,
            });
        }
        if matches!(command, SLPIN | SLPOUT) && self.now_ns < self.sleep_toggle_at_ns {
            self.errors.push(ModelError::TooSoon {
                command,
                wait_ns: self.sleep_toggle_at_ns - self.now_ns,
            });
        }
        if param_count(command).is_none() {
            self.errors.push(ModelError::UnknownCommand(command));
            return;
        }
        self.command = Some(command);
        match command {
            SWRESET => {
                self.reset_registers();
                self.ready_at_ns = self.now_ns + 5 * MS;
                self.sleep_toggle_at_ns = self.now_ns + 120 * MS;
            }
            SLPIN | SLPOUT => {
                self.sleeping = command == SLPIN;
                self.ready_at_ns = self.now_ns + 5 * MS;
                self.sleep_toggle_at_ns = self.now_ns + 120 * MS;
            }
            NORON => self.normal_mode = true,
            INVOFF | INVON => self.inverted = command == INVON,
            DISPOFF | DISPON => self.display_on = command == DISPON,
            RAMWR => (self.col, self.row) = (self.caset.0, self.raset.0),
            _ => {}
        }
    }

    fn end_command(&mut self) {
        let Some(command) = self.command.take() else {
            return;
        };
        let needed = param_count(command).unwrap_or(0);
        if self.params.len() < needed {
            self.errors.push(ModelError::MissingParams {
                command,
                got: self.params.len(),
                needed,
            });
        }
        self.params.clear();
        if self.half_pixel.take().is_some() {
            self.errors.push(ModelError::HalfPixel { command });
        }
    }

    fn data(&mut self, bytes: &[u8]) {
        let Some(command) = self.command else {
            if !bytes.is_empty() {
                self.errors.push(ModelError::DataWithoutCommand);
            }
            return;
        };
        if matches!(command, RAMWR | RAMWRC) {
            return self.pixels(bytes);
        }
        let needed = param_count(command).unwrap_or(0);
        for &b in bytes {
            if self.params.len() == needed {
                self.errors.push(ModelError::ExtraData { command });
                return;
            }
            self.params.push(b);
            if self.params.len() == needed {
                self.apply(command);
            }
        }
    }

    fn apply(&mut self, command: u8) {
        let p = &self.params;
        let word = |i: usize| u16::from_be_bytes([p[i], p[i + 1]]);
        match command {
            CASET | RASET => {
                let (start, end) = (word(0), word(2));
                let limit = if command == CASET {
                    PANEL_WIDTH
                } else {
                    PANEL_HEIGHT
                };
                if start > end || end >= limit {
                    self.errors.push(ModelError::BadAddress { command });
                } else if command == CASET {
                    self.caset = (start, end);
                } else {
                    self.raset = (start, end);
                }
            }
            MADCTL => {
                self.madctl = p[0];
                if p[0] != MADCTL_DEFAULT {
                    self.errors.push(ModelError::UnsupportedMadctl(p[0]));
                }
            }
            COLMOD => {
                self.colmod = p[0];
                if !is_16_bit(p[0]) {
                    self.errors.push(ModelError::UnsupportedColmod(p[0]));
                }
            }
            _ => {}
        }
    }

    fn pixels(&mut self, bytes: &[u8]) {
        if !is_16_bit(self.colmod) {
            if !bytes.is_empty() {
                self.errors.push(ModelError::PixelsNot16Bit {
                    colmod: self.colmod,
                });
            }
            return;
        }
        for &b in bytes {
            match self.half_pixel.take() {
                None => self.half_pixel = Some(b),
                Some(high) => self.store(u16::from_be_bytes([high, b])),
            }
        }
    }

    fn store(&mut self, raw: u16) {
        let i = self.row as usize * PANEL_WIDTH as usize + self.col as usize;
        self.ram[i] = Rgb565::from(RawU16::new(raw));
        self.writes[i] += 1;
        if self.col < self.caset.1 {
            self.col += 1;
        } else {
            self.col = self.caset.0;
            self.row = if self.row < self.raset.1 {
                self.row + 1
            } else {
                self.raset.0
            };
        }
    }

    /// The pixel at RAM column `x`, row `y` (black if never written; `None` outside the RAM).
    pub fn pixel(&self, x: u16, y: u16) -> Option<Rgb565> {
        (x < PANEL_WIDTH && y < PANEL_HEIGHT)
            .then(|| self.ram[y as usize * PANEL_WIDTH as usize + x as usize])
    }

    /// How many times the pixel at (`x`, `y`) has been written (0 outside the RAM).
    pub fn writes_at(&self, x: u16, y: u16) -> u32 {
        if x < PANEL_WIDTH && y < PANEL_HEIGHT {
            self.writes[y as usize * PANEL_WIDTH as usize + x as usize]
        } else {
            0
        }
    }

    /// Sets every pixel's write count back to 0 (between frames).
    pub fn clear_write_counts(&mut self) {
        self.writes.fill(0);
    }

    /// The whole RAM, row-major, 240 pixels a row.
    pub fn ram(&self) -> &[Rgb565] {
        &self.ram
    }

    /// The pixels of `window`, row-major, `window.width` a row (parts outside the RAM are
    /// left out).
    pub fn read_window(&self, window: &Window) -> Vec<Rgb565> {
        let mut out = Vec::with_capacity(window.width as usize * window.height as usize);
        for y in window.y_offset..window.y_offset.saturating_add(window.height) {
            for x in window.x_offset..window.x_offset.saturating_add(window.width) {
                out.extend(self.pixel(x, y));
            }
        }
        out
    }

    /// Column window (XS, XE), inclusive.
    pub fn caset(&self) -> (u16, u16) {
        self.caset
    }
    /// Row window (YS, YE), inclusive.
    pub fn raset(&self) -> (u16, u16) {
        self.raset
    }
    /// The address counter (column, row).
    pub fn address(&self) -> (u16, u16) {
        (self.col, self.row)
    }
    /// The `MADCTL` value in force.
    pub fn madctl(&self) -> u8 {
        self.madctl
    }
    /// The `COLMOD` value in force (`0x66` after reset).
    pub fn colmod(&self) -> u8 {
        self.colmod
    }
    /// Whether the panel is in sleep mode.
    pub fn sleeping(&self) -> bool {
        self.sleeping
    }
    /// Whether the display is on.
    pub fn display_on(&self) -> bool {
        self.display_on
    }
    /// Whether inversion is on.
    pub fn inverted(&self) -> bool {
        self.inverted
    }
    /// Whether normal display mode is on.
    pub fn normal_mode(&self) -> bool {
        self.normal_mode
    }
    /// Every command byte received, in order.
    pub fn commands(&self) -> &[u8] {
        &self.commands
    }
    /// Every protocol mistake seen, in order.
    pub fn errors(&self) -> &[ModelError] {
        &self.errors
    }
    /// Nanoseconds the clock has advanced.
    pub fn now_ns(&self) -> u64 {
        self.now_ns
    }
}
