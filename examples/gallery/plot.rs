//! The gallery's pictures: per system a PNG of the motion over time, the drift
//! of its conserved quantity and its constraint residuals; and GIF animations of
//! the double pendulum, the rolling disk and the point in the cavity.

use crate::figure::Figure;
use crate::layout::{self, Shown};
use lagrange::Error;
use lagrange::picture::COLORS;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Values below this are drawn at it on the log panels.
const FLOOR: f64 = 1e-17;

fn err(e: impl std::fmt::Display) -> Error {
    Error::Io(std::io::Error::other(format!("gallery plot: {e}")))
}

/// The system's PNG: the coordinates that carry the behaviour against t, the
/// rates of the cyclic ones on a panel of their own (see `layout`), a row's
/// own panels (`Figure::extra`, an estimate against the truth); below, the
/// conserved quantity's relative drift and the constraint residuals on log
/// axes, where present.
pub(crate) fn system_png(path: &Path, title: &str, fig: &Figure) -> Result<(), Error> {
    let names: Vec<&str> = fig.names.iter().map(String::as_str).collect();
    let motion = layout::motion_panels(&names, &fig.cyclic);
    let panels = motion.len()
        + fig.extra.len()
        + usize::from(fig.drift.is_some())
        + usize::from(fig.residuals.is_some());
    let root = BitMapBackend::new(path, (900, 260 * panels as u32 + 40)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let body = root.titled(title, ("sans-serif", 22)).map_err(err)?;
    let areas = body.split_evenly((panels, 1));
    let mut next = areas.iter();
    for panel in &motion {
        let series: Vec<(String, &[f64])> = panel
            .series
            .iter()
            .map(|(i, label, shown)| {
                let values = match shown {
                    Shown::Value => &fig.q[*i],
                    Shown::Rate => &fig.v[*i],
                };
                (label.clone(), values.as_slice())
            })
            .collect();
        linear_panel(next.next().unwrap_or(&body), &fig.t, panel.y_label, &series)?;
    }
    for extra in &fig.extra {
        let series: Vec<(String, &[f64])> = (extra.series.iter())
            .map(|(name, s)| (name.clone(), s.as_slice()))
            .collect();
        linear_panel(
            next.next().unwrap_or(&body),
            &extra.t,
            extra.y_label,
            &series,
        )?;
    }
    if let Some(d) = &fig.drift {
        log_panel(
            next.next().unwrap_or(&body),
            fig,
            "|I(t) − I(0)| / |I(0)|",
            &[("conserved quantity".into(), d.clone())],
            false,
        )?;
    }
    if let Some(r) = &fig.residuals {
        let pos: Vec<f64> = r.iter().map(|x| x[0]).collect();
        let vel: Vec<f64> = r.iter().map(|x| x[1]).collect();
        log_panel(
            next.next().unwrap_or(&body),
            fig,
            "constraint residuals",
            &[("|Φ|".into(), pos), ("|G q̇ + g|".into(), vel)],
            true,
        )?;
    }
    root.present().map_err(err)
}

fn range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return -1.0..1.0;
    }
    let pad = ((hi - lo) * 0.05).max(1e-9);
    lo - pad..hi + pad
}

fn linear_panel(
    area: &DrawingArea<BitMapBackend, Shift>,
    t: &[f64],
    y_label: &str,
    series: &[(String, &[f64])],
) -> Result<(), Error> {
    let (t0, t1) = (
        t.first().copied().unwrap_or(0.0),
        t.last().copied().unwrap_or(1.0),
    );
    let y = range(series.iter().flat_map(|(_, s)| s.iter().copied()));
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(t0..t1, y)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("t")
        .y_desc(y_label)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err)?;
    for (k, (name, s)) in series.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        chart
            .draw_series(LineSeries::new(
                t.iter().copied().zip(s.iter().copied()),
                color.stroke_width(2),
            ))
            .map_err(err)?
            .label(name.as_str())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(2)));
    }
    legend(&mut chart)
}

/// A log panel; values below the floor (zeros, where a projection lands on
/// the constraint exactly) are drawn on it. `dots` draws points instead of
/// a line, for quantities that jump between round-off and zero.
fn log_panel(
    area: &DrawingArea<BitMapBackend, Shift>,
    fig: &Figure,
    y_label: &str,
    series: &[(String, Vec<f64>)],
    dots: bool,
) -> Result<(), Error> {
    let (t0, t1) = fig.span();
    let values = || series.iter().flat_map(|(_, s)| s.iter().copied());
    let hi = values().fold(FLOOR, f64::max);
    let lo = values()
        .filter(|v| *v > 0.0)
        .fold(hi, f64::min)
        .max(hi * 1e-8)
        .max(FLOOR);
    let (lo, hi) = (lo / 3.0, hi * 3.0);
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(t0..t1, (lo..hi).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("t")
        .y_desc(y_label)
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err)?;
    for (k, (name, s)) in series.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        let points = fig.t.iter().copied().zip(s.iter().map(|v| v.clamp(lo, hi)));
        let drawn = if dots {
            chart.draw_series(points.map(|p| Circle::new(p, 1, color.filled())))
        } else {
            chart.draw_series(LineSeries::new(points, color.stroke_width(2)))
        };
        drawn
            .map_err(err)?
            .label(name.as_str())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(2)));
    }
    legend(&mut chart)
}

fn legend<'a, 'b, X: Ranged, Y: Ranged>(
    chart: &mut ChartContext<'a, BitMapBackend<'b>, Cartesian2d<X, Y>>,
) -> Result<(), Error>
where
    'b: 'a,
{
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(err)
}

/// The path of a point `at(q)` over every recorded step up to t.
fn trail(fig: &Figure, t: f64, at: impl Fn(&[f64]) -> (f64, f64)) -> Vec<(f64, f64)> {
    let upto = fig.t.partition_point(|&s| s <= t);
    let mut q = vec![0.0; fig.q.len()];
    (0..upto)
        .map(|k| {
            for (i, c) in fig.q.iter().enumerate() {
                q[i] = c[k];
            }
            at(&q)
        })
        .collect()
}

/// Frames of an animation: `draw(area, t)` for `frames` times over the span.
fn animate(
    path: &Path,
    fig: &Figure,
    frames: usize,
    size: (u32, u32),
    mut draw: impl FnMut(&DrawingArea<BitMapBackend, Shift>, f64, usize) -> Result<(), Error>,
) -> Result<(), Error> {
    let (t0, t1) = fig.span();
    let root = BitMapBackend::gif(path, size, 50)
        .map_err(err)?
        .into_drawing_area();
    for k in 0..frames {
        let t = t0 + (t1 - t0) * k as f64 / (frames - 1) as f64;
        root.fill(&WHITE).map_err(err)?;
        draw(&root, t, k)?;
        root.present().map_err(err)?;
    }
    Ok(())
}

/// The double pendulum: both rods and the path of the outer bob.
pub(crate) fn double_pendulum_gif(
    path: &Path,
    fig: &Figure,
    l1: f64,
    l2: f64,
) -> Result<(), Error> {
    let reach = (l1 + l2) * 1.1;
    let bob = |q: &[f64]| {
        let p1 = (l1 * q[0].sin(), -l1 * q[0].cos());
        (p1, (p1.0 + l2 * q[1].sin(), p1.1 - l2 * q[1].cos()))
    };
    animate(path, fig, 160, (420, 420), |root, t, _| {
        let (p1, p2) = bob(&fig.at(t));
        let trail = trail(fig, t, |q| bob(q).1);
        let mut chart = ChartBuilder::on(root)
            .caption(format!("double pendulum, t = {t:.2} s"), ("sans-serif", 18))
            .margin(10)
            .build_cartesian_2d(-reach..reach, -reach..reach)
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(trail, COLORS[1].mix(0.5)))
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new([(0.0, 0.0), p1, p2], BLACK.stroke_width(3)))
            .map_err(err)?;
        chart
            .draw_series([p1, p2].map(|p| Circle::new(p, 7, COLORS[0].filled())))
            .map_err(err)?;
        Ok(())
    })
}

/// The rolling disk seen from above: the contact's path, and the disk as the
/// segment where its plane meets the ground, tilted by θ.
pub(crate) fn rolling_disk_gif(path: &Path, fig: &Figure, radius: f64) -> Result<(), Error> {
    let x = range(fig.q[0].iter().copied());
    let y = range(fig.q[1].iter().copied());
    let half = (x.end - x.start).max(y.end - y.start) / 2.0 + 2.0 * radius;
    let (cx, cy) = ((x.start + x.end) / 2.0, (y.start + y.end) / 2.0);
    animate(path, fig, 120, (420, 420), |root, t, _| {
        let q = fig.at(t);
        let (px, py, psi, theta) = (q[0], q[1], q[2], q[3]);
        let trail = trail(fig, t, |q| (q[0], q[1]));
        // The disk's plane contains the heading (cos ψ, sin ψ); its top view
        // is that diameter, and the centre sits a sin θ sideways.
        let (hx, hy) = (psi.cos(), psi.sin());
        let side = radius * theta.sin();
        let centre = (px + side * psi.sin(), py - side * psi.cos());
        let rim = [
            (centre.0 - radius * hx, centre.1 - radius * hy),
            (centre.0 + radius * hx, centre.1 + radius * hy),
        ];
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("rolling disk (top view), t = {t:.2} s"),
                ("sans-serif", 18),
            )
            .margin(10)
            .build_cartesian_2d(cx - half..cx + half, cy - half..cy + half)
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(trail, COLORS[1].stroke_width(2)))
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(rim, COLORS[0].stroke_width(6)))
            .map_err(err)?;
        chart
            .draw_series([Circle::new((px, py), 4, BLACK.filled())])
            .map_err(err)?;
        Ok(())
    })
}

/// The point in the spherical cavity, projected on the x–z plane: the wall's
/// great circle and the path, bounces then sliding.
pub(crate) fn cavity_gif(path: &Path, fig: &Figure, radius: f64) -> Result<(), Error> {
    let reach = radius * 1.15;
    let circle: Vec<(f64, f64)> = (0..=200)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 200.0;
            (radius * a.cos(), radius * a.sin())
        })
        .collect();
    animate(path, fig, 120, (420, 420), |root, t, _| {
        let q = fig.at(t);
        let trail = trail(fig, t, |q| (q[0], q[2]));
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("point in a cavity (x–z), t = {t:.2} s"),
                ("sans-serif", 18),
            )
            .margin(10)
            .build_cartesian_2d(-reach..reach, -reach..reach)
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(
                circle.iter().copied(),
                BLACK.stroke_width(2),
            ))
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(trail, COLORS[1].mix(0.7)))
            .map_err(err)?;
        chart
            .draw_series([Circle::new((q[0], q[2]), 6, COLORS[3].filled())])
            .map_err(err)?;
        Ok(())
    })
}
