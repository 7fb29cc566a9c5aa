//! Gallery rows of systems in minimal coordinates, integrated as
//! M q̈ + h = Q with DOPRI5: pendulums, a rheonomic surface, free bodies.

use crate::catalog::*;
use crate::row::{Row, TOL, row, run};
use lagrange::prelude::*;

/// The double pendulum of the row and of its animation.
pub(crate) const DOUBLE_PENDULUM: DoublePendulum = DoublePendulum {
    m1: 1.0,
    m2: 1.0,
    l1: 1.0,
    l2: 1.0,
    g: 9.81,
};

/// The pendulum from 179°: rising zero crossings of θ, located on the dense
/// output while stepping, give the period, checked against 4√(l/g)K.
pub(crate) fn pendulum_period(system: &'static str) -> Result<Row, Error> {
    let pendulum = Pendulum::<f64> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let th0 = 179f64.to_radians();
    let exact = 4.0 * (pendulum.l / pendulum.g).sqrt() * elliptic_k((th0 / 2.0).sin());
    let period = std::cell::Cell::new(f64::NAN);
    row(
        system,
        &pendulum,
        0.0..20.0,
        true,
        || {
            let run = Simulation::new(&pendulum)
                .integrator(Dopri5::tol(TOL))
                .event(Event::new(|_, q: &Vector1<f64>, _| q[0]).rising())
                .run([th0], [0.0], 0.0..20.0)?;
            if let [a, b, ..] = run.times(0)[..] {
                period.set(b - a);
            }
            Ok::<_, Error>(run.trajectory)
        },
        |_| {
            format!(
                "period {:.9} s, exact 4√(l/g)K: rel. error {:.1e}",
                period.get(),
                (period.get() - exact).abs() / exact
            )
        },
    )
}

/// C1 in (θ, φ): p_φ = sin²θ φ̇ is conserved.
pub(crate) fn spherical(system: &'static str) -> Result<Row, Error> {
    let spherical = SphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    run(
        system,
        &spherical,
        ([1.0, 0.0], [0.0, 2.0]),
        0.0..20.0,
        true,
        |tr| {
            let (q, v) = tr.final_state();
            let p0 = (1.0f64).sin().powi(2) * 2.0;
            let p1 = q[0].sin().powi(2) * v[1];
            format!("p_φ drift {:.1e}", ((p1 - p0) / p0).abs())
        },
    )
}

pub(crate) fn ellipsoid(system: &'static str) -> Result<Row, Error> {
    let ellipsoid = GrowingEllipsoid {
        m: 1.0,
        a: 1.0,
        b: 0.8,
        c: 0.6,
        g: 9.81,
    };
    run(
        system,
        &ellipsoid,
        ([1.0, 0.3], [0.2, 1.0]),
        1.0..4.0,
        false,
        |_| "rheonomic: no integral".to_string(),
    )
}

/// C3: the centre of mass falls freely, z_C(t) = 2t − g t²/2.
pub(crate) fn dumbbell(system: &'static str) -> Result<Row, Error> {
    let dumbbell = Dumbbell {
        m1: 1.0,
        m2: 2.0,
        l: 1.0,
        gx: 0.0,
        gy: 0.0,
        gz: -9.81,
    };
    run(
        system,
        &dumbbell,
        ([0.0, 0.0, 0.0, 0.3, 0.0], [1.0, 0.0, 2.0, 1.5, 0.7]),
        0.0..1.5,
        true,
        |tr| {
            let (q, _) = tr.final_state();
            format!(
                "z_C(1.5) = {:.6} (exact {:.6})",
                q[2],
                2.0 * 1.5 - 9.81 * 1.5 * 1.5 / 2.0
            )
        },
    )
}

pub(crate) fn heavy_particle(system: &'static str) -> Result<Row, Error> {
    let particle = HeavyParticle { m: 1.0, g: 9.81 };
    run(
        system,
        &particle,
        ([0.0, 0.0], [1.0, 3.0]),
        0.0..1.0,
        true,
        |_| "parabola y + B = (2A/g)√(h − gz − A²)".to_string(),
    )
}

pub(crate) fn double_pendulum(system: &'static str) -> Result<Row, Error> {
    run(
        system,
        &DOUBLE_PENDULUM,
        ([2.0, 2.5], [0.0, 0.0]),
        0.0..20.0,
        true,
        |_| "chaotic".to_string(),
    )
}

pub(crate) fn chain(system: &'static str) -> Result<Row, Error> {
    let chain = Chain5 {
        m: 1.0,
        l: 0.5,
        g: 9.81,
    };
    run(
        system,
        &chain,
        ([1.0, 0.2, -0.2, 0.3, 0.1], [0.0; 5]),
        0.0..10.0,
        true,
        |_| String::new(),
    )
}

pub(crate) fn driven(system: &'static str) -> Result<Row, Error> {
    let driven = DrivenPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
        c: 0.3,
        a: 1.2,
        w: 2.0,
        f: 0.5,
    };
    run(system, &driven, ([0.5], [0.0]), 0.0..20.0, false, |tr| {
        format!("θ(20) = {:.6}", tr.final_state().0[0])
    })
}
