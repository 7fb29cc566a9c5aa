//! Gallery rows of nonholonomic systems in reduced form (independent speeds or
//! quasi-velocities): the polar quasi-velocity, the sphere on a turning plane,
//! the rolling disk on a steady circle, the Chaplygin sleigh.

use crate::catalog::constrained::*;
use crate::row::{Row, TOL, row};
use lagrange::prelude::*;

/// The rolling disk's radius (its row and its animation).
pub(crate) const DISK_RADIUS: f64 = 0.5;

pub(crate) fn polar(system: &'static str) -> Result<Row, Error> {
    let polar = PolarQuasiVelocity {
        m: 1.3,
        k: 2.0,
        s: 0.4,
    };
    row(
        system,
        &polar,
        0.0..5.0,
        false,
        || {
            Simulation::new(&polar)
                .integrator(Dopri5::tol(TOL))
                .run_reduced([1.0, 0.3], [0.2, 0.9], 0.0..5.0)
        },
        |_| "Gibbs–Appell; transverse force: no integral".to_string(),
    )
}

/// C9: the velocity of the sphere's centre turns at 2Ω/7.
pub(crate) fn turntable(system: &'static str) -> Result<Row, Error> {
    let (m, a, big_omega) = (1.0, 0.2, 3.0);
    let turntable = SphereOnTurntable {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
        big_omega,
    };
    row(
        system,
        &turntable,
        0.0..10.0,
        false,
        || {
            Simulation::new(&turntable)
                .integrator(Dopri5::tol(TOL))
                .run_reduced(
                    [1.0, 0.5, 0.3, 1.2, 0.0],
                    [0.0, 0.0, 0.8, -0.4, 2.0],
                    0.0..10.0,
                )
        },
        |tr| {
            let v = tr.velocities();
            let (v0, v1) = (v[0], v[v.len() - 1]);
            let turned =
                (v1[1].atan2(v1[0]) - v0[1].atan2(v0[0])).rem_euclid(std::f64::consts::TAU);
            let expected = (2.0 * big_omega / 7.0 * 10.0).rem_euclid(std::f64::consts::TAU);
            format!("velocity turned {turned:.6} rad (2Ωt/7: {expected:.6})")
        },
    )
}

/// Steady circular rolling from the closed-form condition: the tilt stays.
pub(crate) fn rolling_disk(system: &'static str) -> Result<Row, Error> {
    let (m, a) = (1.0, DISK_RADIUS);
    let disk = RollingDisk {
        m,
        a,
        b: m * a * a / 4.0,
        c: m * a * a / 2.0,
        g: 9.81,
    };
    let theta0 = 0.3;
    let (q0, v0) = disk.steady_circle(theta0, 2.0);
    row(
        system,
        &disk,
        0.0..3.0,
        true,
        || {
            Simulation::new(&disk)
                .integrator(Dopri5::tol(TOL))
                .run_reduced(q0, v0, 0.0..3.0)
        },
        |tr| format!("tilt(3) − tilt(0) = {:.1e}", tr.final_state().0[3] - theta0),
    )
}

pub(crate) fn sleigh(system: &'static str) -> Result<Row, Error> {
    let sleigh = ChaplyginSleigh {
        m: 1.0,
        i: 0.2,
        b: 0.5,
    };
    row(
        system,
        &sleigh,
        0.0..60.0,
        true,
        || {
            Simulation::new(&sleigh)
                .integrator(Dopri5::tol(TOL))
                .run_reduced([0.0, 0.0, 0.0], [0.3, 0.0, 2.0], 0.0..60.0)
        },
        |tr| format!("turn rate(60) = {:.1e}", tr.final_state().1[2]),
    )
}
