//! Holonomic constraints with multipliers: the planar pendulum as a point (x, y)
//! on a rod, against the θ-pendulum; drift control; redundant constraints;
//! consistent initial conditions; typed errors.

mod common;

use common::constrained::{CartesianPendulum, DrivenPendulum};
use common::{Pendulum, pendulum_period, sv};
use lagrange_runtime::Failure;
use lagrange_runtime::{
    ConstrainedDynamics, Dopri5, Drift, Error, Integrator, Rk4, SecondOrder, Simulation,
    Trajectory, check_consistency, project_consistent,
};
use nalgebra::{Vector1, Vector2};

type Rod = CartesianPendulum<1>;

#[test]
fn same_motion_as_the_theta_pendulum() {
    let sys = Rod::standard();
    let angular = Pendulum::standard();
    let (theta0, rate0) = (1.0, 0.5);
    let (q0, v0) = sys.state(theta0, rate0);
    let span = 0.0..10.0;
    let cart = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-11))
        .run_constrained(q0, v0, span.clone())
        .unwrap();
    let polar = Simulation::new(&angular)
        .integrator(Dopri5::tol(1e-11))
        .run(sv([theta0]), sv([rate0]), span)
        .unwrap();
    let mut worst: f64 = 0.0;
    for k in 0..=200 {
        let t = 0.05 * k as f64;
        let (q, v) = cart.state_at(t).unwrap();
        let (th, w) = polar.state_at(t).unwrap();
        let (x, y) = sys.state(th[0], w[0]);
        worst = worst.max((q - x).amax()).max((v - y).amax());
    }
    let [phi, vel] = cart.max_residuals();
    eprintln!(
        "Cartesian vs θ pendulum over 10 s: max state difference {worst:e}; \
         energy drift {:e}; max residuals |Phi| {phi:e}, |G v| {vel:e}",
        cart.integral_drift()
    );
    assert!(worst < 1e-8, "{worst:e}");
    assert!(cart.integral_drift() < 1e-9, "{:e}", cart.integral_drift());
}

#[test]
fn tension_from_the_multiplier() {
    let sys = Rod::standard();
    let (q0, v0) = sys.state(2.0, 1.0);
    let tr = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-11))
        .run_constrained(q0, v0, 0.0..5.0)
        .unwrap();
    let dynamics = ConstrainedDynamics::new(&sys);
    let mut worst: f64 = 0.0;
    for ((t, q), v) in tr.times().iter().zip(tr.positions()).zip(tr.velocities()) {
        let sol = dynamics.solve(*t, q, v).unwrap();
        // The reaction Gᵀλ = 2λ (x, y) pulls towards the pivot with magnitude T.
        let tension = -2.0 * sol.multipliers[0] * sys.l;
        let expected = sys.tension(q, v);
        worst = worst.max((tension - expected).abs() / expected.abs());
        assert!((sol.reactions - q * (-tension / sys.l)).amax() < 1e-9 * expected.abs());
        // The equations of motion hold with these reactions.
        let residual = sol.accelerations * sys.m - Vector2::new(0.0, -sys.m * sys.g);
        assert!((residual - sol.reactions).amax() < 1e-12);
    }
    eprintln!(
        "rod tension from λ vs m(|v|²/l − g y/l): max rel. difference {worst:e} over {} points",
        tr.len()
    );
    assert!(worst < 1e-9, "{worst:e}");
}

/// The residuals over the first and the last `share` of a run.
fn early_late(tr: &Trajectory<f64, 2>, share: f64) -> ([f64; 2], [f64; 2]) {
    let t_end = *tr.times().last().unwrap();
    let mut early = [0.0f64; 2];
    let mut late = [0.0f64; 2];
    for (t, r) in tr.times().iter().zip(tr.residuals()) {
        let slot = if *t <= share * t_end {
            &mut early
        } else if *t >= (1.0 - share) * t_end {
            &mut late
        } else {
            continue;
        };
        slot[0] = slot[0].max(r[0]);
        slot[1] = slot[1].max(r[1]);
    }
    (early, late)
}

#[test]
fn drift_grows_without_control_and_is_held_by_baumgarte_and_projection() {
    let sys = Rod::standard();
    let (q0, v0) = sys.state(1.0, 0.0);
    let span = 0.0..200.0 * pendulum_period(sys.l, sys.g, 1.0);
    let run = |drift: Drift| {
        Simulation::new(&sys)
            .integrator(Dopri5::tol(1e-6).max_steps(1_000_000))
            .drift(drift)
            .run_constrained(q0, v0, span.clone())
            .unwrap()
    };
    let none = run(Drift::None);
    // α, β a few times the pendulum's frequency √(g/l) ≈ 3.1 /s.
    let baumgarte = run(Drift::Baumgarte {
        alpha: 10.0,
        beta: 10.0,
    });
    let projection = run(Drift::Projection {
        tol: 1e-13,
        max_iter: 10,
    });
    for (name, tr) in [
        ("none", &none),
        ("Baumgarte", &baumgarte),
        ("projection", &projection),
    ] {
        let (early, late) = early_late(tr, 0.1);
        eprintln!(
            "drift {name:>10}: first 20 periods |Phi| {:.2e} |G v| {:.2e}; last 20 periods \
             |Phi| {:.2e} |G v| {:.2e}; energy drift {:.2e}; {:?}",
            early[0],
            early[1],
            late[0],
            late[1],
            tr.integral_drift(),
            tr.stats()
        );
    }
    // Without control the position residual keeps growing.
    let (early, late) = early_late(&none, 0.1);
    assert!(late[0] > 5.0 * early[0], "{early:?} {late:?}");
    assert!(late[0] > 1e-5, "{late:?}");
    // Baumgarte: bounded, orders of magnitude below the uncontrolled run.
    let (b_early, b_late) = early_late(&baumgarte, 0.1);
    assert!(
        b_late[0] < 2.0 * b_early[0].max(1e-12),
        "{b_early:?} {b_late:?}"
    );
    assert!(b_late[0] < 1e-3 * late[0], "{b_late:?} vs {late:?}");
    // Projection: round-off throughout.
    let [phi, vel] = projection.max_residuals();
    assert!(phi < 1e-13 && vel < 1e-13, "{phi:e} {vel:e}");
    assert!(projection.integral_drift() < none.integral_drift());
}

#[test]
fn projection_works_with_rk4_too() {
    let sys = Rod::standard();
    let (q0, v0) = sys.state(1.0, 0.0);
    let tr = Simulation::new(&sys)
        .integrator(Rk4::step(0.01))
        .drift(Drift::projection())
        .run_constrained(q0, v0, 0.0..20.0)
        .unwrap();
    let [phi, vel] = tr.max_residuals();
    assert!(phi < 1e-12 && vel < 1e-12, "{phi:e} {vel:e}");
}

#[test]
fn redundant_constraints_are_an_error_unless_least_squares() {
    let twice = CartesianPendulum::<2>::standard();
    let once = Rod::standard();
    let (q0, v0) = once.state(1.0, 0.5);
    let e = Simulation::new(&twice)
        .run_constrained(q0, v0, 0.0..1.0)
        .unwrap_err();
    match &e.error {
        Error::RedundantConstraints {
            t,
            coordinates,
            ratio,
            dependent,
            ..
        } => {
            assert_eq!(*t, 0.0);
            assert_eq!(coordinates, &["x", "y"]);
            assert_eq!(dependent, &["rod_again"]);
            assert!(*ratio < 1e-12, "{ratio:e}");
        }
        other => panic!("expected RedundantConstraints, got {other:?}"),
    }
    eprintln!("{e}");
    assert!(e.to_string().contains("x = 0.84"), "{e}");

    let sim = |least_squares| {
        Simulation::new(&twice)
            .integrator(Dopri5::tol(1e-10))
            .least_squares(least_squares)
            .drift(Drift::projection())
    };
    let lsq = sim(true).run_constrained(q0, v0, 0.0..5.0).unwrap();
    let single = Simulation::new(&once)
        .integrator(Dopri5::tol(1e-10))
        .drift(Drift::projection())
        .run_constrained(q0, v0, 0.0..5.0)
        .unwrap();
    let mut worst: f64 = 0.0;
    for k in 0..=50 {
        let t = 0.1 * k as f64;
        let (a, b) = (lsq.state_at(t).unwrap(), single.state_at(t).unwrap());
        worst = worst.max((a.0 - b.0).amax()).max((a.1 - b.1).amax());
    }
    eprintln!("same rod twice (least squares) vs once: max state difference {worst:e}");
    assert!(worst < 1e-9, "{worst:e}");
    // Minimum-norm multipliers split the tension evenly between the copies.
    let both = sim(true)
        .constrained_dynamics::<f64, 2>()
        .solve(0.0, &q0, &v0);
    let one = ConstrainedDynamics::new(&once)
        .solve(0.0, &q0, &v0)
        .unwrap();
    let both = both.unwrap();
    assert!((both.multipliers[0] - both.multipliers[1]).abs() < 1e-12);
    assert!((both.multipliers[0] - 0.5 * one.multipliers[0]).abs() < 1e-12);
    assert!((both.accelerations - one.accelerations).amax() < 1e-12);
    assert!((both.reactions - one.reactions).amax() < 1e-12);
}

#[test]
fn inconsistent_initial_conditions() {
    let sys = Rod::standard();
    let (q, v) = sys.state(1.0, 0.5);
    // 1 % too long a rod, and a radial velocity component.
    let (q_bad, v_bad) = (q * 1.01, v + q * 0.2);
    let e = Simulation::new(&sys)
        .run_constrained(q_bad, v, 0.0..1.0)
        .unwrap_err();
    match &e.error {
        Error::InconsistentInitialConditions {
            position_residual,
            tolerance,
            constraint,
            ..
        } => {
            assert!((position_residual - (1.01f64.powi(2) - 1.0)).abs() < 1e-14);
            assert_eq!((*tolerance, *constraint), (1e-10, "rod"));
        }
        other => panic!("expected InconsistentInitialConditions, got {other:?}"),
    }
    eprintln!("{e}");
    // Positions fine, velocities not.
    let e = check_consistency(&sys, &q, &v_bad, 0.0, 1e-10).unwrap_err();
    match e {
        Error::InconsistentInitialConditions {
            position_residual,
            velocity_residual,
            ..
        } => {
            assert!(position_residual < 1e-15);
            assert!(
                (velocity_residual - 0.4).abs() < 1e-14,
                "{velocity_residual}"
            );
        }
        other => panic!("{other:?}"),
    }
    let [phi, vel] = check_consistency(&sys, &q, &v, 0.0, 1e-10).unwrap();
    assert!(phi < 1e-15 && vel < 1e-15);

    // The projection lands on both manifolds to round-off.
    let (qp, vp) = project_consistent(&sys, q_bad, v_bad, 0.0).unwrap();
    let [phi, vel] = check_consistency(&sys, &qp, &vp, 0.0, 1e-14).unwrap();
    eprintln!("projected initial state: |Phi| {phi:e}, |G v| {vel:e}");
    // With M = m I the M-weighted step is the radial one: the direction is kept.
    assert!((qp.normalize() - q.normalize()).amax() < 1e-15);
    // The velocity correction removes exactly the radial component.
    assert!((vp - v).amax() < 1e-12, "{vp} {v}");

    let tr = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-10))
        .project_initial(true)
        .run_constrained(q_bad, v_bad, 0.0..1.0)
        .unwrap();
    assert_eq!(tr.positions()[0], qp);
    assert!(tr.max_residuals()[0] < 1e-9);
}

#[test]
fn projection_that_cannot_converge_is_an_error() {
    let sys = Rod::standard();
    let (q, v) = sys.state(1.0, 0.5);
    let dynamics = ConstrainedDynamics::new(&sys).drift(Drift::Projection {
        tol: 1e-14,
        max_iter: 1,
    });
    // Far from the circle: one Gauss–Newton step is not enough.
    match dynamics.consistent_state(0.0, q * 3.0, v) {
        Err(Error::ProjectionFailed {
            iterations,
            residual,
            ..
        }) => {
            assert_eq!(iterations, 1);
            assert!(residual > 1e-3, "{residual}");
        }
        other => panic!("expected ProjectionFailed, got {other:?}"),
    }
    // The pivot is a point where the constraint gradient vanishes.
    let e = project_consistent(&sys, Vector2::zeros(), v, 0.0).unwrap_err();
    assert!(
        matches!(&e, Error::RedundantConstraints { dependent, .. } if dependent == &["rod"]),
        "{e:?}"
    );
    // Invalid settings are reported before anything runs.
    let e = Simulation::new(&sys)
        .drift(Drift::Projection {
            tol: 0.0,
            max_iter: 3,
        })
        .run_constrained(q, v, 0.0..1.0)
        .unwrap_err();
    assert!(matches!(e.error, Error::Settings(_)), "{e:?}");
}

#[test]
fn non_finite_states_are_typed_errors() {
    let nan = CartesianPendulum::<1> {
        m: f64::NAN,
        l: 1.0,
        g: 9.81,
    };
    let (q, v) = nan.state(1.0, 0.5);
    for drift in [Drift::None, Drift::projection()] {
        match Simulation::new(&nan)
            .drift(drift)
            .run_constrained(q, v, 0.0..1.0)
        {
            Err(Failure {
                error: Error::NonFiniteState { t, .. },
                ..
            }) => assert_eq!(t, 0.0),
            other => panic!("expected NonFiniteState, got {other:?}"),
        }
    }
    let sys = Rod::standard();
    let d = ConstrainedDynamics::new(&sys);
    let bad = Vector2::new(f64::NAN, 0.0);
    assert!(matches!(
        d.solve(0.0, &bad, &v),
        Err(Error::NonFiniteState { .. })
    ));
    assert!(matches!(
        d.consistent_state(0.0, q, bad),
        Err(Error::NonFiniteState { .. })
    ));
    assert!(matches!(
        check_consistency(&sys, &q, &bad, 0.0, 1e-10),
        Err(Error::NonFiniteState { .. })
    ));
    // A state far enough out overflows |v|² to infinity in γ.
    let huge = Vector2::new(1e200, 1e200);
    assert!(matches!(
        d.solve(0.0, &q, &huge),
        Err(Error::NonFiniteState { .. })
    ));
    // A NaN initial state is an invalid problem, as for unconstrained runs.
    assert!(matches!(
        Simulation::new(&sys).run_constrained(bad, v, 0.0..1.0),
        Err(Failure {
            error: Error::Settings(_),
            ..
        })
    ));
}

/// θ̈ = −(g sin θ + 2 l̇ θ̇) / l: the driven pendulum in its angle.
struct DrivenAngle<'a>(&'a DrivenPendulum);

impl SecondOrder<f64, 1> for DrivenAngle<'_> {
    fn acceleration(
        &self,
        t: f64,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
    ) -> Result<Vector1<f64>, Error> {
        let [l, ld, _] = self.0.length(t);
        Ok(Vector1::new(-(self.0.g * q[0].sin() + 2.0 * ld * v[0]) / l))
    }
}

#[test]
fn rheonomic_constraint_driven_rod_length() {
    let sys = DrivenPendulum::standard();
    let (theta0, rate0, t0) = (0.8, 0.0, 0.5);
    let (q0, v0) = sys.state(theta0, rate0, t0);
    let span = t0..10.0;
    let angle = Dopri5::tol(1e-11)
        .integrate(
            &DrivenAngle(&sys),
            span.start,
            span.end,
            sv([theta0]),
            sv([rate0]),
        )
        .unwrap();
    for drift in [Drift::None, Drift::projection()] {
        let cart = Simulation::new(&sys)
            .integrator(Dopri5::tol(1e-11))
            .drift(drift)
            .run_constrained(q0, v0, span.clone())
            .unwrap();
        let mut worst: f64 = 0.0;
        for k in 0..=95 {
            let t = t0 + 0.1 * k as f64;
            let (q, v) = cart.state_at(t).unwrap();
            let (th, w) = angle.state_at(t).unwrap();
            let (x, y) = sys.state(th[0], w[0], t);
            worst = worst.max((q - x).amax()).max((v - y).amax());
        }
        let [phi, vel] = cart.max_residuals();
        eprintln!(
            "driven rod, {drift:?}: max state difference to the angle form {worst:e}; \
             residuals |Phi| {phi:e}, |G v + g| {vel:e}"
        );
        assert!(worst < 1e-8, "{worst:e}");
        if drift != Drift::None {
            assert!(phi <= 1e-12 && vel <= 1e-12, "{phi:e} {vel:e}");
        }
    }
    // The initial check sees the time: the same state is inconsistent at t = 0.
    assert!(check_consistency(&sys, &q0, &v0, t0, 1e-12).is_ok());
    assert!(matches!(
        check_consistency(&sys, &q0, &v0, 0.0, 1e-12),
        Err(Error::InconsistentInitialConditions { .. })
    ));
    let (q, v) = project_consistent(&sys, q0, v0, 0.0).unwrap();
    let [phi, vel] = check_consistency(&sys, &q, &v, 0.0, 1e-14).unwrap();
    eprintln!("driven rod projected at t = 0: |Phi| {phi:e}, |G v + g| {vel:e}");
}
