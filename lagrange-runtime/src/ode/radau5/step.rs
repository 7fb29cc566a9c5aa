//! One RADAU5 run as a state with the phases of a step in `radau5.f`: the
//! Jacobian and the factorisations (labels 20–22), the starting values and the
//! simplified Newton iteration for the stage values (label 30 on), the error
//! estimate, and the step-size and Jacobian-reuse decisions after an accepted
//! or a rejected step. The goto structure of the Fortran code becomes
//! [`Entry`]: where the next attempt starts.

// Index loops mirror the formulas of radau5.f, component by component.
#![allow(clippy::needless_range_loop)]

use super::linear::{Work, decompose, estimate, jacobian, rhs_into, solve_stages, to_pair};
use super::{Constants, Radau5, constants};
use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::func::{abs, sqrt};
use crate::ode::run::Run;
use crate::ode::{DenseSegment, SecondOrder, Stats, settle};
use nalgebra::SVector;

/// Where the next attempt starts.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Entry {
    /// With a new Jacobian (and new factorisations).
    Jacobian,
    /// With the Jacobian kept, factorised anew for the current h.
    Factorise,
    /// With the Jacobian and the factorisations kept.
    Step,
}

/// How the Newton iteration of an attempt ended.
pub(super) enum Newton<T> {
    /// Converged after this many iterations.
    Converged(usize),
    /// Converging too slowly: retry with h multiplied by this factor.
    Slow(T),
    /// Diverging or out of iterations: retry with h / 2.
    Failed,
}

/// radau5.f's tuning: the transformed tolerances, the Newton stopping
/// criterion and the step-size factors.
struct Tuning<T> {
    uround: T,
    rtol: T,
    atol: T,
    /// Newton's stopping criterion on the scaled correction.
    fnewt: T,
    /// Newton iterations allowed per attempt (NIT).
    nit: usize,
    safe: T,
    /// The Jacobian is kept while the Newton contraction θ stays below this.
    thet: T,
    /// The factorisations are kept while h_new/h lies in [quot1, quot2].
    quot1: T,
    quot2: T,
    /// h_new/h lies in [1/facl, 1/facr].
    facl: T,
    facr: T,
    cfac: T,
    hmaxn: T,
    t1: T,
    max_steps: usize,
}

/// A run of RADAU5 between two attempts.
pub(super) struct State<T: Real, const N: usize, const Q: usize> {
    k: Constants<T>,
    w: Work<T>,
    p: Tuning<T>,
    pub t: T,
    pub h: T,
    /// The state y = (q, v) at t, and its derivative f(t, y).
    y: Vec<T>,
    y0: Vec<T>,
    /// The step size of the last accepted step (for the starting values).
    hold: T,
    /// h and the error of the last accepted step (Gustafsson's controller).
    hacc: T,
    erracc: T,
    /// Newton's rate estimate θ/(1 − θ), carried over from the last attempt.
    faccon: T,
    /// The Newton contraction θ of the last attempt.
    theta: T,
    /// fac1 = γ/h, alphn = α/h, betan = β/h for the current h.
    fac1: T,
    alphn: T,
    betan: T,
    /// The last attempt was rejected (so the next accepted step may not grow).
    reject: bool,
    /// No step accepted yet.
    pub first: bool,
    /// The attempt ends at t1.
    last: bool,
    /// The Jacobian was computed at the current t.
    caljac: bool,
    entry: Entry,
    /// A state-dependent failure of the right-hand side inside a Newton
    /// iteration, kept so that repeated failures down to underflow report it.
    pending_error: Option<Error>,
}

impl<T: Real, const N: usize, const Q: usize> State<T, N, Q> {
    /// Sets up a run from (q0, v0) at t0 (one evaluation of the right-hand side).
    pub fn new<F: SecondOrder<T, N, Q>>(
        radau: &Radau5,
        rhs: &F,
        (t0, t1): (T, T),
        (q0, v0): (SVector<T, Q>, SVector<T, N>),
        stats: &mut Stats,
    ) -> Result<Self, Error> {
        let control = &radau.control;
        let n = Q + N;
        // radau5.f's tolerance transformation and Newton stopping criterion.
        let uround = T::default_epsilon();
        let rtol_t = 0.1 * control.rtol.powf(2.0 / 3.0);
        let (rtol, atol) = (T::lit(rtol_t), T::lit(rtol_t * control.atol / control.rtol));
        let nit = radau.max_newton;
        let safe = T::lit(0.9);
        let p = Tuning {
            uround,
            rtol,
            atol,
            fnewt: (T::lit(10.0) * uround / rtol).max(T::lit(0.03f64.min(rtol_t.sqrt()))),
            nit,
            safe,
            thet: T::lit(0.001),
            quot1: T::one(),
            quot2: T::lit(1.2),
            facl: T::lit(5.0),
            facr: T::lit(0.125),
            cfac: safe * T::lit((1 + 2 * nit) as f64),
            hmaxn: control.hmax.map_or(t1 - t0, T::lit).min(t1 - t0),
            t1,
            max_steps: control.max_steps,
        };
        let mut h = T::lit(control.h0.unwrap_or(1e-6)).min(p.hmaxn);
        let mut last = false;
        if t0 + h * T::lit(1.0001) - t1 >= T::zero() {
            h = t1 - t0;
            last = true;
        }
        let mut state = Self {
            k: constants(),
            w: Work::new(n),
            p,
            t: t0,
            h,
            y: q0.iter().chain(v0.iter()).copied().collect(),
            y0: vec![T::zero(); n],
            hold: h,
            hacc: h,
            erracc: T::lit(1e-2),
            faccon: T::one(),
            theta: T::zero(),
            fac1: T::zero(),
            alphn: T::zero(),
            betan: T::zero(),
            reject: false,
            first: true,
            last,
            caljac: false,
            entry: Entry::Jacobian,
            pending_error: None,
        };
        state.set_scal();
        rhs_into(rhs, t0, &state.y, &mut state.y0, &mut stats.evaluations)?;
        Ok(state)
    }

    /// The error weights atol + rtol |y| at the current y.
    fn set_scal(&mut self) {
        for i in 0..Q + N {
            self.w.scal[i] = self.p.atol + self.p.rtol * abs(self.y[i]);
        }
    }

    /// Computes the Jacobian and factorises the iteration matrices as the
    /// entry asks. False if the matrices are singular: the step is halved and
    /// the attempt starts over (label 78).
    pub fn prepare<F: SecondOrder<T, N, Q>>(
        &mut self,
        rhs: &F,
        stats: &mut Stats,
    ) -> Result<bool, Error> {
        if self.entry == Entry::Jacobian {
            jacobian(rhs, self.t, &self.y, &self.y0, &mut self.w.jac, stats)?;
            stats.jacobians += 1;
            self.caljac = true;
            self.entry = Entry::Factorise;
        }
        let k = &self.k;
        let h = self.h;
        (self.fac1, self.alphn, self.betan) = (k.u1 / h, k.alph / h, k.beta / h);
        if self.entry == Entry::Factorise {
            stats.factorizations += 1;
            if !decompose(&mut self.w, self.fac1, self.alphn, self.betan) {
                self.retry(self.h * T::lit(0.5));
                if abs(self.h) <= abs(self.t) * self.p.uround {
                    return Err(Error::NewtonFailure {
                        t: self.t.to_f64(),
                        h: self.h.to_f64(),
                        iterations: 0,
                    });
                }
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Before an attempt with the current factorisation (label 30): the step
    /// budget, and a step that no longer moves t (reported as the pending
    /// failure of the right-hand side, if there is one).
    pub fn check_attempt(&mut self, stats: &Stats) -> Result<(), Error> {
        let t = self.t;
        let h = self.h;
        if stats.steps() >= self.p.max_steps {
            return Err(Error::TooManySteps {
                t: t.to_f64(),
                max_steps: self.p.max_steps,
                needed: None,
            });
        }
        if T::lit(0.1) * abs(h) <= abs(t) * self.p.uround || !h.is_finite() {
            if let Some(e) = self.pending_error.take() {
                return Err(e);
            }
            return Err(Error::StepSizeUnderflow {
                t: t.to_f64(),
                h: h.to_f64(),
            });
        }
        Ok(())
    }

    /// Starts the next attempt over with step `h`, keeping the Jacobian if it
    /// is current.
    pub fn retry(&mut self, h: T) {
        self.h = h;
        self.reject = true;
        self.last = false;
        self.entry = if self.caljac {
            Entry::Factorise
        } else {
            Entry::Jacobian
        };
    }

    /// Starting values of the stages: zero at the first step, else the
    /// previous collocation polynomial extrapolated.
    pub fn starting_values(&mut self) {
        let k = &self.k;
        let w = &mut self.w;
        if self.first {
            for s in 0..3 {
                w.z[s].fill(T::zero());
                w.f[s].fill(T::zero());
            }
            return;
        }
        let c3q = self.h / self.hold;
        let cq = [k.c1 * c3q, k.c2 * c3q, c3q];
        for i in 0..Q + N {
            let ak1 = w.cont[0][i];
            let ak2 = w.cont[1][i];
            let ak3 = w.cont[2][i];
            let zi = cq.map(|c| c * (ak1 + (c - k.c2m1) * (ak2 + (c - k.c1m1) * ak3)));
            for s in 0..3 {
                w.z[s][i] = zi[s];
            }
            for s in 0..3 {
                w.f[s][i] = k.ti[s][0] * zi[0] + k.ti[s][1] * zi[1] + k.ti[s][2] * zi[2];
            }
        }
    }

    /// The simplified Newton iteration for the stage values, with radau5.f's
    /// tests on the contraction θ: too slow a convergence ends the attempt
    /// early with a smaller step.
    pub fn newton<F: SecondOrder<T, N, Q>>(
        &mut self,
        rhs: &F,
        stats: &mut Stats,
    ) -> Result<Newton<T>, Error> {
        let nit = self.p.nit;
        let uround = self.p.uround;
        let fnewt = self.p.fnewt;
        let mut newt = 0;
        self.faccon = self.faccon.max(uround).powf(T::lit(0.8));
        self.theta = abs(self.p.thet);
        let mut dynold = T::zero();
        let mut thqold = T::zero();
        loop {
            if newt >= nit || !self.stage_residuals(rhs, stats)? {
                return Ok(Newton::Failed);
            }
            solve_stages(&mut self.w, self.fac1, self.alphn, self.betan);
            newt += 1;
            let dyno = self.correction_norm();
            if !dyno.is_finite() {
                return Ok(Newton::Failed);
            }
            if newt > 1 && newt < nit {
                let thq = dyno / dynold;
                self.theta = if newt == 2 { thq } else { sqrt(thq * thqold) };
                thqold = thq;
                if self.theta < T::lit(0.99) {
                    let theta = self.theta;
                    self.faccon = theta / (T::one() - theta);
                    let dyth = self.faccon * dyno * theta.powi((nit - 1 - newt) as i32) / fnewt;
                    if dyth >= T::one() {
                        let qnewt = T::lit(1e-4).max(T::lit(20.0).min(dyth));
                        let expo = -T::one() / T::lit((4 + nit - 1 - newt) as f64);
                        return Ok(Newton::Slow(T::lit(0.8) * qnewt.powf(expo)));
                    }
                } else {
                    return Ok(Newton::Failed);
                }
            }
            dynold = dyno.max(uround);
            self.update_stages();
            if self.faccon * dyno <= fnewt {
                return Ok(Newton::Converged(newt));
            }
        }
    }

    /// f at the three stage points y + z_s, transformed by T⁻¹ (the Newton
    /// right-hand side), into z. False if the right-hand side failed at a
    /// stage state; the failure is kept as the pending error.
    fn stage_residuals<F: SecondOrder<T, N, Q>>(
        &mut self,
        rhs: &F,
        stats: &mut Stats,
    ) -> Result<bool, Error> {
        let k = &self.k;
        let w = &mut self.w;
        let t = self.t;
        let h = self.h;
        let cs = [k.c1, k.c2, T::one()];
        for s in 0..3 {
            for i in 0..Q + N {
                w.tmp[i] = self.y[i] + w.z[s][i];
            }
            let ts = if s == 2 { t + h } else { t + cs[s] * h };
            let tmp = &w.tmp;
            let zs = &mut w.z[s];
            match rhs_into::<T, N, Q, F>(rhs, ts, tmp, zs, &mut stats.evaluations) {
                Ok(()) => {}
                // A Newton iterate the right-hand side cannot evaluate (far
                // off the solution) is a failed iteration, as in RADAU5's
                // handling of a diverging Newton: halve the step. If the
                // steps underflow, this error is the one reported.
                Err(e) if e.is_state_dependent() => {
                    self.pending_error = Some(e);
                    return Ok(false);
                }
                Err(e) => return Err(e),
            }
        }
        for i in 0..Q + N {
            let a = [w.z[0][i], w.z[1][i], w.z[2][i]];
            for s in 0..3 {
                w.z[s][i] = k.ti[s][0] * a[0] + k.ti[s][1] * a[1] + k.ti[s][2] * a[2];
            }
        }
        Ok(true)
    }

    /// The scaled RMS norm of the Newton correction.
    fn correction_norm(&self) -> T {
        let n = Q + N;
        let mut dyno = T::zero();
        for i in 0..n {
            for s in 0..3 {
                let r = self.w.z[s][i] / self.w.scal[i];
                dyno += r * r;
            }
        }
        sqrt(dyno / T::lit((3 * n) as f64))
    }

    /// Adds the correction to the transformed stages f and transforms back
    /// into the stage increments z = T f.
    fn update_stages(&mut self) {
        let k = &self.k;
        let w = &mut self.w;
        for i in 0..Q + N {
            let fi = [0, 1, 2].map(|s| w.f[s][i] + w.z[s][i]);
            for s in 0..3 {
                w.f[s][i] = fi[s];
            }
            for s in 0..3 {
                w.z[s][i] = k.t[s][0] * fi[0] + k.t[s][1] * fi[1] + k.t[s][2] * fi[2];
            }
        }
    }

    /// The filtered error estimate of the converged attempt (ESTRAD).
    pub fn error<F: SecondOrder<T, N, Q>>(
        &mut self,
        rhs: &F,
        stats: &mut Stats,
    ) -> Result<T, Error> {
        let again = self.first || self.reject;
        let k = &self.k;
        let w = &mut self.w;
        let y = &self.y;
        let y0 = &self.y0;
        estimate(rhs, k, w, self.t, self.h, y, y0, again, stats)
    }

    /// The step size the error `err` proposes after `newt` Newton iterations:
    /// (quot, h / quot).
    pub fn proposal(&self, err: T, newt: usize) -> (T, T) {
        let p = &self.p;
        let fac = p.safe.min(p.cfac / T::lit((newt + 2 * p.nit) as f64));
        let quot = p.facr.max(p.facl.min(err.powf(T::lit(0.25)) / fac));
        (quot, self.h / quot)
    }

    /// Accepts the attempt, records the step, and decides the next one.
    /// Returns whether the run ends here (t1 reached, or the system stops it).
    pub fn accept<F: SecondOrder<T, N, Q>>(
        &mut self,
        rhs: &F,
        err: T,
        (mut quot, mut hnew): (T, T),
        run: &mut Run<T, N, Q>,
    ) -> Result<bool, Error> {
        let h = self.h;
        let p = &self.p;
        self.first = false;
        run.stats.accepted += 1;
        self.pending_error = None;
        if run.stats.accepted > 1 {
            // Gustafsson's predictive controller.
            let facgus = (self.hacc / h) * (err * err / self.erracc).powf(T::lit(0.25)) / p.safe;
            let facgus = p.facr.max(p.facl.min(facgus));
            quot = quot.max(facgus);
            hnew = h / quot;
        }
        self.hacc = h;
        self.erracc = T::lit(1e-2).max(err);
        self.hold = h;
        let stop = self.advance(rhs, run)?;
        self.caljac = false;
        if self.last || stop {
            return Ok(true);
        }
        self.next_step(hnew);
        Ok(false)
    }

    /// Moves to the end of the accepted step: the new y, the collocation
    /// polynomial for the next starting values, f there, the projection, and
    /// the recorded step (the cubic Hermite interpolant as dense output).
    /// Returns whether the system stops the run.
    fn advance<F: SecondOrder<T, N, Q>>(
        &mut self,
        rhs: &F,
        run: &mut Run<T, N, Q>,
    ) -> Result<bool, Error> {
        let k = &self.k;
        let w = &mut self.w;
        let y = &mut self.y;
        let y_old = to_pair::<T, N, Q>(y);
        let f_old = to_pair::<T, N, Q>(&self.y0);
        for i in 0..Q + N {
            y[i] += w.z[2][i];
            let z1 = w.z[0][i];
            let z2 = w.z[1][i];
            let z3 = w.z[2][i];
            w.cont[0][i] = (z2 - z3) / k.c2m1;
            let ak = (z1 - z2) / k.c1mc2;
            let acont3 = (ak - z1 / k.c1) / k.c2;
            w.cont[1][i] = (ak - w.cont[0][i]) / k.c1m1;
            w.cont[2][i] = w.cont[1][i] - acont3;
        }
        let t_prev = self.t;
        self.t = if self.last {
            self.p.t1
        } else {
            t_prev + self.h
        };
        let t = self.t;
        let mut p = to_pair::<T, N, Q>(y);
        if !p.is_finite() {
            return Err(Error::non_finite(t, &p.q, &p.v));
        }
        // The derivative at the new point: the next step's y0 and the
        // Hermite end slope.
        let ev = &mut run.stats.evaluations;
        rhs_into::<T, N, Q, F>(rhs, t, y, &mut self.y0, ev)?;
        let segment = DenseSegment::hermite(t_prev, t, &y_old, &f_old, &p, &to_pair(&self.y0));
        let projected = settle(rhs, t, &mut p.q, &mut p.v)?;
        // The normalised quaternions go on, as in the other methods.
        y[..Q].copy_from_slice(p.q.as_slice());
        if projected {
            y[Q..Q + N].copy_from_slice(p.v.as_slice());
            rhs_into::<T, N, Q, F>(rhs, t, y, &mut self.y0, ev)?;
        }
        self.set_scal();
        run.record(rhs, segment, p.q, p.v)
    }

    /// After an accepted step: the next step size (no growth after a
    /// rejection, landing on t1), and whether the Jacobian and the
    /// factorisations can be kept (θ small and h almost unchanged).
    fn next_step(&mut self, hnew: T) {
        let p = &self.p;
        let mut hnew = hnew.min(p.hmaxn);
        if self.reject {
            hnew = hnew.min(self.h);
        }
        self.reject = false;
        if self.t + hnew / p.quot1 - p.t1 >= T::zero() {
            self.h = p.t1 - self.t;
            self.last = true;
        } else {
            let qt = hnew / self.h;
            if self.theta <= p.thet && qt >= p.quot1 && qt <= p.quot2 {
                self.entry = Entry::Step;
                return;
            }
            self.h = hnew;
        }
        self.entry = if self.theta <= p.thet {
            Entry::Factorise
        } else {
            Entry::Jacobian
        };
    }
}
