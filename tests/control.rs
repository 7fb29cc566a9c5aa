//! Catalog systems driven by controllers: computed-torque tracking of the two-link
//! arm, LQR on the cart-pole (continuous and sampled).

use crate::catalog;

use catalog::control::{CartPole, TwoLinkArm};
use lagrange::linear::Lqr;
use lagrange::nalgebra::DMatrix;
use lagrange::prelude::*;

/// Computed torque τ = M (q̈_d + K_d ė + K_p e) − (Q − h)|_{u=0}: with the
/// exact model every joint error obeys ë + K_d ė + K_p e = 0.
#[test]
fn arm_computed_torque_tracks_with_the_designed_error_dynamics() {
    let arm = TwoLinkArm::standard();
    let gains = (100.0, 20.0); // critically damped at ω = 10 rad/s
    let e0 = Vector2::new(0.1, -0.1);
    let [qd0, vd0, _] = TwoLinkArm::reference(0.0);
    let run = Simulation::new(&arm)
        .integrator(Dopri5::tol(1e-11))
        .feedback(|t, q, v| arm.computed_torque(gains, t, q, v))
        .run(qd0 + e0, vd0, 0.0..3.0)
        .unwrap();
    let traj = run.trajectory();
    let mut worst = 0.0f64;
    for (t, q) in traj.times().iter().zip(traj.positions()) {
        // e(t) = e0 (1 + ω t) e^{−ω t} with ė(0) = 0.
        let exact = e0 * (1.0 + 10.0 * t) * (-10.0 * t).exp();
        let e = TwoLinkArm::reference(*t)[0] - q;
        worst = worst.max((e + exact).abs().max());
    }
    assert!(worst < 1e-8, "error dynamics off by {worst:e}");
    let (q_end, _) = traj.final_state();
    let tracking = (TwoLinkArm::reference(3.0)[0] - q_end).abs().max();
    assert!(tracking < 1e-9, "tracking error at 3 s: {tracking:e}");
    // One recorded torque pair per stored state.
    assert_eq!(run.inputs().len(), traj.len());
}

/// The LQR design for the cart-pole about upright, from the symbolic
/// linearisation: Q = diag(10, 100, 1, 1), R = 0.1.
fn cart_pole_lqr(cp: &CartPole) -> Lqr {
    let lin = cp.upright().unwrap();
    assert_eq!(lin.states(), ["x", "theta", "x'", "theta'"]);
    assert_eq!(lin.inputs(), ["force"]);
    // The textbook linear model: θ̈ = ((M + m) g θ − F) / (M l), ẍ = (F − m g θ) / M.
    let (mc, mp, l, g) = (cp.m_c, cp.m_p, cp.l, cp.g);
    let a = DMatrix::from_row_slice(
        4,
        4,
        &[
            0.0,
            0.0,
            1.0,
            0.0, //
            0.0,
            0.0,
            0.0,
            1.0, //
            0.0,
            -mp * g / mc,
            0.0,
            0.0, //
            0.0,
            (mc + mp) * g / (mc * l),
            0.0,
            0.0,
        ],
    );
    let b = DMatrix::from_column_slice(4, 1, &[0.0, 0.0, 1.0 / mc, -1.0 / (mc * l)]);
    assert!((lin.a() - &a).abs().max() < 1e-14, "{}", lin.a());
    assert!((lin.b() - &b).abs().max() < 1e-14, "{}", lin.b());
    let q = DMatrix::from_diagonal(&lagrange::nalgebra::DVector::from_vec(vec![
        10.0, 100.0, 1.0, 1.0,
    ]));
    let r = DMatrix::from_element(1, 1, 0.1);
    let design = lin.lqr(&q, &r).unwrap();
    assert!(
        design.residual < 1e-12,
        "Riccati residual {:e}",
        design.residual
    );
    assert!(design.closed_loop.iter().all(|l| l.re < 0.0));
    design
}

/// Continuous LQR feedback u = −K x from a 0.3 rad tilt: the pole is caught
/// and the cart returns to the origin.
#[test]
fn cart_pole_lqr_settles_from_a_tilt() {
    let cp = CartPole::standard();
    let k = cart_pole_lqr(&cp).gain;
    let law = StateFeedback::from_gain(&k, &cp.upright().unwrap(), &CartPole::COORDINATES).unwrap();
    let run = Simulation::new(&cp)
        .integrator(Dopri5::tol(1e-10))
        .control(law)
        .run([0.0, 0.3], [0.0, 0.0], 0.0..10.0)
        .unwrap();
    let (q, v) = run.trajectory().final_state();
    eprintln!("continuous LQR at 10 s: x = {:.1e}, θ = {:.1e}", q[0], q[1]);
    assert!(q.abs().max() < 1e-4 && v.abs().max() < 1e-4, "{q} {v}");
    let peak = run.inputs().iter().map(|u| u[0].abs()).fold(0.0, f64::max);
    assert!(peak > 1.0, "the controller must act: peak force {peak}");
}

/// The same gain in a 100 Hz digital loop with zero-order hold.
#[test]
fn cart_pole_lqr_at_100_hz_with_zero_order_hold() {
    let cp = CartPole::standard();
    let k = cart_pole_lqr(&cp).gain;
    let law = StateFeedback::from_gain(&k, &cp.upright().unwrap(), &CartPole::COORDINATES).unwrap();
    let run = Simulation::new(&cp)
        .integrator(Dopri5::tol(1e-10))
        .sampled(0.01, move |_, q, v| law.input(q, v))
        .run([0.0, 0.3], [0.0, 0.0], 0.0..10.0)
        .unwrap();
    let (q, v) = run.trajectory().final_state();
    eprintln!("100 Hz LQR at 10 s: x = {:.1e}, θ = {:.1e}", q[0], q[1]);
    assert!(q.abs().max() < 1e-4 && v.abs().max() < 1e-4, "{q} {v}");
    // Held between samples: the input changes only at multiples of 10 ms.
    let traj = run.trajectory();
    for w in traj.times().windows(2).zip(run.inputs().windows(2)) {
        let ((t0, t1), (u0, u1)) = ((w.0[0], w.0[1]), (w.1[0], w.1[1]));
        let sample = (t1 / 0.01).round() * 0.01;
        if u0 != u1 {
            assert!(
                (t1 - sample).abs() < 1e-9 && t1 > t0,
                "input changed at {t1}"
            );
        }
    }
}
