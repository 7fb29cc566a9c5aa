//! [`EventSimulation`]: a [`Simulation`] that watches events.

use super::{Simulation, form};
use crate::error::{Failure, unit_quaternions};
use crate::event::{Event, EventRun, Events, watched};
use crate::numeric::Real;
use crate::ode::{Continuation, Integrator, check_problem, failed_at_start};
use crate::system::{Constrained, Lagrangian, Reduced};
use nalgebra::SVector;
use std::ops::Range;

/// A [`Simulation`] with events, built by [`Simulation::event`].
#[derive(Debug)]
pub struct EventSimulation<'a, 'e, S, I, T: Real, const N: usize, const Q: usize = N> {
    pub(super) simulation: Simulation<'a, S, I>,
    pub(super) events: Events<'e, T, N, Q>,
}

impl<'a, 'e, S, I: Integrator, T: Real, const N: usize, const Q: usize>
    EventSimulation<'a, 'e, S, I, T, N, Q>
{
    /// Adds another event; occurrences name events by the order they were added
    /// (the first one, given to [`Simulation::event`], is 0).
    pub fn event(mut self, event: Event<'e, T, N, Q>) -> Self {
        self.events = self.events.with(event);
        self
    }

    /// Sets how many events may stop and restart the integration (default
    /// [`DEFAULT_MAX_EVENTS`](crate::event::DEFAULT_MAX_EVENTS)).
    pub fn max_events(mut self, n: usize) -> Self {
        self.events = self.events.max_events(n);
        self
    }

    /// The simulation without its events.
    pub fn simulation(&self) -> &Simulation<'a, S, I> {
        &self.simulation
    }

    /// [`Simulation::run`] watching the events: in the form the system's
    /// description asked for, like [`Simulation::run`].
    ///
    /// # Errors
    /// As [`Simulation::run`] and [`Events::integrate`].
    pub fn run(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<EventRun<T, N, Q>, Failure<EventRun<T, N, Q>>>
    where
        S: Lagrangian<T, N, Q>,
    {
        let start = form::Start {
            builder: self,
            q0: q0.into(),
            v0: v0.into(),
            span,
        };
        self.simulation.system.visit_form(start)
    }

    /// [`run`](Self::run) with the unconstrained dynamics (refused at compile
    /// time for a constrained system).
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn run_unconstrained(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<EventRun<T, N, Q>, Failure<EventRun<T, N, Q>>>
    where
        S: Lagrangian<T, N, Q>,
    {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let terms = sim.system.parameter_terms();
        let dynamics = sim.dynamics().with_parameter_terms(&terms);
        let failed = |e| failed_at_start(&dynamics, span.start, q0, v0, e).map(EventRun::unstarted);
        sim.check_singular_tolerance::<T, N, Q>().map_err(failed)?;
        let q0 = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q0).map_err(failed)?;
        let limits = watched(sim.system.position_limits(), sim.limits);
        let from = Continuation::start(span.start);
        self.events.continue_run(
            &sim.integrator,
            (&dynamics, limits),
            from,
            span.start,
            span.end,
            q0,
            v0,
        )
    }

    /// [`Simulation::run_constrained`] watching the events; after an action
    /// the state is projected onto the constraints if the drift control
    /// projects.
    ///
    /// # Errors
    /// As [`Simulation::run_constrained`] and [`Events::integrate`].
    pub fn run_constrained<const K: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<EventRun<T, N, Q>, Failure<EventRun<T, N, Q>>>
    where
        S: Constrained<T, N, K, Q>,
    {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let start = |e| {
            let dynamics = sim.constrained_dynamics::<T, K>();
            failed_at_start(&dynamics, span.start, q0, v0, e).map(EventRun::unstarted)
        };
        check_problem(span.start, span.end, &q0, &v0).map_err(start)?;
        let (dynamics, q0, v0) = sim
            .prepare_constrained::<T, N, K, Q>(span.start, q0, v0)
            .map_err(start)?;
        let terms = sim.system.parameter_terms();
        let dynamics = dynamics.with_parameter_terms(&terms);
        let limits = watched(sim.system.position_limits(), sim.limits);
        let from = Continuation::start(span.start);
        self.events.continue_run(
            &sim.integrator,
            (&dynamics, limits),
            from,
            span.start,
            span.end,
            q0,
            v0,
        )
    }

    /// [`Simulation::run_reduced`] watching the events; after an action the
    /// velocities are rebuilt from the speeds, so that the state satisfies the
    /// velocity constraints again.
    ///
    /// # Errors
    /// As [`Simulation::run_reduced`] and [`Events::integrate`].
    pub fn run_reduced<const K: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<EventRun<T, N, Q>, Failure<EventRun<T, N, Q>>>
    where
        S: Reduced<T, N, K, Q>,
    {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let terms = sim.system.parameter_terms();
        let dynamics = sim.reduced_dynamics::<T, K>().with_parameter_terms(&terms);
        let (q0, v0) = sim.prepare_reduced(&dynamics, &span, q0, v0).map_err(|e| {
            failed_at_start(&dynamics, span.start, q0, v0, e).map(EventRun::unstarted)
        })?;
        let limits = watched(sim.system.position_limits(), sim.limits);
        let from = Continuation::start(span.start);
        self.events.continue_run(
            &sim.integrator,
            (&dynamics, limits),
            from,
            span.start,
            span.end,
            q0,
            v0,
        )
    }
}
