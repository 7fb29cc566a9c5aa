//! [`Simulation::run_atlas`]: a system written in Euler angles, run through
//! every orientation by switching charts; what each of the builder's options
//! makes of it ([`AtlasRuns`]). The controlled run is in `atlas_control`.

use super::Simulation;
use super::formulation::checked_start;
use super::options::{NoEvents, Unforced};
use crate::atlas::{self, AtlasRun};
use crate::error::{Error, Failure};
use crate::event::{Event, Events};
use crate::numeric::Real;
use crate::ode::{Integrator, Sample, Trajectory};
use crate::system::Atlas;
use nalgebra::SVector;
use std::ops::Range;

impl<S, I: Integrator, C, E> Simulation<'_, S, I, C, E> {
    /// Runs a system that has an atlas (`emit(atlas)`) from (q0, v0), given in
    /// the user's coordinates, through every orientation: each Euler-angle
    /// rotation moves to its second chart when its own degrades and comes back
    /// when it can (see [`crate::atlas`]). [`run`](Self::run) on the same
    /// system stays in the user's chart and stops at its singular set with
    /// [`Error::SingularMassMatrix`](crate::Error::SingularMassMatrix): that is the opt-out.
    ///
    /// On the singular set itself (θ = 0 of z-x-z) the initial rates still
    /// fix ω = E q̇ (e.g. ψ̇ + φ̇ is the spin about the axis), which the
    /// second chart takes over exactly.
    ///
    /// With events ([`event`](Self::event)) each event's function, terminal
    /// test and action read the user's coordinates: while a rotation is in
    /// its second chart they are its user's angles nearest those it had when
    /// it left the user's chart, and their rates E⁻¹ ω, as
    /// [`AtlasRun::user_state`] reads them, so an event on an angle is the
    /// same function in every chart. On the user's singular set itself the
    /// angles' rates are not defined and read NaN (an event function that
    /// reads them there stops the run with
    /// [`Error::EventFunction`](crate::Error::EventFunction)). An action's
    /// state goes back into the charts of the moment, then into regular
    /// ones. The occurrences ([`AtlasRun::occurrences`]) hold the user's
    /// coordinates; the switches are not among them
    /// ([`AtlasRun::switches`]). The switches restart the integration as
    /// actions do, so the budget of [`max_events`](Self::max_events) is not
    /// applied here.
    ///
    /// With an input source ([`feedback`](Self::feedback) and the others) the
    /// source sees the user's coordinates too, so a controller written for
    /// the user's description runs unchanged, and one that reads only the
    /// angles, or no state, is smooth through the user's singular set. The
    /// rates of the first and last angle grow as 1/s near that set (s the
    /// conditioning, |cos θ| for yaw–pitch–roll) and on the set itself read
    /// NaN: a controller that passes them on stops the run with
    /// [`Error::NonFiniteInput`](crate::Error::NonFiniteInput). In the second
    /// chart the inputs' generalized forces are the free twin's
    /// ([`DrivenAtlas`](crate::DrivenAtlas)), the same forces in its
    /// coordinates; the recorded inputs ([`AtlasRun::inputs`]) are the
    /// source's at each point.
    ///
    /// A system with constraints, holonomic or nonholonomic (a ball rolling
    /// without slipping), runs in the multiplier form in every chart (the
    /// twin carries the same rows): (q0, v0) must satisfy them to the
    /// [`consistency_tolerance`](Self::consistency_tolerance), and no drift
    /// control is applied.
    ///
    /// # Errors
    /// As [`run`](Self::run); [`Error::Settings`](crate::Error::Settings) also for an [`Atlas`]
    /// whose free twin does not have the documented layout, and for a
    /// constrained system with [`drift`](Self::drift) control or
    /// [`least_squares`](Self::least_squares);
    /// [`Error::InconsistentInitialConditions`](crate::Error::InconsistentInitialConditions).
    pub fn run_atlas<T: Real, const N: usize, const F: usize>(
        &self,
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<AtlasRunOf<Self, T, N, F>, Failure<AtlasRunOf<Self, T, N, F>>>
    where
        Self: AtlasRuns<T, N, F>,
    {
        self.run_through_charts(q0.into(), v0.into(), span)
    }

    /// The checks of every atlas run, before the first step: the settings,
    /// the system's parameters, the span and initial state, the constraints
    /// at the start (and that the constraint settings are ones the atlas
    /// applies), and the twin's layout.
    pub(super) fn atlas_checks<T: Real, const N: usize, const F: usize>(
        &self,
        span: &Range<T>,
        q0: &SVector<T, N>,
        v0: &SVector<T, N>,
    ) -> Result<(), Error>
    where
        S: Atlas<T, N, F>,
    {
        checked_start(self.system, &self.settings, span, *q0, v0)?;
        let s = &self.settings;
        let consistency = s.tolerances.consistency;
        let state = (q0, v0);
        atlas::check_start::<S, T, N, F>(
            self.system,
            span.start,
            state,
            consistency,
            s.drift,
            s.least_squares,
        )?;
        if !atlas::layout_agrees(self.system) {
            return Err(atlas::layout_error());
        }
        Ok(())
    }

    /// An atlas run without inputs, watching the user's events `user`.
    fn atlas_with<T: Real, const N: usize, const F: usize>(
        &self,
        user: &[Event<'_, T, N>],
        q0: SVector<T, N>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<AtlasRun<T, N>, Failure<AtlasRun<T, N>>>
    where
        S: Atlas<T, N, F>,
    {
        let terms = self.system.parameter_terms();
        let dynamics = self.dynamics().with_parameter_terms(&terms);
        if let Err(error) = self.atlas_checks::<T, N, F>(&span, &q0, &v0) {
            let sample = Sample::of(&dynamics, span.start, &q0, &v0);
            let trajectory = Trajectory::start(span.start, q0, v0, sample);
            let run = atlas::unstarted(trajectory, Vec::new(), S::EULER);
            return Err(Failure::new(error, run));
        }
        let span = (span.start, span.end);
        atlas::integrate(&self.integrator, dynamics, user, span, q0, v0)
    }
}

/// What an atlas run of the builder `B` returns (see [`AtlasRuns`]).
pub type AtlasRunOf<B, T, const N: usize, const F: usize> = <B as AtlasRuns<T, N, F>>::Output;

/// What a [`Simulation::run_atlas`] with these options returns: an
/// [`AtlasRun`], with the inputs when a source drives it. Implemented for
/// every combination of the option slots; not meant to be implemented
/// elsewhere.
#[diagnostic::on_unimplemented(
    message = "`run_atlas` needs a system with an atlas whose options fit it",
    label = "needs `emit(atlas)` (and, with an input source, the system's inputs)",
    note = "add `emit(atlas)` to a description written in Euler angles (`rotation(..)`); with an input source the twin must be driven too (`DrivenAtlas`), which `inputs(..)` with `emit(atlas)` emits"
)]
pub trait AtlasRuns<T: Real, const N: usize, const F: usize> {
    /// The run's result.
    type Output;

    /// Runs through the charts from (q0, v0) over `span`.
    #[doc(hidden)]
    fn run_through_charts(
        &self,
        q0: SVector<T, N>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<Self::Output, Failure<Self::Output>>;
}

impl<S, I, T, const N: usize, const F: usize> AtlasRuns<T, N, F>
    for Simulation<'_, S, I, Unforced, NoEvents>
where
    S: Atlas<T, N, F>,
    I: Integrator,
    T: Real,
{
    type Output = AtlasRun<T, N>;

    fn run_through_charts(
        &self,
        q0: SVector<T, N>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<Self::Output, Failure<Self::Output>> {
        self.atlas_with::<T, N, F>(&[], q0, v0, span)
    }
}

impl<'e, S, I, T, const N: usize, const F: usize> AtlasRuns<T, N, F>
    for Simulation<'_, S, I, Unforced, Events<'e, T, N>>
where
    S: Atlas<T, N, F>,
    I: Integrator,
    T: Real,
{
    type Output = AtlasRun<T, N>;

    fn run_through_charts(
        &self,
        q0: SVector<T, N>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<Self::Output, Failure<Self::Output>> {
        self.atlas_with::<T, N, F>(self.events.events(), q0, v0, span)
    }
}
