//! The gallery row of C10: a point in a spherical cavity, impacts with
//! restitution 0.7 until the bounces die out, then sliding on the wall with a
//! multiplier. The run is made of phases, so the row is assembled here.

use std::time::Instant;

use crate::catalog::cavity::Cavity;
use crate::figure::Figure;
use crate::row::Row;
use lagrange::prelude::*;

/// The cavity's radius (its row and its animation).
pub(crate) const RADIUS: f64 = 1.0;

pub(crate) fn row(system: &'static str) -> Result<Row, Error> {
    let cavity = Cavity::new(1.0, 9.81, RADIUS, 0.7);
    let start = Instant::now();
    let run = cavity.simulate(
        Vector3::new(0.3, 0.0, 0.2),
        Vector3::new(0.5, 2.0, 1.0),
        0.0..8.0,
    )?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let mut stats = lagrange::Stats::default();
    let mut outside = 0.0f64;
    for phase in &run.phases {
        stats.add(phase.trajectory().stats());
    }
    for (_, q, _) in run.points() {
        outside = outside.max(q.norm() - cavity.r);
    }
    let points: Vec<(f64, [f64; 3], [f64; 3])> = run
        .points()
        .map(|(t, q, v)| (t, [q[0], q[1], q[2]], [v[0], v[1], v[2]]))
        .collect();
    Ok(Row {
        system,
        about: "",
        dof: 3,
        span: 8.0,
        accepted: stats.accepted,
        rejected: stats.rejected,
        evaluations: stats.evaluations,
        drift: None,
        residuals: None,
        note: format!(
            "{} impacts, sliding from t = {:.3}, max |x| − R = {outside:.1e}",
            run.impacts.len(),
            run.slides.first().copied().unwrap_or(f64::NAN)
        ),
        wall_ms,
        figure: Some(Figure::from_points(&["x", "y", "z"], &points)),
        // The run is made of phases of two systems (free flight and sliding
        // on the wall): one scene would need both; its GIF shows it instead.
        scene: None,
        still: None,
        frames: None,
    })
}
