//! What every integration does around its method: record the accepted steps,
//! count the work, and end with the trajectory or with a failure that carries
//! the trajectory up to the last accepted step.
//!
//! [`Run`] holds that bookkeeping, so that an integrator's file holds only its
//! stages and its own decisions; [`fixed_steps`] is the step sequence of the
//! fixed-step methods.

use super::{Continuation, DenseSegment, Record, Sample, SecondOrder, Stats, Trajectory};
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::clock::Stopwatch;
use nalgebra::SVector;

/// One integration in progress: the trajectory recorded so far, the work done,
/// and the clock started with it.
pub(crate) struct Run<T: Real, const N: usize, const Q: usize = N> {
    pub traj: Trajectory<T, N, Q>,
    pub stats: Stats,
    started: Stopwatch,
}

impl<T: Real, const N: usize, const Q: usize> Run<T, N, Q> {
    /// Starts the clock and records the initial state with `sample`, going on
    /// from the recording `from`.
    pub fn start(
        record: Record,
        from: Continuation<T>,
        t0: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        sample: Sample<T>,
    ) -> Self {
        let started = Stopwatch::start();
        Self {
            traj: Trajectory::start_recording(record, from, t0, q0, v0, sample),
            stats: Stats::default(),
            started,
        }
    }

    /// [`start`](Self::start) with the initial state sampled from `rhs`.
    pub fn of<F: SecondOrder<T, N, Q>>(
        record: Record,
        from: Continuation<T>,
        rhs: &F,
        t0: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Self {
        Self::start(record, from, t0, q0, v0, Sample::of(rhs, t0, &q0, &v0))
    }

    /// Records an accepted step: `segment` its dense output, (q, v) the state
    /// at its end (after any projection). The system's
    /// [`after_step`](SecondOrder::after_step) sees the step first; its answer,
    /// whether the run stops here, is returned.
    pub fn record<F: SecondOrder<T, N, Q>>(
        &mut self,
        rhs: &F,
        segment: DenseSegment<T, N, Q>,
        q: SVector<T, Q>,
        v: SVector<T, N>,
    ) -> Result<bool, Error> {
        // The event layer reads the segment too: normalised quaternions there.
        let segment = segment.with_orientations(F::ORIENTATIONS);
        let stop = rhs.after_step(&segment, &q, &v)?;
        self.push(rhs, segment, q, v);
        Ok(stop)
    }

    /// Stores a step without asking [`after_step`](SecondOrder::after_step),
    /// sampling the recorded points from `rhs`.
    pub fn push<F: SecondOrder<T, N, Q>>(
        &mut self,
        rhs: &F,
        segment: DenseSegment<T, N, Q>,
        q: SVector<T, Q>,
        v: SVector<T, N>,
    ) {
        let segment = segment.with_orientations(F::ORIENTATIONS);
        self.traj
            .push_sampled(segment, q, v, |t, q, v| Sample::of(rhs, t, q, v));
    }

    /// The end of the run: the trajectory, or the failure with it as the
    /// partial result; the statistics (with the wall time) are set either way.
    pub fn finish(
        mut self,
        outcome: Result<(), Error>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>> {
        self.stats.wall_time = self.started.elapsed();
        self.traj.set_stats(self.stats);
        match outcome {
            Ok(()) => Ok(self.traj),
            Err(error) => Err(Failure::new(error, self.traj)),
        }
    }
}
/// The `n` fixed steps from t0 to t1 as (start, end) pairs: step k ends at
/// t0 + k·h, computed from k rather than accumulated, so that a step chosen as
/// T/n lands on T up to one rounding; the last one ends exactly at t1.
pub(crate) fn fixed_steps<T: Real>(t0: T, t1: T, h: T, n: usize) -> impl Iterator<Item = (T, T)> {
    let end = move |k: usize| {
        if k == n {
            t1
        } else {
            t0 + h * T::lit(k as f64)
        }
    };
    (1..=n).map(move |k| (if k == 1 { t0 } else { end(k - 1) }, end(k)))
}
