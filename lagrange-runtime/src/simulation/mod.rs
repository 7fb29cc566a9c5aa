//! The user-facing entry point: system + integrator + options + initial state
//! → a run.
//!
//! One builder, [`Simulation`], whose options compose (`options`): events,
//! an input source, the tolerances and constraint settings, the joint limits.
//! A run takes a formulation (`formulation`: the unconstrained, multiplier or
//! reduced dynamics, each with its checks of the start) and hands it to what
//! the options make of a run (`kind`: the integrator alone, the event driver,
//! or the piecewise driver of a controlled run, `drive`). The atlas's runs
//! (`atlas`, `atlas_control`) switch Euler charts on the way.

mod atlas;
mod atlas_control;
mod contacts;
mod control_run;
mod drive;
mod form;
mod formulation;
mod kind;
mod options;

pub use atlas::{AtlasRunOf, AtlasRuns};
pub use control_run::ControlRun;
pub use kind::Runs;
#[allow(deprecated)]
pub use options::{Control, ControlledSimulation, EventSimulation, NoEvents, Unforced};

use crate::contact::{Compliant, ContactSettings};
use crate::error::{Error, Failure, Progress};
use crate::event::LimitPolicy;
use crate::mechanics::Tolerances;
use crate::mechanics::constraint::{ConstrainedDynamics, Drift};
use crate::mechanics::dynamics::Dynamics;
use crate::mechanics::reduced::ReducedDynamics;
use crate::numeric::Real;
use crate::ode::Dopri5;
use crate::ode::{Integrator, Trajectory};
use crate::system::{Constrained, Lagrangian, Reduced};
use formulation::{Multipliers, Speeds, Unconstrained};
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
/// # One builder, options that compose
///
/// Every run starts here, and the options compose in any order:
///
/// - the integrator ([`integrator`](Self::integrator)) and the tolerances
///   ([`tolerances`](Self::tolerances), [`singular_tolerance`](Self::singular_tolerance), ...);
/// - the constraint settings ([`drift`](Self::drift),
///   [`least_squares`](Self::least_squares), [`project_initial`](Self::project_initial));
/// - events ([`event`](Self::event), [`max_events`](Self::max_events)): the
///   run then returns an [`EventRun`](crate::EventRun);
/// - an input source ([`feedback`](Self::feedback), [`sampled`](Self::sampled),
///   [`open_loop`](Self::open_loop), [`control`](Self::control)): the run then
///   returns a [`ControlRun`], with the events' occurrences if there are any;
/// - the joint limits ([`joint_limits`](Self::joint_limits)).
///
/// and there is one run per formulation: [`run`](Self::run) takes it from the
/// system's description (unconstrained, or the multiplier form, or the
/// reduced form when only that is emitted);
/// [`run_unconstrained`](Self::run_unconstrained),
/// [`run_constrained`](Self::run_constrained) (multipliers) and
/// [`run_reduced`](Self::run_reduced) (independent speeds) name it; and
/// [`run_atlas`](Self::run_atlas) runs a system written in Euler angles
/// through every orientation. Every run checks its settings and its initial
/// state in the same place before the first step, and a failure hands back
/// what was computed before it ([`Failure`]).
#[derive(Debug)]
pub struct Simulation<'a, S, I = Dopri5, C = Unforced, E = NoEvents> {
    pub(crate) system: &'a S,
    pub(crate) integrator: I,
    pub(crate) settings: Settings,
    pub(crate) control: C,
    pub(crate) events: E,
}

/// The settings every run reads, whatever its options: checked in one place
/// ([`check`](Self::check)) before the first step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    pub tolerances: Tolerances,
    pub drift: Drift,
    pub least_squares: bool,
    pub project_initial: bool,
    pub limits: LimitPolicy,
    pub contacts: ContactSettings,
    pub compliant: Option<Compliant>,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            tolerances: Tolerances::default(),
            drift: Drift::None,
            least_squares: false,
            project_initial: false,
            limits: LimitPolicy::Stop,
            contacts: ContactSettings::default(),
            compliant: None,
        }
    }
}

impl Settings {
    /// The tolerances and the drift control's own settings.
    pub(crate) fn check(&self) -> Result<(), Error> {
        self.tolerances.check()?;
        self.drift.check()
    }
}

impl<S, I: Clone, C: Clone, E: Clone> Clone for Simulation<'_, S, I, C, E> {
    fn clone(&self) -> Self {
        Self {
            system: self.system,
            integrator: self.integrator.clone(),
            settings: self.settings,
            control: self.control.clone(),
            events: self.events.clone(),
        }
    }
}

impl<'a, S> Simulation<'a, S> {
    /// A simulation of `system` with the default integrator ([`Dopri5::default`],
    /// tolerance 1e-8), the default [`Tolerances`], no events and no inputs.
    pub fn new(system: &'a S) -> Self {
        Self {
            system,
            integrator: Dopri5::default(),
            settings: Settings::default(),
            control: Unforced,
            events: NoEvents,
        }
    }
}

impl<'a, S, I, C, E> Simulation<'a, S, I, C, E> {
    /// Chooses the integrator.
    pub fn integrator<J: Integrator>(self, integrator: J) -> Simulation<'a, S, J, C, E> {
        Simulation {
            system: self.system,
            integrator,
            settings: self.settings,
            control: self.control,
            events: self.events,
        }
    }

    /// Sets every tolerance at once: the same [`Tolerances`] a
    /// [`Linearizer`](crate::linear::Linearizer) takes, so that both judge
    /// singularity, redundancy and consistency at the same thresholds.
    pub fn tolerances(mut self, tolerances: Tolerances) -> Self {
        self.settings.tolerances = tolerances;
        self
    }

    /// Sets the threshold on the mass matrix's pivot ratio min L_ii² / max L_ii²
    /// below which the run stops with [`Error::SingularMassMatrix`]
    /// ([`Tolerances::singular`]).
    pub fn singular_tolerance(mut self, tolerance: f64) -> Self {
        self.settings.tolerances.singular = tolerance;
        self
    }

    /// Sets the pivot ratio of G M⁻¹ Gᵀ below which constraints count as
    /// redundant ([`Tolerances::redundant`], default 1e-12).
    pub fn redundant_tolerance(mut self, tolerance: f64) -> Self {
        self.settings.tolerances.redundant = tolerance;
        self
    }

    /// Sets the absolute tolerance of the initial-condition check on max |Φ| and
    /// max |G q̇ + g| ([`Tolerances::consistency`], default 1e-10).
    pub fn consistency_tolerance(mut self, tolerance: f64) -> Self {
        self.settings.tolerances.consistency = tolerance;
        self
    }

    /// Whether the runs watch the system's position limits
    /// ([`Lagrangian::position_limits`]: a URDF robot's `<limit>`s): by
    /// default ([`LimitPolicy::Stop`]) a coordinate leaving its limits stops
    /// the run with [`Error::JointLimit`], located on the dense output;
    /// [`LimitPolicy::Ignore`] runs through them. Every run follows it, with
    /// events or inputs too (the atlas runs do not watch limits yet); with
    /// events a limit is watched up to the step's first stopping event, so
    /// an event that acts at the limit (a bounce) comes first. The trajectory
    /// the [`Failure`] keeps ends at the last accepted step before the
    /// crossing; the error's `t` is the crossing.
    pub fn joint_limits(mut self, policy: LimitPolicy) -> Self {
        self.settings.limits = policy;
        self
    }

    /// Sets the thresholds of [`run_contacts`](Self::run_contacts): the rest
    /// speed below which bounces end, the stick speed, the gap tolerance and
    /// the budget of changes ([`ContactSettings`]).
    pub fn contact_settings(mut self, settings: ContactSettings) -> Self {
        self.settings.contacts = settings;
        self
    }

    /// Makes [`run_contacts`](Self::run_contacts) treat every contact as
    /// compliant ([`Compliant`]): a spring and damper along its normal while
    /// it is sunk, with friction regularised at low slip, integrated by
    /// this simulation's integrator as one smooth motion, without events.
    /// The damping matches each contact's restitution on an isolated impact.
    pub fn compliant_contacts(mut self, model: Compliant) -> Self {
        self.settings.compliant = Some(model);
        self
    }

    /// Chooses the drift control of [`run_constrained`](Self::run_constrained)
    /// (default [`Drift::None`]).
    pub fn drift(mut self, drift: Drift) -> Self {
        self.settings.drift = drift;
        self
    }

    /// With `true`, redundant constraints are accepted with minimum-norm
    /// multipliers instead of stopping with [`Error::RedundantConstraints`].
    pub fn least_squares(mut self, on: bool) -> Self {
        self.settings.least_squares = on;
        self
    }

    /// With `true`, [`run_constrained`](Self::run_constrained) projects an
    /// inconsistent initial state onto the constraints (with the projection
    /// settings of the drift control, or the defaults) instead of stopping with
    /// [`Error::InconsistentInitialConditions`].
    pub fn project_initial(mut self, on: bool) -> Self {
        self.settings.project_initial = on;
        self
    }

    /// The forward dynamics this simulation integrates.
    pub fn dynamics<T: Real>(&self) -> Dynamics<'a, S, T> {
        Dynamics::new(self.system)
            .with_singular_tolerance(T::lit(self.settings.tolerances.singular))
    }

    /// The constrained forward dynamics [`run_constrained`](Self::run_constrained)
    /// integrates.
    pub fn constrained_dynamics<T: Real, const K: usize>(
        &self,
    ) -> ConstrainedDynamics<'a, S, T, K> {
        let s = &self.settings;
        ConstrainedDynamics::new(self.system)
            .with_singular_tolerance(T::lit(s.tolerances.singular))
            .with_redundant_tolerance(T::lit(s.tolerances.redundant))
            .least_squares(s.least_squares)
            .drift(s.drift)
    }

    /// The reduced forward dynamics [`run_reduced`](Self::run_reduced) integrates.
    pub fn reduced_dynamics<T: Real, const K: usize>(&self) -> ReducedDynamics<'a, S, T, K> {
        ReducedDynamics::new(self.system)
            .with_singular_tolerance(T::lit(self.settings.tolerances.singular))
    }
}

impl<S, I: Integrator, C, E> Simulation<'_, S, I, C, E> {
    /// Integrates from (q0, v0) at `span.start` to `span.end`, in the form the
    /// system's description asked for: the unconstrained dynamics, or for a
    /// constrained `#[derive(Lagrangian)]` system the multiplier form (with this
    /// simulation's drift control and consistency checks) or, when only that
    /// is emitted, the reduced form. [`run_constrained`](Self::run_constrained)
    /// and [`run_reduced`](Self::run_reduced) choose a form explicitly.
    ///
    /// What it returns depends on the options: a [`Trajectory`]; with events
    /// an [`EventRun`](crate::EventRun); with an input source a [`ControlRun`].
    ///
    /// # Errors
    /// A [`Failure`] with the error and what was computed before it:
    /// [`Error::Settings`] for a bad tolerance, integrator setting,
    /// time span or initial state; [`Error::NonUnitQuaternion`] for an
    /// initial quaternion off unit norm; otherwise whatever the dynamics,
    /// the events, the inputs or the integrator report
    /// ([`Error::SingularMassMatrix`], [`Error::NonFiniteState`],
    /// [`Error::StepSizeUnderflow`], [`Error::TooManySteps`],
    /// [`Error::NonFiniteInput`], [`Error::JointLimit`]; for constrained
    /// systems those of [`run_constrained`](Self::run_constrained)).
    pub fn run<T: Real, const N: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Run<Self, T, N, Q>, Failure<Run<Self, T, N, Q>>>
    where
        S: Lagrangian<T, N, Q>,
        Self: Runs<T, N, Q>,
    {
        let start = form::Start {
            builder: self,
            q0: q0.into(),
            v0: v0.into(),
            span,
        };
        self.system.visit_form(start)
    }

    /// [`run`](Self::run) with the unconstrained dynamics, whatever the system
    /// (a constrained one is refused at compile time: its constraints would be
    /// ignored).
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn run_unconstrained<T: Real, const N: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Run<Self, T, N, Q>, Failure<Run<Self, T, N, Q>>>
    where
        S: Lagrangian<T, N, Q>,
        Self: Runs<T, N, Q>,
    {
        let terms = self.system.parameter_terms();
        let form = Unconstrained {
            settings: &self.settings,
            dynamics: self.dynamics().with_parameter_terms(&terms),
        };
        self.run_form(&form, q0.into(), v0.into(), span)
    }

    /// Integrates a [`Constrained`] system in the multiplier form, with the
    /// drift control chosen by [`drift`](Self::drift).
    ///
    /// The initial state must satisfy the constraints to the consistency
    /// tolerance at both levels; with [`project_initial`](Self::project_initial)
    /// it is projected onto them instead (the run then starts at the projected
    /// state). With events, the state after an action is projected onto the
    /// constraints if the drift control projects; with inputs, they add to
    /// the forces before the multipliers are solved for.
    ///
    /// # Errors
    /// As [`run`](Self::run); [`Error::InconsistentInitialConditions`];
    /// [`Error::ProjectionFailed`]; [`Error::RedundantConstraints`].
    pub fn run_constrained<T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Run<Self, T, N, Q>, Failure<Run<Self, T, N, Q>>>
    where
        S: Constrained<T, N, K, Q>,
        Self: Runs<T, N, Q>,
    {
        let terms = self.system.parameter_terms();
        let form = Multipliers {
            settings: &self.settings,
            dynamics: self
                .constrained_dynamics::<T, K>()
                .with_parameter_terms(&terms),
        };
        self.run_form(&form, q0.into(), v0.into(), span)
    }

    /// Integrates a [`Reduced`] system (independent speeds). v0 is first
    /// replaced by velocities(q0, speeds(q0, v0)), the admissible velocity
    /// with the same speeds (for speeds the macro picked, with the velocities
    /// the constraints leave free where those are fixed); after every step,
    /// and after an event's action, v is rebuilt from the speeds. With free
    /// orientations q0 holds their unit quaternions (scaled to unit norm
    /// first) and v0 their body-axis angular velocities; the quaternions are
    /// stepped on the group, as in [`run_constrained`](Self::run_constrained).
    /// With inputs, F* gains Wᵀ ΔQ.
    ///
    /// # Errors
    /// As [`run`](Self::run) ([`Error::SingularMassMatrix`] for a singular M*).
    pub fn run_reduced<T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Run<Self, T, N, Q>, Failure<Run<Self, T, N, Q>>>
    where
        S: Reduced<T, N, K, Q>,
        Self: Runs<T, N, Q>,
    {
        let terms = self.system.parameter_terms();
        let form = Speeds {
            settings: &self.settings,
            dynamics: self.reduced_dynamics::<T, K>().with_parameter_terms(&terms),
        };
        self.run_form(&form, q0.into(), v0.into(), span)
    }
}

/// What a run of the builder `B` returns: a [`Trajectory`], an
/// [`EventRun`](crate::EventRun) or a [`ControlRun`] (see [`Runs`]).
pub type Run<B, T, const N: usize, const Q: usize> = <B as Runs<T, N, Q>>::Output;

impl<T: Real, const N: usize, const Q: usize> Progress for Trajectory<T, N, Q> {
    fn progress(&self) -> (usize, Option<f64>) {
        (self.len(), self.times().last().map(|t| t.to_f64()))
    }
}
