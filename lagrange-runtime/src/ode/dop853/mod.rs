//! Dormand–Prince 8(5,3), following Hairer & Wanner's DOP853 (Hairer, Nørsett,
//! Wanner, *Solving ODEs I*, 2nd ed., §II.5 and §II.10, and the Fortran code
//! `dop853.f`).
//!
//! What is kept from DOP853: the 12-stage tableau of order 8, the error estimate
//! that combines the 5th-order and 3rd-order embedded differences
//!
//! ```text
//! err = |h| · ‖e₅‖² / sqrt(N (‖e₅‖² + 0.01 ‖e₃‖²))
//! ```
//!
//! (which behaves like an 8th-order estimate for small h yet stays robust when h
//! is large), the step-size controller with fac1 = 0.333, fac2 = 6, safe = 0.9,
//! β = 0 and exponent 1/8, the `hinit` starting step for order 8, the rule that a
//! step following a rejection may not grow, the "stretch the last step by up to
//! 1 %" rule, and the 7th-order continuous extension (three extra evaluations per
//! accepted step), and the stiffness test (every 1000 accepted steps, then at
//! every step while h·|λ| stays beyond 6.1; 15 times ends the run with
//! [`Error::ProbablyStiff`]). What is left out: per-component tolerances.
//!
//! The loop around the stages is the one DOPRI5 runs too
//! ([`explicit`](super::explicit)); this file holds the stages, the error
//! estimate and the continuous extension, `tableau` the coefficients.

use super::explicit::{self, Attempt, EmbeddedMethod, PiController, Settings, Tolerance};
use super::settings::{StepControl, step_control_builders};
use super::{DenseSegment, Integrator, Pair, SecondOrder};
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::func::{abs, sqrt};
use crate::ode::{Continuation, Record, Trajectory};
use nalgebra::SVector;

/// Adaptive Dormand–Prince 8(5,3) with dense output of order 7.
///
/// The method of choice for smooth problems at tight tolerances (1e-8 and
/// below), where it needs far fewer evaluations than [`Dopri5`](crate::Dopri5).
///
/// Evaluations per run: 1 at the start, 1 for the starting-step guess (unless
/// [`h0`](Self::h0) is given), 11 per attempted step, 1 per accepted step (the
/// derivative at the new point, reused as the next step's first stage) and 3 per
/// accepted step for the 7th-order dense output (none with
/// [`hermite_dense`](Self::hermite_dense)). Hairer's code reports the same count,
/// except that it counts the starting-step evaluation even when h0 is given.
///
/// ```
/// use lagrange_runtime::Dop853;
/// let method = Dop853::tol(1e-12).hmax(0.5).max_steps(1_000_000);
/// # let _ = method;
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dop853 {
    control: StepControl,
    dense7: bool,
    stiffness_test: usize,
    /// What the trajectory keeps of the steps.
    record: Record,
}

impl Default for Dop853 {
    /// rtol = atol = 1e-10.
    fn default() -> Self {
        Self::tol(1e-10)
    }
}

impl Dop853 {
    /// What the trajectory keeps of the steps (default: every step with its
    /// dense output); see [`Record`].
    pub fn record(mut self, record: Record) -> Self {
        self.record = record;
        self
    }

    /// Relative and absolute tolerance both equal to `tol`.
    pub fn tol(tol: f64) -> Self {
        Self::new(tol, tol)
    }

    /// Relative tolerance `rtol` and absolute tolerance `atol`. A component is
    /// accurate enough when its local error is below atol + rtol·|y|.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self {
            record: Record::Steps,
            control: StepControl::new(rtol, atol),
            dense7: true,
            stiffness_test: 1000,
        }
    }

    step_control_builders!("Hairer's `hinit` estimates it");

    /// Tests for stiffness every `n` accepted steps (Hairer's NSTIFF, default
    /// 1000); 0 switches the test off. A stiff problem then ends in
    /// [`Error::ProbablyStiff`], which names Radau5, instead of creeping to the
    /// step budget at the stability limit.
    pub fn stiffness_test(mut self, n: usize) -> Self {
        self.stiffness_test = n;
        self
    }

    /// Replaces the 7th-order continuous extension by the cubic Hermite
    /// interpolant, saving 3 of the 15 evaluations per accepted step when only
    /// the step end points matter (the dense output is then 3rd order).
    pub fn hermite_dense(mut self) -> Self {
        self.dense7 = false;
        self
    }
}

mod tableau;

/// The tableau converted once per run to the system's scalar.
struct Coefficients<T> {
    c: [T; 16],
    a2: [T; 1],
    a3: [T; 2],
    a4: [T; 2],
    a5: [T; 3],
    a6: [T; 3],
    a7: [T; 4],
    a8: [T; 5],
    a9: [T; 6],
    a10: [T; 7],
    a11: [T; 8],
    a12: [T; 9],
    b: [T; 8],
    bhh: [T; 3],
    er: [T; 8],
    a14: [T; 8],
    a15: [T; 8],
    a16: [T; 8],
    d: [[T; 12]; 4],
}

impl<T: Real> Coefficients<T> {
    fn new() -> Self {
        use tableau::*;
        fn lits<T: Real, const K: usize>(xs: [f64; K]) -> [T; K] {
            xs.map(T::lit)
        }
        Self {
            c: lits(C),
            a2: lits(A2),
            a3: lits(A3),
            a4: lits(A4),
            a5: lits(A5),
            a6: lits(A6),
            a7: lits(A7),
            a8: lits(A8),
            a9: lits(A9),
            a10: lits(A10),
            a11: lits(A11),
            a12: lits(A12),
            b: lits(B),
            bhh: lits(BHH),
            er: lits(ER),
            a14: lits(A14),
            a15: lits(A15),
            a16: lits(A16),
            d: D.map(lits),
        }
    }
}

impl Integrator for Dop853 {
    fn continue_run<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        from: Continuation<T>,
        t0: T,
        t1: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>> {
        let settings = Settings {
            control: self.control,
            stiffness_test: self.stiffness_test,
            record: self.record,
        };
        let method = Method {
            co: Coefficients::<T>::new(),
            dense7: self.dense7,
        };
        explicit::continue_run(&method, &settings, rhs, from, (t0, t1), (q0, v0))
    }

    fn max_steps(&self) -> usize {
        self.control.max_steps
    }
}

/// DOP853 as the explicit loop runs it: the tableau, and which dense output
/// the accepted steps get.
struct Method<T> {
    co: Coefficients<T>,
    /// The 7th-order continuous extension, rather than the cubic Hermite one.
    dense7: bool,
}

/// The stages of one attempt that the solution, the error estimate, the dense
/// output and the stiffness test need (k2..k5 enter only later stages).
struct Stages<T: Real, const N: usize, const Q: usize> {
    /// k6..k12: the stages after k1 that the 8th-order weights combine.
    k: [Pair<T, N, Q>; 7],
    /// The argument of the 12th stage, at t_new (for the stiffness test).
    y12: Pair<T, N, Q>,
    /// Σ b_i k_i, kept without the factor h for the 3rd-order estimate.
    slope: Pair<T, N, Q>,
    /// The 8th-order solution y + h · slope.
    y_new: Pair<T, N, Q>,
}

impl<T: Real, const N: usize, const Q: usize> Stages<T, N, Q> {
    /// k1 and k6..k12, the stages the 8th-order weights combine.
    fn main<'a>(&'a self, k1: &'a Pair<T, N, Q>) -> [&'a Pair<T, N, Q>; 8] {
        let [k6, k7, k8, k9, k10, k11, k12] = &self.k;
        [k1, k6, k7, k8, k9, k10, k11, k12]
    }
}

impl<T: Real, const N: usize, const Q: usize> EmbeddedMethod<T, N, Q> for Method<T> {
    const NAME: &'static str = "DOP853";
    const ORDER: u32 = 8;
    const STABILITY_LIMIT: f64 = 6.1;
    type Stages = Stages<T, N, Q>;

    fn controller() -> PiController<T> {
        PiController::dop853()
    }

    /// k2..k12 and the 8th-order solution; each row of the tableau names the
    /// stages it combines.
    fn stages<F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        &Attempt { t, h, t_new, y, k1 }: &Attempt<'_, T, N, Q>,
        ev: &mut usize,
    ) -> Result<Stages<T, N, Q>, Error> {
        let co = &self.co;
        let c = co.c;
        let stage = |a: Pair<T, N, Q>, ci: T, ev: &mut usize| a.derivative(rhs, t + ci * h, ev);
        let k2 = stage(y.add_combination(h, co.a2, [k1]), c[1], ev)?;
        let k3 = stage(y.add_combination(h, co.a3, [k1, &k2]), c[2], ev)?;
        let k4 = stage(y.add_combination(h, co.a4, [k1, &k3]), c[3], ev)?;
        let k5 = stage(y.add_combination(h, co.a5, [k1, &k3, &k4]), c[4], ev)?;
        let k6 = stage(y.add_combination(h, co.a6, [k1, &k4, &k5]), c[5], ev)?;
        let k7 = stage(y.add_combination(h, co.a7, [k1, &k4, &k5, &k6]), c[6], ev)?;
        let k8 = stage(
            y.add_combination(h, co.a8, [k1, &k4, &k5, &k6, &k7]),
            c[7],
            ev,
        )?;
        let k9 = stage(
            y.add_combination(h, co.a9, [k1, &k4, &k5, &k6, &k7, &k8]),
            c[8],
            ev,
        )?;
        let k10 = stage(
            y.add_combination(h, co.a10, [k1, &k4, &k5, &k6, &k7, &k8, &k9]),
            c[9],
            ev,
        )?;
        let k11 = stage(
            y.add_combination(h, co.a11, [k1, &k4, &k5, &k6, &k7, &k8, &k9, &k10]),
            c[10],
            ev,
        )?;
        let y12 = y.add_combination(h, co.a12, [k1, &k4, &k5, &k6, &k7, &k8, &k9, &k10, &k11]);
        let k12 = y12.derivative(rhs, t_new, ev)?;
        let slope = Pair::combination(T::one(), co.b, [k1, &k6, &k7, &k8, &k9, &k10, &k11, &k12]);
        let y_new = y.add_combination(h, [T::one()], [&slope]);
        Ok(Stages {
            k: [k6, k7, k8, k9, k10, k11, k12],
            y12,
            slope,
            y_new,
        })
    }

    fn solution(s: &Stages<T, N, Q>) -> &Pair<T, N, Q> {
        &s.y_new
    }

    /// DOP853's blend of the 5th-order difference e₅ = Σ er_i k_i and the
    /// 3rd-order one e₃ = slope − Σ bhh_i k_i: with s₅, s₃ their scaled
    /// squares over all Q + N components,
    /// err = |h| s₅ / sqrt(n (s₅ + 0.01 s₃)).
    fn error(&self, a: &Attempt<'_, T, N, Q>, s: &Stages<T, N, Q>, tol: &Tolerance<T>) -> T {
        let main = s.main(a.k1);
        let e5 = Pair::combination(T::one(), self.co.er, main);
        let e3 = s
            .slope
            .add_combination(-T::one(), self.co.bhh, [a.k1, main[4], main[7]]);
        let [s5, s3] = tol.scaled_squares([&e5, &e3], a.y, &s.y_new);
        let mut deno = s5 + T::lit(0.01) * s3;
        if deno <= T::zero() {
            deno = T::one();
        }
        abs(a.h) * s5 * sqrt(T::one() / (deno * T::lit((Q + N) as f64)))
    }

    /// k13 = f(t_new, y_new), evaluated only for an accepted step, as in
    /// `dop853.f`.
    fn end_slope<F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        t_new: T,
        s: &Stages<T, N, Q>,
        ev: &mut usize,
    ) -> Result<Pair<T, N, Q>, Error> {
        s.y_new.derivative(rhs, t_new, ev)
    }

    fn last_stage(s: &Stages<T, N, Q>) -> [&Pair<T, N, Q>; 2] {
        [&s.y12, &s.k[6]]
    }

    /// The 7th-order continuous extension (three more stages), or the cubic
    /// Hermite interpolant with [`hermite_dense`](Dop853::hermite_dense).
    fn dense<F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        a: &Attempt<'_, T, N, Q>,
        s: &Stages<T, N, Q>,
        k13: &Pair<T, N, Q>,
        ev: &mut usize,
    ) -> Result<DenseSegment<T, N, Q>, Error> {
        if self.dense7 {
            self.co.dense(rhs, a, s.main(a.k1), &s.y_new, k13, ev)
        } else {
            Ok(DenseSegment::hermite(
                a.t, a.t_new, a.y, a.k1, &s.y_new, k13,
            ))
        }
    }
}

impl<T: Real> Coefficients<T> {
    /// The 7th-order continuous extension of an accepted step: three more stages
    /// (at 0.1, 0.2 and 7/9 of the step) and the coefficients r₅..r₈.
    fn dense<const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        &Attempt { t, h, y, .. }: &Attempt<'_, T, N, Q>,
        [k1, k6, k7, k8, k9, k10, k11, k12]: [&Pair<T, N, Q>; 8],
        y_new: &Pair<T, N, Q>,
        k13: &Pair<T, N, Q>,
        ev: &mut usize,
    ) -> Result<DenseSegment<T, N, Q>, Error> {
        let c = self.c;
        let k14 = y
            .add_combination(h, self.a14, [k1, k7, k8, k9, k10, k11, k12, k13])
            .derivative(rhs, t + c[13] * h, ev)?;
        let k15 = y
            .add_combination(h, self.a15, [k1, k6, k7, k8, k11, k12, k13, &k14])
            .derivative(rhs, t + c[14] * h, ev)?;
        let k16 = y
            .add_combination(h, self.a16, [k1, k6, k7, k8, k9, k13, &k14, &k15])
            .derivative(rhs, t + c[15] * h, ev)?;
        let (r1, r2, r3, r4) = DenseSegment::cubic_part(h, y, k1, y_new, k13);
        let ks = [k1, k6, k7, k8, k9, k10, k11, k12, k13, &k14, &k15, &k16];
        let [r5, r6, r7, r8] = self.d.map(|d| Pair::combination(h, d, ks));
        let t_new = t + h;
        Ok(DenseSegment::new(
            t,
            t_new,
            h,
            [r1, r2, r3, r4, r5, r6, r7, r8],
        ))
    }
}
