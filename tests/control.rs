//! Catalog systems driven by controllers: computed-torque tracking of the two-link
//! arm, LQR on the cart-pole (continuous and sampled).

#[path = "../examples/catalog/mod.rs"]
mod catalog;

use catalog::control::TwoLinkArm;
use lagrange::prelude::*;

/// The reference the arm tracks: q_d(t), q̇_d(t), q̈_d(t).
fn reference(t: f64) -> [Vector2<f64>; 3] {
    [
        Vector2::new(0.5 * t.sin(), 0.8 + 0.4 * (1.5 * t).cos()),
        Vector2::new(0.5 * t.cos(), -0.6 * (1.5 * t).sin()),
        Vector2::new(-0.5 * t.sin(), -0.9 * (1.5 * t).cos()),
    ]
}

/// Computed torque τ = M (q̈_d + K_d ė + K_p e) − (Q − h)|_{u=0}: with the
/// exact model every joint error obeys ë + K_d ė + K_p e = 0.
#[test]
fn arm_computed_torque_tracks_with_the_designed_error_dynamics() {
    let arm = TwoLinkArm::standard();
    let (kp, kd) = (100.0, 20.0); // critically damped at ω = 10 rad/s
    let e0 = Vector2::new(0.1, -0.1);
    let [qd0, vd0, _] = reference(0.0);
    let run = Simulation::new(&arm)
        .integrator(Dopri5::tol(1e-11))
        .feedback(|t, q: &Vector2<f64>, v: &Vector2<f64>| {
            let [qd, vd, ad] = reference(t);
            let a = ad + (vd - v) * kd + (qd - q) * kp;
            let (m, unforced) = arm.mass_matrix_and_rhs(q, v, t);
            m * a - unforced
        })
        .run(qd0 + e0, vd0, 0.0..3.0)
        .unwrap();
    let traj = run.trajectory();
    let mut worst = 0.0f64;
    for (t, q) in traj.times().iter().zip(traj.positions()) {
        // e(t) = e0 (1 + ω t) e^{−ω t} with ė(0) = 0.
        let exact = e0 * (1.0 + 10.0 * t) * (-10.0 * t).exp();
        let e = reference(*t)[0] - q;
        worst = worst.max((e + exact).abs().max());
    }
    assert!(worst < 1e-8, "error dynamics off by {worst:e}");
    let (q_end, _) = traj.final_state();
    let tracking = (reference(3.0)[0] - q_end).abs().max();
    assert!(tracking < 1e-9, "tracking error at 3 s: {tracking:e}");
    // One recorded torque pair per stored state.
    assert_eq!(run.inputs().len(), traj.len());
}
