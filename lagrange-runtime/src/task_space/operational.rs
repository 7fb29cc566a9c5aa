//! Operational-space control: computed torque in task space
//! ([`OperationalSpace`]) toward a moving [`Goal`].

use nalgebra::{Matrix3, SMatrix, SVector, Vector3, Vector6};

use super::damped::{Damping, damped_inverse};
use super::ik::positive;
use super::{rotation_error, stack};
use crate::error::Error;
use crate::pose::Kinematics;
use crate::system::Lagrangian;

/// Where a frame should be at one instant: its origin's position, velocity
/// and acceleration, and its rotation (frame → world), angular velocity and
/// angular acceleration, all in world axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Goal {
    /// The origin's position.
    pub position: Vector3<f64>,
    /// The origin's velocity.
    pub velocity: Vector3<f64>,
    /// The origin's acceleration.
    pub acceleration: Vector3<f64>,
    /// The frame's rotation (frame → world).
    pub rotation: Matrix3<f64>,
    /// The frame's angular velocity.
    pub angular_velocity: Vector3<f64>,
    /// The frame's angular acceleration.
    pub angular_acceleration: Vector3<f64>,
}

impl Goal {
    /// A goal at rest at `position` with axes `rotation` (a set point).
    pub fn at_rest(position: Vector3<f64>, rotation: Matrix3<f64>) -> Self {
        Goal {
            position,
            velocity: Vector3::zeros(),
            acceleration: Vector3::zeros(),
            rotation,
            angular_velocity: Vector3::zeros(),
            angular_acceleration: Vector3::zeros(),
        }
    }
}

/// The solution of ë + 2ω ė + ω² e = 0 (critical damping) from e(0) = e0,
/// ė(0) = de0: e(t) = (e0 + (de0 + ω e0) t) e^(−ωt), per component; the
/// error an [`OperationalSpace`] controller with the exact model gives.
pub fn critically_damped(
    e0: &Vector6<f64>,
    de0: &Vector6<f64>,
    omega: f64,
    t: f64,
) -> Vector6<f64> {
    (e0 + (de0 + e0 * omega) * t) * (-omega * t).exp()
}

/// A null-space posture: q̈₀ = −ω² (q − q_rest) − 2ω q̇, projected onto the
/// motions that leave the task alone.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Posture<const N: usize> {
    rest: SVector<f64, N>,
    omega: f64,
}

/// Computed torque in task space for a robot with N joints: the frame of
/// one body is driven onto a [`Goal`] with stiffness K_p = ω² and damping
/// K_d = 2ω (critical damping at ω rad/s), through the robot's own frame
/// Jacobian J, J̇ q̇ and inverse dynamics:
///
/// ```text
/// q̈* = J⁺ (ẍ_d + K_d ė + K_p e − J̇ q̇) [+ (I − J⁺ J) q̈₀],   τ = M q̈* + h − Q
/// ```
///
/// with e = (p_d − p, log(R_d Rᵀ)) and ė = (ṗ_d − ṗ, ω_d − ω). With the
/// exact model the task error obeys ë + K_d ė + K_p e = 0 in position (and
/// in orientation while the error turns about a fixed axis; to first order
/// otherwise). J⁺ is [`damped_inverse`]: J⁻¹ for six joints away from
/// singularities, damped near them so that the command stays finite; with
/// more joints the minimum-norm inverse, with fewer the least-squares one.
/// For a redundant arm an optional [`posture`](Self::posture) acts in J's
/// null space (the projection I − J⁺ J).
///
/// τ is the robot's joint torque, so the robot's inputs must be its joint
/// torques, one per coordinate in order (`generalized_force(joint = u)` for
/// each joint): then [`feedback`](Self::feedback) is a
/// [`Simulation::feedback`](crate::Simulation::feedback) law.
///
/// ```
/// # use lagrange_runtime::task_space::{Goal, OperationalSpace};
/// # use lagrange_runtime::{Driven, Kinematics, Lagrangian, Simulation, Dopri5};
/// # use nalgebra::{Matrix3, SVector, Vector3};
/// # fn demo<S>(robot: &S, q0: SVector<f64, 6>) -> Result<(), Box<dyn std::error::Error>>
/// # where S: Kinematics<f64, 6> + Lagrangian<f64, 6> + Driven<f64, 6, 6> {
/// let osc = OperationalSpace::new(robot, "tool0", 10.0)?;
/// let goal = Goal::at_rest(Vector3::new(0.4, 0.1, 0.4), Matrix3::identity());
/// let run = Simulation::new(robot)
///     .integrator(Dopri5::tol(1e-9))
///     .feedback(osc.feedback(move |_| goal))
///     .run(q0, SVector::zeros(), 0.0..1.0)?;
/// # Ok(())
/// # }
/// ```
pub struct OperationalSpace<'a, S, const N: usize> {
    robot: &'a S,
    frame: usize,
    omega: f64,
    damping: Damping,
    posture: Option<Posture<N>>,
}

impl<S, const N: usize> Clone for OperationalSpace<'_, S, N> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S, const N: usize> Copy for OperationalSpace<'_, S, N> {}

/// The settings (the robot need not be `Debug`).
impl<S, const N: usize> std::fmt::Debug for OperationalSpace<'_, S, N> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OperationalSpace")
            .field("frame", &self.frame)
            .field("omega", &self.omega)
            .field("damping", &self.damping)
            .field("posture", &self.posture)
            .finish()
    }
}

/// The name settings errors give.
const OWNER: &str = "operational space";

impl<'a, S, const N: usize> OperationalSpace<'a, S, N>
where
    S: Kinematics<f64, N> + Lagrangian<f64, N>,
{
    /// The controller for the body named `frame`, critically damped at
    /// `omega` rad/s, with [`Damping`]'s default (J's inverse damped below
    /// σ_min = 0.01 with λ up to 0.05) and no posture.
    ///
    /// # Errors
    /// [`Error::UnknownBody`] if the robot has no such body;
    /// [`Error::Settings`] for an `omega` that is not positive and finite.
    pub fn new(robot: &'a S, frame: &str, omega: f64) -> Result<Self, Error> {
        let index = S::body_index(frame).ok_or_else(|| Error::UnknownBody {
            body: frame.to_string(),
            count: S::BODIES.len(),
            bodies: S::BODIES.to_vec(),
        })?;
        positive(OWNER, "omega", omega)?;
        Ok(OperationalSpace {
            robot,
            frame: index,
            omega,
            damping: Damping::default(),
            posture: None,
        })
    }

    /// The same controller with J's inverse damped as `damping` says.
    ///
    /// # Errors
    /// [`Error::Settings`] for a threshold or damping that is not positive
    /// and finite.
    pub fn damping(mut self, damping: Damping) -> Result<Self, Error> {
        positive(OWNER, "damping.threshold", damping.threshold)?;
        positive(OWNER, "damping.damping", damping.damping)?;
        self.damping = damping;
        Ok(self)
    }

    /// The same controller with a posture for a redundant arm: the joints
    /// pulled toward `rest`, critically damped at `omega` rad/s, in the
    /// null space of J (I − J⁺ J), so the task is not disturbed (where J⁺ is
    /// not damped).
    ///
    /// # Errors
    /// [`Error::Settings`] for an `omega` that is not positive and finite
    /// or a `rest` that is not finite.
    pub fn posture(mut self, rest: SVector<f64, N>, omega: f64) -> Result<Self, Error> {
        positive(OWNER, "posture omega", omega)?;
        if let Some(x) = rest.iter().find(|x| !x.is_finite()) {
            positive(OWNER, "posture rest", *x)?;
        }
        self.posture = Some(Posture { rest, omega });
        Ok(self)
    }

    /// The robot.
    pub fn robot(&self) -> &'a S {
        self.robot
    }

    /// The driven body's index in [`Posed::BODIES`](crate::Posed::BODIES).
    pub fn frame(&self) -> usize {
        self.frame
    }

    /// The error dynamics' natural frequency ω, rad/s.
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// Where and how much J's inverse is damped.
    pub fn damping_settings(&self) -> Damping {
        self.damping
    }

    /// The frame's origin and rotation (frame → world) at q.
    pub fn pose(&self, q: &SVector<f64, N>) -> (Vector3<f64>, Matrix3<f64>) {
        let pose = self
            .robot
            .frame_pose(self.frame, q, 0.0)
            .expect("the frame was checked to be one of the robot's bodies");
        (pose.origin, pose.rotation)
    }

    /// The frame's world-aligned Jacobian at q.
    pub fn jacobian(&self, q: &SVector<f64, N>) -> SMatrix<f64, 6, N> {
        self.robot
            .frame_jacobian(self.frame, q, 0.0)
            .expect("the frame was checked to be one of the robot's bodies")
    }

    /// The task error e = (p_d − p, log(R_d Rᵀ)) and its rate
    /// ė = (ṗ_d − ṗ, ω_d − ω) at (q, q̇).
    pub fn error(
        &self,
        goal: &Goal,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> (Vector6<f64>, Vector6<f64>) {
        self.error_with(&self.jacobian(q), goal, q, v)
    }

    /// The task error and its rate with the frame Jacobian at q given.
    fn error_with(
        &self,
        jacobian: &SMatrix<f64, 6, N>,
        goal: &Goal,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> (Vector6<f64>, Vector6<f64>) {
        let (p, r) = self.pose(q);
        let e = stack(goal.position - p, rotation_error(&goal.rotation, &r));
        let de = stack(goal.velocity, goal.angular_velocity) - jacobian * v;
        (e, de)
    }

    /// The commanded joint accelerations q̈* and J's smallest singular
    /// value; NaN if J is not finite.
    pub fn accelerations(
        &self,
        goal: &Goal,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> (SVector<f64, N>, f64) {
        let jacobian = self.jacobian(q);
        let (e, de) = self.error_with(&jacobian, goal, q, v);
        let (kp, kd) = (self.omega * self.omega, 2.0 * self.omega);
        let bias = self
            .robot
            .frame_bias(self.frame, q, v, 0.0)
            .expect("the frame was checked to be one of the robot's bodies");
        let task = stack(goal.acceleration, goal.angular_acceleration) + de * kd + e * kp - bias;
        let Some(inverse) = damped_inverse(&jacobian, &self.damping) else {
            return (SVector::repeat(f64::NAN), f64::NAN);
        };
        let mut a = inverse.inverse * task;
        if let Some(Posture { rest, omega }) = &self.posture {
            let rest_acceleration = -(q - rest) * (omega * omega) - v * (2.0 * omega);
            let projection = SMatrix::<f64, N, N>::identity() - inverse.inverse * jacobian;
            a += projection * rest_acceleration;
        }
        (a, inverse.smallest)
    }

    /// The joint torques τ = M q̈* + h − Q that give q̈*, by the robot's
    /// inverse dynamics. A NaN (from a J that is not finite) reaches the
    /// run, which stops with [`Error::NonFiniteInput`] naming the input.
    pub fn torque(
        &self,
        goal: &Goal,
        t: f64,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> SVector<f64, N> {
        let (a, _) = self.accelerations(goal, q, v);
        self.robot.inverse_dynamics(q, v, &a, t)
    }

    /// The controller as a feedback law u = τ(t, q, q̇) toward the goal
    /// `goal(t)`, for [`Simulation::feedback`](crate::Simulation::feedback)
    /// (the robot's inputs its joint torques).
    pub fn feedback(
        &self,
        goal: impl Fn(f64) -> Goal + 'a,
    ) -> impl Fn(f64, &SVector<f64, N>, &SVector<f64, N>) -> SVector<f64, N> + 'a {
        let controller = *self;
        move |t, q, v| controller.torque(&goal(t), t, q, v)
    }
}
