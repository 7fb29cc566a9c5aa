//! The driver of a run with events: the list of events and its budget, and
//! the integrator's runs from one stopping event to the next.

use super::watch::{Stop, Watch};
use super::{Event, EventRun, Occurrence};
use crate::error::SettingsError;
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::func::abs;
use crate::ode::{Continuation, Integrator, Sample, SecondOrder, Trajectory, check_problem};
use nalgebra::SVector;

/// A list of events and the budget of restarts, ready to drive any
/// [`Integrator`] on any [`SecondOrder`] system ([`Simulation::event`] builds
/// one for a [`Lagrangian`](crate::Lagrangian) system).
///
/// [`Simulation::event`]: crate::Simulation::event
#[derive(Debug)]
pub struct Events<'a, T: Real, const N: usize, const Q: usize = N> {
    pub(super) events: Vec<Event<'a, T, N, Q>>,
    pub(super) max_events: usize,
}

impl<T: Real, const N: usize, const Q: usize> Default for Events<'_, T, N, Q> {
    fn default() -> Self {
        Self::new()
    }
}

/// Default budget of events that stop the integration (actions and the
/// terminal one).
pub const DEFAULT_MAX_EVENTS: usize = 10_000;

impl<'a, T: Real, const N: usize, const Q: usize> Events<'a, T, N, Q> {
    /// No events yet; budget [`DEFAULT_MAX_EVENTS`].
    pub fn new() -> Self {
        Self {
            events: Vec::new(),
            max_events: DEFAULT_MAX_EVENTS,
        }
    }

    /// Adds an event; its index in occurrences is the number added before it.
    pub fn with(mut self, event: Event<'a, T, N, Q>) -> Self {
        self.events.push(event);
        self
    }

    /// Sets how many events may stop and restart the integration before the
    /// run ends with [`Error::TooManyEvents`] (default [`DEFAULT_MAX_EVENTS`]).
    pub fn max_events(mut self, n: usize) -> Self {
        self.max_events = n;
        self
    }

    /// The events, in order.
    pub fn events(&self) -> &[Event<'a, T, N, Q>] {
        &self.events
    }

    /// Integrates `rhs` with `integrator` from (q0, v0) at t0 to t1 (or to a
    /// terminal event), watching the events.
    ///
    /// A crossing exactly at t0 (g(t0) = 0) is not an event: the sign is taken
    /// from the first step.
    ///
    /// # Errors
    /// [`Error::Settings`] for a zero event budget or a bad span or
    /// initial state; [`Error::EventFunction`] if an event function is not
    /// finite; [`Error::NonFiniteState`] if an action produces a non-finite
    /// state; [`Error::TooManyEvents`], [`Error::EventsAccumulate`]; whatever
    /// the integrator and the system report.
    pub fn integrate<I: Integrator, F: SecondOrder<T, N, Q>>(
        &self,
        integrator: &I,
        rhs: &F,
        t0: T,
        t1: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<EventRun<T, N, Q>, Failure<EventRun<T, N, Q>>> {
        let from = Continuation::start(t0);
        self.continue_run(integrator, (rhs, &[]), from, t0, t1, q0, v0)
    }

    /// [`integrate`](Self::integrate) as the next piece of a run whose
    /// recording stands at `from` (see [`Integrator::continue_run`]), watching
    /// `limits` too (up to each step's first stopping event).
    ///
    /// # Errors
    /// As [`integrate`](Self::integrate).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn continue_run<I: Integrator, F: SecondOrder<T, N, Q>>(
        &self,
        integrator: &I,
        (rhs, limits): (&F, &'static [crate::system::JointLimit]),
        from: Continuation<T>,
        t0: T,
        t1: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<EventRun<T, N, Q>, Failure<EventRun<T, N, Q>>> {
        let started = crate::numeric::clock::Stopwatch::start();
        let watch = Watch::new(rhs, &self.events, limits);
        // Everything computed before a failure (the pieces so far, the failed
        // piece's accepted steps, the occurrences) goes back with it.
        let mut so_far = SoFar {
            trajectory: None,
            terminated_by: None,
            from,
        };
        let outcome = self.pieces(integrator, &watch, (t0, t1), q0, v0, &mut so_far);
        let mut trajectory = so_far
            .trajectory
            .unwrap_or_else(|| Trajectory::start(t0, q0, v0, Sample::of(rhs, t0, &q0, &v0)));
        let mut stats = *trajectory.stats();
        stats.wall_time = started.elapsed();
        trajectory.set_stats(stats);
        let run = EventRun {
            trajectory,
            occurrences: watch.into_occurrences(),
            terminated_by: so_far.terminated_by,
        };
        match outcome {
            Ok(()) => Ok(run),
            Err(error) => Err(Failure::new(error, run)),
        }
    }

    /// The integrator's runs from stop to stop, joined into `so_far`: each
    /// ends at t1 or at a stopping event, whose action is applied before the
    /// next run starts from the new state.
    fn pieces<I: Integrator, F: SecondOrder<T, N, Q>>(
        &self,
        integrator: &I,
        watch: &Watch<'_, 'a, F, T, N, Q>,
        (t0, t1): (T, T),
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        so_far: &mut SoFar<T, N, Q>,
    ) -> Result<(), Error> {
        check_problem(t0, t1, &q0, &v0)?;
        if self.max_events == 0 {
            let setting = "max_events";
            return Err(SettingsError::ZeroCount {
                owner: "events",
                setting,
            }
            .into());
        }
        watch.reset(t0, &q0, &v0, None)?;
        // Two restarts closer than this are "no progress".
        let stalled_within = T::lit(64.0) * T::default_epsilon() * (abs(t0) + abs(t1));
        let mut t = t0;
        let mut q = q0;
        let mut v = v0;
        let mut restarts = 0usize;
        let mut stalled = 0usize;
        loop {
            let from = so_far.continuation();
            let piece = match integrator.continue_run(watch, from, t, t1, q, v) {
                Ok(piece) => piece,
                Err(failure) => {
                    join(&mut so_far.trajectory, *failure.partial);
                    return Err(failure.error);
                }
            };
            let Some(stop) = watch.take_stop() else {
                join(&mut so_far.trajectory, piece);
                break;
            };
            let event = &self.events[stop.event];
            let (qa, va) = self.act(watch, &stop, piece, so_far)?;
            if event.ends(stop.t, &qa, &va) {
                so_far.terminated_by = Some(stop.event);
                break;
            }
            restarts += 1;
            within_budget(so_far.trajectory.as_ref(), integrator.max_steps(), stop.t)?;
            stalled = if stop.t - t <= stalled_within {
                stalled + 1
            } else {
                0
            };
            self.check_progress(&stop, restarts, stalled)?;
            // An event on the end time (up to round-off) leaves nothing to
            // integrate: a restart would only fail on a vanishing step.
            if t1 - stop.t <= stalled_within {
                break;
            }
            // Past the surface the fired event's sign is already the new one.
            let fired = (!event.lands_past()).then_some((stop.event, stop.before));
            watch.reset(stop.t, &qa, &va, fired)?;
            (t, q, v) = (stop.t, qa, va);
        }
        Ok(())
    }

    /// Applies the stopping event's action (if any) at the stop, projects the
    /// new state onto the constraints, cuts `piece` there, joins it and records
    /// the occurrence. Returns the state after the action.
    fn act<F: SecondOrder<T, N, Q>>(
        &self,
        watch: &Watch<'_, 'a, F, T, N, Q>,
        stop: &Stop<T, N, Q>,
        mut piece: Trajectory<T, N, Q>,
        so_far: &mut SoFar<T, N, Q>,
    ) -> Result<(SVector<T, Q>, SVector<T, N>), Error> {
        let rhs = watch.rhs;
        let mut qa = stop.q;
        let mut va = stop.v;
        if let Some(action) = &self.events[stop.event].action {
            action(stop.t, &mut qa, &mut va);
            if !qa.iter().chain(va.iter()).all(|x| x.is_finite()) {
                join(&mut so_far.trajectory, piece);
                return Err(Error::non_finite(stop.t, &qa, &va));
            }
            // An action may leave a quaternion off the unit sphere.
            crate::ode::settle(rhs, stop.t, &mut qa, &mut va)?;
        }
        piece.truncate_last(stop.t, qa, va, Sample::of(rhs, stop.t, &qa, &va));
        join(&mut so_far.trajectory, piece);
        watch.record(Occurrence {
            event: stop.event,
            t: stop.t,
            q: stop.q,
            v: stop.v,
            q_after: qa,
            v_after: va,
        });
        Ok((qa, va))
    }

    /// Refuses a restart past the event budget, or the third in a row without
    /// the integration advancing.
    fn check_progress(
        &self,
        stop: &Stop<T, N, Q>,
        restarts: usize,
        stalled: usize,
    ) -> Result<(), Error> {
        let event = &self.events[stop.event];
        if restarts > self.max_events {
            return Err(Error::TooManyEvents {
                t: stop.t.to_f64(),
                event: event.label(stop.event),
                max_events: self.max_events,
            });
        }
        if stalled >= 3 {
            return Err(Error::EventsAccumulate {
                t: stop.t.to_f64(),
                event: event.label(stop.event),
                count: stalled,
            });
        }
        Ok(())
    }
}

/// What an event run has computed so far.
struct SoFar<T: Real, const N: usize, const Q: usize> {
    trajectory: Option<Trajectory<T, N, Q>>,
    terminated_by: Option<usize>,
    /// Where the recording stood when the run started.
    from: Continuation<T>,
}

impl<T: Real, const N: usize, const Q: usize> SoFar<T, N, Q> {
    /// Where the next piece's recording goes on from.
    fn continuation(&self) -> Continuation<T> {
        self.trajectory
            .as_ref()
            .map_or(self.from, Trajectory::continuation)
    }
}

/// Refuses to go on once the pieces so far have spent the integrator's step
/// budget, which bounds the whole run (each piece alone stays within it, so a
/// run ends within two budgets however many pieces it has).
pub(crate) fn within_budget<T: Real, const N: usize, const Q: usize>(
    so_far: Option<&Trajectory<T, N, Q>>,
    max_steps: usize,
    t: T,
) -> Result<(), Error> {
    match so_far {
        Some(whole) if whole.stats().steps() >= max_steps => Err(Error::TooManySteps {
            t: t.to_f64(),
            max_steps,
            needed: None,
        }),
        _ => Ok(()),
    }
}

fn join<T: Real, const N: usize, const Q: usize>(
    whole: &mut Option<Trajectory<T, N, Q>>,
    piece: Trajectory<T, N, Q>,
) {
    match whole {
        Some(w) => {
            w.append(piece);
        }
        None => *whole = Some(piece),
    }
}
