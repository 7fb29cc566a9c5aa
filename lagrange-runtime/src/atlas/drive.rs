//! A run through the atlas: the switching events beside the user's, and
//! the record of the run as an [`AtlasRun`].

use super::{Charted, Charts, LEAVE_BELOW, RETURN_ABOVE, user_view};
use crate::error::{Error, Failure};
use crate::event::{BackFn, Event, Events, Occurrence, ViewFn};
use crate::mechanics::Dynamics;
use crate::numeric::Real;
use crate::ode::{Integrator, Sample, Trajectory};
use crate::system::{Atlas, EulerRotation};
use nalgebra::SVector;

use super::run::{AtlasRun, ChartSwitch};

/// The event that moves rotation k out of its chart of the moment when that
/// chart degrades: g is the margin left before the threshold, falling
/// through zero.
pub(crate) fn switching<'e, T: Real, const N: usize>(
    charts: &'e Charts<T>,
    k: usize,
    body: &str,
) -> Event<'e, T, N> {
    let in_second = move || charts.mask() >> k & 1 == 1;
    Event::new(move |_, q: &SVector<T, N>, _: &SVector<T, N>| {
        let s = charts.user_conditioning(k, q);
        if in_second() {
            T::lit(RETURN_ABOVE) - s
        } else {
            s - T::lit(LEAVE_BELOW)
        }
    })
    .falling()
    .action(move |t, q, v| {
        // The map cannot fail away from the target chart's singular set,
        // which the thresholds keep far off; if it did, the non-finite
        // state ends the run with a typed error.
        if charts.switch(t, k, q, v).is_err() {
            q.fill(T::lit(f64::NAN));
        }
    })
    .named(format!("chart switch of {body}"))
}

/// A state given in the user's coordinates after an event's action, back
/// in the charts of time t (nearest the angles `held` before the action),
/// then in regular charts: what a user's event's action hands the run.
pub(crate) fn back_to_charts<T: Real, const N: usize>(
    charts: &Charts<T>,
    t: T,
    held: &SVector<T, N>,
    q: &mut SVector<T, N>,
    v: &mut SVector<T, N>,
) {
    charts.user_to_charts(t, held, q, v);
    if charts.settle(t, q, v).is_err() {
        q.fill(T::lit(f64::NAN));
    }
}

/// The user's events, read on the user's coordinates through `into` (their
/// actions mapped back through `back`), then one switching event per
/// rotation: event k of the user's is event k here, the switches follow.
/// The switches restart the integration like actions, so the budget of
/// stopping events is not applied (accumulating user events still end the
/// run with [`Error::EventsAccumulate`]).
pub(crate) fn watched<'v, T: Real, const N: usize>(
    user: &'v [Event<'_, T, N>],
    charts: &'v Charts<T>,
    rotations: &'static [EulerRotation],
    into: ViewFn<'v, T, N>,
    back: BackFn<'v, T, N>,
) -> Events<'v, T, N> {
    let events = (user.iter()).fold(Events::new().max_events(usize::MAX >> 8), |events, e| {
        events.with(e.viewed(into, back))
    });
    (rotations.iter().enumerate()).fold(events, |events, (k, r)| {
        events.with(switching(charts, k, r.body))
    })
}

/// What a run through the atlas computed, in the charts it held.
pub(crate) struct Held<T: Real, const N: usize, const P: usize> {
    pub trajectory: Trajectory<T, N>,
    pub inputs: Vec<SVector<T, P>>,
    pub input_names: [&'static str; P],
    /// Every occurrence, the switches' included.
    pub occurrences: Vec<Occurrence<T, N>>,
    pub terminated_by: Option<usize>,
}

/// The run as an [`AtlasRun`]: the switches from `charts`' record, each
/// point's charts, the first `user` events' occurrences in the user's
/// coordinates.
pub(crate) fn finish<T: Real, const N: usize, const P: usize>(
    held: Held<T, N, P>,
    charts: &Charts<T>,
    rotations: &'static [EulerRotation],
    user: usize,
) -> AtlasRun<T, N, P> {
    let log = charts.log();
    let start = charts.start();
    let mut mask = start;
    let switches: Vec<ChartSwitch<T>> = (log.iter())
        .map(|s| {
            mask ^= 1 << s.rotation;
            ChartSwitch {
                t: s.t,
                rotation: s.rotation,
                to_second: mask >> s.rotation & 1 == 1,
            }
        })
        .collect();
    let points = (held.trajectory.times().iter()).map(|&t| charts.mask_at(t));
    let view = |mask: u64, t: T, q: &SVector<T, N>, v: &SVector<T, N>| {
        user_view(rotations, mask, |k| charts.near_at(t, k), q, v)
    };
    let occurrences = (held.occurrences.into_iter())
        .filter(|o| o.event < user)
        .map(|o| {
            let (q, v) = view(charts.mask_before(o.t), o.t, &o.q, &o.v);
            let (q_after, v_after) = view(charts.mask_at(o.t), o.t, &o.q_after, &o.v_after);
            Occurrence {
                q,
                v,
                q_after,
                v_after,
                ..o
            }
        })
        .collect();
    AtlasRun {
        charts: points.collect(),
        trajectory: held.trajectory,
        switches,
        rotations,
        start,
        near: log.iter().map(|s| s.near).collect(),
        start_near: charts.start_near(),
        inputs: held.inputs,
        input_names: held.input_names,
        occurrences,
        terminated_by: held.terminated_by.filter(|&e| e < user),
    }
}

/// A run that stopped before its first step, in the user's charts.
pub(crate) fn unstarted<T: Real, const N: usize, const P: usize>(
    trajectory: Trajectory<T, N>,
    inputs: Vec<SVector<T, P>>,
    rotations: &'static [EulerRotation],
) -> AtlasRun<T, N, P> {
    let held = Held {
        trajectory,
        inputs,
        input_names: [""; P],
        occurrences: Vec::new(),
        terminated_by: None,
    };
    finish(held, &Charts::new(rotations), rotations, 0)
}

/// Integrates `dynamics` from (q0, v0) in the user's charts over [t0, t1],
/// switching charts as the rotations go, watching the user's events `user`
/// on the user's coordinates.
///
/// The caller has checked the start (the twin's layout among it).
///
/// # Errors
/// Whatever the integrator, the events and the dynamics report.
pub(crate) fn integrate<S, T, I, const N: usize, const F: usize>(
    integrator: &I,
    dynamics: Dynamics<'_, S, T>,
    user: &[Event<'_, T, N>],
    (t0, t1): (T, T),
    q0: SVector<T, N>,
    v0: SVector<T, N>,
) -> Result<AtlasRun<T, N>, Failure<AtlasRun<T, N>>>
where
    S: Atlas<T, N, F>,
    T: Real,
    I: Integrator,
{
    let charts = Charts::new(S::EULER);
    let charted = Charted::<S, T, N, F>::new(dynamics, &charts);
    let unstarted = |error: Error, q: SVector<T, N>, v: SVector<T, N>| {
        let trajectory = Trajectory::start(t0, q, v, Sample::of(&charted, t0, &q, &v));
        Failure::new(error, unstarted(trajectory, Vec::new(), S::EULER))
    };
    let mut q = q0;
    let mut v = v0;
    if let Err(e) = charts.enter_regular(t0, &mut q, &mut v) {
        return Err(unstarted(e, q0, v0));
    }
    let into = |t, q: &SVector<T, N>, v: &SVector<T, N>| charts.user_view(t, q, v);
    let back = |t, held: &SVector<T, N>, q: &mut SVector<T, N>, v: &mut SVector<T, N>| {
        back_to_charts(&charts, t, held, q, v)
    };
    let events = watched(user, &charts, S::EULER, &into, &back);
    let held = |run: crate::event::EventRun<T, N>| Held {
        trajectory: run.trajectory,
        inputs: Vec::new(),
        input_names: [],
        occurrences: run.occurrences,
        terminated_by: run.terminated_by,
    };
    match events.integrate(integrator, &charted, t0, t1, q, v) {
        Ok(run) => Ok(finish(held(run), &charts, S::EULER, user.len())),
        Err(f) => Err(f.map(|run| finish(held(run), &charts, S::EULER, user.len()))),
    }
}
