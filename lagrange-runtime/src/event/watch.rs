//! The event observer: the system seen through the events, which samples
//! every event function after each accepted step and locates the crossings
//! on the step's dense output.

use super::{Event, Occurrence};
use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::func::abs;
use crate::numeric::root::brent_bracket;
use crate::ode::{DenseSegment, Mechanical, SecondOrder};
use crate::system::JointLimit;
use nalgebra::{SMatrix, SVector};
use std::cell::RefCell;

/// The event occurrence that ends an integrator's run.
#[derive(Clone, Copy)]
pub(super) struct Stop<T: Real, const N: usize, const Q: usize> {
    pub event: usize,
    pub t: T,
    pub q: SVector<T, Q>,
    pub v: SVector<T, N>,
    /// The event function's value on the old side of the crossing.
    pub before: T,
}

struct WatchState<T: Real, const N: usize, const Q: usize> {
    /// Each event function at the last recorded state; zero means "sign not
    /// known yet" (exactly zero there), and the next sample sets it.
    last: Vec<T>,
    /// The event that fired at the start of this integrator run, until its
    /// first step is checked: its start value is the forced pre-crossing sign.
    fired: Option<usize>,
    found: Vec<Occurrence<T, N, Q>>,
    stop: Option<Stop<T, N, Q>>,
}

/// The system seen through the event observer: everything is delegated, and
/// [`after_step`](SecondOrder::after_step) watches the events.
pub(super) struct Watch<'w, 'e, F, T: Real, const N: usize, const Q: usize> {
    pub rhs: &'w F,
    events: &'w [Event<'e, T, N, Q>],
    /// The position limits watched up to the step's first stopping event.
    limits: &'static [JointLimit],
    state: RefCell<WatchState<T, N, Q>>,
}

impl<'w, 'e, F: SecondOrder<T, N, Q>, T: Real, const N: usize, const Q: usize>
    Watch<'w, 'e, F, T, N, Q>
{
    /// `rhs` watched for `events` and `limits`, nothing found yet.
    pub fn new(
        rhs: &'w F,
        events: &'w [Event<'e, T, N, Q>],
        limits: &'static [JointLimit],
    ) -> Self {
        Self {
            rhs,
            events,
            limits,
            state: RefCell::new(WatchState {
                last: Vec::with_capacity(events.len()),
                fired: None,
                found: Vec::new(),
                stop: None,
            }),
        }
    }

    /// The stopping occurrence that ended the integrator's last run, if one did.
    pub fn take_stop(&self) -> Option<Stop<T, N, Q>> {
        self.state.borrow_mut().stop.take()
    }

    /// Records the occurrence of a stopping event (after its action).
    pub fn record(&self, occurrence: Occurrence<T, N, Q>) {
        self.state.borrow_mut().found.push(occurrence);
    }

    /// Every occurrence found, in time order.
    pub fn into_occurrences(self) -> Vec<Occurrence<T, N, Q>> {
        self.state.into_inner().found
    }

    /// Samples every event function at the start of a run. After an action,
    /// the fired event keeps the sign it had before the crossing (its value at
    /// the cut is zero up to round-off, on either side), so it does not fire
    /// again at once.
    pub fn reset(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        fired: Option<(usize, T)>,
    ) -> Result<(), Error> {
        let mut st = self.state.borrow_mut();
        st.last.clear();
        st.fired = fired.map(|(k, _)| k);
        for (i, event) in self.events.iter().enumerate() {
            let mut g = event.value(i, t, q, v)?;
            if let Some((k, before)) = fired
                && k == i
                && !same_sign(g, before)
            {
                g = if before > T::zero() {
                    T::lit(f64::MIN_POSITIVE)
                } else {
                    -T::lit(f64::MIN_POSITIVE)
                };
            }
            st.last.push(g);
        }
        Ok(())
    }
}

/// Whether a and b are both positive or both negative (zero matches nothing).
fn same_sign<T: Real>(a: T, b: T) -> bool {
    (a > T::zero() && b > T::zero()) || (a < T::zero() && b < T::zero())
}

/// The crossings of one event inside one step: up to two, one per half step.
/// `samples` are (t, g) at the start, the midpoint and the end.
///
/// `fired`: the event fired at the start of the step (the restart point) and
/// its start value is only the sign it had before. Right after that root the
/// function is below its round-off level, and a bracket reaching down to the
/// start would find noise there instead of a genuine second crossing (a small
/// bounce inside the first half step). So the left end is moved to the
/// furthest point start + (mid − start)/2^k where the function shows the old
/// sign; if there is none, the action did not resolve the event and the
/// crossing is reported right after the start (the driver then stops with
/// [`Error::EventsAccumulate`]).
fn crossings<T: Real, const N: usize, const Q: usize>(
    event: &Event<'_, T, N, Q>,
    segment: &DenseSegment<T, N, Q>,
    samples: [(T, T); 3],
    fired: bool,
) -> [Option<(T, T)>; 2] {
    let on_segment = |s: T| {
        let (q, v) = segment.eval(s);
        (event.g)(s, &q, &v)
    };
    let mut out = [None; 2];
    for (k, pair) in samples.windows(2).enumerate() {
        let ((mut ta, mut ga), (tb, gb)) = (pair[0], pair[1]);
        // A zero start has no sign: the later sample sets it, no crossing.
        if ga == T::zero() || same_sign(ga, gb) || !event.direction.admits(ga) {
            continue;
        }
        if fired && k == 0 {
            let before = ga;
            let mut offset = (tb - ta) * T::lit(0.5);
            let mut found = false;
            for _ in 0..60 {
                let s = ta + offset;
                if s <= ta {
                    break;
                }
                let gs = on_segment(s);
                if same_sign(gs, before) {
                    (ta, ga, found) = (s, gs, true);
                    break;
                }
                offset *= T::lit(0.5);
            }
            if !found {
                out[k] = Some((ta + offset.max(T::default_epsilon() * abs(ta)), before));
                continue;
            }
        }
        let t = if gb == T::zero() {
            tb
        } else {
            let (b, fb, c, fc) = brent_bracket(on_segment, ta, tb, ga, gb);
            // The end of the final bracket on the old side of the crossing,
            // or on the new side for a restart.
            if event.lands_past() {
                if same_sign(fb, ga) { c } else { b }
            } else if same_sign(fb, ga) || fb == T::zero() || !same_sign(fc, ga) {
                b
            } else {
                c
            }
        };
        out[k] = Some((t, ga));
    }
    out
}

impl<F: SecondOrder<T, N, Q>, T: Real, const N: usize, const Q: usize> SecondOrder<T, N, Q>
    for Watch<'_, '_, F, T, N, Q>
{
    const ORIENTATIONS: &'static [crate::numeric::orientation::Orientation] = F::ORIENTATIONS;

    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        self.rhs.acceleration(t, q, v)
    }

    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        self.rhs.integral(t, q, v)
    }

    fn residuals(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> [T; 2] {
        self.rhs.residuals(t, q, v)
    }

    fn project(&self, t: T, q: &mut SVector<T, Q>, v: &mut SVector<T, N>) -> Result<bool, Error> {
        self.rhs.project(t, q, v)
    }

    fn mechanical(&self) -> Option<&dyn Mechanical<T, N, Q>> {
        self.rhs.mechanical()
    }

    fn jacobian(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Option<Result<(SMatrix<T, N, Q>, SMatrix<T, N, N>), Error>> {
        self.rhs.jacobian(t, q, v)
    }

    fn after_step(
        &self,
        segment: &DenseSegment<T, N, Q>,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<bool, Error> {
        // The wrapped system's own observer first (an event layer inside
        // another): if it alone stops, the run ends there, before t1.
        let inner_stop = self.rhs.after_step(segment, q, v)?;
        if self.events.is_empty() {
            return match super::limits::first_crossing(self.limits, segment, q, segment.end()) {
                None => Ok(inner_stop),
                Some(error) => Err(error),
            };
        }
        let mut guard = self.state.borrow_mut();
        let st = &mut *guard;
        let ta = segment.start();
        let tb = segment.end();
        let tm = ta + (tb - ta) * T::lit(0.5);
        let (qm, vm) = segment.eval(tm);
        let first_new = st.found.len();
        let fired = st.fired.take();
        let mut stop: Option<Stop<T, N, Q>> = None;
        for (i, event) in self.events.iter().enumerate() {
            let gm = event.value(i, tm, &qm, &vm)?;
            let gb = event.value(i, tb, q, v)?;
            let samples = [(ta, st.last[i]), (tm, gm), (tb, gb)];
            st.last[i] = gb;
            let fresh = fired == Some(i);
            for (t, before) in crossings(event, segment, samples, fresh)
                .into_iter()
                .flatten()
            {
                let (qc, vc) = if t == tb { (*q, *v) } else { segment.eval(t) };
                if event.stops() {
                    // Only the first crossing of a stopping event matters.
                    if stop.is_none_or(|s| t < s.t) {
                        stop = Some(Stop {
                            event: i,
                            t,
                            q: qc,
                            v: vc,
                            before,
                        });
                    }
                    break;
                }
                st.found.push(Occurrence {
                    event: i,
                    t,
                    q: qc,
                    v: vc,
                    q_after: qc,
                    v_after: vc,
                });
            }
        }
        // A limit crossed before the step's first stop ends the run; the
        // step is not recorded, nor are its occurrences.
        let until = stop.map_or(tb, |s| s.t);
        if let Some(error) = super::limits::first_crossing(self.limits, segment, q, until) {
            st.found.truncate(first_new);
            return Err(error);
        }
        if let Some(s) = &stop {
            drop_after(&mut st.found, first_new, s.t);
        }
        st.found[first_new..]
            .sort_by(|a, b| a.t.partial_cmp(&b.t).unwrap_or(std::cmp::Ordering::Equal));
        st.stop = stop;
        Ok(stop.is_some() || inner_stop)
    }
}

/// Drops the occurrences from index `from` on that come after `t`: crossings
/// after a stop belong to a motion that will not happen.
fn drop_after<T: Real, const N: usize, const Q: usize>(
    found: &mut Vec<Occurrence<T, N, Q>>,
    from: usize,
    t: T,
) {
    let mut k = from;
    while k < found.len() {
        if found[k].t > t {
            found.swap_remove(k);
        } else {
            k += 1;
        }
    }
}
