//! Planning on derived systems: equilibria and steady motions
//! (`linear::Trim`) against closed forms — an arm holding a pose against
//! gravity, a satellite kept spinning about a non-principal axis (an
//! orientation, in its tangent space), the trimmed point linearised and
//! stabilised — a plan (`plan::Ddp`) moving the UR5's tool to a target
//! within its torque limits through its emitted kinematics, and MPC
//! swinging up a cart-pole heavier than its model.

use crate::catalog;
use crate::operational::Ur5;

use catalog::control::{CartPole, TwoLinkArm};
use catalog::free::Satellite;
use lagrange::linear::{OperatingPoint, StepMethod, Transition, Trim, linearize};
use lagrange::nalgebra::{DMatrix, DVector, SVector, Vector1, Vector2, Vector3};
use lagrange::plan::{Ddp, FramePosition, Mpc, OptimalControl};
use lagrange::pose::Kinematics;
use lagrange::prelude::*;
use std::f64::consts::PI;

/// The torques that hold the arm still at (q1, q2) are its gravity torques:
/// τ1 = g (m1 l1 cos q1 + m2 (l1 cos q1 + l2 cos(q1 + q2))),
/// τ2 = g m2 l2 cos(q1 + q2).
#[test]
fn an_arm_holds_a_pose_against_gravity() {
    let arm = TwoLinkArm::standard();
    let (q1, q2) = (0.3, 0.8);
    let at = OperatingPoint::new(Vector2::new(q1, q2), Vector2::zeros());
    let held = Trim::new().hold(&["q1", "q2"]).solve(&arm, &at).unwrap();
    let TwoLinkArm { m1, m2, l1, l2, g } = arm;
    let tau2 = g * m2 * l2 * (q1 + q2).cos();
    let tau1 = g * (m1 * l1 * q1.cos() + m2 * l1 * q1.cos()) + tau2;
    assert!(
        (held.u - Vector2::new(tau1, tau2)).amax() < 1e-12,
        "u = {}",
        held.u
    );
    assert!(held.residual < 1e-12);
}

/// Euler's equations I ω̇ + ω × I ω = τ: a steady spin ω needs τ = ω × I ω,
/// whatever the attitude (held here at a tilted one).
#[test]
fn a_satellite_kept_spinning_off_its_principal_axes() {
    let sat = Satellite {
        m: 10.0,
        a: 1.0,
        b: 2.0,
        c: 2.5,
    };
    let half: f64 = 0.4;
    let attitude = SVector::<f64, 4>::new(half.cos(), half.sin() * 0.6, 0.0, half.sin() * 0.8);
    let omega = Vector3::new(0.7, -0.4, 1.1);
    let at = OperatingPoint::on_group(attitude, omega);
    let found = Trim::new().hold(&["attitude"]).solve(&sat, &at).unwrap();
    let inertia_omega = Vector3::new(sat.a * omega.x, sat.b * omega.y, sat.c * omega.z);
    let expected = omega.cross(&inertia_omega);
    assert!(
        (found.u - expected).amax() < 1e-12,
        "u = {} vs {expected}",
        found.u
    );
    assert_eq!(found.q, attitude);
}

/// The arm trimmed at a pose, then linearised there with the inputs found
/// and stabilised by LQR: the closed loop's eigenvalues are in the left
/// half-plane (unheld, the arm falls from that pose).
#[test]
fn a_trimmed_pose_is_an_operating_point() {
    let arm = TwoLinkArm::standard();
    let at = OperatingPoint::new(Vector2::new(-0.5, 1.4), Vector2::zeros());
    let held = Trim::new().hold(&["q1", "q2"]).solve(&arm, &at).unwrap();
    let lin = linearize(&arm, &held.operating_point()).unwrap();
    let q = DMatrix::identity(4, 4);
    let r = DMatrix::identity(2, 2);
    let design = lin.lqr(&q, &r).unwrap();
    assert!(design.closed_loop.iter().all(|z| z.re < 0.0));
    let a = lagrange::accelerations(&arm, &held.q, &held.v, 0.0).unwrap();
    let gravity_alone = a.amax();
    assert!(
        gravity_alone > 1.0,
        "unheld, the arm falls: |q̈| = {gravity_alone}"
    );
}

/// The UR5's tool drawn to a point 20 cm away in 0.6 s, its torques held
/// within ±40 N·m (the file allows 150): the plan ends within a millimetre
/// of the target, at rest, inside the bounds and within the joint limits
/// of position and speed.
#[test]
fn the_ur5_reaches_a_point_within_its_torque_limits() {
    let ur5 = Ur5 {};
    let tool = Ur5::body_index("tool0").expect("the UR5 has tool0");
    let home = SVector::<f64, 6>::from([0.0, -1.2, 1.5, -1.8, -1.57, 0.0]);
    let zero = SVector::<f64, 6>::zeros();
    let start = lagrange::Configuration::new(&ur5, home, 0.0).unwrap();
    let (bodies, _) = start.poses();
    let target = bodies[tool].origin + Vector3::new(0.1, 0.15, -0.05);
    // Gravity compensation at home is the input target, so that holding
    // still costs nothing.
    let hold = Trim::new()
        .hold(&Ur5::COORDINATES)
        .solve(&ur5, &OperatingPoint::new(home, zero))
        .unwrap();
    let weight = |d: [f64; 12]| DMatrix::from_diagonal(&DVector::from_column_slice(&d));
    let still = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
    // Speed costs a little all the way: without it the tool's target leaves
    // the last wrist free, and the plan spins it through its ±2π limits.
    let problem = OptimalControl::new(
        Transition::new(&ur5, 0.02).unwrap(),
        30,
        (home, zero),
        weight(still) * 0.1,
        DMatrix::identity(6, 6) * 1e-4,
    )
    .input_target(hold.u)
    .final_weight(weight(still) * 1000.0)
    .final_cost(FramePosition::new(&ur5, tool, target, 1e5))
    .input_bounds(SVector::repeat(-40.0), SVector::repeat(40.0));
    let plan = Ddp::new()
        .tolerance(1e-4)
        .solve(&problem, &[hold.u; 30])
        .unwrap();
    let end = lagrange::Configuration::new(&ur5, plan.q[30], 0.0).unwrap();
    let (bodies, _) = end.poses();
    let miss = (bodies[tool].origin - target).norm();
    assert!(miss < 1e-3, "the tool ends {miss:e} m from the target");
    assert!(
        plan.v[30].amax() < 0.05,
        "moving at the end: {}",
        plan.v[30]
    );
    assert!(plan.u.iter().all(|u| u.amax() <= 40.0));
    // Within the file's joint limits all the way (a plan may not leave
    // what a run would stop at).
    let inside = |q: &SVector<f64, 6>| {
        (q.iter().zip(Ur5::JOINT_LIMITS)).all(|(x, (lower, upper))| (lower..=upper).contains(x))
    };
    assert!(
        plan.q.iter().all(inside),
        "the plan leaves the joint limits"
    );
    // And below the file's speed limits, 3.15 rad/s.
    let fastest = plan.v.iter().map(|v| v.amax()).fold(0.0, f64::max);
    assert!(fastest < 3.15, "a joint turns at {fastest} rad/s");
}

/// The UR5 with a torque input at each joint and its Jacobians emitted.
#[derive(Lagrangian)]
#[lagrange(
    urdf = "robots/ur5.urdf",
    inputs(u1, u2, u3, u4, u5, u6),
    generalized_force(
        shoulder_pan_joint = u1,
        shoulder_lift_joint = u2,
        elbow_joint = u3,
        wrist_1_joint = u4,
        wrist_2_joint = u5,
        wrist_3_joint = u6
    ),
    gravity = [0, 0, -9.81],
    emit(jacobians)
)]
struct Ur5Differentiable {}

/// A step's derivatives from the UR5's emitted Jacobians, each stage's q̈ and
/// its derivatives in one evaluation on the stack: the numbers the stages'
/// linearisations give (to 1e-12 relative) and central differences of the
/// step (to 1e-6 relative), by RK4 and semi-implicit Euler.
#[test]
fn a_step_s_derivatives_from_the_ur5_s_emitted_jacobians() {
    let ur5 = Ur5Differentiable {};
    let q = SVector::<f64, 6>::from([0.3, -1.1, 1.4, -1.9, -1.5, 0.4]);
    let v = SVector::<f64, 6>::from([0.5, -0.3, 0.8, 1.1, -0.6, 0.9]);
    let u = SVector::<f64, 6>::from([2.0, -30.0, -10.0, 1.0, 0.5, -0.2]);
    for method in [StepMethod::Rk4, StepMethod::SemiImplicitEuler] {
        let fast = Transition::new(&ur5, 0.02).unwrap().method(method);
        let slow = fast.clone().through_linearizer(true);
        let d = fast.derivatives(&q, &v, &u, 0.0).unwrap();
        let e = slow.derivatives(&q, &v, &u, 0.0).unwrap();
        let scale = d.dx.amax().max(d.du.amax());
        let off = (&d.dx - &e.dx).amax().max((&d.du - &e.du).amax()) / scale;
        assert!(off < 1e-12, "{method:?}: {off:e} from the linearizer's");
        let step = |q: SVector<f64, 6>, v: SVector<f64, 6>, u: SVector<f64, 6>| {
            let (q1, v1) = fast.step(&q, &v, &u, 0.0).unwrap();
            DVector::from_iterator(12, q1.iter().chain(v1.iter()).copied())
        };
        let eps = 1e-6;
        let mut worst = 0.0_f64;
        for j in 0..18 {
            let (mut qp, mut vp, mut up) = (q, v, u);
            let (mut qm, mut vm, mut um) = (q, v, u);
            match j {
                0..6 => (qp[j] += eps, qm[j] -= eps),
                6..12 => (vp[j - 6] += eps, vm[j - 6] -= eps),
                _ => (up[j - 12] += eps, um[j - 12] -= eps),
            };
            let column = (step(qp, vp, up) - step(qm, vm, um)) / (2.0 * eps);
            let exact = match j {
                0..12 => d.dx.column(j).into_owned(),
                _ => d.du.column(j - 12).into_owned(),
            };
            worst = worst.max((column - exact).amax() / scale);
        }
        assert!(
            worst < 1e-6,
            "{method:?}: {worst:e} from central differences"
        );
    }
}

/// MPC designed on the catalog's cart-pole flies one whose pole is 50 %
/// heavier: re-planned at 20 Hz over 2.5 s with at most ten iterations a
/// sample, each warm-started from the last plan's states and inputs
/// shifted, it swings the pole up from hanging and holds it.
#[test]
fn mpc_swings_up_a_cart_pole_heavier_than_its_model() {
    let model = CartPole::standard();
    let real = CartPole {
        m_p: 1.5 * model.m_p,
        ..model
    };
    let weight = |d: [f64; 4]| DMatrix::from_diagonal(&DVector::from_column_slice(&d));
    let problem = OptimalControl::new(
        Transition::new(&model, 0.05).unwrap(),
        50,
        (Vector2::new(0.0, PI), Vector2::zeros()),
        weight([1.0, 0.0, 0.1, 0.1]),
        DMatrix::from_element(1, 1, 0.01),
    )
    .goal(Vector2::zeros(), Vector2::zeros())
    .final_weight(weight([100.0, 1000.0, 10.0, 100.0]))
    .input_bounds(Vector1::new(-5.0), Vector1::new(5.0));
    let mut mpc = Mpc::new(problem, Ddp::new().max_iterations(10));
    let run = Simulation::new(&real)
        .sampled(0.05, |t, q, v| mpc.control(t, q, v))
        .run([0.0, PI], [0.0; 2], 0.0..8.0)
        .unwrap();
    let (q, v) = run.trajectory().final_state();
    assert!(
        q[1].abs() < 1e-2 && v[1].abs() < 1e-2,
        "θ = {}, θ̇ = {}",
        q[1],
        v[1]
    );
    assert_eq!(mpc.samples().len(), 161);
    assert!(mpc.samples().iter().all(|s| s.iterations <= 10));
}
