//! The Whipple bicycle (Meijaard, Papadopoulos, Ruina & Schwab 2007).

#[path = "../examples/catalog/mod.rs"]
mod catalog;

use catalog::bicycle::Bicycle;
use lagrange::prelude::*;

#[test]
fn upright_reference_is_consistent() {
    let b = Bicycle::benchmark();
    let (q, v) = b.upright(5.0);
    let (q, v) = (SVector::<f64, 8>::from(q), SVector::<f64, 8>::from(v));
    let phi = b.constraint_positions(&q, 0.0);
    let (g, g0) = b.constraint_jacobian(&q, 0.0);
    let vel = g * v + g0;
    assert!(phi.abs().max() < 1e-15, "{phi}");
    assert!(vel.abs().max() < 1e-14, "{vel}");
}

/// Roll rate 0.5 rad/s from upright; returns |φ| + |δ| over the last second.
fn roll_perturbation(speed: f64, seconds: f64) -> (f64, f64) {
    let b = Bicycle::benchmark();
    let (q, mut v) = b.upright(speed);
    v[3] = 0.5;
    let traj = Simulation::new(&b)
        .integrator(Dopri5::tol(1e-9))
        .drift(Drift::projection())
        .project_initial(true)
        .run_constrained(q, v, 0.0..seconds)
        .unwrap();
    let [phi_res, vel_res] = traj.max_residuals();
    assert!(phi_res < 1e-10 && vel_res < 1e-10, "{phi_res} {vel_res}");
    let amplitude = |from: f64, to: f64| {
        traj.times()
            .iter()
            .zip(traj.positions())
            .filter(|(t, _)| **t >= from && **t <= to)
            .map(|(_, q)| q[3].abs() + q[6].abs())
            .fold(0.0f64, f64::max)
    };
    (amplitude(0.0, 1.0), amplitude(seconds - 1.0, seconds))
}

#[test]
fn self_stable_at_5_unstable_at_3() {
    let (early, late) = roll_perturbation(5.0, 8.0);
    eprintln!("5 m/s: {early:.3e} -> {late:.3e}");
    assert!(late < 0.2 * early);
    let (early, late) = roll_perturbation(3.0, 4.0);
    eprintln!("3 m/s: {early:.3e} -> {late:.3e}");
    assert!(late > 2.0 * early);
}
