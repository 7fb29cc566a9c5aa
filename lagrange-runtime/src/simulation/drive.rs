//! The piecewise driver of a controlled run: one integrator run between
//! consecutive breaks of the source (sample instants, table breakpoints),
//! each with its inputs recorded at the stored points.

use super::ControlRun;
use crate::control::{InputForces, InputSource, check_input};
use crate::error::SettingsError;
use crate::error::{Error, Failure};
use crate::event::Occurrence;
use crate::event::within_budget;
use crate::event::{Events, LimitPolicy, Limited};
use crate::numeric::Real;
use crate::numeric::func::abs;
use crate::ode::{Continuation, Integrator, Sample, SecondOrder, Trajectory};
use crate::system::{Driven, JointLimit};
use nalgebra::SVector;
use std::ops::Range;

/// What a controlled run is driven by: the integrator, the system, the
/// source, the events and the watched limits (assembled by a controlled
/// run, or by one that reads them through other coordinates, as the atlas's).
pub(crate) struct Driver<'r, 'e, S, I, C, T: Real, const N: usize, const P: usize, const Q: usize> {
    pub integrator: &'r I,
    pub system: &'r S,
    pub source: &'r C,
    pub events: &'r Events<'e, T, N, Q>,
    /// The limits watched (none when they are ignored).
    pub limits: &'static [JointLimit],
}

impl<S, I, C, T, const N: usize, const P: usize, const Q: usize> Driver<'_, '_, S, I, C, T, N, P, Q>
where
    I: Integrator,
    T: Real,
    S: Driven<T, N, P, Q>,
    C: InputSource<T, N, P, Q>,
{
    /// Integrates piece by piece between the source's breaks (one piece when it
    /// has none), each piece with the dynamics `make` builds from its forcing.
    /// `prepare` checks the settings and gives the initial state to start from
    /// (projected, for the constrained forms). On a failure the run so far (the
    /// pieces, the failed piece's accepted steps, their inputs, the
    /// occurrences; the given initial state alone if none) goes back with the
    /// error.
    pub(crate) fn drive<'s, D: SecondOrder<T, N, Q>>(
        &'s self,
        make: impl Fn(InputForces<'s, S, Piece<'s, C, T, P>, P>) -> D,
        span: Range<T>,
        (q0, v0): (SVector<T, Q>, SVector<T, N>),
        prepare: impl FnOnce() -> Result<(SVector<T, Q>, SVector<T, N>), Error>,
    ) -> Result<ControlRun<T, N, P, Q>, Failure<ControlRun<T, N, P, Q>>> {
        let started = crate::numeric::clock::Stopwatch::start();
        let mut record = Record {
            whole: None,
            inputs: Vec::new(),
            occurrences: Vec::new(),
            terminated_by: None,
            from: Continuation::start(span.start),
        };
        let outcome =
            prepare().and_then(|(q, v)| self.pieces(&make, span.clone(), q, v, &mut record));
        let mut trajectory = match record.whole {
            Some(w) => w,
            None => {
                let rhs = make(InputForces::new(self.system, Piece::Live(self.source)));
                record.inputs = vec![self.source.input(span.start, &q0, &v0)];
                Trajectory::start(span.start, q0, v0, Sample::of(&rhs, span.start, &q0, &v0))
            }
        };
        let mut stats = *trajectory.stats();
        stats.wall_time = started.elapsed();
        trajectory.set_stats(stats);
        let run = ControlRun {
            trajectory,
            inputs: record.inputs,
            occurrences: record.occurrences,
            terminated_by: record.terminated_by,
            coordinates: S::COORDINATES,
            velocities: S::VELOCITIES,
            input_names: S::INPUTS,
            bounds: self.source.bounds(),
            speed_limits: self.source.speed_limits(),
        };
        match outcome {
            Ok(()) => Ok(run),
            Err(error) => Err(Failure::new(error, run)),
        }
    }

    /// The pieces of [`drive`](Self::drive), recorded into `record`.
    fn pieces<'s, D: SecondOrder<T, N, Q>>(
        &'s self,
        make: &impl Fn(InputForces<'s, S, Piece<'s, C, T, P>, P>) -> D,
        span: Range<T>,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        record: &mut Record<T, N, P, Q>,
    ) -> Result<(), Error> {
        self.source.check()?;
        let t0 = span.start;
        let t1 = span.end;
        self.check_budget(t0, t1)?;
        // Breaks within this of each other (or of t1) are one instant.
        let eps = T::lit(64.0) * T::default_epsilon() * (abs(t0) + abs(t1));
        let held = self.source.held();
        let mut ends_on_break = false;
        let mut t = t0;
        let mut q = q0;
        let mut v = v0;
        loop {
            let (end, on_break) = self.piece_end((t0, t1), t, eps);
            if let Some(on_break) = on_break {
                ends_on_break = on_break;
            }
            let source = if held {
                let u = self.source.input(t, &q, &v);
                check_input::<S, T, N, P, Q>(t, &q, &v, &u)?;
                Piece::Held(u, self.source)
            } else {
                Piece::Live(self.source)
            };
            let rhs = make(InputForces::new(self.system, source));
            let (piece, stop) = self.piece(&rhs, source, (t, end), (q, v), record)?;
            (q, v) = piece.final_state();
            let reached = *piece.times().last().expect("a trajectory holds its start");
            self.record(piece, source, record, true)?;
            if stop.is_some() {
                record.terminated_by = stop;
                break;
            }
            if end >= t1 {
                break;
            }
            let max_steps = self.integrator.max_steps();
            within_budget(record.whole.as_ref(), max_steps, reached)?;
            t = reached;
        }
        if held && ends_on_break && record.terminated_by.is_none() {
            self.sample_at_end(t1, record)?;
        }
        Ok(())
    }

    /// Where the piece starting at `t` ends: the source's next break, or t1.
    /// With a break at t1 (within `eps`), also whether the run ends on it.
    fn piece_end(&self, (t0, t1): (T, T), t: T, eps: T) -> (T, Option<bool>) {
        // A piece cut by an event a round-off before its end leaves t
        // just short of a break: that break is this instant.
        let mut next = self.source.next_break(t0, t);
        while let Some(b) = next
            && b - t <= eps
        {
            next = self.source.next_break(t0, b);
        }
        match next {
            Some(b) if b < t1 - eps => (b, None),
            Some(b) => (t1, Some(b <= t1 + eps)),
            None => (t1, None),
        }
    }

    /// Integrates one piece over `span` from `state`, watching the events if
    /// there are any: the piece and the terminal event that ended it. On a
    /// failure the failed piece's steps (and occurrences) are recorded.
    fn piece<D: SecondOrder<T, N, Q>>(
        &self,
        rhs: &D,
        source: Piece<'_, C, T, P>,
        (t, end): (T, T),
        (q, v): (SVector<T, Q>, SVector<T, N>),
        record: &mut Record<T, N, P, Q>,
    ) -> Result<(Trajectory<T, N, Q>, Option<usize>), Error> {
        let integrator = self.integrator;
        let from = record
            .whole
            .as_ref()
            .map_or(record.from, Trajectory::continuation);
        let limits = self.limits;
        if self.events.events().is_empty() {
            let rhs = Limited::new(rhs, limits, LimitPolicy::Stop);
            return match integrator.continue_run(&rhs, from, t, end, q, v) {
                Ok(piece) => Ok((piece, None)),
                Err(f) => {
                    self.record(*f.partial, source, record, false)?;
                    Err(f.error)
                }
            };
        }
        match self
            .events
            .continue_run(integrator, (rhs, limits), from, t, end, q, v)
        {
            Ok(run) => {
                record.occurrences.extend(run.occurrences);
                Ok((run.trajectory, run.terminated_by))
            }
            Err(f) => {
                record.occurrences.extend(f.partial.occurrences);
                self.record(f.partial.trajectory, source, record, false)?;
                Err(f.error)
            }
        }
    }

    /// The end time is a sample instant of a held source: records the new
    /// sample there.
    fn sample_at_end(&self, t1: T, record: &mut Record<T, N, P, Q>) -> Result<(), Error> {
        let trajectory = record
            .whole
            .as_ref()
            .expect("the loop integrates at least one piece");
        let (q, v) = trajectory.final_state();
        let u = self.source.input(t1, &q, &v);
        check_input::<S, T, N, P, Q>(t1, &q, &v, &u)?;
        *record.inputs.last_mut().expect("one input per point") = u;
        Ok(())
    }

    /// Refuses, before any work, a source with more breaks in the span than
    /// the integrator's step budget for the whole run: every piece between
    /// two breaks takes at least one step.
    fn check_budget(&self, t0: T, t1: T) -> Result<(), Error> {
        let max_steps = self.integrator.max_steps();
        match self.source.breaks_within(t0, t1) {
            Some(n) if n >= max_steps as f64 => Err(SettingsError::Budget {
                owner: "input source",
                what: "restarts the run (each piece at least one step)",
                asked: n,
                limit: max_steps as f64,
                start: t0.to_f64(),
                end: t1.to_f64(),
                advice: "the integrator's max_steps is the step budget of the whole run: \
                         sample less often, shorten the span, or raise .max_steps(n) on the \
                         integrator"
                    .into(),
            }
            .into()),
            _ => Ok(()),
        }
    }

    /// Appends a piece and the inputs at the points it adds (the piece's
    /// first point replaces the last one recorded, or a thinned recording
    /// drops both: see [`Trajectory::continuation`]). With `check` a
    /// non-finite input is the error (after the piece is recorded); a failed
    /// piece's inputs are recorded as they are.
    fn record(
        &self,
        piece: Trajectory<T, N, Q>,
        source: Piece<'_, C, T, P>,
        record: &mut Record<T, N, P, Q>,
        check: bool,
    ) -> Result<(), Error> {
        // The piece is recorded even when one of its inputs is refused: the
        // failure hands back everything computed, one input per point.
        let from = match &mut record.whole {
            Some(w) => w.append(piece),
            None => {
                record.whole = Some(piece);
                0
            }
        };
        let whole = record.whole.as_ref().expect("just recorded");
        record.inputs.truncate(from);
        record.inputs.reserve(whole.len() - from);
        let mut refused = Ok(());
        let points = whole.times().iter().zip(whole.positions());
        for ((&tk, qk), vk) in points.zip(whole.velocities()).skip(from) {
            // A held sample was checked when it was taken.
            let (u, live) = match source {
                Piece::Held(u, c) => (c.limit(tk, qk, vk, u), false),
                Piece::Live(_) => (self.source.input(tk, qk, vk), true),
            };
            if check && live && refused.is_ok() {
                refused = check_input::<S, T, N, P, Q>(tk, qk, vk, &u);
            }
            record.inputs.push(u);
        }
        refused
    }
}

/// A controlled run as it is recorded, piece by piece.
struct Record<T: Real, const N: usize, const P: usize, const Q: usize> {
    whole: Option<Trajectory<T, N, Q>>,
    inputs: Vec<SVector<T, P>>,
    occurrences: Vec<Occurrence<T, N, Q>>,
    terminated_by: Option<usize>,
    /// Where the recording starts (the grid's origin is the run's t0).
    from: Continuation<T>,
}

/// The source of one piece of a controlled run: a held sample or the source
/// itself.
#[derive(Debug)]
pub(crate) enum Piece<'c, C, T: Real, const P: usize> {
    /// A held sample, kept within what the source's actuators give at each
    /// state ([`InputSource::limit`]).
    Held(SVector<T, P>, &'c C),
    Live(&'c C),
}

impl<C, T: Real, const P: usize> Clone for Piece<'_, C, T, P> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<C, T: Real, const P: usize> Copy for Piece<'_, C, T, P> {}

impl<C, T, const N: usize, const P: usize, const Q: usize> InputSource<T, N, P, Q>
    for Piece<'_, C, T, P>
where
    T: Real,
    C: InputSource<T, N, P, Q>,
{
    #[inline]
    fn input(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P> {
        match self {
            Piece::Held(u, c) => c.limit(t, q, v, *u),
            Piece::Live(c) => c.input(t, q, v),
        }
    }
}
