//! A robot arm under operational-space control: the UR5 read from its URDF
//! file and a goal for its tool frame (position and orientation, with their
//! rates) moving on a circle, for the library's controller
//! ([`OperationalSpace`], in `lagrange::task_space`):
//!
//! ```text
//! q̈* = J⁺ (ẍ_d + K_d ė + K_p e − J̇ q̇),   τ = M q̈* + h − Q   (at zero input)
//! ```
//!
//! with the tool frame's world-aligned Jacobian, its J̇ q̇ and the robot's
//! own inverse dynamics (recursive Newton–Euler), so the model is exact and
//! the task error e = (p_d − p, log(R_d Rᵀ)) obeys ë + K_d ė + K_p e = 0 in
//! position, and in orientation while the error turns about a fixed axis (a
//! yaw error while the goal turns about the vertical, as here). Included by
//! path where used (the gallery, `tests/operational_space.rs`), not by the
//! catalog's `mod.rs`, so the other tests do not build the arm.

#![allow(dead_code)]

use lagrange::Error;
use lagrange::Lagrangian;
use lagrange::nalgebra::{Matrix3, Rotation3, SVector, Vector3};
use lagrange::task_space::{Goal, InverseKinematics, OperationalSpace, Target};

/// The UR5 read from its URDF file, with a torque input at each joint.
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
    emit(inverse_dynamics, kinematics, regressor),
    // The scene (visual only): the links as a line through the joints, the
    // joints as cylinders and balls. The file's wrist inertias are far larger
    // than the wrists, so their default inertia boxes would hide the arm.
    shape(line(
        shoulder_pan_joint_origin,
        shoulder_lift_joint_origin,
        elbow_joint_origin,
        wrist_1_joint_origin,
        wrist_2_joint_origin,
        wrist_3_joint_origin,
        ee_fixed_joint_origin
    )),
    shape(base_link, cylinder(radius = 0.07, length = 0.09, axis = z), at = [0, 0, 0.045]),
    shape(shoulder_link, cylinder(radius = 0.06, length = 0.14, axis = y)),
    shape(upper_arm_link, cylinder(radius = 0.055, length = 0.12, axis = y)),
    shape(forearm_link, sphere(radius = 0.05)),
    shape(wrist_1_link, sphere(radius = 0.045)),
    shape(wrist_2_link, sphere(radius = 0.045)),
    shape(wrist_3_link, cylinder(radius = 0.04, length = 0.05, axis = y)),
)]
pub struct Ur5 {}

/// A goal going round a horizontal circle at a constant rate, its frame
/// turning with it about the vertical: at angle φ = rate · t the origin is at
/// centre + radius (cos φ, sin φ, 0) and the rotation is rot_z(φ) · `start`.
#[derive(Clone, Copy, Debug)]
pub struct Circle {
    pub centre: Vector3<f64>,
    pub radius: f64,
    /// rad/s.
    pub rate: f64,
    /// The frame's rotation at φ = 0.
    pub start: Matrix3<f64>,
}

impl Circle {
    /// The goal at time t.
    pub fn at(&self, t: f64) -> Goal {
        let (w, r) = (self.rate, self.radius);
        let (s, c) = (w * t).sin_cos();
        Goal {
            position: self.centre + Vector3::new(r * c, r * s, 0.0),
            velocity: Vector3::new(-r * w * s, r * w * c, 0.0),
            acceleration: Vector3::new(-r * w * w * c, -r * w * w * s, 0.0),
            rotation: Rotation3::from_axis_angle(&Vector3::z_axis(), w * t).into_inner()
                * self.start,
            angular_velocity: Vector3::new(0.0, 0.0, w),
            angular_acceleration: Vector3::zeros(),
        }
    }
}

/// The gallery's and the tests' circle for the UR5's `tool0`: radius 0.1 m
/// about (0.45, 0.1, 0.4) m, once round in 4 s, the tool pointing down
/// (its z axis along −z) and turning with the circle about the vertical
/// (the wrist's last joint turns once the other way: one round keeps it
/// within its ±2π).
pub fn tool_circle() -> Circle {
    Circle {
        centre: Vector3::new(0.45, 0.1, 0.4),
        radius: 0.1,
        rate: std::f64::consts::FRAC_PI_2,
        start: Matrix3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0),
    }
}

/// Where the UR5 starts, at rest, off the circle's goal at t = 0: its tool
/// 4 cm outside the circle and 3 cm above it, turned 0.3 rad about the
/// vertical behind the goal's rotation (by the library's inverse kinematics
/// from the gallery's home pose with the last joint at π).
///
/// # Errors
/// The inverse kinematics' failure, if it does not converge.
pub fn start_off_the_circle(
    osc: &OperationalSpace<'_, Ur5, 6>,
    circle: &Circle,
) -> Result<SVector<f64, 6>, Error> {
    let goal = circle.at(0.0);
    let outward = (goal.position - circle.centre).normalize();
    let position = goal.position + outward * 0.04 + Vector3::new(0.0, 0.0, 0.03);
    let rotation =
        Rotation3::from_axis_angle(&Vector3::z_axis(), -0.3).into_inner() * goal.rotation;
    let home = SVector::<f64, 6>::from([0.0, -1.57, 1.57, -1.57, -1.57, std::f64::consts::PI]);
    let target = Target::Pose { position, rotation };
    let solution = InverseKinematics::new().solve(osc.robot(), osc.frame(), &target, &home)?;
    Ok(solution.q)
}
