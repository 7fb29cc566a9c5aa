//! The spherical pendulum in (θ, φ): conservation away from the poles, typed
//! errors at them.

mod common;

use common::{SphericalPendulum, pendulum_period, sv};
use lagrange_runtime::{Dopri5, Error, Rk4, Simulation};

#[test]
fn energy_and_p_phi_conserved_over_100_swings() {
    let sys = SphericalPendulum::standard();
    let (q0, v0) = (sv([1.0, 0.0]), sv([0.0, 2.0]));
    // With this much φ̇ the θ oscillation (between 1 rad and a smaller turning
    // angle) is about twice as fast as a planar swing of amplitude 1 rad, so 51
    // planar periods hold just over 100 swings.
    let span = 51.0 * pendulum_period(sys.l, sys.g, 1.0);
    let tr = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12).max_steps(1_000_000))
        .run(q0, v0, 0.0..span)
        .unwrap();
    // A swing is one full θ oscillation: two zeros of θ̇.
    let swings = tr.crossings(|_, _, v| v[0]).unwrap().len() / 2;
    assert!(swings >= 100, "{swings} swings");
    let energy_drift = tr.integral_drift();
    let p0 = sys.p_phi(&q0, &v0);
    let p_drift = tr
        .positions()
        .iter()
        .zip(tr.velocities())
        .map(|(q, v)| (sys.p_phi(q, v) - p0).abs() / p0.abs())
        .fold(0.0, f64::max);
    eprintln!(
        "{swings} swings, {:?}: energy drift {energy_drift:e}, p_phi drift {p_drift:e}",
        tr.stats()
    );
    assert!(energy_drift < 1e-9, "{energy_drift:e}");
    assert!(p_drift < 1e-9, "{p_drift:e}");
}

#[test]
fn start_at_the_pole_is_a_singular_mass_matrix() {
    let sys = SphericalPendulum::standard();
    let e = Simulation::new(&sys)
        .run(sv([0.0, 0.0]), sv([0.1, 1.0]), 0.0..1.0)
        .unwrap_err();
    match &e.error {
        Error::SingularMassMatrix {
            t,
            q,
            ratio,
            direction,
            atlas,
        } => {
            assert!(!atlas);
            assert_eq!((*t, q.as_slice()), (0.0, &[0.0, 0.0][..]));
            assert!(*ratio <= 0.0);
            // At the pole φ turns nothing: the message names it.
            assert_eq!(direction, "1.000 phi");
        }
        other => panic!("expected SingularMassMatrix, got {other:?}"),
    }
    assert!(e.to_string().contains("t = 0,"), "{e}");
    assert!(e.to_string().contains("no inertia along 1.000 phi"), "{e}");
}

#[test]
fn planar_swing_through_the_pole_is_caught_at_the_quarter_period() {
    // Released from rest with φ̇ = 0, the motion is planar and θ passes through the
    // pole θ = 0 a quarter period after release. With 100 RK4 steps per quarter
    // period a step lands on it (to RK4's accuracy), where sin²θ ≈ 0.
    let sys = SphericalPendulum::standard();
    let theta0 = 0.3;
    let quarter = 0.25 * pendulum_period(sys.l, sys.g, theta0);
    let e = Simulation::new(&sys)
        .integrator(Rk4::step(quarter / 100.0))
        .run(sv([theta0, 0.0]), sv([0.0, 0.0]), 0.0..2.0 * quarter)
        .unwrap_err();
    match &e.error {
        Error::SingularMassMatrix { t, q, ratio, .. } => {
            eprintln!("caught at t = {t} (quarter period {quarter}), q = {q:?}, ratio {ratio:e}");
            assert!((t - quarter).abs() < 1e-12, "{t} vs {quarter}");
            assert!(q[0].abs() < 1e-6 && *ratio < 1e-12);
        }
        other => panic!("expected SingularMassMatrix, got {other:?}"),
    }
    assert!(e.to_string().contains(&format!("t = {quarter},")), "{e}");
    // A looser singular tolerance is a user decision: with 0 nothing is caught
    // unless M is exactly singular.
    let tr = Simulation::new(&sys)
        .integrator(Rk4::step(quarter / 100.0))
        .singular_tolerance(0.0)
        .run(sv([theta0, 0.0]), sv([0.0, 0.0]), 0.0..2.0 * quarter);
    assert!(tr.is_ok(), "{:?}", tr.err());
}
