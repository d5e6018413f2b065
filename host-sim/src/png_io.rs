//! PNG in and out: frames are written as 8-bit RGB (no alpha), exactly their size; references
//! are read back as 8-bit RGB for comparison.

use crate::output::Output;
use crate::render::Image;
use crate::SimError;
use std::io::Write;
use std::path::Path;

/// Encodes `image` as an 8-bit RGB PNG into `out`.
pub fn encode(image: &Image, out: impl Write) -> Result<(), png::EncodingError> {
    let mut encoder = png::Encoder::new(out, image.width as u32, image.height as u32);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&image.to_rgb8())?;
    writer.finish()
}

/// Encodes `image` as an 8-bit RGB PNG in memory; errors name `path`, where it will go.
pub fn encode_for(image: &Image, path: &Path) -> Result<Vec<u8>, SimError> {
    let mut bytes = Vec::new();
    encode(image, &mut bytes).map_err(|e| SimError::Io {
        path: path.display().to_string(),
        action: "encode PNG",
        source: std::io::Error::other(e),
    })?;
    Ok(bytes)
}

/// Writes `image` to `path` as an 8-bit RGB PNG, through [`Output`]: the file is only put in
/// place once the frame is encoded and written, so a failed run never leaves a file behind.
pub fn write(image: &Image, path: &Path) -> Result<(), SimError> {
    let out = Output::open(path)?;
    out.write(&encode_for(image, path)?)
}

/// An 8-bit RGB picture read from a PNG.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgb8Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `3 × width × height` bytes, top row first.
    pub data: Vec<u8>,
}

/// Why a PNG could not be read as 8-bit RGB.
#[derive(Debug)]
pub enum DecodeError {
    /// Not a valid PNG.
    Png(png::DecodingError),
    /// A valid PNG, but not 8-bit RGB.
    NotRgb8 {
        /// Its colour type.
        color: png::ColorType,
        /// Its bit depth.
        depth: png::BitDepth,
    },
}

impl std::fmt::Display for DecodeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DecodeError::Png(e) => write!(f, "bad PNG: {e}"),
            DecodeError::NotRgb8 { color, depth } => {
                write!(f, "PNG is {color:?} at {depth:?}, not 8-bit RGB")
            }
        }
    }
}

impl std::error::Error for DecodeError {}

/// Decodes an 8-bit RGB PNG (as [`encode`] writes). Other colour types and depths are
/// rejected, so a reference that is not what this simulator writes cannot compare equal.
pub fn decode(bytes: &[u8]) -> Result<Rgb8Image, DecodeError> {
    let mut reader = png::Decoder::new(bytes)
        .read_info()
        .map_err(DecodeError::Png)?;
    let mut data = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut data).map_err(DecodeError::Png)?;
    if info.color_type != png::ColorType::Rgb || info.bit_depth != png::BitDepth::Eight {
        return Err(DecodeError::NotRgb8 {
            color: info.color_type,
            depth: info.bit_depth,
        });
    }
    data.truncate(info.buffer_size());
    Ok(Rgb8Image {
        width: info.width,
        height: info.height,
        data,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::pixelcolor::{Rgb565, RgbColor};

    #[test]
    fn round_trip() {
        let image = Image {
            width: 3,
            height: 2,
            pixels: vec![
                Rgb565::RED,
                Rgb565::GREEN,
                Rgb565::BLUE,
                Rgb565::BLACK,
                Rgb565::WHITE,
                Rgb565::new(16, 32, 8),
            ],
        };
        let mut bytes = Vec::new();
        encode(&image, &mut bytes).unwrap();
        let back = decode(&bytes).unwrap();
        assert_eq!((back.width, back.height), (3, 2));
        assert_eq!(back.data, image.to_rgb8());
        assert_eq!(&back.data[..6], &[255, 0, 0, 0, 255, 0]);
    }
}
