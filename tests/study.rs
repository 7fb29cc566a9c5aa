//! The work-precision study's building blocks: the closed forms it measures
//! against, the new catalog systems, and the study API on a derived system.

use crate::catalog;

use catalog::study::*;
use catalog::{Pendulum, SphericalPendulum, elliptic_k};
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use lagrange::study::{Method, ReferenceKind};
use lagrange::{Dop853, Gauss, StormerVerlet};

#[test]
fn elliptic_k_and_sn_match_known_values() {
    // K(0) = π/2; K(sin 45°) = 1.854074677301372 (A&S table 17.1).
    assert!((elliptic_k(0.0) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert!((elliptic_k(std::f64::consts::FRAC_1_SQRT_2) - 1.854_074_677_301_372).abs() < 1e-14);
    // sn(u | 0) = sin u; sn(K | m) = 1; sn is odd with period 4K.
    assert!((jacobi_sn(0.7, 0.0) - 0.7f64.sin()).abs() < 1e-15);
    let m = 0.9f64;
    let k = elliptic_k(m.sqrt());
    assert!((jacobi_sn(k, m) - 1.0).abs() < 1e-14);
    assert!((jacobi_sn(0.3 + 4.0 * k, m) - jacobi_sn(0.3, m)).abs() < 1e-13);
    assert!((jacobi_sn(-0.3, m) + jacobi_sn(0.3, m)).abs() < 1e-15);
}

#[test]
fn pendulum_closed_form_matches_a_tight_integration() {
    let sys = Pendulum::<f64> {
        m: 1.0,
        l: 1.5,
        g: 9.81,
    };
    let theta0 = 170f64.to_radians();
    let period = pendulum_period(sys.l, sys.g, theta0);
    let traj = Simulation::new(&sys)
        .integrator(Dop853::tol(1e-13).max_steps(1_000_000))
        .run([theta0], [0.0], 0.0..2.3 * period)
        .unwrap();
    for (t, q) in traj.times().iter().zip(traj.positions()).step_by(7) {
        let exact = pendulum_angle(sys.l, sys.g, theta0, *t);
        assert!((q[0] - exact).abs() < 1e-8, "t = {t}: {} vs {exact}", q[0]);
    }
    // A whole number of periods brings it back to θ0.
    assert!((pendulum_angle(sys.l, sys.g, theta0, 3.0 * period) - theta0).abs() < 1e-12);
}

#[test]
fn kepler_orbit_matches_a_tight_integration() {
    let sys = Kepler { m: 2.0, k: 3.0 };
    let orbit = KeplerOrbit {
        a: 1.3,
        e: 0.6,
        mu: sys.k / sys.m,
    };
    let (q0, v0) = orbit.initial();
    let t_end = 2.7 * orbit.period();
    let traj = Simulation::new(&sys)
        .integrator(Dop853::tol(1e-13).max_steps(1_000_000))
        .run(q0, v0, 0.0..t_end)
        .unwrap();
    for (t, q) in traj.times().iter().zip(traj.positions()).step_by(5) {
        let [x, y] = orbit.position(*t);
        assert!(
            (q[0] - x).abs() < 1e-8 && (q[1] - y).abs() < 1e-8,
            "t = {t}: {q:?} vs ({x}, {y})"
        );
    }
    assert!(traj.integral_drift() < 1e-11);
}

#[test]
fn spring_pendulum_starts_at_its_static_stretch() {
    let sys = SpringPendulum {
        m: 1.0,
        k: 1e6,
        l: 1.0,
        g: 9.81,
    };
    let (q0, v0) = sys.at_rest(1.0);
    // At rest the spring force along the rod balances gravity's radial part,
    // so the radial acceleration vanishes: a is perpendicular to the rod.
    let a = lagrange::accelerations(&sys, &SVector::from(q0), &SVector::from(v0), 0.0).unwrap();
    let radial = (a[0] * q0[0] + a[1] * q0[1]) / (q0[0].hypot(q0[1]));
    assert!(radial.abs() < 1e-6, "radial acceleration {radial}");
    assert!((a.norm() - 9.81 * 1f64.sin()).abs() < 1e-4, "{a:?}");
}

/// The Gauss integrator needs Hamilton's form: the catalog's spherical pendulum
/// asks for it (`emit(hamiltonian)`), its ∂T/∂q equals the hand derivation
/// m l² sin θ cos θ φ̇², and Gauss conserves energy and p_φ; a derived system
/// without it is refused with a typed error.
#[test]
fn gauss_runs_on_the_derived_spherical_pendulum() {
    let sys = SphericalPendulum {
        m: 1.3,
        l: 0.9,
        g: 9.81,
    };
    let (q, v) = (SVector::from([0.7, 0.2]), SVector::from([0.4, 1.9]));
    let grad = sys.kinetic_gradient(&q, &v, 0.0).expect("emitted");
    let by_hand = sys.m * sys.l * sys.l * q[0].sin() * q[0].cos() * v[1] * v[1];
    assert!(
        (grad[0] - by_hand).abs() < 1e-14 && grad[1] == 0.0,
        "{grad}"
    );
    let traj = Simulation::new(&sys)
        .integrator(Gauss::step(0.01))
        .run([1.0, 0.0], [0.0, 2.0], 0.0..10.0)
        .unwrap();
    assert!(traj.integral_drift() < 1e-6, "{}", traj.integral_drift());
    let p_phi = |q: &SVector<f64, 2>, v: &SVector<f64, 2>| q[0].sin().powi(2) * v[1];
    let (q, v) = traj.final_state();
    assert!((p_phi(&q, &v) - p_phi(&traj.positions()[0], &traj.velocities()[0])).abs() < 1e-10);
    let plain = catalog::HeavyParticle { m: 1.0, g: 9.81 };
    let e = Simulation::new(&plain)
        .integrator(Gauss::step(0.01))
        .run([0.0, 0.0], [1.0, 1.0], 0.0..1.0)
        .unwrap_err();
    assert!(
        matches!(e.error, Error::Settings(ref m) if m.to_string().contains("kinetic_gradient"))
    );
}

/// The study API end to end on a derived system with a closed form: the
/// symplectic methods' energy error stays bounded, the errors fall with the
/// step, and the DOP853 reference agrees with Kepler's equation.
#[test]
fn study_of_the_kepler_problem() {
    let sys = Kepler { m: 1.0, k: 1.0 };
    let orbit = KeplerOrbit {
        a: 1.0,
        e: 0.6,
        mu: 1.0,
    };
    let (q0, v0) = orbit.initial();
    let t_end = 2.0 * orbit.period();
    let run = |m: Method| Simulation::new(&sys).integrator(m).run(q0, v0, 0.0..t_end);
    let sweep = || Sweep::steps("Störmer–Verlet", &[0.01, 0.005], StormerVerlet::step);
    let exact = WorkPrecision::new(run)
        .exact(move |t| SVector::from(orbit.position(t)))
        .sweep(sweep())
        .run()
        .unwrap();
    let errors: Vec<f64> = exact
        .rows()
        .iter()
        .map(|r| r.measurement().unwrap().error)
        .collect();
    // Second order: halving h divides the error by about 4.
    assert!((3.0..5.0).contains(&(errors[0] / errors[1])), "{errors:?}");
    let computed = WorkPrecision::new(run).sweep(sweep()).run().unwrap();
    let ReferenceKind::Computed {
        uncertainty: Some(u),
        ..
    } = *computed.reference()
    else {
        panic!("{:?}", computed.reference());
    };
    assert!(u < 1e-10, "reference uncertainty {u:e}");
    for (a, b) in exact.rows().iter().zip(computed.rows()) {
        let (a, b) = (a.measurement().unwrap(), b.measurement().unwrap());
        assert!(
            (a.error - b.error).abs() < 1e-9,
            "{} vs {}",
            a.error,
            b.error
        );
    }
}

/// A study of a system with an orientation compares rotations on the group
/// (`.orientations(..)`), and without that call is refused: its errors are
/// angles, falling at Gauss's order 4, and blind to the quaternion's sign.
#[test]
fn a_study_of_a_tumbling_body_measures_angles_on_the_group() {
    use lagrange::study::Sweep;
    let (sys, omega) = (TumblingBody::PLATE, TumblingBody::SPIN);
    let run = |m: Method| {
        Simulation::new(&sys)
            .integrator(m)
            .run([1.0, 0.0, 0.0, 0.0], omega, 0.0..10.0)
    };
    let refused = WorkPrecision::new(run)
        .sweep(Sweep::steps("Gauss", &[0.1], Gauss::step))
        .run();
    assert!(
        matches!(&refused, Err(lagrange::Error::Settings(m)) if m.to_string().contains(".orientations(")),
        "{refused:?}"
    );
    let study = WorkPrecision::new(run)
        .orientations(TumblingBody::ORIENTATIONS)
        .sweep(Sweep::steps("Gauss", &[0.2, 0.1], Gauss::step))
        .repeats(1, std::time::Duration::ZERO)
        .run()
        .unwrap();
    let errors: Vec<f64> = (study.rows().iter())
        .map(|r| r.measurement().unwrap().error)
        .collect();
    let ratio = errors[0] / errors[1];
    assert!((14.0..18.0).contains(&ratio), "{errors:?}");
    // Against the run's own final rotation, as q and as −q: no error.
    let final_q = study.rows()[1].measurement().unwrap().final_state.0.clone();
    let study_at = |q: [f64; 4]| {
        WorkPrecision::new(run)
            .orientations(TumblingBody::ORIENTATIONS)
            .exact(move |_| SVector::from(q))
            .sweep(Sweep::steps("Gauss", &[0.1], Gauss::step))
            .repeats(1, std::time::Duration::ZERO)
            .run()
            .unwrap()
            .rows()[0]
            .measurement()
            .unwrap()
            .error
    };
    let q = [final_q[0], final_q[1], final_q[2], final_q[3]];
    assert!(study_at(q) < 1e-14);
    assert!(study_at(q.map(|x| -x)) < 1e-14);
}
