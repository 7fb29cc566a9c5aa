//! Typed errors of the runtime.
//!
//! Every variant says *what* went wrong and *where*: the time and, for failures of
//! the dynamics, the generalized coordinates. Scalars are converted to `f64` so
//! that the error type does not depend on the scalar the system is computed in.

/// Everything that can go wrong while evaluating the dynamics or integrating.
///
/// `Clone`: a clone of an [`Io`](Error::Io) error keeps its kind, its OS error
/// code and its message (the wrapped error object itself cannot be cloned).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The mass matrix is not positive definite (its Cholesky factorisation
    /// breaks down) or is numerically singular: the smallest squared pivot of the
    /// factorisation divided by the largest one, `ratio`, fell below the singular
    /// tolerance. `direction` names what M has no inertia along: a chart
    /// singularity when those are angles (the pole θ = 0 of a spherical
    /// pendulum in (θ, φ); a description with `emit(atlas)` runs through
    /// its Euler charts' with `run_atlas`), else a massless body or an
    /// orientation no body turns.
    #[error(
        "mass matrix singular or not positive definite at t = {t}, q = {q:?} \
         (pivot ratio min L_ii^2 / max L_ii^2 = {ratio:e}){}{}",
        no_inertia(direction),
        if *atlas {
            "; this description has `emit(atlas)`: call `run_atlas`, which runs through \
             its Euler charts' singular sets"
        } else {
            ""
        }
    )]
    SingularMassMatrix {
        /// Time of the failed evaluation.
        t: f64,
        /// Generalized coordinates at which the mass matrix was evaluated.
        q: Vec<f64>,
        /// min_i L_ii² / max_i L_ii² of the Cholesky factor (≤ 0 when a pivot is not positive).
        ratio: f64,
        /// The direction of least inertia, in the velocities' names
        /// ("0.707 psi - 0.707 phi"); empty where the matrix was not at hand.
        direction: String,
        /// Whether the system has `emit(atlas)`
        /// ([`Lagrangian::ATLAS`](crate::Lagrangian::ATLAS)): then the message
        /// says to call `run_atlas`.
        atlas: bool,
    },

    /// A state, a mass matrix, a right-hand side or an acceleration contains a NaN
    /// or an infinity (non-finite parameters, overflow, a division by zero in the
    /// user's expressions).
    #[error("non-finite state or dynamics at t = {t}, q = {q:?}, v = {v:?}")]
    NonFiniteState {
        /// Time of the failed evaluation.
        t: f64,
        /// Generalized coordinates.
        q: Vec<f64>,
        /// Generalized velocities.
        v: Vec<f64>,
    },

    /// The constraints are redundant: some rows of the constraint Jacobian G are
    /// (numerically) linear combinations of the others, or vanish (a constraint
    /// whose gradient is zero at q, such as x² + y² − l² at the origin), so the
    /// multipliers are not unique. Detected by a pivoted Cholesky factorisation of G M⁻¹ Gᵀ whose
    /// pivot ratio fell below the redundancy tolerance. Remove the dependent
    /// constraints, or opt into least squares (minimum-norm multipliers).
    #[error(
        "redundant constraints at t = {t}, q = {}: {dependent:?} depend on the other \
         constraints or have a vanishing gradient there (pivot ratio of G M^-1 G^T = \
         {ratio:e}); remove them or enable least squares",
        named(coordinates, q)
    )]
    RedundantConstraints {
        /// Time of the failed evaluation.
        t: f64,
        /// Generalized coordinates.
        q: Vec<f64>,
        /// Their names.
        coordinates: Vec<&'static str>,
        /// Pivot ratio at which the factorisation stopped (≤ 0 for a zero pivot).
        ratio: f64,
        /// Names of the constraints found to depend on the others (which ones of a
        /// dependent set are named depends on the pivoting order).
        dependent: Vec<&'static str>,
    },

    /// The initial state violates the constraints: Φ(q0, t0) ≠ 0 or
    /// G q̇0 + g ≠ 0 beyond the tolerance. Project it first (the runtime can do it:
    /// `Simulation::project_initial(true)` or `project_consistent`).
    #[error(
        "inconsistent initial conditions at t = {t}, q = {}: |Phi| = {position_residual:e}, \
         |G v + g| = {velocity_residual:e}, tolerance {tolerance:e}; worst constraint: \
         {constraint}",
        named(coordinates, q)
    )]
    InconsistentInitialConditions {
        /// Initial time.
        t: f64,
        /// Initial coordinates.
        q: Vec<f64>,
        /// Their names.
        coordinates: Vec<&'static str>,
        /// max |Φ_i| over the holonomic rows.
        position_residual: f64,
        /// max |(G q̇ + g)_i| over all rows.
        velocity_residual: f64,
        /// The tolerance both residuals must meet.
        tolerance: f64,
        /// The constraint with the largest residual at the first level that fails
        /// (positions before velocities).
        constraint: &'static str,
    },

    /// Gauss–Newton projection onto Φ(q, t) = 0 did not reach the tolerance in the
    /// allowed number of iterations (the tolerance may be below the round-off level
    /// of Φ, or the state far from the constraint manifold).
    #[error(
        "projection onto the constraints did not converge at t = {t}, q = {}: \
         |Phi| = {residual:e} after {iterations} iterations, tolerance {tolerance:e}",
        named(coordinates, q)
    )]
    ProjectionFailed {
        /// Time of the projection.
        t: f64,
        /// Coordinates reached.
        q: Vec<f64>,
        /// Their names.
        coordinates: Vec<&'static str>,
        /// max |Φ_i| reached.
        residual: f64,
        /// Iterations done.
        iterations: usize,
        /// The tolerance asked for.
        tolerance: f64,
    },

    /// The adaptive step size became negligible relative to the time: the
    /// problem is probably stiff or singular near `t`.
    #[error("step size underflow at t = {t}: h = {h:e} is negligible relative to t")]
    StepSizeUnderflow {
        /// Time reached.
        t: f64,
        /// The step size that was too small.
        h: f64,
    },

    /// An explicit method detected stiffness, as Hairer's DOPRI5 and DOP853 do:
    /// h·|λ|, with |λ| estimated from the last stage of accepted steps, stayed
    /// beyond the method's stability boundary (3.25 for DOPRI5, 6.1 for DOP853)
    /// for 15 tests, so the step is held down by stability, not accuracy.
    #[error(
        "{method}: the problem seems stiff at t = {t} (h·λ = {h_lambda:.2} beyond the \
         stability boundary in {tests} tests): integrate it with Radau5, or switch the test \
         off with `.stiffness_test(0)`"
    )]
    ProbablyStiff {
        /// The method that stopped.
        method: &'static str,
        /// Time reached.
        t: f64,
        /// The last estimate of h·|λ|.
        h_lambda: f64,
        /// Consecutive tests beyond the boundary.
        tests: usize,
    },

    /// The reduced form's stacked velocity rows A = [U; G] (the speeds, then the
    /// constraints) are dependent at this state: the speeds do not determine the
    /// velocities here (a speed parallel to a constraint, two constraints
    /// alike). A regular state never gives this error, whatever the pivots a
    /// symbolic solution would have chosen.
    #[error(
        "the reduced form's velocity rows {rows:?} are linearly dependent at t = {t}, q = {} \
         (pivot ratio {ratio:e}): the speeds do not determine the velocities here; name \
         `speeds(...)` independent of the constraints at this state, or integrate the \
         multiplier form (`run_constrained`, with `formulation(multipliers, reduced)`)",
        named(coordinates, q)
    )]
    ReducedFormBreakdown {
        /// Time of the evaluation.
        t: f64,
        /// Generalized coordinates.
        q: Vec<f64>,
        /// Their names.
        coordinates: Vec<&'static str>,
        /// The speeds and constraints in the dependency.
        rows: Vec<&'static str>,
        /// The largest pivot left over the first when elimination stopped.
        ratio: f64,
    },

    /// The integrator exceeded its step budget, the integrator's
    /// `.max_steps(n)` setting, before reaching the end time. A fixed-step
    /// method (RK4, Störmer–Verlet, Gauss, RATTLE) knows the count it needs
    /// before the first step and refuses the run at once, with `t` the start
    /// time; an adaptive one stops where the budget ran out.
    #[error("{}", too_many_steps(*t, *max_steps, *needed))]
    TooManySteps {
        /// Time reached (the start time when a fixed-step method refuses up
        /// front).
        t: f64,
        /// The configured budget (`.max_steps(n)`).
        max_steps: usize,
        /// The steps the run needs, when known before it starts (a fixed-step
        /// method: span / step, rounded up).
        needed: Option<usize>,
    },

    /// The Newton iteration for the stages of an implicit method did not
    /// converge within its iteration budget, even after the step was reduced (the
    /// adaptive methods) or at the given step (the fixed-step methods): the step is
    /// too large for the nonlinearity, or the system is singular there.
    #[error(
        "implicit stage equations did not converge at t = {t} with step h = {h:e} \
         after {iterations} Newton iterations; try a smaller step"
    )]
    NewtonFailure {
        /// Start of the failed step.
        t: f64,
        /// Its step size.
        h: f64,
        /// Newton iterations done in the last attempt.
        iterations: usize,
    },

    /// An event function returned NaN or an infinity.
    #[error("event function `{event}` is not finite at t = {t}, q = {q:?}, v = {v:?}")]
    EventFunction {
        /// The event's name (its own, or `event #k` by position).
        event: String,
        /// Time of the failed evaluation.
        t: f64,
        /// Generalized coordinates.
        q: Vec<f64>,
        /// Generalized velocities.
        v: Vec<f64>,
    },

    /// More events that restart the integration (actions) than the budget
    /// allows: usually impacts accumulating (Zeno behaviour, a ball coming to
    /// rest with restitution e < 1). Raise the budget, or model the resting
    /// contact as a constraint.
    #[error(
        "more than {max_events} events stopped the integration; the last one, \
         `{event}`, at t = {t} (impacts accumulating?)"
    )]
    TooManyEvents {
        /// Time of the last event.
        t: f64,
        /// Name of the last event.
        event: String,
        /// The configured budget.
        max_events: usize,
    },

    /// Events fired repeatedly without the integration advancing: an action
    /// that does not resolve its event (the state after it still crosses at
    /// once, e.g. an impact law that does not reverse the normal velocity), or
    /// impacts accumulating at round-off scale (Zeno point).
    #[error(
        "event `{event}` fired {count} times in a row at t = {t} without the \
         integration advancing: its action does not resolve the event, or \
         impacts accumulate there (Zeno point)"
    )]
    EventsAccumulate {
        /// Time where the events pile up.
        t: f64,
        /// Name of the event.
        event: String,
        /// Consecutive events without progress.
        count: usize,
    },

    /// A coordinate left its position limits (a URDF joint's `<limit>`, see
    /// [`Lagrangian::position_limits`](crate::Lagrangian::position_limits)):
    /// the run stops at the first point of the step's dense output on or past
    /// the limit, located by root finding. Limits are not yet contacts; turn the
    /// watch off with
    /// [`Simulation::joint_limits`](crate::Simulation::joint_limits)`(LimitPolicy::Ignore)`.
    #[error(
        "joint `{joint}` (coordinate {coordinate}) left its limits [{lower}, {upper}]: \
         {value} at t = {t}; the limits are watched, not enforced (turn the watch off \
         with `.joint_limits(LimitPolicy::Ignore)`)"
    )]
    JointLimit {
        /// The joint's name (its coordinate's).
        joint: &'static str,
        /// The coordinate's index in q.
        coordinate: usize,
        /// Its value at `t`: on the limit or just past it.
        value: f64,
        /// The lower limit.
        lower: f64,
        /// The upper limit.
        upper: f64,
        /// Time of the crossing.
        t: f64,
    },

    /// An orientation's quaternion in an initial state, an operating point,
    /// a configuration to evaluate at or an argument of the
    /// [`orientation`](crate::orientation) utilities is not a rotation: not
    /// finite, or its norm further from 1 than
    /// [`UNIT_TOLERANCE`](crate::numeric::orientation::UNIT_TOLERANCE) (within
    /// it, the quaternion is normalised silently).
    #[error(
        "the quaternion of `{orientation}` has norm {norm}, not 1 (within {tolerance} \
         it is normalised): give a unit quaternion (w, x, y, z), scalar first"
    )]
    NonUnitQuaternion {
        /// The orientation's name (its body), from the coordinates' names;
        /// for a lone quaternion, the argument's name (`q`, `q0`).
        orientation: String,
        /// The quaternion's norm (NaN if a component is not finite).
        norm: f64,
        /// The tolerance it missed.
        tolerance: f64,
    },

    /// An input (from a controller, an open-loop signal or a table) is NaN or
    /// infinite. Reported where it was computed, never passed on to the
    /// dynamics as a NaN force.
    #[error(
        "input `{input}` is not finite ({value}) at t = {t}, q = {q:?}, v = {v:?}; \
         the controller or input signal produced it"
    )]
    NonFiniteInput {
        /// Time of the evaluation (for a sampled controller, the sample instant).
        t: f64,
        /// The input's name (from [`Driven::INPUTS`](crate::Driven::INPUTS)); the
        /// first non-finite one.
        input: &'static str,
        /// Its value (NaN or ±∞).
        value: f64,
        /// Generalized coordinates the controller was given.
        q: Vec<f64>,
        /// Generalized velocities the controller was given.
        v: Vec<f64>,
    },

    /// A parameter gives the system a mass or an inertia no body has: a
    /// negative mass, a negative principal moment, principal moments that break
    /// the triangle inequality (A + B ≥ C, ...), or an inertia tensor whose
    /// second-moment matrix tr(I)/2·E − I is not positive semidefinite.
    /// Literal values are refused at compile time; values computed from the
    /// struct's fields are checked by [`Lagrangian::check_parameters`](crate::Lagrangian::check_parameters)
    /// before every run.
    #[error("non-physical parameters: `{body}`: {entry} = {value}: {reason}")]
    NonPhysicalParameter {
        /// The body (or point mass) whose mass or inertia is wrong, or the
        /// coordinate whose joint's `damping` or `armature` is.
        body: &'static str,
        /// Which entry: `mass`, a principal moment `A`, `B`, `C`, a tensor
        /// entry `Ixx`, `Iyy`, `Izz`, or `inertia tensor` for the tensor as a whole.
        entry: &'static str,
        /// The entry's value (for the tensor as a whole, the most negative
        /// eigenvalue of its second-moment matrix).
        value: f64,
        /// The rule broken, and what it means.
        reason: String,
    },

    /// A scene's pose is not finite: the position or rotation of a body or point
    /// at a sampled time is NaN or ∞ (a non-finite parameter, or a chart
    /// singularity of the description's rotation).
    #[error(
        "the scene's pose of `{name}` at t = {t} is not finite; check the parameters and the state there"
    )]
    NonFinitePose {
        /// Time of the sampled frame.
        t: f64,
        /// The body or point.
        name: String,
    },

    /// A body asked for by name or index that the system does not have
    /// ([`Posed::BODIES`](crate::Posed::BODIES)).
    #[error("the system has no body `{body}` (it has {count} bodies: {bodies:?})")]
    UnknownBody {
        /// The name asked for, or the index written out.
        body: String,
        /// How many bodies the system has.
        count: usize,
        /// Their names, in order.
        bodies: Vec<&'static str>,
    },

    /// Inverse kinematics stopped at its iteration limit with the frame
    /// still further from its target than the tolerance: an unreachable
    /// target (beyond the arm's reach, or outside the joint limits), or a
    /// start that leads into a singularity. The best iterate is in the
    /// [`Failure`]'s `partial`.
    #[error(
        "inverse kinematics of `{body}` did not converge in {iterations} iterations: \
         residual {residual:e} > tolerance {tolerance:e} (unreachable target, or a start \
         that leads into a singularity)"
    )]
    InverseKinematics {
        /// The frame's body.
        body: &'static str,
        /// The iterations made.
        iterations: usize,
        /// The smallest residual reached (the norm of the task error:
        /// metres and radians).
        residual: f64,
        /// The tolerance asked for.
        tolerance: f64,
    },

    /// A setting, the time span, the initial state or data given to a
    /// builder cannot be used (a negative tolerance, an empty span, a NaN
    /// initial state, an input table whose times go back, ...); see
    /// [`SettingsError`] for the cause.
    #[error("invalid settings: {0}")]
    Settings(#[from] SettingsError),

    /// A method the computation needs is not provided by the system (a trait
    /// method whose default returns `None`). Linearisation uses symbolic
    /// derivatives only, never silent finite differences: derive the system with
    /// `emit(jacobians)`, or implement the method by hand.
    #[error(
        "{needed_for} needs `{method}`, which this system does not provide; add \
         `emit(jacobians)` to its #[derive(Lagrangian)] (or implement `{method}` by hand)"
    )]
    MissingDerivatives {
        /// The trait method that returned `None`, e.g. `Lagrangian::rhs_jacobians`.
        method: &'static str,
        /// What needed it, e.g. `linearisation`.
        needed_for: &'static str,
    },

    /// Linearisation, eigen-analysis or LQR design failed; see
    /// [`LinearError`].
    #[error(transparent)]
    Linear(#[from] LinearError),

    /// Trajectory optimisation failed; see [`PlanError`].
    #[error(transparent)]
    Plan(#[from] PlanError),

    /// A contact run met a rigid-contact problem without an answer (or with
    /// many), or contacts it cannot use.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// Parameter identification failed; see [`IdentifyError`].
    #[error(transparent)]
    Identify(#[from] IdentifyError),

    /// Writing output (CSV) failed.
    #[error("i/o error: {0}")]
    Io(#[from] std::io::Error),
}

mod checks;
mod clone;
mod contact;
mod failure;
mod identify;
mod linear;
mod messages;
mod plan;
mod settings;
mod singular;

pub(crate) use checks::{check_finite_inputs, check_tolerance, unit_quaternions};
pub use contact::{ContactError, ContactFault};
pub use failure::{Failure, Progress};
pub use identify::IdentifyError;
pub use linear::{LinearError, StatePoint};
pub use plan::PlanError;
pub use settings::SettingsError;

use messages::{named, no_inertia, too_many_steps};

use crate::numeric::Real;

use nalgebra::SVector;

/// Converts a state vector to `f64`s for an error report.
pub(crate) fn to_vec<T: Real, const N: usize>(x: &SVector<T, N>) -> Vec<f64> {
    x.iter().map(|&c| c.to_f64()).collect()
}

impl Error {
    /// Whether the right-hand side failed because of the state it was evaluated
    /// at (a chart singularity, an overflow, dependent constraint rows there).
    /// An adaptive integrator that meets such a failure in a *trial* stage rejects
    /// the step and retries smaller: the trial state may be far off the solution
    /// (a stiff transient, an overshoot). If the step underflows the error is
    /// reported as it is, not as a step-size underflow.
    pub fn is_state_dependent(&self) -> bool {
        matches!(
            self,
            Error::SingularMassMatrix { .. }
                | Error::NonFiniteState { .. }
                | Error::RedundantConstraints { .. }
                | Error::ReducedFormBreakdown { .. }
        )
    }

    /// A [`Error::NonFiniteState`] for the given time and state.
    pub(crate) fn non_finite<T: Real, const N: usize, const Q: usize>(
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Self {
        Error::NonFiniteState {
            t: t.to_f64(),
            q: to_vec(q),
            v: to_vec(v),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_time_and_coordinates() {
        let e = Error::SingularMassMatrix {
            t: 0.5,
            q: vec![1e-9, 2.0],
            ratio: 1e-18,
            direction: "1.000 y".into(),
            atlas: false,
        };
        let s = e.to_string();
        assert!(s.contains("t = 0.5"), "{s}");
        assert!(s.contains("[1e-9, 2.0]"), "{s}");
        assert!(s.contains("1e-18"), "{s}");
        assert!(s.contains("no inertia along 1.000 y"), "{s}");
        assert!(!s.contains("run_atlas`, which"), "{s}");
        let e = Error::non_finite(
            1.5_f64,
            &SVector::<f64, 1>::new(f64::NAN),
            &SVector::<f64, 1>::new(0.0),
        );
        assert!(
            e.to_string().contains("t = 1.5, q = [NaN], v = [0.0]"),
            "{e}"
        );
        let e = Error::RedundantConstraints {
            t: 2.0,
            q: vec![0.5, -1.0],
            coordinates: vec!["x", "y"],
            ratio: 1e-17,
            dependent: vec!["rod2"],
        };
        let s = e.to_string();
        assert!(s.contains("t = 2, q = (x = 0.5, y = -1.0)"), "{s}");
        assert!(s.contains("[\"rod2\"]") && s.contains("1e-17"), "{s}");
        let e: Error = std::io::Error::other("disk full").into();
        assert!(e.to_string().contains("disk full"));
    }
}
