//! Work-precision diagrams as PNG, with plotters and the bundled font
//! (`picture` holds what every picture shares).

use super::{Measurement, Row, Study};
use crate::error::Error;
use crate::picture::{COLORS, plot_error, register_font};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Errors and drifts below this are drawn at it: a log axis has no zero, and
/// nothing below f64 round-off is meaningful anyway.
const FLOOR: f64 = 1e-17;

/// One panel: which cost on x, which accuracy measure on y.
struct Panel {
    x_label: &'static str,
    y_label: &'static str,
    x: fn(&Measurement) -> f64,
    y: fn(&Measurement) -> Option<f64>,
}

const PANELS: [Panel; 3] = [
    Panel {
        x_label: "RHS evaluations",
        y_label: "max |q - q_ref| at t_end",
        x: |m| m.stats.evaluations as f64,
        y: |m| Some(m.error),
    },
    Panel {
        x_label: "wall time [s]",
        y_label: "max |q - q_ref| at t_end",
        x: |m| m.wall_time.as_secs_f64(),
        y: |m| Some(m.error),
    },
    Panel {
        x_label: "wall time [s]",
        y_label: "max relative drift of the integral",
        x: |m| m.wall_time.as_secs_f64(),
        y: |m| m.drift,
    },
];

impl Study {
    /// Draws the study as a log-log PNG of 1500 × 500 pixels: final-time
    /// position error against RHS evaluations and against wall time, and the
    /// drift of the conserved integral against wall time (left empty for a
    /// non-conservative study). One colour per method, its settings joined in
    /// sweep order; failed runs are not drawn, the legend counts them.
    ///
    /// # Errors
    /// [`Error::Io`] if the font cannot be loaded or the file not written.
    pub fn plot_png(&self, path: impl AsRef<Path>, title: &str) -> Result<(), Error> {
        register_font()?;
        let root = BitMapBackend::new(path.as_ref(), (1500, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let body = root.titled(title, ("sans-serif", 22)).map_err(plot_error)?;
        let groups = self.by_method();
        for (area, panel) in body.split_evenly((1, 3)).iter().zip(&PANELS) {
            draw_panel(area, panel, &groups)?;
        }
        root.present().map_err(plot_error)
    }

    /// The rows grouped by method, in order of first appearance.
    fn by_method(&self) -> Vec<(&str, Vec<&Row>)> {
        let mut groups: Vec<(&str, Vec<&Row>)> = Vec::new();
        for row in &self.rows {
            match groups.iter_mut().find(|(name, _)| *name == row.method) {
                Some((_, rows)) => rows.push(row),
                None => groups.push((&row.method, vec![row])),
            }
        }
        groups
    }
}

/// The points of one method on one panel, in sweep order.
fn points(rows: &[&Row], panel: &Panel) -> Vec<(f64, f64)> {
    rows.iter()
        .filter_map(|r| r.measurement())
        .filter_map(|m| Some(((panel.x)(m), (panel.y)(m)?)))
        .filter(|(x, y)| x.is_finite() && *x > 0.0 && y.is_finite())
        .map(|(x, y)| (x, y.max(FLOOR)))
        .collect()
}

/// A log range covering `values` with some margin; (1, 10) when there are none.
fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if !(lo.is_finite() && hi > 0.0) {
        return 1.0..10.0;
    }
    // A factor 2 on each side keeps markers off the frame; a single point
    // still gets a decade.
    let lo = lo / 2.0;
    let hi = hi * 2.0;
    if hi / lo < 10.0 {
        lo / 3.0..hi * 3.0
    } else {
        lo..hi
    }
}

/// A setting as its point's label: the fewest significant digits (at most
/// [`SETTING_DIGITS`]) that give back the value run, so that 2.5e-4 is not
/// printed as 3e-4 and read as another run's.
pub(super) fn setting_label(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    (0..SETTING_DIGITS)
        .map(|decimals| format!("{x:.decimals$e}"))
        .find(|s| s.parse::<f64>() == Ok(x))
        .unwrap_or_else(|| format!("{x:.prec$e}", prec = SETTING_DIGITS - 1))
}

/// The most significant digits a point's label shows (a setting that needs
/// more, h = 0.1 / 3, is shown rounded to these).
const SETTING_DIGITS: usize = 4;

/// A log axis's tick label: the decades (`1e-3`), and nothing at the ticks
/// between them, whose labels would overlap the decades'.
pub(super) fn decade_label(v: f64) -> String {
    if !(v.is_finite() && v > 0.0) {
        return String::new();
    }
    let exponent = v.log10().round();
    let decade = 10f64.powi(exponent as i32);
    if ((v - decade) / decade).abs() < 1e-9 {
        format!("1e{exponent}")
    } else {
        String::new()
    }
}

/// How many labels of `label` pixels (with their spacing) fit along an axis
/// of `length` pixels; at least 2, so that an axis is never left bare.
pub(super) fn labels_that_fit(length: u32, label: u32) -> usize {
    (length / label.max(1)).max(2) as usize
}

/// Each point with its setting (step or tolerance), so that a reader can find
/// the run in the table.
fn setting_labels(rows: &[&Row], panel: &Panel) -> Vec<((f64, f64), String)> {
    rows.iter()
        .filter_map(|r| {
            let m = r.measurement()?;
            let x = (panel.x)(m);
            let y = (panel.y)(m)?;
            (x.is_finite() && x > 0.0 && y.is_finite())
                .then(|| ((x, y.max(FLOOR)), setting_label(r.setting.value())))
        })
        .collect()
}

fn draw_panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    panel: &Panel,
    groups: &[(&str, Vec<&Row>)],
) -> Result<(), Error> {
    let series: Vec<Vec<(f64, f64)>> = groups.iter().map(|(_, rows)| points(rows, panel)).collect();
    let all = || series.iter().flatten();
    let x_range = log_range(all().map(|p| p.0));
    let y_range = log_range(all().map(|p| p.1));
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())
        .map_err(plot_error)?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label)
        .y_desc(panel.y_label)
        // Decades only, and no more of them than fit: plotters adds
        // intermediate ticks (2e-3, 3e-3, ...) on a short log axis, and their
        // labels ran into one another.
        .x_labels(labels_that_fit(area.dim_in_pixel().0, 44))
        .y_labels(labels_that_fit(area.dim_in_pixel().1, 20))
        .x_label_formatter(&|v| decade_label(*v))
        .y_label_formatter(&|v| decade_label(*v))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        // Only the decades: the minor lines of a log mesh triple the PNG's size
        // and add nothing a reader of orders of magnitude needs.
        .light_line_style(TRANSPARENT)
        .draw()
        .map_err(plot_error)?;
    for (k, ((name, rows), pts)) in groups.iter().zip(&series).enumerate() {
        let color = COLORS[k % COLORS.len()];
        // Offset from the marker so the label does not sit under it.
        chart
            .draw_series(setting_labels(rows, panel).into_iter().map(|(p, text)| {
                EmptyElement::at(p)
                    + Text::new(text, (6, -4), ("sans-serif", 10).into_font().color(&color))
            }))
            .map_err(plot_error)?;
        let failed = rows.iter().filter(|r| r.outcome.is_err()).count();
        let label = if failed > 0 {
            format!("{name} ({failed} failed)")
        } else {
            name.to_string()
        };
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
            .map_err(plot_error)?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
            .map_err(plot_error)?;
    }
    // A legend on every panel: each is read on its own.
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .label_font(("sans-serif", 13))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(plot_error)?;
    Ok(())
}
