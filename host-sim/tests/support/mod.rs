//! Test support shared by host-sim's test files: golden-image comparison with the bless
//! switch, and a small deterministic generator.
#![allow(dead_code)]

use std::path::Path;
use zrow_sim::png_io;
use zrow_sim::render::Image;

/// Compares `image` with the PNG at `reference`. With `bless`, writes it there instead. On a
/// mismatch (or a missing reference) writes `image` to `actual` and says what differs.
pub fn compare_golden(
    image: &Image,
    reference: &Path,
    actual: &Path,
    bless: bool,
) -> Result<(), String> {
    let mut png = Vec::new();
    png_io::encode(image, &mut png).map_err(|e| e.to_string())?;
    if bless {
        std::fs::write(reference, &png).map_err(|e| e.to_string())?;
        let _ = std::fs::remove_file(actual);
        return Ok(());
    }
    let want = match std::fs::read(reference) {
        Ok(bytes) => png_io::decode(&bytes).map_err(|e| format!("{}: {e}", reference.display()))?,
        Err(e) => {
            std::fs::write(actual, &png).map_err(|e| e.to_string())?;
            return Err(format!(
                "{}: {e} (bless with ZROW_BLESS=1; wrote {})",
                reference.display(),
                actual.display()
            ));
        }
    };
    let got = image.to_rgb8();
    let same_size = got.len() == want.data.len();
    let differing = got
        .chunks(3)
        .zip(want.data.chunks(3))
        .filter(|(a, b)| a != b)
        .count();
    if same_size && differing == 0 {
        let _ = std::fs::remove_file(actual);
        return Ok(());
    }
    std::fs::write(actual, &png).map_err(|e| e.to_string())?;
    Err(format!(
        "{}: {} (see {})",
        reference.display(),
        if same_size {
            format!("{differing} pixels differ")
        } else {
            format!("reference is {}x{}", want.width, want.height)
        },
        actual.display()
    ))
}

/// xorshift64*: small, deterministic, good enough to pick mutations.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in `0..n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}
