//! [`Simulation::run_atlas`]: a system written in Euler angles, run through
//! every orientation by switching charts; with events
//! ([`EventSimulation::run_atlas`]) and with inputs
//! ([`ControlledSimulation::run_atlas`](super::ControlledSimulation::run_atlas),
//! in `atlas_control`).

use super::{EventSimulation, Simulation};
use crate::atlas::{self, AtlasRun};
use crate::error::{Failure, check_tolerance};
use crate::event::Event;
use crate::numeric::Real;
use crate::ode::{Integrator, Sample, Trajectory, check_problem};
use crate::system::Atlas;
use nalgebra::SVector;
use std::ops::Range;

impl<S, I: Integrator> Simulation<'_, S, I> {
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
    /// With events ([`Simulation::event`], then
    /// [`EventSimulation::run_atlas`]) and with inputs
    /// ([`Simulation::feedback`] and the other controls, then
    /// [`ControlledSimulation::run_atlas`](crate::ControlledSimulation::run_atlas))
    /// the events and the controller read the user's coordinates.
    ///
    /// A system with constraints, holonomic or nonholonomic (a ball rolling
    /// without slipping), runs in the multiplier form in every chart (the
    /// twin carries the same rows): (q0, v0) must satisfy them to the
    /// [`consistency_tolerance`](Self::consistency_tolerance), and no drift
    /// control is applied.
    ///
    /// # Errors
    /// As [`run`](Self::run); [`Error::InvalidSettings`](crate::Error::InvalidSettings) also for an [`Atlas`]
    /// whose free twin does not have the documented layout, and for a
    /// constrained system with [`drift`](Self::drift) control or
    /// [`least_squares`](Self::least_squares);
    /// [`Error::InconsistentInitialConditions`](crate::Error::InconsistentInitialConditions).
    pub fn run_atlas<T: Real, const N: usize, const F: usize>(
        &self,
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<AtlasRun<T, N>, Failure<AtlasRun<T, N>>>
    where
        S: Atlas<T, N, F>,
    {
        self.atlas_with::<T, N, F>(&[], q0.into(), v0.into(), span)
    }

    /// [`run_atlas`](Self::run_atlas) watching the user's events `user`.
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
        let c = &self.constraints;
        let (tolerance, settings) = (
            c.consistency_tolerance,
            (c.consistency_tolerance, c.drift, c.least_squares),
        );
        let checked = self
            .check_singular_tolerance::<T, N, N>()
            .and_then(|()| check_problem(span.start, span.end, &q0, &v0))
            .and_then(|()| check_tolerance("consistency tolerance", tolerance))
            .and_then(|()| {
                atlas::check_start::<S, T, N, F>(self.system, span.start, (&q0, &v0), settings)
            });
        if let Err(error) = checked {
            let sample = Sample::of(&dynamics, span.start, &q0, &v0);
            let trajectory = Trajectory::start(span.start, q0, v0, sample);
            let run = atlas::unstarted(trajectory, Vec::new(), S::EULER);
            return Err(Failure::new(error, run));
        }
        let span = (span.start, span.end);
        atlas::integrate(&self.integrator, dynamics, user, span, q0, v0)
    }
}

impl<S, I: Integrator, T: Real, const N: usize> EventSimulation<'_, '_, S, I, T, N> {
    /// [`Simulation::run_atlas`] watching the events: each event's function,
    /// terminal test and action read the user's coordinates. While a
    /// rotation is in its second chart they are its user's angles nearest
    /// those it had when it left the user's chart, and their rates
    /// E⁻¹ ω, as [`AtlasRun::user_state`] reads them: an event on an angle
    /// is the same function in every chart, located on the dense output of
    /// the chart of the moment to the same tolerance as in
    /// [`run`](Self::run). On the user's singular set itself the angles'
    /// rates are not defined and read NaN (an event function that reads
    /// them there stops the run with
    /// [`Error::EventFunction`](crate::Error::EventFunction)). An action's
    /// state goes back into the charts of the moment, then into regular
    /// ones. The occurrences ([`AtlasRun::occurrences`]) hold the user's
    /// coordinates; the switches are not among them
    /// ([`AtlasRun::switches`]). The switches restart the integration as
    /// actions do, so the budget of [`max_events`](Self::max_events) is not
    /// applied here.
    ///
    /// # Errors
    /// As [`Simulation::run_atlas`] and [`Events::integrate`](crate::Events::integrate).
    pub fn run_atlas<const F: usize>(
        &self,
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<AtlasRun<T, N>, Failure<AtlasRun<T, N>>>
    where
        S: Atlas<T, N, F>,
    {
        let user = self.events.events();
        (self.simulation).atlas_with::<T, N, F>(user, q0.into(), v0.into(), span)
    }
}
