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

use super::adaptive::{Stepping, first_step};
use super::controller::PiController;
use super::run::Run;
use super::settings::{StepControl, step_control_builders};
use super::{
    DenseSegment, Integrator, Pair, SecondOrder, Stats, check_orientations, check_problem, settle,
};
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

    fn validate(&self) -> Result<(), Error> {
        self.control.validate("DOP853", 0.0, false)
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
        let mut run = Run::of(self.record, from, rhs, t0, q0, v0);
        // Everything computed before a failure goes back with it.
        let outcome = self.run(rhs, (t0, t1), Pair::new(q0, v0), &mut run);
        run.finish(outcome)
    }

    fn max_steps(&self) -> usize {
        self.control.max_steps
    }
}

/// The stages of one attempt that the solution, the error estimate, the dense
/// output and the stiffness test need (k2..k5 enter only later stages).
struct Stages<T: Real, const N: usize, const Q: usize> {
    /// k6..k12: the stages after k1 that the 8th-order weights combine.
    k: [Pair<T, N, Q>; 7],
    /// The argument of the 12th stage, at t_new (for the stiffness test).
    y12: Pair<T, N, Q>,
}

impl Dop853 {
    /// Checks the settings and the problem, then steps from y0 at t0 to t1.
    fn run<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        (t0, t1): (T, T),
        y0: Pair<T, N, Q>,
        run: &mut Run<T, N, Q>,
    ) -> Result<(), Error> {
        self.record.check_span(t0, t1, Q + N)?;
        self.validate()?;
        self.control.check_precision::<T>("DOP853")?;
        check_problem(t0, t1, &y0.q, &y0.v)?;
        check_orientations(rhs, &y0.q)?;
        let co = Coefficients::<T>::new();
        let rtol = T::lit(self.control.rtol);
        let atol = T::lit(self.control.atol);
        let stats = &mut run.stats;
        let mut y = y0;
        let mut k1 = y0.derivative(rhs, t0, &mut stats.evaluations)?;
        let h = first_step(
            &self.control,
            8,
            rhs,
            (t0, t1),
            &y,
            &k1,
            &mut stats.evaluations,
        )?;
        let mut steps = Stepping::new(&self.control, PiController::dop853(), t0, t1, h);
        let mut stiffness = super::StiffnessTest::new("DOP853", self.stiffness_test, 6.1);
        loop {
            let (t_new, last) = steps.begin(&run.stats)?;
            let t = steps.t;
            let h = steps.h;
            let s = match stages(rhs, &co, t, h, t_new, &y, &k1, &mut run.stats.evaluations) {
                Ok(s) => s,
                Err(e) => {
                    steps.stage_failed(e, &mut run.stats)?;
                    continue;
                }
            };
            let [k6, k7, k8, k9, k10, k11, k12] = &s.k;
            let main = [&k1, k6, k7, k8, k9, k10, k11, k12];
            // Σ b_i k_i, kept without the factor h for the 3rd-order estimate.
            let slope = Pair::combination(T::one(), co.b, main);
            let y_new = y.add_combination(h, [T::one()], [&slope]);
            let e5 = Pair::combination(T::one(), co.er, main);
            let e3 = slope.add_combination(-T::one(), co.bhh, [&k1, k9, k12]);
            let err = error_norm(h, &e5, &e3, &y, &y_new, atol, rtol);
            if !steps.judge(err, t_new, &y_new, &mut run.stats)? {
                continue;
            }
            let k13 = y_new.derivative(rhs, t_new, &mut run.stats.evaluations)?;
            // The step is accepted: a stiffness verdict is reported after it
            // is recorded, so the partial trajectory ends where the error says.
            let stiff = stiffness.check(run.stats.accepted, t_new, h, [&y_new, &s.y12, &k13, k12]);
            let segment = if self.dense7 {
                self.dense(rhs, &co, t, h, &y, &y_new, main, &k13, &mut run.stats)?
            } else {
                DenseSegment::hermite(t, t_new, &y, &k1, &y_new, &k13)
            };
            // As in DOPRI5: the dense output keeps the unprojected polynomial;
            // the next first stage is re-evaluated at the projected state.
            let mut y_new = y_new;
            let mut k13 = k13;
            if settle(rhs, t_new, &mut y_new.q, &mut y_new.v)? {
                k13 = y_new.derivative(rhs, t_new, &mut run.stats.evaluations)?;
            }
            let stop = run.record(rhs, segment, y_new.q, y_new.v)?;
            stiff?;
            (y, k1) = (y_new, k13);
            steps.advance(t_new);
            if last || stop {
                return Ok(());
            }
        }
    }
}

/// The stages k2..k12 of an attempt of size h from (t, y) with first stage k1;
/// each row of the tableau names the stages it combines.
#[allow(clippy::too_many_arguments)]
fn stages<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    co: &Coefficients<T>,
    t: T,
    h: T,
    t_new: T,
    y: &Pair<T, N, Q>,
    k1: &Pair<T, N, Q>,
    ev: &mut usize,
) -> Result<Stages<T, N, Q>, Error> {
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
    Ok(Stages {
        k: [k6, k7, k8, k9, k10, k11, k12],
        y12,
    })
}

impl Dop853 {
    /// The 7th-order continuous extension of an accepted step: three more stages
    /// (at 0.1, 0.2 and 7/9 of the step) and the coefficients r₁..r₈.
    #[allow(clippy::too_many_arguments)]
    fn dense<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        co: &Coefficients<T>,
        t: T,
        h: T,
        y: &Pair<T, N, Q>,
        y_new: &Pair<T, N, Q>,
        [k1, k6, k7, k8, k9, k10, k11, k12]: [&Pair<T, N, Q>; 8],
        k13: &Pair<T, N, Q>,
        stats: &mut Stats,
    ) -> Result<DenseSegment<T, N, Q>, Error> {
        let ev = &mut stats.evaluations;
        let c = co.c;
        let k14 = y
            .add_combination(h, co.a14, [k1, k7, k8, k9, k10, k11, k12, k13])
            .derivative(rhs, t + c[13] * h, ev)?;
        let k15 = y
            .add_combination(h, co.a15, [k1, k6, k7, k8, k11, k12, k13, &k14])
            .derivative(rhs, t + c[14] * h, ev)?;
        let k16 = y
            .add_combination(h, co.a16, [k1, k6, k7, k8, k9, k13, &k14, &k15])
            .derivative(rhs, t + c[15] * h, ev)?;
        let (r1, r2, r3, r4) = DenseSegment::cubic_part(h, y, k1, y_new, k13);
        let ks = [k1, k6, k7, k8, k9, k10, k11, k12, k13, &k14, &k15, &k16];
        let [r5, r6, r7, r8] = co.d.map(|d| Pair::combination(h, d, ks));
        let t_new = t + h;
        Ok(DenseSegment::new(
            t,
            t_new,
            h,
            [r1, r2, r3, r4, r5, r6, r7, r8],
        ))
    }
}

/// DOP853's error norm: with sk = atol + rtol·max(|y|, |y_new|) over all Q + N
/// components, s₅ = Σ (e₅/sk)², s₃ = Σ (e₃/sk)²,
/// err = |h| s₅ / sqrt(2N (s₅ + 0.01 s₃)).
fn error_norm<T: Real, const N: usize, const Q: usize>(
    h: T,
    e5: &Pair<T, N, Q>,
    e3: &Pair<T, N, Q>,
    y: &Pair<T, N, Q>,
    y_new: &Pair<T, N, Q>,
    atol: T,
    rtol: T,
) -> T {
    let mut s5 = T::zero();
    let mut s3 = T::zero();
    let parts = [
        (
            e5.q.as_slice(),
            e3.q.as_slice(),
            y.q.as_slice(),
            y_new.q.as_slice(),
        ),
        (
            e5.v.as_slice(),
            e3.v.as_slice(),
            y.v.as_slice(),
            y_new.v.as_slice(),
        ),
    ];
    for (e5, e3, y, y_new) in parts {
        for i in 0..e5.len() {
            let sk = atol + rtol * abs(y[i]).max(abs(y_new[i]));
            let a = e5[i] / sk;
            let b = e3[i] / sk;
            s5 += a * a;
            s3 += b * b;
        }
    }
    let mut deno = s5 + T::lit(0.01) * s3;
    if deno <= T::zero() {
        deno = T::one();
    }
    abs(h) * s5 * sqrt(T::one() / (deno * T::lit((Q + N) as f64)))
}
