//! A trial stage the right-hand side cannot evaluate rejects the step (the
//! adaptive integrators retry smaller) instead of ending the run; a failure on the
//! solution itself is still reported as what it is.

use lagrange_runtime::{Dop853, Dopri5, Error, Integrator, Radau5, SecondOrder};
use nalgebra::SVector;

/// q̈ = −q, whose solution from (1, 0) stays in |q| ≤ 1, with a right-hand side
/// that refuses |q| > 1.5 (as a chart would) and, optionally, any t > `wall`.
struct Fenced {
    wall: f64,
}

impl SecondOrder<f64, 1> for Fenced {
    fn acceleration(
        &self,
        t: f64,
        q: &SVector<f64, 1>,
        _v: &SVector<f64, 1>,
    ) -> Result<SVector<f64, 1>, Error> {
        if q[0].abs() > 1.5 || t > self.wall {
            return Err(Error::SingularMassMatrix {
                direction: String::new(),
                atlas: false,
                t,
                q: vec![q[0]],
                ratio: 0.0,
            });
        }
        Ok(-q)
    }
}

fn run(method: &impl Integrator, wall: f64) -> Result<f64, Error> {
    let traj = method.integrate(
        &Fenced { wall },
        0.0,
        6.0,
        SVector::from([1.0]),
        SVector::from([0.0]),
    )?;
    Ok(traj.final_state().0[0])
}

#[test]
fn trial_stage_failures_are_rejections() {
    // A first step of 5 sends the stages far outside |q| ≤ 1.5.
    let q = run(&Dopri5::tol(1e-10).h0(5.0), f64::INFINITY).unwrap();
    assert!((q - 6f64.cos()).abs() < 1e-8, "{q}");
    let q = run(&Dop853::tol(1e-10).h0(5.0), f64::INFINITY).unwrap();
    assert!((q - 6f64.cos()).abs() < 1e-8, "{q}");
    let q = run(&Radau5::tol(1e-10), f64::INFINITY).unwrap();
    assert!((q - 6f64.cos()).abs() < 1e-7, "{q}");
}

#[test]
fn a_failure_on_the_solution_is_reported_as_itself() {
    for result in [
        run(&Dopri5::tol(1e-10), 2.0),
        run(&Dop853::tol(1e-10), 2.0),
        run(&Radau5::tol(1e-10), 2.0),
    ] {
        match result {
            Err(Error::SingularMassMatrix { t, .. }) => assert!((t - 2.0).abs() < 1e-6, "{t}"),
            other => panic!("expected SingularMassMatrix at t = 2, got {other:?}"),
        }
    }
}
