//! The font of the PNGs' text, shared with zrow-tradeoff (which includes this file by path).
//!
//! Text goes through plotters' `ab_glyph` feature (pure Rust): the TrueType file is read at
//! run time, `$ZROW_FONT` or DejaVu Sans from Debian's `fonts-dejavu-core`.

use plotters::style::{register_font, FontStyle};

/// The default font file.
pub const DEFAULT_FONT: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

/// Registers the font as plotters' "sans-serif".
pub fn init_font() -> Result<(), String> {
    let path = std::env::var("ZROW_FONT").unwrap_or_else(|_| DEFAULT_FONT.into());
    let bytes = std::fs::read(&path).map_err(|e| {
        format!(
            "font {path}: {e} (install it with `apt-get install fonts-dejavu-core`, or set \
             ZROW_FONT to any .ttf file)"
        )
    })?;
    register_font(
        "sans-serif",
        FontStyle::Normal,
        Box::leak(bytes.into_boxed_slice()),
    )
    .map_err(|_| format!("font {path}: not a TrueType font plotters can read"))
}
