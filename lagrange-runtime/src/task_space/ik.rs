//! Damped least-squares inverse kinematics ([`InverseKinematics`]).

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::damped::{Damping, damped_with};
use super::{rotation_error, stack};
use crate::error::{Error, Failure, Progress, SettingsError, to_vec};
use crate::pose::Kinematics;
use crate::system::Lagrangian;

/// Where inverse kinematics should put a frame: its full pose, or its
/// origin alone (the rotation free).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// The frame's origin at `position` and its axes at `rotation` (frame →
    /// world, a rotation matrix), world axes.
    Pose {
        /// The origin's position.
        position: Vector3<f64>,
        /// The frame's rotation.
        rotation: Matrix3<f64>,
    },
    /// The frame's origin at this position; its rotation free.
    Position(Vector3<f64>),
}

/// An iterate of inverse kinematics: the joint positions, the residual
/// there (the Euclidean norm of the task error (p_d − p, log(R_d Rᵀ)),
/// metres and radians, which the steps decrease) and the iterations it
/// took. The answer when it
/// converged, the best iterate (smallest residual) in the
/// [`Failure`] when it did not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<const N: usize> {
    /// The joint positions.
    pub q: SVector<f64, N>,
    /// The residual at q (∞ in a failure found before q was evaluated:
    /// bad settings, target, body or start).
    pub residual: f64,
    /// The damped least-squares steps taken to reach q.
    pub iterations: usize,
}

/// A failure's summary: the iterations made and the residual reached.
impl<const N: usize> Progress for Solution<N> {
    fn progress(&self) -> (usize, Option<f64>) {
        (self.iterations, None)
    }

    fn describe(&self) -> String {
        format!(
            "the closest configuration, reached in {} iteration(s) with |e| = {:e}, is in \
             `Failure::partial`",
            self.iterations, self.residual
        )
    }
}

/// Damped least-squares inverse kinematics for a frame of a robot with any
/// number of joints N: from a start q₀ the steps
/// q ← q + J⁺ e, J⁺ = Jᵀ (J Jᵀ + λ² I)⁻¹ ([`damped_inverse`](super::damped_inverse)),
/// with e = (p_d − p, log(R_d Rᵀ)) for a [`Target::Pose`] (J the frame's
/// world-aligned Jacobian) or e = p_d − p for a [`Target::Position`] (J's
/// rows 0–2), until |e| is within the tolerance. λ is zero while J's
/// smallest singular value stays above the damping's threshold, so the
/// steps are Newton's (quadratic convergence) away from singularities, and
/// bounded near them; near the target λ² is at most |e|² (Levenberg–
/// Marquardt after Yamashita and Fukushima), so a target close to a
/// singularity is still reached fast. A step that does not decrease |e|
/// is halved until it does (at most ten times). With
/// [`joint_limits`](Self::joint_limits) each iterate is clamped into
/// [`Lagrangian::position_limits`].
///
/// Settings are checked by [`solve`](Self::solve): a tolerance that is not
/// positive and finite, a zero iteration limit or a damping that is not
/// positive and finite is [`Error::Settings`].
///
/// ```
/// # use lagrange_runtime::task_space::{InverseKinematics, Target};
/// # fn demo<S: lagrange_runtime::Kinematics<f64, 6> + lagrange_runtime::Lagrangian<f64, 6>>(
/// #     robot: &S, tool: usize, start: nalgebra::SVector<f64, 6>,
/// # ) -> Result<(), lagrange_runtime::Error> {
/// let target = Target::Position(nalgebra::Vector3::new(0.4, 0.1, 0.3));
/// let solution = InverseKinematics::new()
///     .tolerance(1e-12)
///     .max_iterations(50)
///     .solve(robot, tool, &target, &start)?;
/// println!("q = {} in {} steps", solution.q, solution.iterations);
/// # Ok(())
/// # }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InverseKinematics {
    tolerance: f64,
    max_iterations: usize,
    damping: Damping,
    limits: bool,
}

impl Default for InverseKinematics {
    fn default() -> Self {
        Self::new()
    }
}

/// The name settings errors give.
const OWNER: &str = "inverse kinematics";

/// [`SettingsError::Value`] unless `value` is positive and finite.
pub(super) fn positive(
    owner: &'static str,
    setting: &'static str,
    value: f64,
) -> Result<(), Error> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(SettingsError::Value {
            owner,
            setting,
            value,
            requirement: "positive and finite".into(),
        }
        .into())
    }
}

impl InverseKinematics {
    /// Tolerance 1e-12 (metres and radians), at most 100 iterations, J's
    /// inverse damped below σ_min = 0.01 with λ up to 0.05 ([`Damping`]'s
    /// default), joint limits not applied.
    pub fn new() -> Self {
        InverseKinematics {
            tolerance: 1e-12,
            max_iterations: 100,
            damping: Damping::default(),
            limits: false,
        }
    }

    /// The norm of the task error accepted as converged.
    pub fn tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// The most damped least-squares steps taken.
    pub fn max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Where and how much J's inverse is damped.
    pub fn damping(mut self, damping: Damping) -> Self {
        self.damping = damping;
        self
    }

    /// Whether every iterate (and the start) is clamped into the robot's
    /// [`Lagrangian::position_limits`] (a URDF's `<limit>`s).
    pub fn joint_limits(mut self, apply: bool) -> Self {
        self.limits = apply;
        self
    }

    /// Checks the settings.
    ///
    /// # Errors
    /// [`Error::Settings`] for a tolerance or damping that is not positive
    /// and finite, or a zero iteration limit.
    pub fn check(&self) -> Result<(), Error> {
        positive(OWNER, "tolerance", self.tolerance)?;
        positive(OWNER, "damping.threshold", self.damping.threshold)?;
        positive(OWNER, "damping.damping", self.damping.damping)?;
        if self.max_iterations == 0 {
            return Err(SettingsError::ZeroCount {
                owner: OWNER,
                setting: "max_iterations",
            }
            .into());
        }
        Ok(())
    }

    /// The joint positions that put body `body`'s frame (an index of
    /// [`Posed::BODIES`](crate::Posed::BODIES); [`Kinematics::body_index`]
    /// finds it by name) on `target`, from `start`.
    ///
    /// # Errors
    /// In a [`Failure`] whose `partial` is the best iterate (the start, for
    /// an error found before the first step):
    /// [`Error::InverseKinematics`] when the iteration limit is reached
    /// with the residual above the tolerance; [`Error::Settings`] for bad
    /// settings ([`check`](Self::check)), a target that is not finite or
    /// whose rotation is not a rotation matrix (to 1e-9);
    /// [`Error::UnknownBody`] for an index past the bodies;
    /// [`Error::NonFiniteState`] for a start, or an iterate's pose, that
    /// is not finite.
    pub fn solve<S, const N: usize>(
        &self,
        robot: &S,
        body: usize,
        target: &Target,
        start: &SVector<f64, N>,
    ) -> Result<Solution<N>, Failure<Solution<N>>>
    where
        S: Kinematics<f64, N> + Lagrangian<f64, N>,
    {
        let unsolved = Solution {
            q: *start,
            residual: f64::INFINITY,
            iterations: 0,
        };
        let fail = |error: Error| Failure::new(error, unsolved);
        self.check().map_err(fail)?;
        check_target(target).map_err(fail)?;
        if body >= S::BODIES.len() {
            return Err(fail(Error::UnknownBody {
                body: body.to_string(),
                count: S::BODIES.len(),
                bodies: S::BODIES.to_vec(),
            }));
        }
        if !start.iter().all(|x| x.is_finite()) {
            return Err(fail(non_finite(start)));
        }
        let result = match target {
            Target::Pose { position, rotation } => self.iterate(robot, start, |q| {
                let pose = robot.frame_pose(body, q, 0.0)?;
                let e = stack(
                    position - pose.origin,
                    rotation_error(rotation, &pose.rotation),
                );
                Some((e, robot.frame_jacobian(body, q, 0.0)?))
            }),
            Target::Position(position) => self.iterate(robot, start, |q| {
                let pose = robot.frame_pose(body, q, 0.0)?;
                let rows: SMatrix<f64, 3, N> = robot
                    .frame_jacobian(body, q, 0.0)?
                    .fixed_rows::<3>(0)
                    .into_owned();
                Some((position - pose.origin, rows))
            }),
        };
        result.map_err(|(error, best)| {
            let error = error.unwrap_or(Error::InverseKinematics {
                body: S::BODIES[body],
                iterations: self.max_iterations,
                residual: best.residual,
                tolerance: self.tolerance,
            });
            Failure::new(error, best)
        })
    }

    /// The damped least-squares steps from `start` on the task error and
    /// Jacobian `evaluate` gives (`None` where they are not finite). `Err`
    /// with the best iterate, and the error if it is not the iteration
    /// limit.
    fn iterate<S, const R: usize, const N: usize>(
        &self,
        robot: &S,
        start: &SVector<f64, N>,
        evaluate: impl Fn(&SVector<f64, N>) -> Option<(SVector<f64, R>, SMatrix<f64, R, N>)>,
    ) -> Result<Solution<N>, (Option<Error>, Solution<N>)>
    where
        S: Lagrangian<f64, N>,
    {
        let clamp = |q: &mut SVector<f64, N>| {
            if self.limits {
                for limit in robot.position_limits() {
                    let x = &mut q[limit.coordinate];
                    *x = x.clamp(limit.lower, limit.upper);
                }
            }
        };
        let finite = |q: &SVector<f64, N>| {
            evaluate(q)
                .filter(|(e, j)| e.iter().chain(j.iter()).all(|x| x.is_finite()))
                .ok_or_else(|| non_finite(q))
        };
        let mut q = *start;
        clamp(&mut q);
        let mut best = Solution {
            q,
            residual: f64::INFINITY,
            iterations: 0,
        };
        let (mut e, mut j) = finite(&q).map_err(|error| (Some(error), best))?;
        for iterations in 0..=self.max_iterations {
            let residual = e.norm();
            if residual < best.residual {
                best = Solution {
                    q,
                    residual,
                    iterations,
                };
            }
            if residual <= self.tolerance {
                return Ok(best);
            }
            if iterations == self.max_iterations {
                break;
            }
            // Levenberg–Marquardt's λ² ≤ |e|² (Yamashita and Fukushima): the
            // damping fades as the target nears, so that the steps become
            // Newton's even where the solution sits close to a singularity.
            let lambda2 = |smallest| self.damping.lambda2(smallest).min(residual * residual);
            let inverse = damped_with(&j, lambda2).ok_or((Some(non_finite(&q)), best))?;
            let step = inverse.inverse * e;
            // The step is a descent direction of |e|²: halved until |e|
            // falls (at most ten times), so that the iterates do not bounce
            // about a singularity on the way to an unreachable target.
            let mut scale = 1.0;
            loop {
                let mut trial = q + step * scale;
                clamp(&mut trial);
                let (trial_e, trial_j) = finite(&trial).map_err(|error| (Some(error), best))?;
                if trial_e.norm() < residual || scale < 1e-3 {
                    (q, e, j) = (trial, trial_e, trial_j);
                    break;
                }
                scale /= 2.0;
            }
        }
        Err((None, best))
    }
}

/// [`Error::NonFiniteState`] at q.
fn non_finite<const N: usize>(q: &SVector<f64, N>) -> Error {
    Error::NonFiniteState {
        t: 0.0,
        q: to_vec(q),
        v: Vec::new(),
    }
}

/// [`SettingsError::Value`] for a target that is not finite, or whose
/// rotation is not orthonormal with determinant 1 (to 1e-9).
fn check_target(target: &Target) -> Result<(), Error> {
    let (position, rotation) = match target {
        Target::Pose { position, rotation } => (position, Some(rotation)),
        Target::Position(position) => (position, None),
    };
    let bad = |setting: &'static str, value: f64, requirement: &str| {
        Err(SettingsError::Value {
            owner: OWNER,
            setting,
            value,
            requirement: requirement.into(),
        }
        .into())
    };
    if let Some(x) = position.iter().find(|x| !x.is_finite()) {
        return bad("target position", *x, "finite");
    }
    if let Some(r) = rotation {
        if let Some(x) = r.iter().find(|x| !x.is_finite()) {
            return bad("target rotation", *x, "finite");
        }
        let off = (r.transpose() * r - Matrix3::identity()).amax();
        if off > 1e-9 || r.determinant() < 0.0 {
            return bad(
                "target rotation",
                off,
                "a rotation matrix (RᵀR = I to 1e-9, det R = 1)",
            );
        }
    }
    Ok(())
}
