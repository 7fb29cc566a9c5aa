//! Gallery rows of driven systems: controllers through closures, models from the
//! linearisation.

use crate::catalog::control::TwoLinkArm;
use crate::{Row, TOL, row};
use lagrange::prelude::*;

pub fn rows(rows: &mut Vec<Row>) -> Result<(), Error> {
    rows.push(arm()?);
    Ok(())
}

/// The arm's reference: shoulder and elbow swinging at 1 and 1.5 rad/s.
fn reference(t: f64) -> [Vector2<f64>; 3] {
    [
        Vector2::new(0.5 * t.sin(), 0.8 + 0.4 * (1.5 * t).cos()),
        Vector2::new(0.5 * t.cos(), -0.6 * (1.5 * t).sin()),
        Vector2::new(-0.5 * t.sin(), -0.9 * (1.5 * t).cos()),
    ]
}

/// Computed-torque tracking from a 0.1 rad error: τ = M (q̈_d + K_d ė + K_p e)
/// − (Q − h) at zero torque.
fn arm() -> Result<Row, Error> {
    let arm = TwoLinkArm::standard();
    let (kp, kd) = (100.0, 20.0);
    let [q0, v0, _] = reference(0.0);
    row(
        "two-link arm, computed-torque tracking",
        0.0..5.0,
        false,
        || {
            Simulation::new(&arm)
                .integrator(Dopri5::tol(TOL))
                .feedback(|t, q: &Vector2<f64>, v: &Vector2<f64>| {
                    let [qd, vd, ad] = reference(t);
                    let (m, unforced) = arm.mass_matrix_and_rhs(q, v, t);
                    m * (ad + (vd - v) * kd + (qd - q) * kp) - unforced
                })
                .run(q0 + Vector2::new(0.1, -0.1), v0, 0.0..5.0)
                .map(|run| run.into_trajectory())
        },
        |tr| {
            let after = |from: f64| {
                tr.times()
                    .iter()
                    .zip(tr.positions())
                    .filter(|(t, _)| **t >= from)
                    .map(|(t, q)| (reference(*t)[0] - q).abs().max())
                    .fold(0.0f64, f64::max)
            };
            format!(
                "tracking error {:.1e} rad after 1 s, {:.1e} after 3 s",
                after(1.0),
                after(3.0)
            )
        },
    )
}
