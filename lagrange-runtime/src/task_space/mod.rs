//! Task space: a robot's frames as the work asks for them, over any number
//! of joints N. Damped least-squares inverse kinematics
//! ([`InverseKinematics`]) puts a frame at a target pose or position;
//! operational-space control ([`OperationalSpace`]) drives it along a
//! moving [`Goal`] by computed torque in task space, as a state feedback a
//! [`Simulation`](crate::Simulation) runs; both go through J's damped
//! inverse ([`damped_inverse`]), exact away from singularities and bounded
//! at them.
//!
//! Everything is in `f64`, on the robot's emitted kinematics
//! ([`Kinematics`](crate::Kinematics), `emit(kinematics)`): a frame is a
//! body's ([`Posed::frame_pose`](crate::Posed::frame_pose) and
//! [`Kinematics::frame_jacobian`](crate::Kinematics::frame_jacobian),
//! world-aligned). A task error is (p_d − p, log(R_d Rᵀ)): the position
//! error and the rotation vector, in world axes, that turns the frame onto
//! its goal ([`rotation_error`]).

mod damped;
mod ik;
mod operational;

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3, Vector6};

pub use damped::{DampedInverse, Damping, damped_inverse};
pub use ik::{InverseKinematics, Solution, Target};
pub use operational::{Goal, OperationalSpace, critically_damped};

/// The rotation vector θ n (axis × angle, θ in [0, π]) of the rotation
/// matrix `goal · currentᵀ`: the turn, in world axes, that takes a frame at
/// `current` onto `goal` (log(R_d Rᵀ)). By way of the unit quaternion
/// (nalgebra's `UnitQuaternion`), accurate at small angles and near π.
pub fn rotation_error(goal: &Matrix3<f64>, current: &Matrix3<f64>) -> Vector3<f64> {
    let turn = Rotation3::from_matrix_unchecked(goal * current.transpose());
    UnitQuaternion::from_rotation_matrix(&turn).scaled_axis()
}

/// (a, b) as one 6-vector.
fn stack(a: Vector3<f64>, b: Vector3<f64>) -> Vector6<f64> {
    Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Unit;

    /// log R against the axis and angle it was built from, at small angles
    /// (where acos of the trace loses digits) and near π.
    #[test]
    fn the_rotation_error_inverts_the_exponential() {
        let axis = Unit::new_normalize(Vector3::new(0.3, -0.5, 0.8));
        let base = Rotation3::from_euler_angles(0.2, -0.4, 1.1).into_inner();
        for angle in [1e-9, 1e-4, 0.3, 2.0, 3.0, std::f64::consts::PI - 1e-7] {
            let r = Rotation3::from_axis_angle(&axis, angle).into_inner() * base;
            let log = rotation_error(&r, &base);
            let error = (log - axis.into_inner() * angle).amax();
            assert!(
                error < 1e-14 * angle.max(0.1),
                "θ = {angle}: {log} ({error:e})"
            );
        }
        assert!(rotation_error(&base, &base).amax() < 1e-15);
    }
}
