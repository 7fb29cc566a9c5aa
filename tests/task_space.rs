//! Task-space conveniences (`lagrange::task_space`, `Posed::frame_pose`)
//! against closed forms and independent computations: one frame's pose
//! against every frame's, inverse kinematics of a planar two-link arm
//! against its textbook solution, the UR5 and a seven-joint arm round trip
//! forward then inverse, and the typed failures.

use crate::catalog::constrained::ThreadedTops;
use crate::floating::Quadruped;
use crate::floating_bases::Solo12;
use crate::operational::Ur5;
use crate::urdf_arms::Xarm7;

use lagrange::nalgebra::{Matrix3, Rotation3, SVector, Vector2, Vector3};
use lagrange::pose::{BodyPose, Posed};
use lagrange::prelude::*;
use lagrange::task_space::{Damping, InverseKinematics, OperationalSpace, Solution, Target};
use lagrange::{Configuration, Kinematics};

/// A planar arm of two links in the xy plane turning about z: the upper arm
/// of length 1 from the origin, the forearm of length 0.8, the hand at its
/// end, with the forearm's frame.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a, b),
    body(upper, mass = 1, inertia = [0.01, 0.08, 0.08], at = [0, 0, 0], com = [0.5, 0, 0],
         rotation = rot_z(a)),
    body(fore, mass = 1, inertia = [0.01, 0.05, 0.05], com = [0.4, 0, 0],
         at = [cos(a), sin(a), 0], rotation = rot_z(a + b)),
    body(hand, mass = 0.1, inertia = [0.001, 0.001, 0.001],
         at = [cos(a) + 0.8 * cos(a + b), sin(a) + 0.8 * sin(a + b), 0], rotation = rot_z(a + b)),
    emit(kinematics),
)]
struct TwoLink {}

/// The textbook inverse kinematics of the two-link arm: the elbow angle from
/// the law of cosines, b = ±acos((x² + y² − l1² − l2²) / (2 l1 l2)), and
/// a = atan2(y, x) − atan2(l2 sin b, l1 + l2 cos b).
fn two_link_closed_form(x: f64, y: f64, elbow: f64) -> Vector2<f64> {
    let (l1, l2) = (1.0, 0.8);
    let b = elbow * ((x * x + y * y - l1 * l1 - l2 * l2) / (2.0 * l1 * l2)).acos();
    let a = y.atan2(x) - (l2 * b.sin()).atan2(l1 + l2 * b.cos());
    Vector2::new(a, b)
}

/// Every body's pose from `poses`, the reference.
fn all_poses<S: Posed<f64, N, Q>, const N: usize, const Q: usize>(
    sys: &S,
    q: &SVector<f64, Q>,
) -> Vec<BodyPose<f64>> {
    let mut bodies = vec![BodyPose::default(); S::BODIES.len()];
    let mut points = vec![Vector3::zeros(); S::POINTS.len()];
    sys.poses(q, 0.0, &mut bodies, &mut points);
    bodies
}

/// The largest difference between `frame_pose` and `poses` over the bodies,
/// and `None` past them.
fn frame_pose_off<S: Posed<f64, N, Q>, const N: usize, const Q: usize>(
    sys: &S,
    q: &SVector<f64, Q>,
) -> f64 {
    let all = all_poses(sys, q);
    assert_eq!(sys.frame_pose(all.len(), q, 0.0), None);
    let mut off = 0.0f64;
    for (b, want) in all.iter().enumerate() {
        let got = sys.frame_pose(b, q, 0.0).expect("a body");
        off = off
            .max((got.origin - want.origin).amax())
            .max((got.centre - want.centre).amax())
            .max((got.rotation - want.rotation).amax());
    }
    off
}

/// q with each orientation's quaternion scaled to unit norm.
fn on_the_sphere<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(
    _: &S,
    mut q: SVector<f64, Q>,
) -> SVector<f64, Q> {
    assert!(!S::ORIENTATIONS.is_empty());
    for o in S::ORIENTATIONS {
        let norm = q.fixed_rows::<4>(o.q).norm();
        q.fixed_rows_mut::<4>(o.q).unscale_mut(norm);
    }
    q
}

/// A pseudo-random number in [−1, 1) from a linear congruential state.
fn uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    2.0 * ((*state >> 11) as f64 / (1u64 << 53) as f64) - 1.0
}

fn random<const N: usize>(state: &mut u64, scale: f64) -> SVector<f64, N> {
    SVector::from_fn(|_, _| scale * uniform(state))
}

/// One frame's pose (emitted per body with `emit(kinematics)`, the default
/// otherwise) is `poses`'s entry to round-off: the UR5 and the xArm7 from
/// their URDF, Solo 12 from its URDF on a free base (a quaternion in q),
/// the two-link arm, a catalog quadruped on a free base (the default) and
/// the catalog's threaded tops (Euler angles, the default).
#[test]
fn one_frame_s_pose_is_the_one_poses_gives() {
    let mut state = 7;
    for _ in 0..5 {
        let q: SVector<f64, 6> = random(&mut state, 3.0);
        assert!(frame_pose_off(&Ur5 {}, &q) < 1e-15);
        let q: SVector<f64, 7> = random(&mut state, 3.0);
        assert!(frame_pose_off(&Xarm7 {}, &q) < 1e-15);
        let q: SVector<f64, 2> = random(&mut state, 3.0);
        assert!(frame_pose_off(&TwoLink {}, &q) < 1e-15);
        let q = on_the_sphere::<_, 18, 19>(&Quadruped { g: 9.81 }, random(&mut state, 1.0));
        assert!(frame_pose_off(&Quadruped { g: 9.81 }, &q) < 1e-15);
        let q = on_the_sphere::<_, 18, 19>(&Solo12 {}, random(&mut state, 1.0));
        assert!(frame_pose_off(&Solo12 {}, &q) < 1e-15);
        let q: SVector<f64, 6> = random(&mut state, 3.0);
        let tops = ThreadedTops {
            m: 1.0,
            a: 0.1,
            b: 0.2,
            c: 0.3,
            l: 0.5,
            d: 1.0,
            g: 9.81,
        };
        assert!(frame_pose_off(&tops, &q) < 1e-15);
    }
    // Checked: the configuration's pose is the trait's, None past the bodies.
    let q = SVector::<f64, 6>::from([0.3, -1.2, 1.5, -0.4, 0.8, 0.1]);
    let ur5 = Ur5 {};
    let at = Configuration::new(&ur5, q, 0.0).expect("a finite q");
    let tool = Ur5::body_index("tool0").expect("the UR5 has tool0");
    assert_eq!(at.frame_pose(tool), ur5.frame_pose(tool, &q, 0.0));
    assert_eq!(at.frame_pose(Ur5::BODIES.len()), None);
}

/// Inverse kinematics of the hand's position against the closed form, both
/// elbows: from a start with the elbow bent one way it converges to that
/// elbow's solution, to 1e-12, in a few Newton steps.
#[test]
fn the_two_link_arm_s_inverse_kinematics_is_the_textbook_one() {
    let arm = TwoLink {};
    let hand = TwoLink::body_index("hand").expect("a body");
    let ik = InverseKinematics::new().tolerance(1e-14);
    let (mut worst, mut most) = (0.0f64, 0);
    for (x, y) in [(1.2, 0.5), (-0.3, 1.1), (0.5, -0.9), (1.6, 0.2)] {
        let target = Target::Position(Vector3::new(x, y, 0.0));
        for elbow in [1.0, -1.0] {
            let want = two_link_closed_form(x, y, elbow);
            let start = want + Vector2::new(0.3, -0.25 * elbow);
            let got = ik.solve(&arm, hand, &target, &start).expect("converges");
            let off = (got.q - want).amax();
            assert!(
                off < 1e-12,
                "({x}, {y}) elbow {elbow}: {} against {want}, {off:e}",
                got.q
            );
            assert!(got.iterations <= 8, "{} iterations", got.iterations);
            (worst, most) = (worst.max(off), most.max(got.iterations));
        }
    }
    println!("two-link arm: off the closed form by {worst:e}, at most {most} iterations");
}

/// The UR5's tool put at poses forward kinematics gave from random joint
/// angles, from starts 0.3 rad away per joint: the pose reached agrees with
/// the target to 1e-10 (position and rotation).
#[test]
fn the_ur5_round_trips_forward_then_inverse() {
    let ur5 = Ur5 {};
    let tool = Ur5::body_index("tool0").expect("the UR5 has tool0");
    let ik = InverseKinematics::new();
    let mut state = 11;
    let (mut most, mut total, mut worst) = (0, 0, 0.0f64);
    for _ in 0..20 {
        let truth: SVector<f64, 6> = random(&mut state, 2.5);
        let pose = ur5.frame_pose(tool, &truth, 0.0).expect("a body");
        let target = Target::Pose {
            position: pose.origin,
            rotation: pose.rotation,
        };
        let start = truth + random::<6>(&mut state, 0.3);
        let got = ik.solve(&ur5, tool, &target, &start).expect("converges");
        let reached = ur5.frame_pose(tool, &got.q, 0.0).expect("a body");
        let off = (reached.origin - pose.origin)
            .amax()
            .max((reached.rotation - pose.rotation).amax());
        assert!(off < 1e-10, "pose off by {off:e} at {truth}");
        most = most.max(got.iterations);
        worst = worst.max(off);
        total += got.iterations;
    }
    println!("UR5: pose off by at most {worst:e}, {most} iterations at most, {total} in all");
    assert!(most <= 20, "{most} iterations");
}

/// The seven-joint xArm7 (redundant for a pose) reaches poses of its own,
/// and a position with only three rows of J.
#[test]
fn a_redundant_arm_converges() {
    let arm = Xarm7 {};
    let tool = Xarm7::BODIES.len() - 1;
    let ik = InverseKinematics::new().joint_limits(true);
    let (mut state, mut most) = (5, 0);
    for _ in 0..10 {
        // Inside the joint limits, which the solver keeps to.
        let mut truth: SVector<f64, 7> = random(&mut state, 1.5);
        for limit in arm.position_limits() {
            let x = &mut truth[limit.coordinate];
            *x = x.clamp(limit.lower + 0.3, limit.upper - 0.3);
        }
        let pose = arm.frame_pose(tool, &truth, 0.0).expect("a body");
        let start = truth + random::<7>(&mut state, 0.3);
        let target = Target::Pose {
            position: pose.origin,
            rotation: pose.rotation,
        };
        let got = ik.solve(&arm, tool, &target, &start).expect("converges");
        most = most.max(got.iterations);
        let reached = arm.frame_pose(tool, &got.q, 0.0).expect("a body");
        assert!((reached.origin - pose.origin).amax() < 1e-10);
        assert!((reached.rotation - pose.rotation).amax() < 1e-10);
        for limit in arm.position_limits() {
            let x = got.q[limit.coordinate];
            assert!(limit.lower <= x && x <= limit.upper, "{}", limit.joint);
        }
        let got = ik
            .solve(&arm, tool, &Target::Position(pose.origin), &start)
            .expect("converges");
        let reached = arm.frame_pose(tool, &got.q, 0.0).expect("a body");
        assert!((reached.origin - pose.origin).amax() < 1e-10);
    }
    println!("xArm7: at most {most} iterations for a pose");
    assert!(most <= 20, "{most} iterations");
}

/// The unreachable target.
fn target_point() -> Vector3<f64> {
    Vector3::new(1.2, 1.6, 0.0)
}

/// A target beyond the two-link arm's reach (1.8): the iteration limit is
/// reached with the typed error, and the best iterate is the arm
/// stretched toward the target, its hand 0.2 short of it (the closest
/// point).
#[test]
fn an_unreachable_target_fails_with_the_best_iterate() {
    let arm = TwoLink {};
    let hand = TwoLink::body_index("hand").expect("a body");
    let target = Target::Position(target_point()); // 2.0 away
    let failure = InverseKinematics::new()
        .max_iterations(200)
        .solve(&arm, hand, &target, &Vector2::new(0.3, 0.5))
        .expect_err("out of reach");
    let message = failure.to_string();
    assert!(
        message.contains("the closest configuration, reached in"),
        "{message}"
    );
    let Error::InverseKinematics {
        body,
        iterations,
        residual,
        tolerance,
    } = failure.error
    else {
        panic!("{}", failure.error);
    };
    assert_eq!((body, iterations, tolerance), ("hand", 200, 1e-12));
    let best: &Solution<2> = &failure.partial;
    assert_eq!(best.residual, residual);
    let reached = arm.frame_pose(hand, &best.q, 0.0).expect("a body").origin;
    // The closest point: 1.8 along the direction (0.6, 0.8), 0.2 short.
    let closest = Vector3::new(0.6, 0.8, 0.0) * 1.8;
    // The steps only ever decrease |e|, so they reach the stretched arm.
    assert!((reached - closest).amax() < 1e-6, "{reached}");
    assert!((residual - 0.2).abs() < 1e-12, "{residual}");
    assert_eq!(residual, (target_point() - reached).norm());
    println!("unreachable: best residual {residual} at {reached}");
}

/// Bad settings, a bad body and a target that is no rotation are typed
/// errors, before any step.
#[test]
fn bad_settings_are_typed_errors() {
    let arm = TwoLink {};
    let target = Target::Position(Vector3::new(1.2, 0.5, 0.0));
    let start = Vector2::new(0.3, 0.5);
    let settings = |ik: InverseKinematics| {
        let failure = ik.solve(&arm, 2, &target, &start).expect_err("refused");
        assert_eq!(failure.partial.iterations, 0);
        failure.error
    };
    for ik in [
        InverseKinematics::new().tolerance(0.0),
        InverseKinematics::new().tolerance(f64::NAN),
        InverseKinematics::new().damping(Damping {
            threshold: -1.0,
            damping: 0.05,
        }),
    ] {
        let error = settings(ik);
        assert!(
            matches!(error, Error::Settings(SettingsError::Value { .. })),
            "{error}"
        );
    }
    let error = settings(InverseKinematics::new().max_iterations(0));
    assert!(matches!(
        error,
        Error::Settings(SettingsError::ZeroCount { .. })
    ));
    let error = InverseKinematics::new()
        .solve(&arm, 3, &target, &start)
        .expect_err("no body 3")
        .error;
    assert!(
        matches!(error, Error::UnknownBody { count: 3, .. }),
        "{error}"
    );
    let skewed = Target::Pose {
        position: Vector3::zeros(),
        rotation: Matrix3::identity() * 1.1,
    };
    let error = InverseKinematics::new()
        .solve(&arm, 2, &skewed, &start)
        .expect_err("no rotation")
        .error;
    assert!(
        matches!(error, Error::Settings(SettingsError::Value { .. })),
        "{error}"
    );
    let error = InverseKinematics::new()
        .solve(&arm, 2, &target, &Vector2::new(f64::NAN, 0.0))
        .expect_err("no start")
        .error;
    assert!(matches!(error, Error::NonFiniteState { .. }), "{error}");
    let error = OperationalSpace::new(&arm, "wrist", 10.0).expect_err("no wrist");
    assert!(matches!(error, Error::UnknownBody { .. }), "{error}");
    let error = OperationalSpace::new(&arm, "hand", -1.0).expect_err("ω < 0");
    assert!(
        matches!(error, Error::Settings(SettingsError::Value { .. })),
        "{error}"
    );
}

/// The posture of a redundant arm acts in J's null space: the frame's
/// commanded acceleration J q̈* is the same with and without it, while q̈*
/// differs.
#[test]
fn a_posture_leaves_the_task_alone() {
    let arm = Xarm7 {};
    let tool = Xarm7::BODIES[Xarm7::BODIES.len() - 1];
    let q = SVector::<f64, 7>::from([0.1, -0.4, 0.2, 0.9, -0.3, 1.1, 0.2]);
    let v = SVector::<f64, 7>::from([0.2, -0.1, 0.3, 0.1, -0.2, 0.4, 0.1]);
    let plain = OperationalSpace::new(&arm, tool, 10.0).expect("a body");
    let (p, r) = plain.pose(&q);
    let goal = lagrange::task_space::Goal::at_rest(
        p + Vector3::new(0.05, 0.0, -0.02),
        Rotation3::from_axis_angle(&Vector3::x_axis(), 0.1).into_inner() * r,
    );
    let held = plain.posture(SVector::zeros(), 3.0).expect("a posture");
    let (a, smallest) = plain.accelerations(&goal, &q, &v);
    let (b, _) = held.accelerations(&goal, &q, &v);
    assert!(smallest > 0.01, "σ_min = {smallest}");
    let j = plain.jacobian(&q);
    let task = (j * (a - b)).amax();
    assert!(task < 1e-10, "J (q̈ − q̈₀) = {task:e}");
    assert!((a - b).amax() > 1e-2, "the posture changed nothing");
}

/// The xArm7 with a torque input at each joint, for a run under
/// operational-space control.
#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/xarm7.urdf", dynamics = ignore),
    inputs(u1, u2, u3, u4, u5, u6, u7),
    generalized_force(
        joint1 = u1, joint2 = u2, joint3 = u3, joint4 = u4, joint5 = u5, joint6 = u6, joint7 = u7
    ),
    gravity = [0, 0, -9.81],
    emit(inverse_dynamics, kinematics),
)]
struct DrivenXarm7 {}

/// Seven joints driving a six-dimensional task with a null-space posture:
/// the minimum-norm inverse makes J q̈* the commanded task acceleration and
/// the posture stays out of it, so from rest 4 cm and 0.2 rad off a set
/// point the tool's error is the critically damped closed form, in a run
/// fed by the controller's `feedback`.
#[test]
fn a_redundant_arm_s_tool_error_follows_the_closed_form() {
    let arm = DrivenXarm7 {};
    let q0 = SVector::<f64, 7>::from([0.1, -0.4, 0.2, 0.9, -0.3, 1.1, 0.2]);
    let osc = OperationalSpace::new(&arm, "link_eef", 10.0)
        .and_then(|osc| osc.posture(q0, 2.0))
        .expect("a body, good settings");
    let (p, r) = osc.pose(&q0);
    let turn = Rotation3::from_axis_angle(&Vector3::y_axis(), 0.2).into_inner();
    let goal = lagrange::task_space::Goal::at_rest(p + Vector3::new(0.04, 0.0, -0.02), turn * r);
    let v0 = SVector::<f64, 7>::zeros();
    let (e0, de0) = osc.error(&goal, &q0, &v0);
    let run = Simulation::new(&arm)
        .integrator(Dopri5::tol(1e-11))
        .feedback(osc.feedback(move |_| goal))
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
        let (e, _) = osc.error(&goal, q, v);
        off = off.max((e - lagrange::task_space::critically_damped(&e0, &de0, 10.0, *t)).amax());
        smallest = smallest.min(osc.accelerations(&goal, q, v).1);
    }
    println!(
        "xArm7 under operational-space control: off the closed form by {off:e}, σ_min(J) ≥ {smallest}"
    );
    assert!(
        smallest > 0.01,
        "σ_min(J) = {smallest}: the inverse was damped"
    );
    assert!(off < 1e-8, "task error off the closed form by {off:e}");
}
