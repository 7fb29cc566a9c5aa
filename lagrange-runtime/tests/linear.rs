//! Linearisation, eigen-analysis, stability boundaries and LQR.
//!
//! The linear models are checked against central differences of the runtime's
//! own nonlinear forward dynamics (with the inputs' forces added) at random
//! states, away from equilibrium (q̇ ≠ 0, inputs ≠ 0), so that every term of the
//! formulas (the ∂M q̈0 term, the multipliers' derivative, the velocity-level
//! q-term) shows.

mod common;
#[path = "linear/sled.rs"]
mod sled;
#[path = "linear/stability.rs"]
mod stability;
#[path = "linear/systems.rs"]
mod systems;

use common::numeric::{Lcg, jacobian, rel_diff};
use lagrange_runtime::linear::{Linear, LinearError, Linearizer, OperatingPoint, Verdict};
use lagrange_runtime::{
    ConstrainedDynamics, Dynamics, Error, ReducedDynamics, linearize, linearize_constrained,
    linearize_reduced,
};
use nalgebra::{Complex, DMatrix, DVector, SVector, Vector1, Vector2, Vector3};
use sled::Sled;
use systems::{DoublePendulum, Forced, Rod};

// Hand-written systems without inputs say so, as the derive does for its own.
impl lagrange_runtime::Driven<f64, 2, 0> for common::constrained::CartesianPendulum<2> {}
impl lagrange_runtime::Driven<f64, 3, 0> for common::constrained::Sleigh {}

fn sv<const N: usize>(x: &DVector<f64>, offset: usize) -> SVector<f64, N> {
    SVector::from_fn(|i, _| x[offset + i])
}

// ---------------------------------------------------------------- unconstrained

#[test]
fn double_pendulum_matches_finite_differences_of_the_forward_dynamics() {
    let sys = DoublePendulum::standard();
    let mut rng = Lcg(7);
    let mut worst: [f64; 2] = [0.0; 2];
    for _ in 0..20 {
        let q = Vector2::new(rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5));
        let v = Vector2::new(rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0));
        let u = Vector3::new(
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
            rng.uniform(0.0, 1.0),
        );
        let lin = linearize(&sys, &OperatingPoint::new(q, v).input(u)).unwrap();
        // x = (q, v) → (v, q̈), and u → (0, q̈), from Dynamics::acceleration.
        let rhs = |x: &DVector<f64>, u: Vector3<f64>| {
            let (q, v) = (sv::<2>(x, 0), sv::<2>(x, 2));
            let forced = Forced { sys: &sys, u };
            let a = Dynamics::new(&forced).acceleration(0.0, &q, &v).unwrap();
            DVector::from_vec(vec![v[0], v[1], a[0], a[1]])
        };
        let x0 = DVector::from_vec(vec![q[0], q[1], v[0], v[1]]);
        let a_fd = jacobian(|x| rhs(x, u), &x0, 1e-6);
        let u0 = DVector::from_column_slice(u.as_slice());
        let b_fd = jacobian(|w| rhs(&x0, sv::<3>(w, 0)), &u0, 1e-6);
        worst[0] = worst[0].max(rel_diff(lin.a(), &a_fd));
        worst[1] = worst[1].max(rel_diff(lin.b(), &b_fd));
    }
    eprintln!(
        "double pendulum, 20 random driven states: max rel |A - A_fd| = {:e}, |B - B_fd| = {:e}",
        worst[0], worst[1]
    );
    assert!(worst[0] < 1e-8 && worst[1] < 1e-8, "{worst:?}");
}

#[test]
fn double_pendulum_second_order_form_and_names() {
    let sys = DoublePendulum::standard();
    let lin = linearize(
        &sys,
        &OperatingPoint::<f64, 2>::new(Vector2::zeros(), Vector2::zeros()),
    )
    .unwrap();
    assert_eq!(lin.states(), ["theta1", "theta2", "theta1'", "theta2'"]);
    assert_eq!(lin.inputs(), ["tau", "push", "damp"]);
    let so = lin.second_order().unwrap();
    // At the bottom: K = diag((m1 + m2) g l1, m2 g l2), C = d I, B_u = [1 l1 0; 0 l2 0].
    let k = DMatrix::from_row_slice(
        2,
        2,
        &[
            (sys.m1 + sys.m2) * sys.g * sys.l1,
            0.0,
            0.0,
            sys.m2 * sys.g * sys.l2,
        ],
    );
    assert!((&so.stiffness - &k).amax() < 1e-14);
    assert!((&so.damping - DMatrix::identity(2, 2) * sys.d).amax() < 1e-15);
    let bu = DMatrix::from_row_slice(2, 3, &[1.0, sys.l1, 0.0, 0.0, sys.l2, 0.0]);
    assert!((&so.input - &bu).amax() < 1e-15);
    // Moving: C gains a gyroscopic (skew) part 2k s12 (θ̇2, θ̇1)-terms and the split
    // reassembles it.
    let lin = linearize(
        &sys,
        &OperatingPoint::<f64, 2>::new(Vector2::new(0.4, -0.3), Vector2::new(1.5, -2.0)),
    )
    .unwrap();
    let so = lin.second_order().unwrap();
    let g = so.gyroscopic();
    assert!(g[(0, 1)].abs() > 0.1, "{g}");
    assert!((g.clone() + g.transpose()).amax() == 0.0);
    assert!((so.symmetric_damping() + &g - &so.damping).amax() < 1e-15);
    let kk = so.square_stiffness().unwrap();
    assert!((so.symmetric_stiffness().unwrap() + so.circulatory().unwrap() - kk).amax() < 1e-15);
    // A's lower blocks are −M⁻¹K and −M⁻¹C.
    let minv = so.mass.clone().try_inverse().unwrap();
    assert!((lin.a().view((2, 0), (2, 2)) + &minv * &so.stiffness).amax() < 1e-12);
    assert!((lin.a().view((2, 2), (2, 2)) + &minv * &so.damping).amax() < 1e-12);
}

#[test]
fn dropping_the_steady_motion_term_would_be_caught() {
    // About a steady motion q̈0 ≠ 0; the ∂M/∂q q̈0 term is part of J_q. Without it
    // (rhs_jacobians evaluated at a = 0) the linearisation differs from the
    // finite differences by O(1): the test above can fail.
    use lagrange_runtime::Lagrangian;
    let sys = DoublePendulum::standard();
    let (q, v) = (Vector2::new(1.0, -0.5), Vector2::new(2.0, 1.0));
    let a0 = Dynamics::new(&sys).acceleration(0.0, &q, &v).unwrap();
    let (jq, _) = sys.rhs_jacobians(&q, &v, &a0, 0.0).unwrap();
    let (jq0, _) = sys.rhs_jacobians(&q, &v, &Vector2::zeros(), 0.0).unwrap();
    assert!(a0.amax() > 1.0);
    assert!((jq - jq0).amax() > 0.5, "{}", (jq - jq0).amax());
}

// ------------------------------------------------------------------- holonomic

#[test]
fn rod_about_the_bottom_oscillates_at_sqrt_g_over_l() {
    let sys = Rod::standard();
    let op = OperatingPoint::<f64, 2>::new(Vector2::new(0.0, -sys.l), Vector2::zeros());
    let named = Linearizer::new()
        .coordinates(&["x"])
        .speeds(&["x"])
        .constrained(&sys, &op)
        .unwrap();
    let auto = linearize_constrained(&sys, &op).unwrap();
    assert_eq!(named.states(), ["x", "x'"]);
    assert_eq!(auto.states(), ["x", "x'"], "pivoting picks y as dependent");
    assert_eq!((named.a(), named.b()), (auto.a(), auto.b()));
    assert_eq!(named.second_order(), auto.second_order());
    // Only the automatic model chose its states.
    assert!(named.completed().is_empty());
    assert_eq!(auto.completed(), ["x", "x'"]);
    let w = (sys.g / sys.l).sqrt();
    let ev = named.eigenvalues();
    eprintln!("rod about the bottom: eigenvalues {ev:?}, sqrt(g/l) = {w}");
    assert!((ev[0] - Complex::new(0.0, w)).norm() < 1e-12);
    assert!((ev[1] - Complex::new(0.0, -w)).norm() < 1e-12);
    assert_eq!(named.stability(1e-9).unwrap().verdict, Verdict::Marginal);
    // The torque input: B = (0, 1/(m l)) in x (ΔQ_x = −τ y/l² = τ/l at the bottom).
    assert!((named.b()[(1, 0)] - 1.0 / (sys.m * sys.l)).abs() < 1e-14);
    let so = named.second_order().unwrap();
    assert!((so.mass[(0, 0)] - sys.m).abs() < 1e-14);
    assert!((so.stiffness[(0, 0)] - sys.m * sys.g / sys.l).abs() < 1e-12);
    // The modes: one eigenvector (x, x') ∝ (1, iω).
    for mode in named.modes() {
        assert!(mode.residual < 1e-12, "{mode:?}");
        let ratio = mode.vector[1] / mode.vector[0];
        assert!((ratio - mode.eigenvalue).norm() < 1e-10, "{mode:?}");
    }
}

#[test]
fn rod_matches_finite_differences_in_independent_coordinates() {
    let sys = Rod::standard();
    let mut rng = Lcg(11);
    let mut worst: [f64; 2] = [0.0; 2];
    for _ in 0..20 {
        let (q, v) = sys.state(rng.uniform(-1.0, 1.0), rng.uniform(-3.0, 3.0));
        let u = Vector1::new(rng.uniform(-2.0, 2.0));
        let lin = Linearizer::new()
            .coordinates(&["x"])
            .speeds(&["x"])
            .constrained(&sys, &OperatingPoint::new(q, v).input(u))
            .unwrap();
        // (x, ẋ) → complete the state (y, ẏ) → (ẋ, ẍ) from the saddle-point solve.
        let rhs = |x: &DVector<f64>, u: Vector1<f64>| {
            let guess = (Vector2::new(x[0], q[1]), Vector2::new(x[1], 0.0));
            let (qc, vc) = Linearizer::new()
                .coordinates(&["x"])
                .speeds(&["x"])
                .complete_state(&sys, guess.0, guess.1, 0.0)
                .unwrap();
            let forced = Forced { sys: &sys, u };
            let sol = ConstrainedDynamics::new(&forced)
                .solve(0.0, &qc, &vc)
                .unwrap();
            DVector::from_vec(vec![vc[0], sol.accelerations[0]])
        };
        let x0 = DVector::from_vec(vec![q[0], v[0]]);
        let a_fd = jacobian(|x| rhs(x, u), &x0, 1e-6);
        let b_fd = jacobian(
            |w| rhs(&x0, Vector1::new(w[0])),
            &DVector::from_element(1, u[0]),
            1e-6,
        );
        worst[0] = worst[0].max(rel_diff(lin.a(), &a_fd));
        worst[1] = worst[1].max(rel_diff(lin.b(), &b_fd));
    }
    eprintln!(
        "rod in x, 20 random moving driven states: max rel |A - A_fd| = {:e}, |B - B_fd| = {:e}",
        worst[0], worst[1]
    );
    assert!(worst[0] < 1e-7 && worst[1] < 1e-7, "{worst:?}");
}

#[test]
fn complete_state_holds_the_independent_coordinate() {
    let sys = Rod::standard();
    let x = 0.6;
    let (q, v) = Linearizer::new()
        .coordinates(&["x"])
        .speeds(&["x"])
        .complete_state(&sys, Vector2::new(x, -0.3), Vector2::new(0.7, 5.0), 0.0)
        .unwrap();
    let phi = q.norm_squared() - sys.l * sys.l;
    eprintln!("complete_state: q = {q:?}, v = {v:?}, Phi = {phi:e}");
    assert_eq!(q[0], x, "independent coordinate untouched");
    assert_eq!(v[0], 0.7, "independent speed untouched");
    assert!(phi.abs() < 1e-15);
    assert!((q[1] + (sys.l * sys.l - x * x).sqrt()).abs() < 1e-15);
    assert!((q.dot(&v)).abs() < 1e-15, "G v = 0");
    // The automatic choice at this point keeps x too (|y| > |x| after convergence
    // is not required: pivoting on Φ_q at the guess picks the larger of |2x|, |2y|).
    let (q2, _) = lagrange_runtime::complete_state(
        &sys,
        Vector2::new(0.2, -0.5),
        Vector2::zeros(),
        0.0,
        &[],
        &[],
    )
    .unwrap();
    assert_eq!(q2[0], 0.2);
    // No solution for |x| > l: Newton fails with a typed error naming the residual.
    let e = Linearizer::new()
        .coordinates(&["x"])
        .complete_state(&sys, Vector2::new(1.5, -0.5), Vector2::zeros(), 0.0)
        .unwrap_err();
    eprintln!("{e}");
    match e {
        Error::ProjectionFailed {
            iterations,
            residual,
            ..
        } => {
            assert_eq!(
                iterations,
                lagrange_runtime::linear::DEFAULT_NEWTON_ITERATIONS
            );
            assert!(residual > 0.1);
        }
        other => panic!("{other:?}"),
    }
}

// ---------------------------------------------------------------- nonholonomic

#[test]
fn sled_multiplier_form_matches_finite_differences() {
    let sys = Sled::standard();
    let mut rng = Lcg(23);
    let mut worst: [f64; 2] = [0.0; 2];
    let lin_named = Linearizer::new().speeds(&["x", "theta"]);
    for _ in 0..20 {
        let theta = rng.uniform(-0.7, 0.7);
        let (xd, w) = (rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0));
        let q = Vector3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), theta);
        let v = Vector3::new(xd, xd * theta.tan(), w);
        let u = Vector3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(0.0, 1.0),
        );
        let lin = lin_named
            .constrained(&sys, &OperatingPoint::new(q, v).input(u))
            .unwrap();
        assert_eq!(lin.states(), ["x", "y", "theta", "x'", "theta'"]);
        let rhs = |x: &DVector<f64>, u: Vector3<f64>| {
            let guess_v = Vector3::new(x[3], 0.0, x[4]);
            let (qc, vc) = lin_named
                .complete_state(&sys, sv::<3>(x, 0), guess_v, 0.0)
                .unwrap();
            let forced = Forced { sys: &sys, u };
            let a = ConstrainedDynamics::new(&forced)
                .solve(0.0, &qc, &vc)
                .unwrap()
                .accelerations;
            DVector::from_vec(vec![vc[0], vc[1], vc[2], a[0], a[2]])
        };
        let x0 = DVector::from_vec(vec![q[0], q[1], q[2], v[0], v[2]]);
        let a_fd = jacobian(|x| rhs(x, u), &x0, 1e-6);
        let b_fd = jacobian(
            |w| rhs(&x0, sv::<3>(w, 0)),
            &DVector::from_column_slice(u.as_slice()),
            1e-6,
        );
        worst[0] = worst[0].max(rel_diff(lin.a(), &a_fd));
        worst[1] = worst[1].max(rel_diff(lin.b(), &b_fd));
    }
    eprintln!(
        "sled multiplier form, 20 random moving driven states: max rel |A - A_fd| = {:e}, \
         |B - B_fd| = {:e}",
        worst[0], worst[1]
    );
    assert!(worst[0] < 1e-7 && worst[1] < 1e-7, "{worst:?}");
}

#[test]
fn sled_reduced_form_matches_finite_differences() {
    let sys = Sled::standard();
    let mut rng = Lcg(29);
    let mut worst: [f64; 2] = [0.0; 2];
    for _ in 0..20 {
        let q = Vector3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-3.0, 3.0),
        );
        let speeds = Vector2::new(rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0));
        let reduced = ReducedDynamics::<_, f64, 2>::new(&sys);
        let v = reduced.velocities(0.0, &q, &speeds).unwrap();
        let u = Vector3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(0.0, 1.0),
        );
        let lin = linearize_reduced(&sys, &OperatingPoint::new(q, v).input(u)).unwrap();
        assert_eq!(lin.states(), ["x", "y", "theta", "sigma", "omega"]);
        let rhs = |x: &DVector<f64>, u: Vector3<f64>| {
            let q = sv::<3>(x, 0);
            let v = reduced.velocities(0.0, &q, &sv::<2>(x, 3)).unwrap();
            let forced = Forced { sys: &sys, u };
            let (du, _) = ReducedDynamics::new(&forced).solve(0.0, &q, &v).unwrap();
            DVector::from_vec(vec![v[0], v[1], v[2], du[0], du[1]])
        };
        let x0 = DVector::from_vec(vec![q[0], q[1], q[2], speeds[0], speeds[1]]);
        let a_fd = jacobian(|x| rhs(x, u), &x0, 1e-6);
        let b_fd = jacobian(
            |w| rhs(&x0, sv::<3>(w, 0)),
            &DVector::from_column_slice(u.as_slice()),
            1e-6,
        );
        worst[0] = worst[0].max(rel_diff(lin.a(), &a_fd));
        worst[1] = worst[1].max(rel_diff(lin.b(), &b_fd));
    }
    eprintln!(
        "sled reduced form, 20 random moving driven states: max rel |A - A_fd| = {:e}, \
         |B - B_fd| = {:e}",
        worst[0], worst[1]
    );
    assert!(worst[0] < 1e-7 && worst[1] < 1e-7, "{worst:?}");
}

#[test]
fn sled_straight_motion_on_flat_ground() {
    // Steady straight motion at speed σ0 along θ = 0 on a flat plane: the heading
    // perturbation decays at rate m a σ0 / (ic + m a²), the rest is neutral; the
    // velocity-level q-term gives δẏ = σ0 δθ. Both forms agree.
    let sys = Sled {
        gs: 0.0,
        ..Sled::standard()
    };
    let sigma = 1.7;
    let op = OperatingPoint::<f64, 3>::new(Vector3::zeros(), Vector3::new(sigma, 0.0, 0.0));
    let multiplier = linearize_constrained(&sys, &op).unwrap();
    let reduced = linearize_reduced(&sys, &op).unwrap();
    assert_eq!(multiplier.states(), ["x", "y", "theta", "x'", "theta'"]);
    let iy = multiplier.state_index("y").unwrap();
    let ith = multiplier.state_index("theta").unwrap();
    assert!((multiplier.a()[(iy, ith)] - sigma).abs() < 1e-15);
    let rate = -sys.m * sys.a * sigma / (sys.ic + sys.m * sys.a * sys.a);
    for lin in [&multiplier, &reduced] {
        let ev = lin.eigenvalues();
        eprintln!("sled straight at {sigma} m/s: eigenvalues {ev:?} (expected 0 x4, {rate})");
        let last = ev.last().unwrap();
        assert!((last.re - rate).abs() < 1e-14 && last.im == 0.0);
        assert!(ev[..4].iter().all(|z| z.norm() < 1e-14));
        // The zeros are structural (position, heading and forward speed feed
        // nothing but themselves): the yaw rate alone is asymptotically
        // stable, but a heading (or speed) kick moves the position like t.
        let stab = lin.stability(1e-12).unwrap();
        assert_eq!(stab.without_structural, Verdict::AsymptoticallyStable);
        assert_eq!(stab.verdict, Verdict::PolynomialGrowth { degree: 1 });
        assert_eq!(stab.structural.len(), 4, "{:?}", stab.structural);
        assert!(!stab.structural.contains(&"theta'".to_string()));
        assert!(
            ev[..4].iter().all(|z| *z == Complex::new(0.0, 0.0)),
            "exact zeros"
        );
    }
    // Dropping the ignorable x, y (nothing depends on them) leaves θ, x', θ'.
    let kept = multiplier.select(&["theta", "x'", "theta'"]).unwrap();
    assert_eq!(kept.states(), ["theta", "x'", "theta'"]);
    // Keeping x' without x leaves no second-order form (x' is not the rate of a
    // kept coordinate); the heading block alone has one: M_r = ic + m a² and
    // C = m a σ0 (the projected mass times the decay rate), K = 0.
    assert!(multiplier.second_order().is_some() && kept.second_order().is_none());
    let heading = multiplier.select(&["theta", "theta'"]).unwrap();
    let so = heading.second_order().unwrap();
    let (mr, c, k) = (so.mass[(0, 0)], so.damping[(0, 0)], so.stiffness[(0, 0)]);
    eprintln!("sled heading block: M_r = {mr}, C = {c}, K = {k}");
    assert!((mr - (sys.ic + sys.m * sys.a * sys.a)).abs() < 1e-15);
    assert!((c - sys.m * sys.a * sigma).abs() < 1e-14 && k == 0.0);
    // But dropping θ is refused: y' = σ0 θ depends on it.
    let e = multiplier.select(&["y", "x'", "theta'"]).unwrap_err();
    eprintln!("{e}");
    assert!(matches!(
        e,
        Error::Linear(LinearError::CoupledStates { ref kept, ref dropped, .. })
            if kept == "y" && dropped == "theta"
    ));
}

// --------------------------------------------------------------- typed errors

#[test]
fn inconsistent_operating_point_names_the_residual() {
    let sys = Rod::standard();
    let op = OperatingPoint::<f64, 2>::new(Vector2::new(0.6, -0.7), Vector2::zeros());
    let e = linearize_constrained(&sys, &op).unwrap_err();
    let msg = e.to_string();
    eprintln!("{msg}");
    match e {
        Error::Linear(LinearError::InconsistentOperatingPoint {
            position_residual,
            ref worst,
            ..
        }) => {
            let phi = 0.6f64 * 0.6 + 0.7 * 0.7 - sys.l * sys.l;
            assert!((position_residual - phi.abs()).abs() < 1e-15);
            assert!(worst.contains("rod"));
        }
        ref other => panic!("{other:?}"),
    }
    assert!(msg.contains("complete the state"));
    // A velocity violating the rod.
    let (q, _) = sys.state(0.3, 0.0);
    let e = linearize_constrained(&sys, &OperatingPoint::<f64, 2>::new(q, q)).unwrap_err();
    assert!(matches!(
        e,
        Error::Linear(LinearError::InconsistentOperatingPoint { velocity_residual, .. })
            if velocity_residual > 1.0
    ));
}

#[test]
fn singular_mass_matrix_is_reported() {
    let sys = DoublePendulum {
        m1: 0.0,
        m2: 0.0,
        ..DoublePendulum::standard()
    };
    let e = linearize(
        &sys,
        &OperatingPoint::<f64, 2>::new(Vector2::zeros(), Vector2::zeros()),
    )
    .unwrap_err();
    assert!(matches!(e, Error::SingularMassMatrix { .. }), "{e:?}");
}

#[test]
fn missing_derivatives_ask_for_emit_jacobians() {
    // The common test systems implement no derivatives.
    let pendulum = common::constrained::CartesianPendulum::<1>::standard();
    let (q, v) = pendulum.state(0.3, 1.0);
    let e = linearize_constrained(&pendulum, &OperatingPoint::<f64, 2>::new(q, v)).unwrap_err();
    let msg = e.to_string();
    eprintln!("{msg}");
    assert!(
        msg.contains("emit(jacobians)") && msg.contains("rhs_jacobians"),
        "{msg}"
    );
    let sleigh = common::constrained::Sleigh::standard();
    let (q, v) = (
        Vector3::new(0.0, 0.0, 0.3),
        Vector3::new(0.3f64.cos(), 0.3f64.sin(), 1.0),
    );
    let e = linearize_reduced(&sleigh, &OperatingPoint::<f64, 3>::new(q, v)).unwrap_err();
    assert!(matches!(
        e,
        Error::MissingDerivatives {
            method: "Lagrangian::rhs_jacobians",
            ..
        }
    ));
    let e = linearize(
        &common::Oscillator { m: 1.0, k: 4.0 },
        &OperatingPoint::<f64, 1>::new(SVector::from_element(0.1), SVector::zeros()),
    )
    .unwrap_err();
    assert!(e.to_string().contains("emit(jacobians)"));
}

#[test]
fn redundant_constraints_and_bad_partitions_are_reported() {
    let twice = common::constrained::CartesianPendulum::<2>::standard();
    let (q, v) = twice.state(0.3, 0.0);
    let e = linearize_constrained(&twice, &OperatingPoint::<f64, 2>::new(q, v)).unwrap_err();
    assert!(matches!(e, Error::RedundantConstraints { .. }), "{e:?}");
    let sys = Rod::standard();
    // At θ = π/2 (x = l, y = 0) y cannot be the dependent coordinate.
    let (q, v) = sys.state(std::f64::consts::FRAC_PI_2, 0.0);
    let op = OperatingPoint::<f64, 2>::new(q, v);
    let e = Linearizer::new()
        .coordinates(&["x"])
        .constrained(&sys, &op)
        .unwrap_err();
    eprintln!("{e}");
    assert!(
        matches!(e, Error::Linear(LinearError::SingularPartition { .. })),
        "{e:?}"
    );
    // ... but the automatic choice takes y as independent there.
    let lin = linearize_constrained(&sys, &op).unwrap();
    assert_eq!(lin.states(), ["y", "y'"]);
    let e = Linearizer::new()
        .coordinates(&["z"])
        .constrained(&sys, &op)
        .unwrap_err();
    assert!(
        matches!(e, Error::Linear(LinearError::InvalidPartition { .. })),
        "{e:?}"
    );
}

#[test]
fn select_refuses_a_coupled_state_and_keeps_a_decoupled_block() {
    let sys = DoublePendulum::standard();
    let lin = linearize(
        &sys,
        &OperatingPoint::<f64, 2>::new(Vector2::zeros(), Vector2::zeros()),
    )
    .unwrap();
    let e = lin.select(&["theta1", "theta1'"]).unwrap_err();
    eprintln!("{e}");
    assert!(matches!(
        e,
        Error::Linear(LinearError::CoupledStates { .. })
    ));
    let e = lin.select(&["theta3"]).unwrap_err();
    assert!(matches!(e, Error::Linear(LinearError::UnknownState { .. })));
    // Block-diagonal: two uncoupled oscillators, one kept.
    let m = DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 2.0]));
    let k = DMatrix::from_diagonal(&DVector::from_vec(vec![4.0, 8.0]));
    let c = DMatrix::from_diagonal(&DVector::from_vec(vec![0.1, 0.2]));
    let two = Linear::from_second_order(m, c, k, DMatrix::zeros(2, 0), &["a", "b"], &[]).unwrap();
    let one = two.select(&["b'", "b"]).unwrap();
    assert_eq!(one.states(), ["b", "b'"]);
    let so = one.second_order().unwrap();
    assert_eq!((so.mass[(0, 0)], so.stiffness[(0, 0)]), (2.0, 8.0));
    let ev = one.eigenvalues();
    assert!(
        (ev[0] - Complex::new(-0.05, (4.0f64 - 0.0025).sqrt())).norm() < 1e-14,
        "{ev:?}"
    );
}
