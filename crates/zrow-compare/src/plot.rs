//! The PNGs: relative time against polygons (log-log), and the scenes.
//!
//! Text goes through plotters' `ab_glyph` feature (pure Rust): the TrueType file is read at
//! run time, `$ZROW_FONT` or DejaVu Sans from Debian's `fonts-dejavu-core`.

use crate::bench::SIZE;
use crate::report::{Report, FOLEY};
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use plotters::prelude::*;
use std::path::Path;

pub use crate::font::init_font;

/// A colour per method (ours solid, Foley's dashed in the same colour).
fn colour(method: &str) -> RGBColor {
    match method {
        "depth-sort" => RGBColor(214, 39, 40),
        "zbuffer" => RGBColor(31, 119, 180),
        "warnock" => RGBColor(44, 160, 44),
        "scanline" => RGBColor(148, 103, 189),
        "bsp" => RGBColor(255, 127, 14),
        "tiled" => RGBColor(23, 190, 207),
        _ => RGBColor(90, 90, 90),
    }
}

fn err(e: impl std::fmt::Display) -> String {
    format!("plot: {e}")
}

/// `foley.png`: every method's relative time, Foley's three rows dashed.
pub fn relative_times(rep: &Report, path: &Path) -> Result<(), String> {
    let xs: Vec<f64> = rep.scenes.iter().map(|s| s.polygons as f64).collect();
    let mut ours = vec![];
    for m in &rep.methods {
        let pts: Vec<(f64, f64)> = (0..xs.len())
            .filter_map(|k| Some((xs[k], rep.relative(m.name, k)?)))
            .collect();
        ours.push((m.name, pts));
    }
    let all = ours
        .iter()
        .flat_map(|(_, p)| p.iter().map(|q| q.1))
        .chain(FOLEY.iter().flat_map(|f| f.2));
    let (lo, hi) = all.fold((f64::MAX, f64::MIN), |(l, h), y| (l.min(y), h.max(y)));
    let (lo, hi) = (
        10f64.powf(lo.log10().floor()),
        10f64.powf(hi.log10().ceil()),
    );
    let unit = rep.unit().map_or("?", |u| u.0);
    let root = BitMapBackend::new(path, (1100, 760)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("Foley & van Dam Table 15.3 vs zrow ({SIZE}x{SIZE}, Q16.16, host)"),
            ("sans-serif", 28),
        )
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(80)
        .build_cartesian_2d((70f64..90_000f64).log_scale(), (lo..hi).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("polygons in the scene")
        .y_desc(format!("relative time ({unit} at 100 polygons = 1)"))
        .axis_desc_style(("sans-serif", 20))
        .label_style(("sans-serif", 17))
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| {
            if *y >= 1.0 {
                format!("{y:.0}")
            } else {
                format!("{y}")
            }
        })
        .draw()
        .map_err(err)?;
    for (name, _, f) in FOLEY {
        let c = colour(name_of(name));
        let pts: Vec<(f64, f64)> = [100.0, 2500.0, 60000.0].into_iter().zip(f).collect();
        chart
            .draw_series(DashedLineSeries::new(pts.clone(), 12, 8, c.stroke_width(2)))
            .map_err(err)?
            .label(format!("Foley: {name} (estimate)"))
            .legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (8, 0)], c.stroke_width(2))
                    + PathElement::new(vec![(13, 0), (20, 0)], c.stroke_width(2))
            });
        chart
            .draw_series(
                pts.iter()
                    .map(|&p| TriangleMarker::new(p, 6, c.stroke_width(1))),
            )
            .map_err(err)?;
    }
    for (name, pts) in ours {
        let c = colour(name);
        chart
            .draw_series(LineSeries::new(pts.clone(), c.stroke_width(3)))
            .map_err(err)?
            .label(format!("zrow: {name}"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3)));
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 5, c.filled())))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 17))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerRight)
        .draw()
        .map_err(err)?;
    root.present().map_err(err)
}

/// zrow's name for a row of Foley's table.
fn name_of(foley: &str) -> &'static str {
    FOLEY.iter().find(|f| f.0 == foley).map_or("", |f| f.1)
}

/// `scenes.png`: the frames side by side, each labelled with its polygon count.
pub fn scenes(frames: &[Vec<Rgb565>], path: &Path) -> Result<(), String> {
    let n = frames.len().max(1) as u32;
    let (w, h, gap, label) = (SIZE as u32, SIZE as u32, 12u32, 40u32);
    let root =
        BitMapBackend::new(path, (n * w + (n + 1) * gap, h + label + gap)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let counts = ["100", "2,500", "60,000"];
    for (k, frame) in frames.iter().enumerate() {
        let x0 = gap + k as u32 * (w + gap);
        for (i, p) in frame.iter().enumerate() {
            let (x, y) = ((i % SIZE) as u32, (i / SIZE) as u32);
            let scale = |v: u8, max: u32| ((v as u32 * 255 + max / 2) / max) as u8;
            let c = RGBColor(scale(p.r(), 31), scale(p.g(), 63), scale(p.b(), 31));
            root.draw_pixel(((x0 + x) as i32, (label + y) as i32), &c)
                .map_err(err)?;
        }
        let text = format!("{} polygons", counts.get(k).unwrap_or(&"?"));
        root.draw(&Text::new(
            text,
            (x0 as i32 + 4, 8),
            ("sans-serif", 24).into_font().color(&BLACK),
        ))
        .map_err(err)?;
    }
    root.present().map_err(err)
}
