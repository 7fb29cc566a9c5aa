//! Four more arms straight from their URDF files (`robots/`, from the PyPI
//! package `example-robot-data` 6.0.0, like the UR5 and the Panda of
//! `tests/urdf.rs`): the UR10, the Kinova Jaco j2s6s200 (three continuous
//! joints), the Unitree Z1 (six joints and the gripper's) and the UFactory
//! xArm7. Every entry of M, Q − h, τ (at q̈_k = 0.1 + 0.05 k), the gravity
//! torques, the tool frame's Jacobians and J̇ q̇, the centre of mass and its
//! Jacobian against Pinocchio's `crba`, `nonLinearEffects`, `rnea`,
//! `computeGeneralizedGravity`, `computeFrameJacobian`,
//! `getFrameClassicalAcceleration`, `centerOfMass` and `jacobianCenterOfMass`
//! on the same files, to 1e-12 (`tests/data/urdf_arms_pinocchio.txt`, written
//! by `lagrange-bench/peer/pinocchio/urdf_reference.py`).

use lagrange::prelude::*;
use lagrange::{Kinematics, Route};
use nalgebra::SVector;

// The files' numbers as written (`snap = 0`), as Pinocchio reads them for
// the references below.
#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/ur10.urdf", snap = 0),
    gravity = [0, 0, -9.81],
    emit(inverse_dynamics, kinematics)
)]
struct Ur10 {}

#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/kinova.urdf", snap = 0),
    gravity = [0, 0, -9.81],
    emit(inverse_dynamics, kinematics)
)]
struct Kinova {}

#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/z1.urdf", dynamics = ignore),
    gravity = [0, 0, -9.81],
    emit(inverse_dynamics, kinematics)
)]
struct Z1 {}

#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/xarm7.urdf", dynamics = ignore),
    gravity = [0, 0, -9.81],
    emit(inverse_dynamics, kinematics)
)]
pub(crate) struct Xarm7 {}

const REFERENCE: &str = include_str!("data/urdf_arms_pinocchio.txt");

/// The numbers on the line `robot key ...` of the reference file.
fn reference(robot: &str, key: &str) -> Vec<f64> {
    let line = REFERENCE
        .lines()
        .find(|l| l.split(' ').take(2).eq([robot, key]))
        .unwrap_or_else(|| panic!("no `{robot} {key}` in the reference"));
    line.split(' ')
        .skip(2)
        .map(|x| x.parse().expect("a number"))
        .collect()
}

/// `ours` (row by row) against the reference's `key`, entry by entry, to
/// 1e-12 relative to the larger of 1 and Pinocchio's value.
fn agrees(robot: &str, key: &str, ours: impl IntoIterator<Item = f64>) {
    let theirs = reference(robot, key);
    let ours: Vec<f64> = ours.into_iter().collect();
    assert_eq!(ours.len(), theirs.len(), "{robot} {key}: sizes");
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs().max(1.0),
            "{robot} {key}[{k}]: {a} vs {b}"
        );
    }
}

/// A matrix's entries row by row (nalgebra stores columns).
fn by_rows<const R: usize, const C: usize>(m: &nalgebra::SMatrix<f64, R, C>) -> Vec<f64> {
    m.transpose().iter().copied().collect()
}

/// The reference script's state: q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k.
fn state<const N: usize>() -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_fn(|k, _| 0.3 - 0.17 * k as f64),
        SVector::from_fn(|k, _| 0.5 - 0.21 * k as f64),
    )
}

/// M, Q − h, τ and the gravity torques against Pinocchio, and τ at the
/// accelerations the dynamics give is zero.
fn dynamics_agree<S: Lagrangian<f64, N>, const N: usize>(robot: &str, sys: &S) {
    let (q, v) = state::<N>();
    let (m, rhs) = sys.mass_matrix_and_rhs(&q, &v, 0.0);
    agrees(robot, "M", by_rows(&m));
    agrees(robot, "rhs", rhs.iter().copied());
    let a = SVector::<f64, N>::from_fn(|k, _| 0.1 + 0.05 * k as f64);
    agrees(
        robot,
        "tau",
        sys.inverse_dynamics(&q, &v, &a, 0.0).iter().copied(),
    );
    let g = sys.gravity_torques(&q, 0.0).expect("emitted");
    agrees(robot, "gravity", g.iter().copied());
    let qdd = lagrange::accelerations(sys, &q, &v, 0.0).unwrap();
    let rest = sys.inverse_dynamics(&q, &v, &qdd, 0.0);
    assert!(
        rest.amax() < 1e-10,
        "{robot}: τ at the free accelerations {rest}"
    );
}

/// The tool frame's Jacobian (LOCAL_WORLD_ALIGNED and LOCAL), J̇ q̇, the centre
/// of mass and its Jacobian against Pinocchio.
fn kinematics_agree<S: Kinematics<f64, N>, const N: usize>(robot: &str, sys: &S, frame: &str) {
    let (q, v) = state::<N>();
    let body = S::body_index(frame).expect("the tool frame is a body");
    agrees(
        robot,
        "J",
        by_rows(&sys.frame_jacobian(body, &q, 0.0).unwrap()),
    );
    let local = sys.frame_jacobian_local(body, &q, 0.0).unwrap();
    agrees(robot, "J_local", by_rows(&local));
    agrees(
        robot,
        "bias",
        sys.frame_bias(body, &q, &v, 0.0).unwrap().iter().copied(),
    );
    agrees(robot, "com", sys.center_of_mass(&q, 0.0).iter().copied());
    agrees(
        robot,
        "Jcom",
        by_rows(&sys.center_of_mass_jacobian(&q, 0.0)),
    );
}

#[test]
fn ur10_from_its_urdf_matches_pinocchio() {
    dynamics_agree("ur10", &Ur10 {});
    kinematics_agree("ur10", &Ur10 {}, "tool0");
    assert_eq!(Ur10::ROBOT, "ur10");
}

#[test]
fn kinova_from_its_urdf_matches_pinocchio() {
    dynamics_agree("kinova", &Kinova {});
    kinematics_agree("kinova", &Kinova {}, "j2s6s200_end_effector");
    // Joints 1, 4 and 6 are continuous: one angle each here (Pinocchio's q
    // holds their cosine and sine), and no limits.
    let free = (f64::NEG_INFINITY, f64::INFINITY);
    assert_eq!(Kinova::JOINT_LIMITS[0], free);
    assert_eq!(Kinova::JOINT_LIMITS[3], free);
    assert_eq!(Kinova::JOINT_LIMITS[5], free);
    assert!(Kinova::JOINT_LIMITS[1].0.is_finite());
}

#[test]
fn z1_from_its_urdf_matches_pinocchio() {
    dynamics_agree("z1", &Z1 {});
    kinematics_agree("z1", &Z1 {}, "gripperStator");
    assert_eq!(<Z1 as Lagrangian<f64, 7>>::COORDINATES[6], "jointGripper");
}

#[test]
fn xarm7_from_its_urdf_matches_pinocchio() {
    dynamics_agree("xarm7", &Xarm7 {});
    kinematics_agree("xarm7", &Xarm7 {}, "link_eef");
    assert_eq!(<Xarm7 as Lagrangian<f64, 7>>::ROUTE, Route::Recursive);
}
