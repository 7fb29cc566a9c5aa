//! Gallery rows of holonomic constraints with multipliers and of rigid bodies:
//! the Cartesian spherical pendulum, the rod, the body as particles, the
//! rolling sphere both ways, the threaded tops.

use crate::catalog::constrained::*;
use crate::row::{Row, TOL, row, run};
use lagrange::prelude::*;

/// C1 in Cartesian coordinates with the rod as a constraint; the note is the
/// rod tension from the multiplier at the end.
pub(crate) fn cartesian_pendulum(system: &'static str) -> Result<Row, Error> {
    let cart = CartesianSphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let (th, thd, phd) = (1.0f64, 0.0, 2.0);
    let x0 = [th.sin(), 0.0, -th.cos()];
    let v0 = [th.cos() * thd, th.sin() * phd, th.sin() * thd];
    row(
        system,
        &cart,
        0.0..20.0,
        true,
        || {
            Simulation::new(&cart)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .run_constrained(x0, v0, 0.0..20.0)
        },
        |tr| {
            let (x, v) = tr.final_state();
            let dynamics = ConstrainedDynamics::new(&cart);
            match dynamics.solve(20.0, &x, &v) {
                Ok(sol) => format!(
                    "tension(20) = {:.6}",
                    cart.reactions(&x, &v, 20.0, &sol.multipliers)[0].norm()
                ),
                Err(e) => e.to_string(),
            }
        },
    )
}

pub(crate) fn rod_pair(system: &'static str) -> Result<Row, Error> {
    let pair = RodPair {
        m1: 1.0,
        m2: 2.0,
        l: 1.0,
        gx: 0.0,
        gy: 0.0,
        gz: -9.81,
    };
    row(
        system,
        &pair,
        0.0..1.5,
        true,
        || {
            Simulation::new(&pair)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .run_constrained(
                    [0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
                    [1.0, 0.0, 2.0, 1.0, 1.0, 2.0],
                    0.0..1.5,
                )
        },
        |_| String::new(),
    )
}

/// C4: three particles against the same body by its inertia tensor.
pub(crate) fn three_particles(system: &'static str) -> Result<Row, Error> {
    let particles = ThreeParticleBody::example(9.81);
    let body = particles.as_body();
    let start = (
        [0.0, 0.0, 1.0, 0.3, 1.1, -0.4],
        [0.2, 0.1, 3.0, 0.7, -0.5, 2.0],
    );
    let reference =
        Simulation::new(&body)
            .integrator(Dopri5::tol(TOL))
            .run(start.0, start.1, 0.0..2.0)?;
    run(system, &particles, start, 0.0..2.0, true, |tr| {
        let gap = (tr.final_state().0 - reference.final_state().0).amax();
        format!("vs inertia-tensor body: {gap:.1e}")
    })
}

/// C5: the rolling sphere with multipliers and in reduced form, started alike.
struct Sphere {
    sphere: RollingSphere,
    reduced: RollingSphereReduced,
    /// Reduced coordinates (x, y and the three angles).
    start: [f64; 5],
    /// The independent speeds.
    speeds: [f64; 3],
}

impl Sphere {
    fn new() -> Self {
        let (m, a) = (2.0, 0.3);
        let sphere = RollingSphere {
            m,
            j: 0.4 * m * a * a,
            a,
            g: 9.81,
        };
        let reduced = RollingSphereReduced {
            m,
            j: sphere.j,
            a,
            g: 9.81,
        };
        Sphere {
            sphere,
            reduced,
            start: [0.0, 0.0, 0.2, 0.9, 0.1],
            speeds: [1.5, -0.7, 4.0],
        }
    }

    fn run_reduced(&self) -> Result<Trajectory<f64, 5>, Error> {
        let [s0, s1, s2] = self.speeds;
        Ok(Simulation::new(&self.reduced)
            .integrator(Dopri5::tol(TOL))
            .run_reduced(self.start, [0.0, 0.0, s0, s1, s2], 0.0..10.0)?)
    }
}

/// C5 with multipliers, compared at the end with the reduced form.
pub(crate) fn sphere_multipliers(system: &'static str) -> Result<Row, Error> {
    let s = Sphere::new();
    let reduced_traj = s.run_reduced()?;
    let v5 = reduced_traj.velocities()[0];
    let (a, start) = (s.sphere.a, s.start);
    row(
        system,
        &s.sphere,
        0.0..10.0,
        true,
        || {
            Simulation::new(&s.sphere)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .run_constrained(
                    [0.0, 0.0, a, start[2], start[3], start[4]],
                    [v5[0], v5[1], 0.0, v5[2], v5[3], v5[4]],
                    0.0..10.0,
                )
        },
        |tr| {
            let (qf, _) = tr.final_state();
            let (qr, _) = reduced_traj.final_state();
            let gap = (0..2)
                .map(|i| (qf[i] - qr[i]).abs())
                .chain((2..5).map(|i| (qf[i + 1] - qr[i]).abs()))
                .fold(0.0, f64::max);
            format!("vs reduced form: {gap:.1e}")
        },
    )
}

pub(crate) fn sphere_reduced(system: &'static str) -> Result<Row, Error> {
    let s = Sphere::new();
    row(
        system,
        &s.reduced,
        0.0..10.0,
        true,
        || s.run_reduced(),
        |tr| {
            let (q, _) = tr.final_state();
            format!("centre ({:.4}, {:.4}), straight line", q[0], q[1])
        },
    )
}

pub(crate) fn threaded_tops(system: &'static str) -> Result<Row, Error> {
    let tops = ThreadedTops {
        m: 1.0,
        a: 0.3,
        b: 0.2,
        c: 0.5,
        l: 0.4,
        d: 2.0,
        g: 9.81,
    };
    let (th1, th2) = (0.4f64, 0.7f64);
    let q0 = [0.0, th1, 0.0, 0.5, th2, 0.0];
    let v0 = [
        1.0,
        0.2,
        10.0 - th1.cos(),
        -0.5,
        -0.1,
        -10.0 + 0.5 * th2.cos(),
    ];
    row(
        system,
        &tops,
        0.0..5.0,
        true,
        || {
            Simulation::new(&tops)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .run_constrained(q0, v0, 0.0..5.0)
        },
        |_| String::new(),
    )
}
