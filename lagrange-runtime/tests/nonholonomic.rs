//! A nonholonomic system in both forms: the Chaplygin sleigh on an incline, with a
//! multiplier (Constrained) and in independent speeds (Reduced).

mod common;

use common::constrained::Sleigh;
use lagrange_runtime::Failure;
use lagrange_runtime::{
    ConstrainedDynamics, Dopri5, Drift, Error, ReducedDynamics, Rk4, SecondOrder, Simulation,
};
use nalgebra::{Vector2, Vector3};

/// Heading 0.3 rad, forward speed 1, turning at 2 rad/s.
fn start() -> (Vector3<f64>, Vector3<f64>) {
    let theta: f64 = 0.3;
    let (sigma, omega) = (1.0, 2.0);
    (
        Vector3::new(0.0, 0.0, theta),
        Vector3::new(sigma * theta.cos(), sigma * theta.sin(), omega),
    )
}

#[test]
fn multiplier_and_reduced_forms_agree() {
    let sys = Sleigh::standard();
    let (q0, v0) = start();
    let span = 0.0..10.0;
    let sim = Simulation::new(&sys).integrator(Dopri5::tol(1e-11));
    let multiplier = sim.run_constrained(q0, v0, span.clone()).unwrap();
    let reduced = sim.run_reduced(q0, v0, span).unwrap();
    let mut worst: f64 = 0.0;
    for k in 0..=100 {
        let t = 0.1 * k as f64;
        let (a, b) = (
            multiplier.state_at(t).unwrap(),
            reduced.state_at(t).unwrap(),
        );
        worst = worst.max((a.0 - b.0).amax()).max((a.1 - b.1).amax());
    }
    let slip = |tr: &lagrange_runtime::Trajectory<f64, 3>| {
        tr.positions()
            .iter()
            .zip(tr.velocities())
            .map(|(q, v)| Sleigh::slip(q, v).abs())
            .fold(0.0, f64::max)
    };
    let (slip_m, slip_r) = (slip(&multiplier), slip(&reduced));
    eprintln!(
        "sleigh over 10 s: multiplier vs reduced max state difference {worst:e}; \
         energy drift {:e} (multiplier) {:e} (reduced); max slip {slip_m:e} (multiplier) \
         {slip_r:e} (reduced); recorded velocity residual {:e} / {:e}; {:?} / {:?}",
        multiplier.integral_drift(),
        reduced.integral_drift(),
        multiplier.max_residuals()[1],
        reduced.max_residuals()[1],
        multiplier.stats(),
        reduced.stats(),
    );
    assert!(worst < 1e-8, "{worst:e}");
    assert!(multiplier.integral_drift() < 1e-9);
    assert!(reduced.integral_drift() < 1e-9);
    assert!(slip_r < 1e-14, "{slip_r:e}");
    assert!(reduced.max_residuals()[1] < 1e-14);
    assert!(reduced.max_residuals()[0] == 0.0);
    // The multiplier form drifts off the constraint by the integration error only.
    assert!(slip_m < 1e-8, "{slip_m:e}");
    assert_eq!(multiplier.max_residuals()[0], 0.0);
    // The sleigh really turns and travels (not a trivial motion): it ends up
    // moving down the slope (+x) after ten seconds.
    let (q, v) = reduced.final_state();
    assert!(q[0] > 1.0 && v[0] > 0.0, "{q} {v}");
}

#[test]
fn reduced_accelerations_satisfy_the_multiplier_equations() {
    // At an admissible state the reduced q̈ solves the saddle-point system: the
    // same accelerations, and M q̈ + h − Q lies along Gᵀ.
    let sys = Sleigh::standard();
    let d_m = ConstrainedDynamics::new(&sys);
    let d_r = ReducedDynamics::new(&sys);
    for k in 0..10 {
        let theta = 0.7 * k as f64;
        let q = Vector3::new(0.1 * k as f64, -0.2, theta);
        let (s, c) = theta.sin_cos();
        let (sigma, omega) = (1.0 - 0.3 * k as f64, 0.5 + 0.1 * k as f64);
        let v = Vector3::new(sigma * c, sigma * s, omega);
        let sol = d_m.solve(0.0, &q, &v).unwrap();
        let (du, a) = d_r.solve(0.0, &q, &v).unwrap();
        assert!(
            (sol.accelerations - a).amax() < 1e-13,
            "{} {a}",
            sol.accelerations
        );
        // u̇ of the sleigh equations, written out.
        let j = sys.ic + sys.m * sys.a * sys.a;
        let expected = Vector2::new(
            sys.gs * c + sys.a * omega * omega,
            -sys.m * sys.a * (sigma * omega + sys.gs * s) / j,
        );
        assert!((du - expected).amax() < 1e-13);
        // The lateral reaction: Gᵀ μ with G = (−s, c, 0).
        assert!((sol.reactions - Vector3::new(-s, c, 0.0) * sol.multipliers[0]).amax() < 1e-15);
    }
}

/// The runtime's pivoted solve of the rows [U; G] against the reduced form by
/// hand, at every heading: θ = 0, π/2, π are where a symbolic solve for ẋ or ẏ
/// divides by cos θ or sin θ.
#[test]
fn pivoted_reduction_equals_the_closed_form_at_every_heading() {
    let sys = Sleigh::standard();
    let d = ReducedDynamics::<_, f64, 2>::new(&sys);
    let u = Vector2::new(1.3, -0.4);
    let mut worst: f64 = 0.0;
    for k in 0..=16 {
        let theta = k as f64 * std::f64::consts::PI / 8.0;
        let q = Vector3::new(0.2, -0.1, theta);
        let form = d.form(0.0, &q, &u).unwrap();
        let (m, f, w, kappa) = sys.closed_form(&q, &u);
        worst = worst
            .max((form.mass - m).amax())
            .max((form.force - f).amax())
            .max((form.w - w).amax())
            .max((form.kappa - kappa).amax())
            .max((form.velocities - w * u).amax());
    }
    assert!(worst < 1e-14, "{worst}");
}

#[test]
fn reduced_run_projects_the_initial_velocity_and_stays_admissible() {
    let sys = Sleigh::standard();
    let (q0, v0) = start();
    // A sideways component in v0 is dropped: only the speeds u = U v0 are kept.
    let side = Vector3::new(-q0[2].sin(), q0[2].cos(), 0.0) * 0.3;
    let tr = Simulation::new(&sys)
        .integrator(Rk4::step(0.01))
        .run_reduced(q0, v0 + side, 0.0..5.0)
        .unwrap();
    assert!((tr.velocities()[0] - v0).amax() < 1e-15);
    assert!(tr.max_residuals()[1] < 1e-14, "{:?}", tr.max_residuals());
    // The project hook reports whether it changed anything.
    let d = ReducedDynamics::new(&sys);
    let (mut q, mut v) = (q0, v0 + side);
    assert!(d.project(0.0, &mut q, &mut v).unwrap());
    assert!(Sleigh::slip(&q, &v).abs() < 1e-16);
    // Already admissible: no change reported, v left alone.
    let v_ok = v;
    assert!(!d.project(0.0, &mut q, &mut v).unwrap());
    assert_eq!(v, v_ok);
}

#[test]
fn velocity_projection_for_a_purely_nonholonomic_system() {
    // No holonomic rows: projection only corrects velocities, to its tolerance
    // (a correction is made whenever the residual exceeds it, and it is linear, so
    // it lands at round-off).
    let sys = Sleigh::standard();
    let (q0, v0) = start();
    let tr = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-6))
        .drift(Drift::Projection {
            tol: 1e-14,
            max_iter: 1,
        })
        .run_constrained(q0, v0, 0.0..50.0)
        .unwrap();
    let loose = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-6))
        .run_constrained(q0, v0, 0.0..50.0)
        .unwrap();
    // Baumgarte on a nonholonomic row has only the velocity term: ė = −2α e.
    let damped = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-6))
        .drift(Drift::Baumgarte {
            alpha: 5.0,
            beta: 5.0,
        })
        .run_constrained(q0, v0, 0.0..50.0)
        .unwrap();
    eprintln!(
        "sleigh 50 s at tol 1e-6: velocity residual {:e} without control, {:e} Baumgarte, \
         {:e} with projection",
        loose.max_residuals()[1],
        damped.max_residuals()[1],
        tr.max_residuals()[1]
    );
    let late = |tr: &lagrange_runtime::Trajectory<f64, 3>| {
        tr.times()
            .iter()
            .zip(tr.residuals())
            .filter(|(t, _)| **t > 40.0)
            .map(|(_, r)| r[1])
            .fold(0.0, f64::max)
    };
    eprintln!(
        "  after 40 s: {:e} without control, {:e} Baumgarte",
        late(&loose),
        late(&damped)
    );
    assert!(late(&damped) < 0.1 * late(&loose));
    assert!(tr.max_residuals()[1] <= 1e-14);
    assert!(loose.max_residuals()[1] > 1e3 * tr.max_residuals()[1].max(1e-16));
    // Inconsistent sideways velocity: an error, or projected away on request.
    let side = Vector3::new(-q0[2].sin(), q0[2].cos(), 0.0) * 0.3;
    match Simulation::new(&sys).run_constrained(q0, v0 + side, 0.0..1.0) {
        Err(Failure {
            error:
                Error::InconsistentInitialConditions {
                    velocity_residual,
                    constraint,
                    ..
                },
            ..
        }) => {
            assert!((velocity_residual - 0.3).abs() < 1e-15);
            assert_eq!(constraint, "no_side_slip");
        }
        other => panic!("expected InconsistentInitialConditions, got {other:?}"),
    }
    let tr = Simulation::new(&sys)
        .project_initial(true)
        .run_constrained(q0, v0 + side, 0.0..1.0)
        .unwrap();
    assert_eq!(tr.positions()[0], q0);
    // M-weighted, not Euclidean: the correction also changes θ̇ (the centre of
    // mass is ahead of the edge), but it lands on the constraint.
    assert!(Sleigh::slip(&tr.positions()[0], &tr.velocities()[0]).abs() < 1e-15);
}

#[test]
fn reduced_typed_errors() {
    // Zero inertia and zero offset: M* = diag(m, 0) is singular.
    let flat = Sleigh {
        m: 1.0,
        a: 0.0,
        ic: 0.0,
        gs: 0.5,
    };
    let (q0, v0) = start();
    match Simulation::new(&flat).run_reduced(q0, v0, 0.0..1.0) {
        Err(Failure {
            error: Error::SingularMassMatrix { t, ratio, .. },
            ..
        }) => {
            assert_eq!(t, 0.0);
            assert!(ratio <= 0.0);
        }
        other => panic!("expected SingularMassMatrix, got {other:?}"),
    }
    let nan = Sleigh {
        m: f64::NAN,
        ..Sleigh::standard()
    };
    for result in [
        Simulation::new(&nan).run_reduced(q0, v0, 0.0..1.0),
        Simulation::new(&nan).run_constrained(q0, v0, 0.0..1.0),
    ] {
        assert!(
            matches!(
                result,
                Err(Failure {
                    error: Error::NonFiniteState { t: 0.0, .. },
                    ..
                })
            ),
            "{result:?}"
        );
    }
    let sys = Sleigh::standard();
    let d = ReducedDynamics::new(&sys);
    let bad = Vector3::new(0.0, f64::INFINITY, 0.0);
    assert!(matches!(
        d.solve(0.0, &q0, &bad),
        Err(Error::NonFiniteState { .. })
    ));
    let (mut q, mut v) = (Vector3::new(0.0, 0.0, f64::NAN), v0);
    assert!(matches!(
        d.project(0.0, &mut q, &mut v),
        Err(Error::NonFiniteState { .. })
    ));
}
