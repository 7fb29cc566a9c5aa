//! A run's table drawn as curves against t: the columns chosen by name.

use super::{COLORS, check_size, plot_error, register_font};
use crate::error::{Error, SettingsError};
use crate::numeric::Real;
use crate::table::Table;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// The owner named in a table plot's errors.
const OWNER: &str = "table plot";

/// What [`Table::plot_png`] draws: which columns, the title, the y axis's
/// label and the size in pixels.
///
/// ```
/// use lagrange_runtime::picture::TablePlot;
/// let plot = TablePlot::new()
///     .columns(&["theta", "dot_theta"])
///     .title("pendulum")
///     .size(800, 400);
/// # let _ = plot;
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct TablePlot {
    columns: Option<Vec<String>>,
    title: Option<String>,
    y_label: Option<String>,
    size: (u32, u32),
}

impl Default for TablePlot {
    fn default() -> Self {
        Self::new()
    }
}

impl TablePlot {
    /// Every coordinate (the columns of q) against t, 900 × 400 pixels, no
    /// title.
    pub fn new() -> Self {
        Self {
            columns: None,
            title: None,
            y_label: None,
            size: (900, 400),
        }
    }

    /// The columns to draw, by the table's names (`theta`, `dot_theta`,
    /// `kinetic`, `integral`, `nu_rod`, ...), each in its colour.
    pub fn columns(mut self, names: &[&str]) -> Self {
        self.columns = Some(names.iter().map(|n| n.to_string()).collect());
        self
    }

    /// The title above the plot.
    pub fn title(mut self, title: impl Into<String>) -> Self {
        self.title = Some(title.into());
        self
    }

    /// The y axis's label (default: the columns' names, or "value" when
    /// there are many).
    pub fn y_label(mut self, label: impl Into<String>) -> Self {
        self.y_label = Some(label.into());
        self
    }

    /// The picture's size in pixels (at least 32 × 32).
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    /// The y axis's label for `names`.
    fn label(&self, names: &[String]) -> String {
        if let Some(label) = &self.y_label {
            return label.clone();
        }
        let joined = names.join(", ");
        if joined.chars().count() <= 40 {
            joined
        } else {
            "value".into()
        }
    }
}

/// One column's curve: its name and its points (t, value), a value left empty
/// in the table as `None`.
pub(super) struct Curve {
    pub name: String,
    pub points: Vec<(f64, Option<f64>)>,
}

impl<T: Real, const N: usize, const Q: usize> Table<'_, T, N, Q> {
    /// Draws the columns `plot` names (by default the coordinates) against t
    /// as a PNG at `path`: the axes labelled, one colour per column with a
    /// legend, the title on top. A cell the table leaves empty (a rate where
    /// its chart is singular) breaks the curve there.
    ///
    /// ```no_run
    /// # use lagrange_runtime::{Error, Lagrangian, Trajectory};
    /// use lagrange_runtime::picture::TablePlot;
    /// # fn demo<S: Lagrangian<f64, 2>>(sys: &S, run: &Trajectory<f64, 2>) -> Result<(), Error> {
    /// run.table(sys).plot_png("angles.png", &TablePlot::new().title("double pendulum"))?;
    /// # Ok(()) }
    /// ```
    ///
    /// # Errors
    /// [`Error::Settings`] ([`SettingsError::Data`]) for a column the table
    /// does not have, no column, or a size below 32 × 32 pixels;
    /// [`Error::Io`] if the file cannot be written.
    pub fn plot_png(&self, path: impl AsRef<Path>, plot: &TablePlot) -> Result<(), Error> {
        let curves = self.curves(plot)?;
        check_size(OWNER, plot.size)?;
        let root = BitMapBackend::new(path.as_ref(), plot.size).into_drawing_area();
        draw(&root, plot, &curves)?;
        root.present().map_err(plot_error)
    }

    /// The curves `plot` asks for, checked against the header.
    pub(super) fn curves(&self, plot: &TablePlot) -> Result<Vec<Curve>, Error> {
        let header = self.header();
        let names: Vec<String> = match &plot.columns {
            Some(names) => names.clone(),
            None => self.coordinates().to_vec(),
        };
        if names.is_empty() {
            return Err(data("no column to draw".into()));
        }
        let columns = names
            .iter()
            .map(|n| {
                header.iter().position(|h| h == n).ok_or_else(|| {
                    data(format!(
                        "no column `{n}` in the table: its columns are {header:?}"
                    ))
                })
            })
            .collect::<Result<Vec<usize>, Error>>()?;
        let rows: Vec<Vec<Option<f64>>> = (0..self.len()).map(|k| self.row(k)).collect();
        Ok(names
            .into_iter()
            .zip(columns)
            .map(|(name, j)| Curve {
                name,
                points: rows.iter().filter_map(|r| Some((r[0]?, r[j]))).collect(),
            })
            .collect())
    }
}

fn data(problem: String) -> Error {
    SettingsError::Data {
        owner: OWNER,
        problem,
    }
    .into()
}

/// The span of the finite `values`, widened by 5 % (and around a constant);
/// (−1, 1) when there are none.
pub(super) fn padded(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return -1.0..1.0;
    }
    let pad = ((hi - lo) * 0.05).max(1e-9 * lo.abs().max(hi.abs()).max(1.0));
    lo - pad..hi + pad
}

/// The plot on `area` (the font registered first); gives the mapping from
/// (t, value) to pixels.
pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    plot: &TablePlot,
    curves: &[Curve],
) -> Result<Cartesian2d<RangedCoordf64, RangedCoordf64>, Error> {
    register_font()?;
    area.fill(&WHITE).map_err(plot_error)?;
    let body = match &plot.title {
        Some(title) => area.titled(title, ("sans-serif", 20)).map_err(plot_error)?,
        None => area.clone(),
    };
    let t = time_range(curves);
    let y = padded(
        curves
            .iter()
            .flat_map(|c| c.points.iter().filter_map(|p| p.1)),
    );
    let mut chart = ChartBuilder::on(&body)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(64)
        .build_cartesian_2d(t, y)
        .map_err(plot_error)?;
    let names: Vec<String> = curves.iter().map(|c| c.name.clone()).collect();
    chart
        .configure_mesh()
        .x_desc("t")
        .y_desc(plot.label(&names))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .draw()
        .map_err(plot_error)?;
    for (k, curve) in curves.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        let style = color.stroke_width(2);
        let pieces = pieces(&curve.points);
        for (i, piece) in pieces.iter().enumerate() {
            let drawn = chart
                .draw_series(LineSeries::new(piece.iter().copied(), style))
                .map_err(plot_error)?;
            if i == 0 {
                drawn.label(curve.name.as_str()).legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 18, y)], color.stroke_width(2))
                });
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font(("sans-serif", 13))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(plot_error)?;
    Ok(chart.as_coord_spec().clone())
}

/// The run's span on the t axis, from its first point to its last (padded
/// only when that is a single time).
fn time_range(curves: &[Curve]) -> Range<f64> {
    let times = || curves.iter().flat_map(|c| c.points.iter().map(|p| p.0));
    let lo = times().fold(f64::INFINITY, f64::min);
    let hi = times().fold(f64::NEG_INFINITY, f64::max);
    if lo < hi { lo..hi } else { padded(times()) }
}

/// The runs of consecutive finite values: a curve is broken where a cell is
/// empty or not finite.
pub(super) fn pieces(points: &[(f64, Option<f64>)]) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    for &(t, y) in points {
        match y.filter(|y| y.is_finite()) {
            Some(y) => match out.last_mut() {
                Some(piece) => piece.push((t, y)),
                None => out.push(vec![(t, y)]),
            },
            None if out.last().is_some_and(|p| !p.is_empty()) => out.push(Vec::new()),
            None => {}
        }
    }
    out.retain(|p| !p.is_empty());
    out
}
