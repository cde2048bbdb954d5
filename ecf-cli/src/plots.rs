//! PNG plots of the measurement loop (plotters, bitmap backend, embedded DejaVu Sans font).

use plotters::prelude::*;
use std::path::Path;

static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Registers the embedded font once.
pub fn init_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // the font is embedded at compile time; a failure would be a build defect
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// How a data set is drawn.
#[derive(Clone, Copy)]
pub enum Style {
    /// Markers only (measurements).
    Points,
    /// A line (model).
    Line,
}

/// One data set of a plot.
pub struct Set<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Points (x, y).
    pub xy: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
    /// Palette index.
    pub color: usize,
}

fn bounds(sets: &[Set]) -> ((f64, f64), (f64, f64)) {
    let mut xr = (f64::MAX, f64::MIN);
    let mut yr = (f64::MAX, f64::MIN);
    for s in sets {
        for &(x, y) in &s.xy {
            if x.is_finite() && y.is_finite() {
                xr = (xr.0.min(x), xr.1.max(x));
                yr = (yr.0.min(y), yr.1.max(y));
            }
        }
    }
    let pad = |r: (f64, f64)| {
        if r.0 > r.1 {
            (0.0, 1.0)
        } else {
            let d = r.1 - r.0;
            if d <= 1e-9 * r.1.abs().max(r.0.abs()).max(1e-12) {
                // constant data: a visible range around the value
                let h = (0.1 * r.0.abs()).max(1e-3);
                (r.0 - h, r.1 + h)
            } else {
                (r.0 - 0.05 * d, r.1 + 0.05 * d)
            }
        }
    };
    (pad(xr), pad(yr))
}

/// Writes an x-y plot to `path` (PNG, 900 x 600).
pub fn xy_plot(
    path: &Path,
    title: &str,
    xlabel: &str,
    ylabel: &str,
    sets: &[Set],
) -> Result<(), String> {
    init_font();
    let root = BitMapBackend::new(path, (900, 600)).into_drawing_area();
    let e = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let ((x0, x1), (y0, y1)) = bounds(sets);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_desc(xlabel)
        .y_desc(ylabel)
        .label_style(("sans-serif", 15))
        .draw()
        .map_err(|x| e(&x))?;
    for s in sets {
        let c = Palette99::pick(s.color).to_rgba();
        match s.style {
            Style::Points => {
                chart
                    .draw_series(
                        s.xy.iter()
                            .filter(|p| p.0.is_finite() && p.1.is_finite())
                            .map(|&(x, y)| Circle::new((x, y), 3, c.filled())),
                    )
                    .map_err(|x| e(&x))?
                    .label(s.label)
                    .legend(move |(x, y)| Circle::new((x + 10, y), 3, c.filled()));
            }
            Style::Line => {
                chart
                    .draw_series(LineSeries::new(
                        s.xy.iter()
                            .copied()
                            .filter(|p| p.0.is_finite() && p.1.is_finite()),
                        c.stroke_width(2),
                    ))
                    .map_err(|x| e(&x))?
                    .label(s.label)
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                    });
            }
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .draw()
        .map_err(|x| e(&x))?;
    root.present().map_err(|x| e(&x))?;
    Ok(())
}
