//! A robot arm under operational-space control: the UR5 read from its URDF
//! file, a goal for its tool frame (position and orientation, with their
//! rates) moving on a circle, and computed torque in task space,
//!
//! ```text
//! q̈* = J⁺ (ẍ_d + K_d ė + K_p e − J̇ q̇),   τ = M q̈* + h − Q   (at zero input)
//! ```
//!
//! J is the tool frame's world-aligned Jacobian (`frame_jacobian`: rows 0–2
//! the origin's velocity, rows 3–5 the angular velocity ω in world axes), J̇ q̇
//! its `frame_bias`, and τ the robot's own inverse dynamics (recursive
//! Newton–Euler), so the model is exact. The error is e = (p_d − p,
//! log(R_d Rᵀ)): the position error and the rotation vector, in world axes,
//! that turns the tool onto its goal; ė = (ṗ_d − ṗ, ω_d − ω). The tool then
//! obeys ë + K_d ė + K_p e = 0 exactly in position; in orientation
//! ω_d − ω is the rate of log(R_d Rᵀ) while the error turns about a fixed
//! axis (a yaw error while the goal turns about the vertical, as here), and
//! only to first order otherwise.
//!
//! J⁺ is J⁻¹ away from singularities and a damped least-squares inverse near
//! one ([`damped_inverse`]), so the command stays finite through a singular
//! pose. Included by path where used (the gallery, `tests/operational_space.rs`),
//! not by the catalog's `mod.rs`, so the other tests do not build the arm.

#![allow(dead_code)]

use lagrange::Lagrangian;
use lagrange::nalgebra::{Matrix3, Matrix6, Rotation3, SVector, Vector3, Vector6};
use lagrange::pose::{BodyPose, Kinematics};

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
    emit(inverse_dynamics, kinematics),
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

/// A 6-vector of task coordinates (or their rates): the frame origin's in
/// rows 0–2, the rotation's in rows 3–5, world axes.
pub type Task = Vector6<f64>;

/// Where a frame should be at one instant: its origin's position, velocity
/// and acceleration, and its rotation (frame → world), angular velocity and
/// angular acceleration, all in world axes.
#[derive(Clone, Copy, Debug)]
pub struct Goal {
    pub position: Vector3<f64>,
    pub velocity: Vector3<f64>,
    pub acceleration: Vector3<f64>,
    pub rotation: Matrix3<f64>,
    pub angular_velocity: Vector3<f64>,
    pub angular_acceleration: Vector3<f64>,
}

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
/// vertical behind the goal's rotation (by inverse kinematics from the
/// gallery's home pose with the last joint at π); `None` if inverse
/// kinematics fails.
pub fn start_off_the_circle(
    osc: &OperationalSpace<'_, Ur5>,
    circle: &Circle,
) -> Option<SVector<f64, 6>> {
    let goal = circle.at(0.0);
    let outward = (goal.position - circle.centre).normalize();
    let position = goal.position + outward * 0.04 + Vector3::new(0.0, 0.0, 0.03);
    let rotation =
        Rotation3::from_axis_angle(&Vector3::z_axis(), -0.3).into_inner() * goal.rotation;
    let home = SVector::<f64, 6>::from([0.0, -1.57, 1.57, -1.57, -1.57, std::f64::consts::PI]);
    osc.inverse_kinematics(&position, &rotation, &home)
}

/// The rotation vector θ n (axis × angle, θ in [0, π]) of a rotation
/// matrix: log R. From R = cos θ I + sin θ [n]× + (1 − cos θ) n nᵀ, the
/// angle is atan2(sin θ, cos θ), accurate at small angles (where
/// acos((tr R − 1)/2) loses half the digits and, from a trace rounded past
/// 3, gives NaN); near π the axis comes from the symmetric part n nᵀ.
pub fn rotation_vector(r: &Matrix3<f64>) -> Vector3<f64> {
    let sine_axis = Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    ) / 2.0;
    let (sine, cosine) = (sine_axis.norm(), (r.trace() - 1.0) / 2.0);
    let angle = sine.atan2(cosine);
    if cosine > -0.9 {
        // θ / sin θ → 1 as θ → 0.
        return if sine > 0.0 {
            sine_axis * (angle / sine)
        } else {
            sine_axis
        };
    }
    let outer = ((r + r.transpose()) / 2.0 - Matrix3::identity() * cosine) / (1.0 - cosine);
    let k = outer.diagonal().imax();
    let axis = outer.column(k) / outer[(k, k)].sqrt();
    let sign = if axis.dot(&sine_axis) < 0.0 {
        -1.0
    } else {
        1.0
    };
    axis * (sign * angle)
}

/// The solution of ë + 2ω ė + ω² e = 0 (critical damping) from e(0) = e0,
/// ė(0) = de0: e(t) = (e0 + (de0 + ω e0) t) e^(−ωt), per component.
pub fn critically_damped(e0: &Task, de0: &Task, omega: f64, t: f64) -> Task {
    (e0 + (de0 + e0 * omega) * t) * (-omega * t).exp()
}

/// The inverse of J where its smallest singular value σ_min is at least
/// `threshold`; below it the damped least-squares inverse
/// Jᵀ (J Jᵀ + λ² I)⁻¹ = V diag(σ / (σ² + λ²)) Uᵀ with
/// λ² = `damping`² (1 − (σ_min / threshold)²), which grows from zero at the
/// threshold to `damping`² at the singularity (Nakamura and Hanafusa's
/// variable damping): the inverse is exact away from singularities, its norm
/// at most 1 / `threshold` near one (for `damping` ≥ `threshold`) and
/// 1 / (2 `damping`) at one. Returns the inverse and σ_min; `None` if the SVD
/// does not converge (a J that is not finite).
pub fn damped_inverse(
    j: &Matrix6<f64>,
    threshold: f64,
    damping: f64,
) -> Option<(Matrix6<f64>, f64)> {
    let svd = j.try_svd(true, true, f64::EPSILON, 200)?;
    let (u, v_t) = (svd.u?, svd.v_t?);
    let sigma = svd.singular_values;
    let smallest = sigma.min();
    let lambda2 = if smallest < threshold {
        damping * damping * (1.0 - (smallest / threshold).powi(2))
    } else {
        0.0
    };
    let gains = sigma.map(|s| s / (s * s + lambda2));
    Some((
        v_t.transpose() * Matrix6::from_diagonal(&gains) * u.transpose(),
        smallest,
    ))
}

/// Computed torque in task space for a six-joint arm: the frame of body
/// `frame` is driven onto a [`Goal`] with stiffness K_p = ω² and damping
/// K_d = 2ω (critical damping at ω rad/s), through the robot's own frame
/// Jacobian, J̇ q̇ and inverse dynamics.
pub struct OperationalSpace<'a, S> {
    pub robot: &'a S,
    /// The index of the driven frame in the robot's bodies.
    pub frame: usize,
    /// The error dynamics' natural frequency ω, rad/s.
    pub omega: f64,
    /// Below this smallest singular value of J the inverse is damped.
    pub threshold: f64,
    /// The damping λ at a singularity.
    pub damping: f64,
}

impl<'a, S: Kinematics<f64, 6> + Lagrangian<f64, 6>> OperationalSpace<'a, S> {
    /// The controller for the body named `frame`, critically damped at
    /// `omega`, damping J's inverse below σ_min = 0.01 with λ up to 0.05;
    /// `None` if the robot has no such body.
    pub fn new(robot: &'a S, frame: &str, omega: f64) -> Option<Self> {
        Some(OperationalSpace {
            robot,
            frame: S::body_index(frame)?,
            omega,
            threshold: 0.01,
            damping: 0.05,
        })
    }

    /// The frame's origin and rotation (frame → world) at q.
    pub fn pose(&self, q: &SVector<f64, 6>) -> (Vector3<f64>, Matrix3<f64>) {
        let mut bodies = vec![BodyPose::default(); S::BODIES.len()];
        let mut points = vec![Vector3::zeros(); S::POINTS.len()];
        self.robot.poses(q, 0.0, &mut bodies, &mut points);
        let frame = bodies[self.frame];
        (frame.origin, frame.rotation)
    }

    /// The task error e = (p_d − p, log(R_d Rᵀ)) and its rate
    /// ė = (ṗ_d − ṗ, ω_d − ω) at (q, q̇).
    pub fn error(&self, goal: &Goal, q: &SVector<f64, 6>, v: &SVector<f64, 6>) -> (Task, Task) {
        self.error_with(&self.jacobian(q), goal, q, v)
    }

    /// The task error and its rate with the frame Jacobian at q given.
    fn error_with(
        &self,
        jacobian: &Matrix6<f64>,
        goal: &Goal,
        q: &SVector<f64, 6>,
        v: &SVector<f64, 6>,
    ) -> (Task, Task) {
        let (p, r) = self.pose(q);
        let e = stack(
            goal.position - p,
            rotation_vector(&(goal.rotation * r.transpose())),
        );
        let de = stack(goal.velocity, goal.angular_velocity) - jacobian * v;
        (e, de)
    }

    /// The commanded joint accelerations q̈* = J⁺ (ẍ_d + K_d ė + K_p e − J̇ q̇)
    /// and J's smallest singular value; NaN if J is not finite.
    pub fn accelerations(
        &self,
        goal: &Goal,
        q: &SVector<f64, 6>,
        v: &SVector<f64, 6>,
    ) -> (SVector<f64, 6>, f64) {
        let jacobian = self.jacobian(q);
        let (e, de) = self.error_with(&jacobian, goal, q, v);
        let (kp, kd) = (self.omega * self.omega, 2.0 * self.omega);
        let bias = self
            .robot
            .frame_bias(self.frame, q, v, 0.0)
            .expect("the frame is one of the robot's bodies");
        let task = stack(goal.acceleration, goal.angular_acceleration) + de * kd + e * kp - bias;
        match damped_inverse(&jacobian, self.threshold, self.damping) {
            Some((inverse, smallest)) => (inverse * task, smallest),
            None => (SVector::repeat(f64::NAN), f64::NAN),
        }
    }

    /// The joint torques τ = M q̈* + h − Q that give q̈*, by the robot's
    /// inverse dynamics. A NaN (from a J that is not finite) reaches the
    /// run, which stops with `Error::NonFiniteInput` naming the input.
    pub fn torque(
        &self,
        goal: &Goal,
        t: f64,
        q: &SVector<f64, 6>,
        v: &SVector<f64, 6>,
    ) -> SVector<f64, 6> {
        let (a, _) = self.accelerations(goal, q, v);
        self.robot.inverse_dynamics(q, v, &a, t)
    }

    /// The frame's world-aligned Jacobian at q.
    pub fn jacobian(&self, q: &SVector<f64, 6>) -> Matrix6<f64> {
        self.robot
            .frame_jacobian(self.frame, q, 0.0)
            .expect("the frame is one of the robot's bodies")
    }

    /// The joint angles that put the frame at (p, R), by Newton's method on
    /// the frame Jacobian from `start`: q ← q + J⁻¹ (p − p(q), log(R R(q)ᵀ)),
    /// until the step is below 1e-13; `None` if 50 steps do not get there
    /// (an unreachable pose, or a start that leads to a singularity).
    pub fn inverse_kinematics(
        &self,
        position: &Vector3<f64>,
        rotation: &Matrix3<f64>,
        start: &SVector<f64, 6>,
    ) -> Option<SVector<f64, 6>> {
        let mut q = *start;
        for _ in 0..50 {
            let (p, r) = self.pose(&q);
            let e = stack(position - p, rotation_vector(&(rotation * r.transpose())));
            let step = self.jacobian(&q).lu().solve(&e)?;
            q += step;
            if step.amax() < 1e-13 {
                return Some(q);
            }
        }
        None
    }
}

/// (a, b) as one 6-vector.
fn stack(a: Vector3<f64>, b: Vector3<f64>) -> Task {
    Task::new(a.x, a.y, a.z, b.x, b.y, b.z)
}
