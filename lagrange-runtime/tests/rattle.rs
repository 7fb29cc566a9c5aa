//! RATTLE on the Cartesian pendulum: constraints at round-off, bounded energy
//! error over 10⁵ steps, second order; RK4 without drift control at the same
//! step drifts off the constraint.

mod common;

use common::constrained::{CartesianPendulum, Sleigh};
use lagrange_runtime::{Dopri5, Drift, Error, Rattle, Rk4, Simulation, Trajectory};
use nalgebra::{Vector2, Vector3};

/// max |E − E0| / |E0| over the points k in `range` (as fractions of the run).
fn energy_error(tr: &Trajectory<f64, 2>, from: f64, to: f64) -> f64 {
    let e = tr.integrals();
    let (a, b) = (
        (from * e.len() as f64) as usize,
        (to * e.len() as f64) as usize,
    );
    e[a..b]
        .iter()
        .map(|x| (x - e[0]).abs() / e[0].abs())
        .fold(0.0, f64::max)
}

#[test]
fn long_run_bounded_energy_and_round_off_residuals() {
    let sys = CartesianPendulum::<1>::standard();
    // Potential datum: E0 = m g y0 + ½ m v0² ≠ 0.
    let (q0, v0) = sys.state(1.2, 0.5);
    // 3·10⁴ steps over ~140 periods keep the test at a few seconds in debug
    // builds; examples/rattle.rs runs 10⁶ steps.
    let (h, steps) = (0.01, 30_000);
    let t_end = steps as f64 * h;
    let rattle = Rattle::step(h).integrate(&sys, 0.0, t_end, q0, v0).unwrap();
    assert_eq!(rattle.len(), steps + 1);
    let [phi, vel] = rattle.max_residuals();
    let (early, late) = (
        energy_error(&rattle, 0.0, 0.1),
        energy_error(&rattle, 0.9, 1.0),
    );
    let rk4 = Simulation::new(&sys)
        .integrator(Rk4::step(h))
        .drift(Drift::None)
        .run_constrained(q0, v0, 0.0..t_end)
        .unwrap();
    let [phi_rk4, _] = rk4.max_residuals();
    let (early_rk4, late_rk4) = (energy_error(&rk4, 0.0, 0.1), energy_error(&rk4, 0.9, 1.0));
    eprintln!(
        "RATTLE h = {h}, {steps} steps: |Phi| {phi:.1e}, |G v| {vel:.1e}, energy error first 10% \
         {early:.2e}, last 10% {late:.2e}, wall {:?}",
        rattle.stats().wall_time
    );
    eprintln!(
        "RK4 (no drift control): |Phi| {phi_rk4:.1e}, energy error first 10% {early_rk4:.2e}, \
         last 10% {late_rk4:.2e}"
    );
    // Constraints at round-off at both levels, without any projection.
    assert!(phi < 1e-13 && vel < 1e-13, "{phi:e} {vel:e}");
    // Bounded: the energy error oscillates at O(h²) and does not grow.
    assert!(late < 1e-3 && late < 1.5 * early, "{early:e} -> {late:e}");
    // RK4 at the same step has no such property: the constraint drifts away
    // and its energy error grows steadily.
    assert!(phi_rk4 > 1e4 * phi, "{phi_rk4:e}");
    assert!(late_rk4 > 5.0 * early_rk4, "{early_rk4:e} -> {late_rk4:e}");
}

#[test]
fn second_order_convergence() {
    let sys = CartesianPendulum::<1>::standard();
    let (q0, v0) = sys.state(1.0, 0.0);
    let t_end = 2.0;
    let reference = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-13))
        .drift(Drift::projection())
        .run_constrained(q0, v0, 0.0..t_end)
        .unwrap()
        .final_state();
    let error = |h: f64| {
        let (q, v) = Rattle::step(h)
            .integrate(&sys, 0.0, t_end, q0, v0)
            .unwrap()
            .final_state();
        (q - reference.0).amax().max((v - reference.1).amax())
    };
    let (e1, e2, e3) = (error(0.02), error(0.01), error(0.005));
    eprintln!("RATTLE errors at t = 2: h = 0.02 {e1:.2e}, 0.01 {e2:.2e}, 0.005 {e3:.2e}");
    for (a, b) in [(e1, e2), (e2, e3)] {
        let ratio = a / b;
        assert!((ratio - 4.0).abs() < 0.3, "ratio {ratio}");
    }
}

#[test]
fn typed_errors() {
    let sys = CartesianPendulum::<1>::standard();
    let (q0, v0) = sys.state(1.0, 0.0);
    // Off the constraint.
    let e = Rattle::step(0.01)
        .integrate(&sys, 0.0, 1.0, q0 * 1.01, v0)
        .unwrap_err();
    assert!(
        matches!(e.error, Error::InconsistentInitialConditions { .. }),
        "{e}"
    );
    for h in [0.0, -0.1, f64::NAN] {
        let e = Rattle::step(h)
            .integrate(&sys, 0.0, 1.0, q0, v0)
            .unwrap_err();
        assert!(matches!(e.error, Error::Settings(_)), "{e}");
    }
    let e = Rattle::step(0.01)
        .max_iterations(0)
        .integrate(&sys, 0.0, 1.0, q0, v0)
        .unwrap_err();
    assert!(matches!(e.error, Error::Settings(_)), "{e}");
    // A step so large that the position constraint has no solution along
    // M⁻¹Φ_qᵀ(qₙ) (the pendulum would turn by more than a quarter turn).
    let (q1, v1) = sys.state(0.0, 20.0);
    let e = Rattle::step(0.5)
        .integrate(&sys, 0.0, 1.0, q1, v1)
        .unwrap_err();
    assert!(matches!(e.error, Error::NewtonFailure { .. }), "{e}");
    // The same rod twice: Φ_q M⁻¹ Φ_qᵀ is singular.
    let twice = CartesianPendulum::<2>::standard();
    let e = Rattle::step(0.01)
        .integrate(&twice, 0.0, 1.0, q0, v0)
        .unwrap_err();
    assert!(matches!(e.error, Error::RedundantConstraints { .. }), "{e}");
    // Nonholonomic rows have no position level.
    let e = Rattle::step(0.01)
        .integrate(
            &Sleigh::standard(),
            0.0,
            1.0,
            Vector3::zeros(),
            Vector3::zeros(),
        )
        .unwrap_err();
    assert!(e.to_string().contains("nonholonomic"), "{e}");
    let _ = Vector2::<f64>::zeros();
}
