//! `presets.png`: cost against error, one point per preset.
//!
//! Text goes through plotters' `ab_glyph` feature (pure Rust): the TrueType file is read at
//! run time, `$ZROW_FONT` or DejaVu Sans from Debian's `fonts-dejavu-core`.

use crate::Row;
use plotters::prelude::*;
use std::path::Path;

pub use crate::font::init_font;

fn err(e: impl std::fmt::Display) -> String {
    format!("plot: {e}")
}

/// Cost (emulated M4 instructions per frame, or host µs if the bench was not run) against
/// pixels in error per frame (log scale, +1 so an exact preset shows).
pub fn pareto(rows: &[Row], path: &Path) -> Result<(), String> {
    // M4 instructions if any preset has them (presets without are left out), else host µs.
    let m4 = rows.iter().any(|r| r.instructions().is_some());
    let pts: Vec<(f64, f64, &str)> = rows
        .iter()
        .filter_map(|r| {
            let x = if m4 {
                r.instructions()? / 1e6
            } else {
                r.host_us()
            };
            Some((x, r.error_pixels() + 1.0, r.preset.name))
        })
        .collect();
    let xmax = pts.iter().map(|p| p.0).fold(0.0, f64::max) * 1.15;
    let xmin = pts.iter().map(|p| p.0).fold(f64::MAX, f64::min) * 0.85;
    let ymax = pts.iter().map(|p| p.1).fold(1.0, f64::max) * 3.0;
    let root = BitMapBackend::new(path, (1000, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "zrow presets: cost against error (240x240, mean over cube, mesh1k, interlocked)",
            ("sans-serif", 20),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(xmin..xmax, (0.8f64..ymax).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(if m4 {
            "emulated Cortex-M4 instructions per frame (millions; not cycles)"
        } else {
            "host µs per frame (no emulator counts found)"
        })
        .y_desc("pixels in error per frame + 1")
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(pts.iter().map(|&(x, y, name)| {
            EmptyElement::at((x, y))
                + Circle::new((0, 0), 5, BLUE.filled())
                + Text::new(name.to_string(), (7, -12), ("sans-serif", 14))
        }))
        .map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}
