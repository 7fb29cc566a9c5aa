//! Dormand–Prince 5(4), following Hairer & Wanner's DOPRI5 (Hairer, Nørsett,
//! Wanner, *Solving ODEs I*, 2nd ed., §II.4–II.6 and the Fortran code `dopri5.f`).
//!
//! What is kept from DOPRI5: the tableau with FSAL (the 7th stage is the next
//! step's 1st), the error norm over all 2N components, the PI step-size
//! controller with Lund stabilisation (see [`controller`](super::controller)), the
//! `hinit` starting step, the rule that a step following a rejection may not grow,
//! the "stretch the last step by up to 1 %" rule, and Shampine's continuous
//! extension for dense output, and the stiffness test (every 1000 accepted steps,
//! then at every step while h·|λ| stays beyond 3.25; 15 times ends the run with
//! [`Error::ProbablyStiff`]). What is left out: per-component tolerances.

use super::adaptive::{Stepping, first_step};
use super::controller::PiController;
use super::run::Run;
use super::settings::{StepControl, step_control_builders};
use super::{
    DenseSegment, Integrator, Pair, SecondOrder, check_orientations, check_problem, settle,
};
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::func::{abs, sqrt};
use crate::ode::{Continuation, Record, Trajectory};
use nalgebra::SVector;

/// Adaptive Dormand–Prince 5(4) with dense output of order 4.
///
/// ```
/// use lagrange_runtime::Dopri5;
/// let method = Dopri5::tol(1e-10).hmax(0.1).max_steps(1_000_000);
/// # let _ = method;
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dopri5 {
    control: StepControl,
    stiffness_test: usize,
    /// What the trajectory keeps of the steps.
    record: Record,
}

impl Default for Dopri5 {
    /// rtol = atol = 1e-8.
    fn default() -> Self {
        Self::tol(1e-8)
    }
}

impl Dopri5 {
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

    fn validate(&self) -> Result<(), Error> {
        self.control.validate("DOPRI5", 0.0, false)
    }
}

/// The Dormand–Prince tableau (1980) and Shampine's dense-output weights (1986).
mod tableau {
    pub const C2: f64 = 0.2;
    pub const C3: f64 = 0.3;
    pub const C4: f64 = 0.8;
    pub const C5: f64 = 8.0 / 9.0;
    pub const A21: f64 = 0.2;
    pub const A31: f64 = 3.0 / 40.0;
    pub const A32: f64 = 9.0 / 40.0;
    pub const A41: f64 = 44.0 / 45.0;
    pub const A42: f64 = -56.0 / 15.0;
    pub const A43: f64 = 32.0 / 9.0;
    pub const A51: f64 = 19372.0 / 6561.0;
    pub const A52: f64 = -25360.0 / 2187.0;
    pub const A53: f64 = 64448.0 / 6561.0;
    pub const A54: f64 = -212.0 / 729.0;
    pub const A61: f64 = 9017.0 / 3168.0;
    pub const A62: f64 = -355.0 / 33.0;
    pub const A63: f64 = 46732.0 / 5247.0;
    pub const A64: f64 = 49.0 / 176.0;
    pub const A65: f64 = -5103.0 / 18656.0;
    // The 5th-order weights, which are also the 7th stage's row (FSAL).
    pub const A71: f64 = 35.0 / 384.0;
    pub const A73: f64 = 500.0 / 1113.0;
    pub const A74: f64 = 125.0 / 192.0;
    pub const A75: f64 = -2187.0 / 6784.0;
    pub const A76: f64 = 11.0 / 84.0;
    // Difference between the 5th- and 4th-order weights: the error estimate.
    pub const E1: f64 = 71.0 / 57600.0;
    pub const E3: f64 = -71.0 / 16695.0;
    pub const E4: f64 = 71.0 / 1920.0;
    pub const E5: f64 = -17253.0 / 339200.0;
    pub const E6: f64 = 22.0 / 525.0;
    pub const E7: f64 = -1.0 / 40.0;
    pub const D1: f64 = -12715105075.0 / 11282082432.0;
    pub const D3: f64 = 87487479700.0 / 32700410799.0;
    pub const D4: f64 = -10690763975.0 / 1880347072.0;
    pub const D5: f64 = 701980252875.0 / 199316789632.0;
    pub const D6: f64 = -1453857185.0 / 822651844.0;
    pub const D7: f64 = 69997945.0 / 29380423.0;
}

/// The tableau converted once per run to the system's scalar.
struct Coefficients<T> {
    c: [T; 4],
    a2: [T; 1],
    a3: [T; 2],
    a4: [T; 3],
    a5: [T; 4],
    a6: [T; 5],
    a7: [T; 5],
    e: [T; 6],
    d: [T; 6],
}

impl<T: Real> Coefficients<T> {
    fn new() -> Self {
        use tableau::*;
        fn lits<T: Real, const K: usize>(xs: [f64; K]) -> [T; K] {
            xs.map(T::lit)
        }
        Self {
            c: lits([C2, C3, C4, C5]),
            a2: lits([A21]),
            a3: lits([A31, A32]),
            a4: lits([A41, A42, A43]),
            a5: lits([A51, A52, A53, A54]),
            a6: lits([A61, A62, A63, A64, A65]),
            a7: lits([A71, A73, A74, A75, A76]),
            e: lits([E1, E3, E4, E5, E6, E7]),
            d: lits([D1, D3, D4, D5, D6, D7]),
        }
    }
}

impl Integrator for Dopri5 {
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

/// The stages of one attempt that the error estimate, the dense output and the
/// stiffness test need (k2 enters none of them).
struct Stages<T: Real, const N: usize, const Q: usize> {
    k3: Pair<T, N, Q>,
    k4: Pair<T, N, Q>,
    k5: Pair<T, N, Q>,
    k6: Pair<T, N, Q>,
    /// The argument of the 6th stage, at t_new (for the stiffness test).
    y6: Pair<T, N, Q>,
    /// The 5th-order solution, and its derivative (FSAL: the next k1).
    y_new: Pair<T, N, Q>,
    k7: Pair<T, N, Q>,
}

impl Dopri5 {
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
        self.control.check_precision::<T>("DOPRI5")?;
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
            5,
            rhs,
            (t0, t1),
            &y,
            &k1,
            &mut stats.evaluations,
        )?;
        let mut steps = Stepping::new(&self.control, PiController::dopri5(), t0, t1, h);
        let mut stiffness = super::StiffnessTest::new("DOPRI5", self.stiffness_test, 3.25);
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
            let err_vec = Pair::combination(h, co.e, [&k1, &s.k3, &s.k4, &s.k5, &s.k6, &s.k7]);
            let err = error_norm(&err_vec, &y, &s.y_new, atol, rtol);
            if !steps.judge(err, t_new, &s.y_new, &mut run.stats)? {
                continue;
            }
            // The step is accepted: a stiffness verdict is reported after it
            // is recorded, so the partial trajectory ends where the error says.
            let stiff = stiffness.check(
                run.stats.accepted,
                t_new,
                h,
                [&s.y_new, &s.y6, &s.k7, &s.k6],
            );
            let (r1, r2, r3, r4) = DenseSegment::cubic_part(h, &y, &k1, &s.y_new, &s.k7);
            let r5 = Pair::combination(h, co.d, [&k1, &s.k3, &s.k4, &s.k5, &s.k6, &s.k7]);
            let segment = DenseSegment::new(t, t_new, h, [r1, r2, r3, r4, r5]);
            // A projection moves the end point by about the local error; the
            // dense output keeps the unprojected polynomial, and the first stage
            // of the next step (FSAL) is re-evaluated at the projected state.
            let mut y_new = s.y_new;
            let mut k7 = s.k7;
            if settle(rhs, t_new, &mut y_new.q, &mut y_new.v)? {
                k7 = y_new.derivative(rhs, t_new, &mut run.stats.evaluations)?;
            }
            let stop = run.record(rhs, segment, y_new.q, y_new.v)?;
            stiff?;
            (y, k1) = (y_new, k7);
            steps.advance(t_new);
            if last || stop {
                return Ok(());
            }
        }
    }
}

/// The stages k2..k7 of an attempt of size h from (t, y) with first stage k1.
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
    let [c2, c3, c4, c5] = co.c;
    let k2 = y
        .add_combination(h, co.a2, [k1])
        .derivative(rhs, t + c2 * h, ev)?;
    let k3 = y
        .add_combination(h, co.a3, [k1, &k2])
        .derivative(rhs, t + c3 * h, ev)?;
    let k4 = y
        .add_combination(h, co.a4, [k1, &k2, &k3])
        .derivative(rhs, t + c4 * h, ev)?;
    let k5 = y
        .add_combination(h, co.a5, [k1, &k2, &k3, &k4])
        .derivative(rhs, t + c5 * h, ev)?;
    let y6 = y.add_combination(h, co.a6, [k1, &k2, &k3, &k4, &k5]);
    let k6 = y6.derivative(rhs, t_new, ev)?;
    let y_new = y.add_combination(h, co.a7, [k1, &k3, &k4, &k5, &k6]);
    let k7 = y_new.derivative(rhs, t_new, ev)?;
    Ok(Stages {
        k3,
        k4,
        k5,
        k6,
        y6,
        y_new,
        k7,
    })
}

/// Hairer's norm sqrt(1/n Σ (e_i / (atol + rtol·max(|y_i|, |y_new_i|)))²) over all
/// Q + N components.
fn error_norm<T: Real, const N: usize, const Q: usize>(
    e: &Pair<T, N, Q>,
    y: &Pair<T, N, Q>,
    y_new: &Pair<T, N, Q>,
    atol: T,
    rtol: T,
) -> T {
    let mut sum = T::zero();
    let parts = [
        (e.q.as_slice(), y.q.as_slice(), y_new.q.as_slice()),
        (e.v.as_slice(), y.v.as_slice(), y_new.v.as_slice()),
    ];
    for (e, y, y_new) in parts {
        for ((&e, &y), &y_new) in e.iter().zip(y).zip(y_new) {
            let sk = atol + rtol * abs(y).max(abs(y_new));
            let r = e / sk;
            sum += r * r;
        }
    }
    sqrt(sum / T::lit((Q + N) as f64))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::Stats;
    use crate::ode::test_problems::Oscillator;
    use nalgebra::Vector1;

    fn run(tol: f64) -> (f64, Stats) {
        let osc = Oscillator { omega: 2.0 };
        let tr = Dopri5::tol(tol)
            .integrate(&osc, 0.0, 10.0, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        let (q, v) = tr.final_state();
        let (qe, ve) = osc.exact(10.0);
        ((q[0] - qe).abs().max((v[0] - ve).abs()), *tr.stats())
    }

    #[test]
    fn error_scales_with_tolerance() {
        let mut prev = f64::INFINITY;
        for tol in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
            let (err, stats) = run(tol);
            // Global error within a modest multiple of tol, and decreasing.
            assert!(err < 100.0 * tol, "tol {tol}: err {err}");
            assert!(err < prev, "tol {tol}: err {err} not below {prev}");
            assert_eq!(stats.evaluations, 2 + 6 * stats.steps());
            prev = err;
        }
    }

    #[test]
    fn settings_are_validated() {
        let osc = Oscillator { omega: 1.0 };
        let go = |m: Dopri5| m.integrate(&osc, 0.0, 1.0, Vector1::new(1.0), Vector1::new(0.0));
        for m in [
            Dopri5::tol(0.0),
            Dopri5::tol(-1.0),
            Dopri5::tol(f64::NAN),
            Dopri5::tol(1e-6).atol(-1.0),
            Dopri5::tol(1e-6).h0(0.0),
            Dopri5::tol(1e-6).hmax(f64::INFINITY),
            Dopri5::tol(1e-6).max_steps(0),
        ] {
            assert!(
                matches!(
                    go(m),
                    Err(Failure {
                        error: Error::Settings(_),
                        ..
                    })
                ),
                "{m:?}"
            );
        }
        assert!(matches!(
            go(Dopri5::tol(1e-12).max_steps(5)),
            Err(Failure {
                error: Error::TooManySteps { max_steps: 5, .. },
                ..
            })
        ));
    }

    /// q̈ = 1/(1 − t)²: v = 1/(1 − t) − 1 blows up at t = 1.
    struct BlowUp;
    impl SecondOrder<f64, 1> for BlowUp {
        fn acceleration(
            &self,
            t: f64,
            _q: &Vector1<f64>,
            _v: &Vector1<f64>,
        ) -> Result<Vector1<f64>, Error> {
            Ok(Vector1::new((1.0 - t).powi(-2)))
        }
    }

    #[test]
    fn step_size_underflow_near_a_blow_up() {
        let e =
            Dopri5::tol(1e-6).integrate(&BlowUp, 0.0, 2.0, Vector1::new(0.0), Vector1::new(0.0));
        match e {
            Err(Failure {
                error: Error::StepSizeUnderflow { t, h },
                ..
            }) => {
                assert!(
                    (t - 1.0).abs() < 1e-6 && h <= 16.0 * f64::EPSILON * t,
                    "t {t}, h {h}"
                );
            }
            other => panic!("expected StepSizeUnderflow, got {other:?}"),
        }
    }

    #[test]
    fn silent_nan_is_an_error() {
        let e = Dopri5::tol(1e-6).integrate(
            &crate::ode::rk4::tests::Poisoned,
            0.0,
            1.0,
            Vector1::new(1.0),
            Vector1::new(0.0),
        );
        assert!(
            matches!(
                e,
                Err(Failure {
                    error: Error::NonFiniteState { .. },
                    ..
                })
            ),
            "{e:?}"
        );
    }

    #[test]
    fn hmax_and_h0_are_respected() {
        let osc = Oscillator { omega: 1.0 };
        let tr = Dopri5::tol(1e-3)
            .h0(1e-3)
            .hmax(0.05)
            .integrate(&osc, 0.0, 1.0, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        assert!((tr.times()[1] - 1e-3).abs() < 1e-18);
        assert!(
            tr.times()
                .windows(2)
                .all(|w| w[1] - w[0] <= 0.05 * (1.0 + 1e-12))
        );
        assert_eq!(*tr.times().last().unwrap(), 1.0);
    }
}
