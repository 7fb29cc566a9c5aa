//! A legged robot with its feet on the ground: Solo 12 from its URDF,
//! dropped onto the floor and standing under PD control, time-stepped by
//! Moreau–Jean, with the event-driven run's standing height beside it.

use crate::figure::Figure;
use crate::free::{csv, free_row};
use crate::legged_robot::{Solo12Standing, dropped, pd};
use crate::row::Row;
use lagrange::prelude::*;
use lagrange::{ChangeKind, ContactRun, ContactState, Dop853, MoreauJean};
use std::time::Instant;

/// The drop's start and the run's end, s.
const SPAN: std::ops::Range<f64> = 0.0..1.5;

/// Dropped level from 0.30 m (its feet 6.5 cm above the floor) in its
/// standing posture, PD control holding the posture (kp = 6 N·m/rad,
/// kd = 0.3 N·m·s/rad): it lands on four feet at once, sags and settles.
pub(crate) fn solo_12(system: &'static str) -> Result<Row, Error> {
    let robot = Solo12Standing {};
    let law = |_: f64, q: &SVector<f64, 19>, v: &SVector<f64, 18>| pd(q, v);
    let start = Instant::now();
    let run = Simulation::new(&robot)
        .integrator(MoreauJean::step(5e-4))
        .feedback(law)
        .run_contacts(dropped(0.30), SVector::zeros(), SPAN)
        .map_err(|f| f.error)?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let exact = Simulation::new(&robot)
        .integrator(Dop853::tol(1e-9))
        .feedback(law)
        .run_contacts(dropped(0.30), SVector::zeros(), SPAN)
        .map_err(|f| f.error)?;
    let note = note(&run, &exact);
    let traj = &run.trajectory;
    let figure = figure(traj, csv(&robot, traj)?);
    let mut row = free_row(system, &robot, traj, SPAN, (note, wall_ms), figure)?;
    // Driven and dissipative: no integral to keep.
    row.drift = None;
    Ok(row)
}

/// When it landed, where it stands, on what, and the event-driven run's
/// answer beside it.
fn note(run: &ContactRun<f64, 18, 19>, exact: &ContactRun<f64, 18, 19>) -> String {
    let landed = (run.changes.iter())
        .find(|c| matches!(c.kind, ChangeKind::Impact { .. } | ChangeKind::Closes))
        .map_or(f64::NAN, |c| c.t);
    let (q, v) = run.trajectory.final_state();
    let sticking = (run.states(SPAN.end).iter())
        .filter(|s| **s == ContactState::Sticking)
        .count();
    let (qe, _) = exact.trajectory.final_state();
    format!(
        "lands at t = {landed:.3} s; stands at base height {:.4} m on {sticking} sticking feet, \
         speed {:.0e}; event-driven (Dop853, {} changes): {:.4} m",
        q[2],
        v.norm(),
        exact.changes.len(),
        qe[2]
    )
}

/// The base's height and the front left leg's hip and knee.
fn figure(traj: &Trajectory<f64, 18, 19>, csv: String) -> Figure {
    let names = <Solo12Standing as Lagrangian<f64, 18, 19>>::COORDINATES;
    let shown = [2, 7, 11];
    let points: Vec<(f64, [f64; 3], [f64; 3])> = (0..traj.len())
        .map(|k| {
            let (q, v) = (&traj.positions()[k], &traj.velocities()[k]);
            (traj.times()[k], shown.map(|i| q[i]), shown.map(|i| v[i]))
        })
        .collect();
    let mut figure = Figure::from_points(&shown.map(|i| names[i]), &points);
    figure.csv = csv;
    figure
}
