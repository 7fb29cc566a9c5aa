//! The step-size loop that DOPRI5 and DOP853 share, as in Hairer's two codes:
//! the step budget and the underflow test before each attempt, the "stretch
//! the last step by up to 1 %" rule, the PI controller's verdict on the error
//! norm, the rule that a step following a rejection may not grow, and the
//! quartered retry after a trial stage the right-hand side cannot evaluate.
//! Each method keeps its stages, its error norm and its dense output.

use super::controller::PiController;
use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::func::{abs, sqrt};
use crate::ode::settings::StepControl;
use crate::ode::{Pair, SecondOrder, Stats};

/// Where an explicit embedded method stands: the time reached, the step to
/// try next, and what the controller remembers.
pub(crate) struct Stepping<T> {
    /// The time reached by the last accepted step.
    pub t: T,
    /// The step size of the current attempt.
    pub h: T,
    t1: T,
    span: T,
    hmax: T,
    max_steps: usize,
    /// 16 ε: a step below 16 ε |t| no longer moves t.
    underflow: T,
    stretch: T,
    /// The last attempt was rejected (so the next accepted step may not grow).
    reject: bool,
    /// The step size proposed by the controller for the step after this one.
    h_new: T,
    ctrl: PiController<T>,
}

impl<T: Real> Stepping<T> {
    /// From t0 towards t1 with the first step `h`; `hmax` defaults to the span.
    pub fn new(control: &StepControl, ctrl: PiController<T>, t0: T, t1: T, h: T) -> Self {
        Self {
            t: t0,
            h,
            t1,
            span: t1 - t0,
            hmax: largest_step(control, t0, t1),
            max_steps: control.max_steps,
            underflow: T::lit(16.0) * T::default_epsilon(),
            stretch: T::lit(1.01),
            reject: false,
            h_new: h,
            ctrl,
        }
    }

    /// Before an attempt: checks the step budget and the step size, and
    /// shortens the step to land on t1. Returns the attempt's end time and
    /// whether it is the last step.
    pub fn begin(&mut self, stats: &Stats) -> Result<(T, bool), Error> {
        let t = self.t;
        let h = self.h;
        if stats.steps() >= self.max_steps {
            return Err(Error::TooManySteps {
                t: t.to_f64(),
                max_steps: self.max_steps,
                needed: None,
            });
        }
        if h <= self.underflow * abs(t) || !h.is_finite() {
            return Err(Error::StepSizeUnderflow {
                t: t.to_f64(),
                h: h.to_f64(),
            });
        }
        // Stretch the last step by up to 1 % rather than leave a sliver.
        let last = t + self.stretch * h - self.t1 > T::zero();
        if last {
            self.h = self.t1 - t;
        }
        let t_new = if last { self.t1 } else { t + self.h };
        Ok((t_new, last))
    }

    /// A trial stage failed with `e`. If the failure is one of the state (a
    /// trial state the right-hand side cannot evaluate), the attempt is
    /// rejected and retried with a quarter of the step; anything else, or a
    /// step that would fall below the floor, ends the run with `e`.
    pub fn stage_failed(&mut self, e: Error, stats: &mut Stats) -> Result<(), Error> {
        if !e.is_state_dependent() {
            return Err(e);
        }
        // Relative to the span as well as to t, so that t = 0 has a floor.
        let floor = self.underflow * abs(self.t).max(abs(self.span));
        self.h = retry_smaller(self.h, floor, e)?;
        self.reject = true;
        stats.rejected += 1;
        Ok(())
    }

    /// The controller's verdict on an attempt with error norm `err` ending at
    /// (t_new, y_new): true if accepted (counted, and the next step size
    /// proposed), false if rejected (counted, and the step size reduced).
    pub fn judge<const N: usize, const Q: usize>(
        &mut self,
        err: T,
        t_new: T,
        y_new: &Pair<T, N, Q>,
        stats: &mut Stats,
    ) -> Result<bool, Error> {
        if err.partial_cmp(&T::zero()).is_none() {
            // NaN (unordered): only a right-hand side that returns NaN without
            // an error gets here.
            return Err(Error::non_finite(t_new, &y_new.q, &y_new.v));
        }
        self.h_new = self.ctrl.propose(self.h, err);
        if err <= T::one() {
            self.ctrl.accept(err);
            stats.accepted += 1;
            Ok(true)
        } else {
            self.h = self.ctrl.reject(self.h);
            self.reject = true;
            stats.rejected += 1;
            Ok(false)
        }
    }

    /// After an accepted step to `t_new`: moves on, with the proposed step
    /// limited by hmax and, after a rejection, by the step just taken.
    pub fn advance(&mut self, t_new: T) {
        self.t = t_new;
        let mut h_new = self.h_new.min(self.hmax);
        if self.reject {
            h_new = h_new.min(self.h);
        }
        self.reject = false;
        self.h = h_new;
    }
}

/// The largest step: the setting, or by default the span.
fn largest_step<T: Real>(control: &StepControl, t0: T, t1: T) -> T {
    control.hmax.map_or(t1 - t0, T::lit)
}

/// The first step: the setting (at most hmax), or Hairer's `hinit` estimate
/// for a method of order `order` (one more evaluation).
pub(crate) fn first_step<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    control: &StepControl,
    order: u32,
    rhs: &F,
    (t0, t1): (T, T),
    y: &Pair<T, N, Q>,
    f0: &Pair<T, N, Q>,
    evaluations: &mut usize,
) -> Result<T, Error> {
    let hmax = largest_step(control, t0, t1);
    let rtol = T::lit(control.rtol);
    let atol = T::lit(control.atol);
    match control.h0 {
        Some(h0) => Ok(T::lit(h0).min(hmax)),
        None => hinit(rhs, t0, y, f0, hmax, rtol, atol, order, evaluations),
    }
}

/// After a trial stage failed at its state: a quarter of the step, or the failure
/// itself once the step would be below `floor` (so a genuine singularity on the
/// solution is reported as what it is, after about 25 retries from h = 1).
fn retry_smaller<T: Real>(h: T, floor: T, e: Error) -> Result<T, Error> {
    let h = h * T::lit(0.25);
    if h <= floor { Err(e) } else { Ok(h) }
}

/// Hairer's starting step: make an explicit Euler step small compared with the
/// solution (h = 0.01 ‖y‖/‖f‖), estimate the second derivative from one more
/// evaluation, and choose h so that h^order · max(‖f‖, ‖y''‖) = 0.01 (order 5 for
/// DOPRI5, 8 for DOP853). The norms are unnormalised sums, as in `dopri5.f`.
#[allow(clippy::too_many_arguments)]
fn hinit<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    t0: T,
    y: &Pair<T, N, Q>,
    f0: &Pair<T, N, Q>,
    hmax: T,
    rtol: T,
    atol: T,
    order: u32,
    evaluations: &mut usize,
) -> Result<T, Error> {
    let sk = |x: T| atol + rtol * abs(x);
    let weighted = |a: &Pair<T, N, Q>, b: Option<&Pair<T, N, Q>>| {
        let mut s = T::zero();
        let parts = [
            (a.q.as_slice(), b.map(|b| b.q.as_slice()), y.q.as_slice()),
            (a.v.as_slice(), b.map(|b| b.v.as_slice()), y.v.as_slice()),
        ];
        for (a, b, y) in parts {
            for i in 0..a.len() {
                let x = b.map_or(a[i], |b| a[i] - b[i]) / sk(y[i]);
                s += x * x;
            }
        }
        s
    };
    let dnf = weighted(f0, None);
    let dny = weighted(y, None);
    let tiny = T::lit(1e-10);
    let mut h = if dnf <= tiny || dny <= tiny {
        T::lit(1e-6)
    } else {
        sqrt(dny / dnf) * T::lit(0.01)
    };
    h = h.min(hmax);
    let y1 = y.add_combination(h, [T::one()], [f0]);
    let f1 = y1.derivative(rhs, t0 + h, evaluations)?;
    let der2 = sqrt(weighted(&f1, Some(f0))) / h;
    let der12 = abs(der2).max(sqrt(dnf));
    let h1 = if der12 <= T::lit(1e-15) {
        T::lit(1e-6).max(abs(h) * T::lit(1e-3))
    } else {
        (T::lit(0.01) / der12).powf(T::lit(1.0 / f64::from(order)))
    };
    Ok((T::lit(100.0) * h).min(h1).min(hmax))
}
