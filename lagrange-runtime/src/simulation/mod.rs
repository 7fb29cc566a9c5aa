//! The user-facing entry point: system + integrator + initial state → trajectory.

mod atlas;
mod atlas_control;
mod controlled;
mod events;
mod form;

pub use controlled::{ControlRun, ControlledSimulation};
pub use events::EventSimulation;

use crate::error::{Error, Failure, Progress, check_tolerance, unit_quaternions};
use crate::event::{Event, Events, LimitPolicy, Limited};
use crate::mechanics::constraint::{
    ConstrainedDynamics, DEFAULT_CONSISTENCY_TOLERANCE, DEFAULT_REDUNDANT_TOLERANCE, Drift,
};
use crate::mechanics::dynamics::{DEFAULT_SINGULAR_TOLERANCE, Dynamics};
use crate::mechanics::reduced::ReducedDynamics;
use crate::numeric::Real;
use crate::ode::Trajectory;
use crate::ode::{Dopri5, Integrator, check_problem, failed_at_start};
use crate::system::{Constrained, Lagrangian, Reduced};
use nalgebra::SVector;
use std::ops::Range;

/// A configured simulation of a [`Lagrangian`] system.
///
/// ```
/// # use lagrange_runtime::{Lagrangian, Simulation, Dopri5, Rk4};
/// # use nalgebra::{SMatrix, SVector, Vector1, Matrix1};
/// # struct Pendulum;
/// # impl Lagrangian<f64, 1> for Pendulum {
/// #     const COORDINATES: [&'static str; 1] = ["theta"];
/// #     const RHEONOMIC: bool = false;
/// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
/// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
/// #     fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-q[0].sin()) }
/// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
/// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
/// #     }
/// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
/// #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { -q[0].cos() }
/// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
/// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
/// #     }
/// # }
/// let sys = Pendulum;
/// let traj = Simulation::new(&sys)
///     .integrator(Dopri5::tol(1e-10))
///     .run([1.0], [0.0], 0.0..10.0)?;
/// assert!(traj.integral_drift() < 1e-8);
///
/// let coarse = Simulation::new(&sys)
///     .integrator(Rk4::step(1e-2))
///     .singular_tolerance(1e-10)
///     .run([1.0], [0.0], 0.0..1.0)?;
/// assert_eq!(coarse.len(), 101);
/// # Ok::<(), lagrange_runtime::Error>(())
/// ```
///
/// Constrained systems run with [`run_constrained`](Self::run_constrained) (the
/// multiplier form) or [`run_reduced`](Self::run_reduced) (independent speeds);
/// the constraint settings ([`drift`](Self::drift),
/// [`least_squares`](Self::least_squares), ...) only affect those.
#[derive(Debug)]
pub struct Simulation<'a, S, I = Dopri5> {
    pub(crate) system: &'a S,
    pub(crate) integrator: I,
    singular_tolerance: f64,
    constraints: ConstraintSettings,
    pub(crate) limits: LimitPolicy,
}

/// The settings that only matter to [`Simulation::run_constrained`].
#[derive(Clone, Copy, Debug)]
struct ConstraintSettings {
    drift: Drift,
    least_squares: bool,
    redundant_tolerance: f64,
    consistency_tolerance: f64,
    project_initial: bool,
}

impl Default for ConstraintSettings {
    fn default() -> Self {
        Self {
            drift: Drift::None,
            least_squares: false,
            redundant_tolerance: DEFAULT_REDUNDANT_TOLERANCE,
            consistency_tolerance: DEFAULT_CONSISTENCY_TOLERANCE,
            project_initial: false,
        }
    }
}

impl<S, I: Clone> Clone for Simulation<'_, S, I> {
    fn clone(&self) -> Self {
        Self {
            system: self.system,
            integrator: self.integrator.clone(),
            singular_tolerance: self.singular_tolerance,
            constraints: self.constraints,
            limits: self.limits,
        }
    }
}

impl<'a, S> Simulation<'a, S> {
    /// A simulation of `system` with the default integrator ([`Dopri5::default`],
    /// tolerance 1e-8) and singular tolerance (1e-12).
    pub fn new(system: &'a S) -> Self {
        Self {
            system,
            integrator: Dopri5::default(),
            singular_tolerance: DEFAULT_SINGULAR_TOLERANCE,
            constraints: ConstraintSettings::default(),
            limits: LimitPolicy::Stop,
        }
    }
}

impl<'a, S, I: Integrator> Simulation<'a, S, I> {
    /// Chooses the integrator.
    pub fn integrator<J: Integrator>(self, integrator: J) -> Simulation<'a, S, J> {
        Simulation {
            system: self.system,
            integrator,
            singular_tolerance: self.singular_tolerance,
            constraints: self.constraints,
            limits: self.limits,
        }
    }

    /// Sets the threshold on the mass matrix's pivot ratio min L_ii² / max L_ii²
    /// below which the run stops with [`Error::SingularMassMatrix`].
    pub fn singular_tolerance(mut self, tolerance: f64) -> Self {
        self.singular_tolerance = tolerance;
        self
    }

    /// Whether the runs watch the system's position limits
    /// ([`Lagrangian::position_limits`]: a URDF robot's `<limit>`s): by
    /// default ([`LimitPolicy::Stop`]) a coordinate leaving its limits stops
    /// the run with [`Error::JointLimit`], located on the dense output;
    /// [`LimitPolicy::Ignore`] runs through them. Every run of this builder,
    /// with events or inputs too, follows it (the atlas runs do not watch
    /// limits yet); with events a limit is watched up to the step's first
    /// stopping event, so an event that acts at the limit (a bounce) comes
    /// first. The trajectory the [`Failure`] keeps ends at the last accepted
    /// step before the crossing; the error's `t` is the crossing.
    pub fn joint_limits(mut self, policy: LimitPolicy) -> Self {
        self.limits = policy;
        self
    }

    /// Chooses the drift control of [`run_constrained`](Self::run_constrained)
    /// (default [`Drift::None`]).
    pub fn drift(mut self, drift: Drift) -> Self {
        self.constraints.drift = drift;
        self
    }

    /// With `true`, redundant constraints are accepted with minimum-norm
    /// multipliers instead of stopping with [`Error::RedundantConstraints`].
    pub fn least_squares(mut self, on: bool) -> Self {
        self.constraints.least_squares = on;
        self
    }

    /// Sets the pivot ratio of G M⁻¹ Gᵀ below which constraints count as
    /// redundant (default 1e-12).
    pub fn redundant_tolerance(mut self, tolerance: f64) -> Self {
        self.constraints.redundant_tolerance = tolerance;
        self
    }

    /// Sets the absolute tolerance of the initial-condition check on max |Φ| and
    /// max |G q̇ + g| (default 1e-10).
    pub fn consistency_tolerance(mut self, tolerance: f64) -> Self {
        self.constraints.consistency_tolerance = tolerance;
        self
    }

    /// With `true`, [`run_constrained`](Self::run_constrained) projects an
    /// inconsistent initial state onto the constraints (with the projection
    /// settings of the drift control, or the defaults) instead of stopping with
    /// [`Error::InconsistentInitialConditions`].
    pub fn project_initial(mut self, on: bool) -> Self {
        self.constraints.project_initial = on;
        self
    }

    /// The forward dynamics this simulation integrates.
    pub fn dynamics<T: Real>(&self) -> Dynamics<'a, S, T> {
        Dynamics::new(self.system).with_singular_tolerance(T::lit(self.singular_tolerance))
    }

    /// The constrained forward dynamics [`run_constrained`](Self::run_constrained)
    /// integrates.
    pub fn constrained_dynamics<T: Real, const K: usize>(
        &self,
    ) -> ConstrainedDynamics<'a, S, T, K> {
        let c = &self.constraints;
        ConstrainedDynamics::new(self.system)
            .with_singular_tolerance(T::lit(self.singular_tolerance))
            .with_redundant_tolerance(T::lit(c.redundant_tolerance))
            .least_squares(c.least_squares)
            .drift(c.drift)
    }

    /// The reduced forward dynamics [`run_reduced`](Self::run_reduced) integrates.
    pub fn reduced_dynamics<T: Real, const K: usize>(&self) -> ReducedDynamics<'a, S, T, K> {
        ReducedDynamics::new(self.system).with_singular_tolerance(T::lit(self.singular_tolerance))
    }

    /// The unconstrained runs' checks: the system's parameters
    /// ([`Lagrangian::check_parameters`]) and the singular tolerance.
    pub(crate) fn check_singular_tolerance<T: Real, const N: usize, const Q: usize>(
        &self,
    ) -> Result<(), Error>
    where
        S: Lagrangian<T, N, Q>,
    {
        self.system.check_parameters()?;
        check_tolerance("singular tolerance", self.singular_tolerance)
    }

    pub(crate) fn check_tolerances(&self) -> Result<(), Error> {
        let c = &self.constraints;
        for (name, tol) in [
            ("singular tolerance", self.singular_tolerance),
            ("redundant tolerance", c.redundant_tolerance),
            ("consistency tolerance", c.consistency_tolerance),
        ] {
            check_tolerance(name, tol)?;
        }
        c.drift.check()
    }

    /// Integrates a [`Constrained`] system (multiplier form) from (q0, v0) at
    /// `span.start` to `span.end`, with the drift control chosen by
    /// [`drift`](Self::drift).
    ///
    /// The initial state must satisfy the constraints to the consistency tolerance
    /// at both levels; with [`project_initial`](Self::project_initial) it is
    /// projected onto them instead (the trajectory then starts at the projected
    /// state).
    ///
    /// # Errors
    /// [`Error::InvalidSettings`] for bad settings, time span or initial state;
    /// [`Error::InconsistentInitialConditions`]; [`Error::ProjectionFailed`];
    /// otherwise what the dynamics or the integrator report
    /// ([`Error::RedundantConstraints`], [`Error::SingularMassMatrix`],
    /// [`Error::NonFiniteState`], ...).
    pub fn run_constrained<T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>>
    where
        S: Constrained<T, N, K, Q>,
    {
        let (q0, v0) = (q0.into(), v0.into());
        let start =
            |e| failed_at_start(&self.constrained_dynamics::<T, K>(), span.start, q0, v0, e);
        check_problem(span.start, span.end, &q0, &v0).map_err(start)?;
        let (dynamics, q0, v0) = self
            .prepare_constrained::<T, N, K, Q>(span.start, q0, v0)
            .map_err(start)?;
        let terms = self.system.parameter_terms();
        let dynamics = dynamics.with_parameter_terms(&terms);
        let limited = Limited::new(&dynamics, self.system.position_limits(), self.limits);
        self.integrator
            .integrate(&limited, span.start, span.end, q0, v0)
    }

    /// The constrained dynamics and the checked (or projected) initial state.
    #[allow(clippy::type_complexity)]
    pub(crate) fn prepare_constrained<T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        t0: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<
        (
            ConstrainedDynamics<'a, S, T, K>,
            SVector<T, Q>,
            SVector<T, N>,
        ),
        Error,
    >
    where
        S: Constrained<T, N, K, Q>,
    {
        self.system.check_parameters()?;
        self.check_tolerances()?;
        let q0 = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q0)?;
        let dynamics = self.constrained_dynamics::<T, K>();
        let (q0, v0) = if self.constraints.project_initial {
            dynamics.consistent_state(t0, q0, v0)?
        } else {
            let tol = T::lit(self.constraints.consistency_tolerance);
            dynamics.check_consistency(t0, &q0, &v0, tol)?;
            (q0, v0)
        };
        Ok((dynamics, q0, v0))
    }

    /// Watches `event` during the run: the first of a list of events (add more
    /// with [`EventSimulation::event`]). The run then returns an [`EventRun`](crate::EventRun):
    /// the trajectory and the occurrences. See [`crate::event`] for how events
    /// are detected, located and acted on.
    ///
    /// The event's scalar and dimension are the system's, so the closures
    /// need no annotation to index the state (`q[0]`, `v[1]`); one that
    /// calls a method on a component (`q[1].cos()`) needs its scalar named
    /// once, see [`Event::new`].
    ///
    /// ```
    /// # use lagrange_runtime::{Event, SecondOrder, Lagrangian, Simulation, Dopri5};
    /// # use nalgebra::{SMatrix, SVector, Vector1, Matrix1};
    /// # struct Fall;
    /// # impl Lagrangian<f64, 1> for Fall {
    /// #     const COORDINATES: [&'static str; 1] = ["z"];
    /// #     const RHEONOMIC: bool = false;
    /// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
    /// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-9.81) }
    /// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
    /// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    /// #     }
    /// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
    /// #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { 9.81 * q[0] }
    /// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
    /// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    /// #     }
    /// # }
    /// // A ball dropped from 1 m bounces with restitution 0.9 (coming to rest
    /// // at 8.6 s); the apexes are where v falls through zero.
    /// let run = Simulation::new(&Fall)
    ///     .integrator(Dopri5::tol(1e-10))
    ///     .event(Event::new(|_, q, _| q[0]).falling().action(|_, _, v| *v *= -0.9))
    ///     .event(Event::new(|_, _, v| v[0]).falling())
    ///     .run([1.0], [0.0], 0.0..5.0)?;
    /// let bounces = run.times(0);
    /// assert!((bounces[0] - (2.0f64 / 9.81).sqrt()).abs() < 1e-12);
    /// assert_eq!(run.times(1).len(), bounces.len());
    /// # Ok::<(), lagrange_runtime::Error>(())
    /// ```
    pub fn event<'e, T: Real, const N: usize, const Q: usize>(
        self,
        event: Event<'e, T, N, Q>,
    ) -> EventSimulation<'a, 'e, S, I, T, N, Q>
    where
        S: Lagrangian<T, N, Q>,
    {
        EventSimulation {
            simulation: self,
            events: Events::new().with(event),
        }
    }

    /// Integrates a [`Reduced`] system (independent speeds) from (q0, v0) at
    /// `span.start` to `span.end`. v0 is first replaced by
    /// velocities(q0, speeds(q0, v0)), the admissible velocity with the same
    /// speeds (for speeds the macro picked, with the velocities the constraints
    /// leave free where those are fixed); after every step v is projected back
    /// onto the constraints keeping the velocities they leave free. With free
    /// orientations q0 holds their unit quaternions (scaled to unit norm
    /// first) and v0 their body-axis angular velocities; the quaternions are
    /// stepped on the group, as in [`run_constrained`](Self::run_constrained).
    ///
    /// # Errors
    /// [`Error::InvalidSettings`] for bad settings, time span or initial state;
    /// [`Error::NonUnitQuaternion`] for an initial quaternion off unit norm;
    /// otherwise what the dynamics or the integrator report
    /// ([`Error::SingularMassMatrix`] for a singular M*, [`Error::NonFiniteState`],
    /// ...).
    pub fn run_reduced<T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>>
    where
        S: Reduced<T, N, K, Q>,
    {
        let (q0, v0) = (q0.into(), v0.into());
        let terms = self.system.parameter_terms();
        let dynamics = self.reduced_dynamics::<T, K>().with_parameter_terms(&terms);
        let (q0, v0) = self
            .prepare_reduced(&dynamics, &span, q0, v0)
            .map_err(|e| failed_at_start(&dynamics, span.start, q0, v0, e))?;
        let limited = Limited::new(&dynamics, self.system.position_limits(), self.limits);
        self.integrator
            .integrate(&limited, span.start, span.end, q0, v0)
    }

    /// The checks of a reduced run and its initial state: q0 with its
    /// quaternions checked and scaled to unit norm, and the admissible
    /// velocities with the speeds of `v0`.
    pub(crate) fn prepare_reduced<T: Real, const N: usize, const K: usize, const Q: usize, F>(
        &self,
        dynamics: &ReducedDynamics<'_, S, T, K, F>,
        span: &Range<T>,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<(SVector<T, Q>, SVector<T, N>), Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        self.system.check_parameters()?;
        self.check_tolerances()?;
        check_problem(span.start, span.end, &q0, &v0)?;
        let q0 = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q0)?;
        let v0 = dynamics.consistent_velocities(span.start, &q0, &v0)?;
        Ok((q0, v0))
    }

    /// Integrates from (q0, v0) at `span.start` to `span.end`, in the form the
    /// system's description asked for: the unconstrained dynamics, or for a
    /// constrained `#[derive(Lagrangian)]` system the multiplier form (with this
    /// simulation's drift control and consistency checks) or, when only that
    /// is emitted, the reduced form. [`run_constrained`](Self::run_constrained)
    /// and [`run_reduced`](Self::run_reduced) choose a form explicitly.
    ///
    /// # Errors
    /// A [`Failure`] with the error and the steps before it:
    /// [`Error::InvalidSettings`] for a bad singular tolerance, integrator
    /// setting, time span or initial state; otherwise whatever the dynamics or
    /// the integrator report ([`Error::SingularMassMatrix`],
    /// [`Error::NonFiniteState`], [`Error::StepSizeUnderflow`],
    /// [`Error::TooManySteps`]; for constrained systems those of
    /// [`run_constrained`](Self::run_constrained)).
    pub fn run<T: Real, const N: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>>
    where
        S: Lagrangian<T, N, Q>,
    {
        let start = form::Start {
            builder: self,
            q0: q0.into(),
            v0: v0.into(),
            span,
        };
        self.system.visit_form(start)
    }

    /// The unconstrained dynamics, whatever the system (a constrained one is
    /// refused at compile time: its constraints would be ignored). What `run`
    /// does for a system without constraints.
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn run_unconstrained<T: Real, const N: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>>
    where
        S: Lagrangian<T, N, Q>,
    {
        let (q0, v0) = (q0.into(), v0.into());
        let terms = self.system.parameter_terms();
        let dynamics = self.dynamics().with_parameter_terms(&terms);
        self.check_singular_tolerance::<T, N, Q>()
            .map_err(|e| failed_at_start(&dynamics, span.start, q0, v0, e))?;
        let q0 = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q0)
            .map_err(|e| failed_at_start(&dynamics, span.start, q0, v0, e))?;
        let limited = Limited::new(&dynamics, self.system.position_limits(), self.limits);
        self.integrator
            .integrate(&limited, span.start, span.end, q0, v0)
    }
}

impl<T: Real, const N: usize, const Q: usize> Progress for Trajectory<T, N, Q> {
    fn progress(&self) -> (usize, Option<f64>) {
        (self.len(), self.times().last().map(|t| t.to_f64()))
    }
}
