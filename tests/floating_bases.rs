//! Floating-base trees on the recursive route (a free root: three sliding
//! joints and a spherical one) against Pinocchio's free flyer
//! (`lagrange-bench/peer/pinocchio/floating.py`, which wrote
//! `tests/data/floating_pinocchio.txt`): the quadruped and the satellite of
//! `examples/catalog/floating.rs`, at a generic state and at one with the
//! root pitched by exactly π/2. Each state is given in Pinocchio's convention
//! (q = (x, y, z, qx, qy, qz, qw, joints), v with the root's linear velocity
//! in its own axes) and mapped here to this crate's (quaternion scalar first
//! after the joints, ẋ in world axes); M, Q − h, q̈ (articulated-body), τ by
//! recursive Newton–Euler and the gravity torques agree to 1e-12, and the
//! tangent-space A (from `emit(jacobians)`: the derivatives of recursive
//! Newton–Euler) agrees with `computeABADerivatives`, mapped to this
//! convention by the chain rule, to 1e-10.

use crate::floating;

use floating::{ArmedSatellite, Quadruped};
use lagrange::prelude::*;
use lagrange::{Kinematics, Route};
use nalgebra::{Quaternion, SVector, UnitQuaternion, Vector3};

const REFERENCE: &str = include_str!("data/floating_pinocchio.txt");

/// The numbers of `key` for `model`'s state `k`.
fn reference(model: &str, k: usize, key: &str) -> Vec<f64> {
    let head = format!("{model} {k} {key} ");
    let line = REFERENCE
        .lines()
        .find(|l| l.starts_with(&head))
        .unwrap_or_else(|| panic!("no {head:?} in the reference file"));
    line[head.len()..]
        .split(' ')
        .map(|x| x.parse().expect("a number"))
        .collect()
}

/// Pinocchio's (q, v) of a free-flyer root with `J` joints after it, in
/// this crate's convention: v_lin (root axes) → ẋ = R v_lin (world axes);
/// this crate's joint k is Pinocchio's `perm[k]`.
fn from_pinocchio<const N: usize, const Q: usize>(
    q_pin: &[f64],
    v_pin: &[f64],
    perm: &[f64],
) -> (SVector<f64, Q>, SVector<f64, N>) {
    let joints = N - 6;
    let (x, y, z, w) = (q_pin[3], q_pin[4], q_pin[5], q_pin[6]);
    let r = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
    let world = r * Vector3::new(v_pin[0], v_pin[1], v_pin[2]);
    let mut q = SVector::<f64, Q>::zeros();
    let mut v = SVector::<f64, N>::zeros();
    for i in 0..3 {
        q[i] = q_pin[i];
        v[i] = world[i];
        v[3 + joints + i] = v_pin[3 + i];
    }
    for (j, &p) in perm.iter().enumerate().take(joints) {
        q[3 + j] = q_pin[7 + p as usize];
        v[3 + j] = v_pin[6 + p as usize];
    }
    q.fixed_rows_mut::<4>(3 + joints)
        .copy_from_slice(&[w, x, y, z]);
    (q, v)
}

fn assert_close(what: &str, got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{what}");
    for (i, (&g, &w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= 1e-12 * w.abs().max(1.0),
            "{what}[{i}]: {g} against Pinocchio's {w} (difference {:e})",
            g - w
        );
    }
}

fn agrees_with_pinocchio<S, const N: usize, const Q: usize>(name: &str, sys: &S)
where
    S: Lagrangian<f64, N, Q>,
{
    assert_eq!(
        S::ROUTE,
        Route::Recursive,
        "{name} left the recursive route"
    );
    for k in 0..2 {
        let at = |key: &str| reference(name, k, key);
        let (q, v) = from_pinocchio::<N, Q>(&at("q_pin"), &at("v_pin"), &at("perm"));
        assert_close(&format!("{name} {k} q"), q.as_slice(), &at("q"));
        assert_close(&format!("{name} {k} v"), v.as_slice(), &at("v"));
        let (m, rhs) = sys.mass_matrix_and_rhs(&q, &v, 0.0);
        let m_rows: Vec<f64> = m.transpose().iter().copied().collect();
        assert_close(&format!("{name} {k} M"), &m_rows, &at("M"));
        assert_close(&format!("{name} {k} Q - h"), rhs.as_slice(), &at("rhs"));
        let accel = lagrange::accelerations(sys, &q, &v, 0.0).expect("a positive definite M");
        assert_close(&format!("{name} {k} q''"), accel.as_slice(), &at("accel"));
        let a = SVector::<f64, N>::from_column_slice(&at("a"));
        let tau = sys.inverse_dynamics(&q, &v, &a, 0.0);
        assert_close(&format!("{name} {k} tau"), tau.as_slice(), &at("tau"));
        let gravity = sys.gravity_torques(&q, 0.0).expect("emitted");
        assert_close(
            &format!("{name} {k} gravity"),
            gravity.as_slice(),
            &at("gravity"),
        );
        let derivatives = (&at("dadq")[..], &at("dadv")[..]);
        tangent_agrees(&format!("{name} {k}"), sys, (&q, &v), derivatives);
    }
}

/// The lower half of the tangent linearisation's A, [∂v̇/∂δ, ∂v̇/∂v], against
/// Pinocchio's (row-major N × N each), to 1e-10.
fn tangent_agrees<S, const N: usize, const Q: usize>(
    what: &str,
    sys: &S,
    (q, v): (&SVector<f64, Q>, &SVector<f64, N>),
    (dq, dv): (&[f64], &[f64]),
) where
    S: Lagrangian<f64, N, Q>,
{
    // From the emitted derivatives of recursive Newton–Euler, not differences.
    let accel = lagrange::accelerations(sys, q, v, 0.0).expect("a positive definite M");
    assert!(sys.rhs_jacobians(q, v, &accel, 0.0).is_some(), "{what}");
    let lin = Linearizer::new()
        .tangent(sys, q, v, 0.0)
        .expect("linearises");
    let a = lin.a();
    for i in 0..N {
        for j in 0..N {
            for (block, want, col) in [("∂v̇/∂δ", dq, j), ("∂v̇/∂v", dv, N + j)] {
                let (g, w) = (a[(N + i, col)], want[i * N + j]);
                assert!(
                    (g - w).abs() <= 1e-10 * w.abs().max(1.0),
                    "{what} {block}[{i}][{j}]: {g} against Pinocchio's {w}"
                );
            }
        }
    }
}

#[test]
fn a_quadruped_matches_pinocchio_s_free_flyer() {
    agrees_with_pinocchio::<_, 18, 19>("quadruped", &Quadruped { g: 9.81 });
}

/// Solo 12 from its URDF (`robots/solo12.urdf`, example-robot-data) made
/// floating-base by `base = floating`, against Pinocchio's
/// `buildModelFromUrdf(.., JointModelFreeFlyer())` on the same file.
#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/solo12.urdf", base = floating),
    gravity = [0, 0, -9.81],
    emit(articulated, inverse_dynamics, jacobians, kinematics)
)]
pub(crate) struct Solo12 {}

#[test]
fn solo_12_from_its_urdf_on_a_free_root_matches_pinocchio() {
    assert_eq!(
        &<Solo12 as Lagrangian<f64, 18, 19>>::COORDINATES[..4],
        &["base_link_x", "base_link_y", "base_link_z", "FL_HAA"]
    );
    agrees_with_pinocchio::<_, 18, 19>("solo12", &Solo12 {});
    // The front-left foot's frame: its Jacobian in world-aligned axes (the
    // columns this crate's velocities) and J̇ q̇, against Pinocchio's
    // getFrameJacobian and getFrameClassicalAcceleration (LOCAL_WORLD_ALIGNED).
    let foot = <Solo12 as Kinematics<f64, 18, 19>>::body_index("FL_FOOT").expect("a link");
    for k in 0..2 {
        let at = |key: &str| reference("solo12", k, key);
        let (q, v) = from_pinocchio::<18, 19>(&at("q_pin"), &at("v_pin"), &at("perm"));
        let j = Solo12 {}.frame_jacobian(foot, &q, 0.0).expect("a body");
        let rows: Vec<f64> = j.transpose().iter().copied().collect();
        assert_close(&format!("foot {k} J"), &rows, &at("foot_J"));
        let bias = Solo12 {}.frame_bias(foot, &q, &v, 0.0).expect("a body");
        assert_close(&format!("foot {k} J'v"), bias.as_slice(), &at("foot_bias"));
    }
}

#[test]
fn a_satellite_with_an_arm_matches_pinocchio_s_free_flyer() {
    agrees_with_pinocchio::<_, 12, 13>("satellite", &ArmedSatellite { g: 9.81 });
}
