//! Operational-space control (`lagrange::task_space::OperationalSpace`) of
//! the UR5 read from its URDF (`examples/catalog/operational.rs`): with the
//! exact model the tool's task error follows the designed linear error
//! dynamics, the orientation error is the rotation vector of R_d Rᵀ, and a
//! singular pose gets a finite, bounded command.

use crate::operational;

use lagrange::nalgebra::{Matrix6, Rotation3, Unit, Vector3, Vector6};
use lagrange::prelude::*;
use lagrange::task_space::{
    Damping, OperationalSpace, critically_damped, damped_inverse, rotation_error,
};
use operational::{Ur5, start_off_the_circle, tool_circle};

type Task = Vector6<f64>;

/// The controllers' damping: below σ_min = 0.01, λ up to 0.05.
const DAMPING: Damping = Damping {
    threshold: 0.01,
    damping: 0.05,
};

const OMEGA: f64 = 10.0;

/// From rest 5 cm off the circle and 0.3 rad behind its turning goal, the
/// task error e = (p_d − p, log(R_d Rᵀ)) is the solution of
/// ë + 2ω ė + ω² e = 0 from e(0), ė(0) = (ṗ_d, ω_d) at every stored point.
#[test]
fn the_tool_error_follows_the_critically_damped_closed_form() {
    let ur5 = Ur5 {};
    let osc = OperationalSpace::new(&ur5, "tool0", OMEGA).expect("the UR5 has tool0");
    let circle = tool_circle();
    let q0 = start_off_the_circle(&osc, &circle).expect("inverse kinematics converges");
    let v0 = SVector::<f64, 6>::zeros();
    let (e0, de0) = osc.error(&circle.at(0.0), &q0, &v0);
    // The start is where it was asked to be: 4 cm out (+x at φ = 0), 3 cm up,
    // 0.3 rad behind about the vertical.
    let asked = Task::new(-0.04, 0.0, -0.03, 0.0, 0.0, 0.3);
    assert!((e0 - asked).amax() < 1e-12, "start error {e0}");
    let run = Simulation::new(&ur5)
        .integrator(Dopri5::tol(1e-11))
        .feedback(osc.feedback(move |t| circle.at(t)))
        .run(q0, v0, 0.0..1.0)
        .expect("the run completes");
    let traj = run.trajectory();
    let (mut off, mut smallest) = (0.0f64, f64::INFINITY);
    for ((t, q), v) in traj
        .times()
        .iter()
        .zip(traj.positions())
        .zip(traj.velocities())
    {
        let goal = circle.at(*t);
        let (e, _) = osc.error(&goal, q, v);
        off = off.max((e - critically_damped(&e0, &de0, OMEGA, *t)).amax());
        smallest = smallest.min(osc.accelerations(&goal, q, v).1);
    }
    println!("UR5 on the circle: off the closed form by {off:e}, σ_min(J) ≥ {smallest}");
    assert!(off < 1e-8, "task error off the closed form by {off:e}");
    // The inverse was never damped, or the closed form would not hold.
    assert!(
        smallest > osc.damping_settings().threshold,
        "σ_min(J) fell to {smallest}"
    );
    let (q1, v1) = traj.final_state();
    let (e1, _) = osc.error(&circle.at(1.0), &q1, &v1);
    assert!(e1.amax() < 1e-3, "tool error at 1 s {e1}");
}

/// J⁺ (damped below σ_min = 0.01, λ = 0.05) is J⁻¹ where J is well
/// conditioned; at the wrist singularity (the second wrist joint at zero
/// lines up the first and third wrist axes) it is bounded by 1/(2λ), and
/// the controller's torque is finite.
#[test]
fn a_singular_pose_gets_a_finite_bounded_command() {
    let ur5 = Ur5 {};
    let osc = OperationalSpace::new(&ur5, "tool0", OMEGA).expect("the UR5 has tool0");
    let circle = tool_circle();
    let q0 = start_off_the_circle(&osc, &circle).expect("inverse kinematics converges");
    let damped = damped_inverse(&osc.jacobian(&q0), &DAMPING).expect("finite J");
    let (inverse, smallest) = (damped.inverse, damped.smallest);
    assert!(smallest > 0.01);
    let identity = osc.jacobian(&q0) * inverse - Matrix6::identity();
    assert!(identity.amax() < 1e-12, "J J⁺ − I = {identity}");

    let mut singular = q0;
    singular[4] = 0.0;
    let damped = damped_inverse(&osc.jacobian(&singular), &DAMPING).expect("finite J");
    let (inverse, smallest) = (damped.inverse, damped.smallest);
    assert!(
        smallest < 1e-12,
        "σ_min(J) = {smallest} at the wrist singularity"
    );
    let norm = inverse.svd(false, false).singular_values.max();
    // σ / (σ² + λ²) ≤ 1 / (2λ) = 10 for every σ.
    assert!(norm <= 10.0 + 1e-9, "‖J⁺‖ = {norm}");
    let v = SVector::<f64, 6>::from([0.1, -0.2, 0.3, -0.1, 0.2, 0.5]);
    let tau = osc.torque(&circle.at(0.0), 0.0, &singular, &v);
    assert!(tau.iter().all(|x| x.is_finite()), "τ = {tau}");
}

/// log R against the axis and angle it was built from, at small angles
/// (where acos of the trace loses digits) and near π (where the axis comes
/// from the symmetric part).
#[test]
fn the_rotation_vector_inverts_the_exponential() {
    let axis = Unit::new_normalize(Vector3::new(0.3, -0.5, 0.8));
    for angle in [1e-9, 1e-4, 0.3, 2.0, 3.0, std::f64::consts::PI - 1e-7] {
        let r = Rotation3::from_axis_angle(&axis, angle).into_inner();
        let log = rotation_error(&r, &Rotation3::identity().into_inner());
        let error = (log - axis.into_inner() * angle).amax();
        assert!(error < 1e-15, "θ = {angle}: {log} ({error:e})");
    }
    let identity = Rotation3::identity().into_inner();
    assert_eq!(rotation_error(&identity, &identity), Vector3::zeros());
}

/// Started at rest exactly at the wrist singularity (σ_min(J) ≈ 1e-17) with
/// the goal 1.6 (m, rad) away, the damped inverse moves the wrist out of it
/// and the tool reaches the circle: the run ends without a non-finite input
/// and with the error below 1e-5 at 2 s.
#[test]
fn a_run_from_the_wrist_singularity_reaches_the_circle() {
    let ur5 = Ur5 {};
    let osc = OperationalSpace::new(&ur5, "tool0", OMEGA).expect("the UR5 has tool0");
    let circle = tool_circle();
    let mut q0 = start_off_the_circle(&osc, &circle).expect("inverse kinematics converges");
    q0[4] = 0.0;
    let v0 = SVector::<f64, 6>::zeros();
    assert!(osc.accelerations(&circle.at(0.0), &q0, &v0).1 < 1e-12);
    let run = Simulation::new(&ur5)
        .integrator(Dopri5::tol(1e-10))
        .feedback(osc.feedback(move |t| circle.at(t)))
        .run(q0, v0, 0.0..2.0)
        .expect("the run goes through the damped region");
    let (q, v) = run.trajectory().final_state();
    let (e, _) = osc.error(&circle.at(2.0), &q, &v);
    assert!(e.amax() < 1e-5, "tool error at 2 s {e}");
    assert!(osc.accelerations(&circle.at(2.0), &q, &v).1 > DAMPING.threshold);
}
