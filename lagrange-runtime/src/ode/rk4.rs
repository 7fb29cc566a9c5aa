//! The classic fourth-order Runge–Kutta method with a fixed step.

use super::run::{Run, fixed_steps};
use super::verlet::fixed_step_count;
use super::{
    DenseSegment, Integrator, Pair, SecondOrder, check_orientations, check_problem, settle,
};
use crate::error::SettingsError;
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::ode::{Continuation, Record, Trajectory};
use nalgebra::SVector;

/// Classic RK4 with a fixed step `h`; the last step is shortened so that the
/// integration lands exactly on the end time.
///
/// Step k ends at t₀ + k·h (computed from k, not accumulated, so that a step
/// chosen as T/n lands on T up to one rounding). Costs 4 evaluations per step plus
/// one at the start; the derivative at each step's end is reused as the next
/// step's first stage and for the dense output, which is the cubic Hermite
/// interpolant through (q, v, a) at both ends of each step (3rd order uniformly:
/// local interpolation error O(h⁴), one order below the method itself).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rk4 {
    h: f64,
    max_steps: usize,
    /// What the trajectory keeps of the steps.
    record: Record,
}

impl Rk4 {
    /// What the trajectory keeps of the steps (default: every step with its
    /// dense output); see [`Record`].
    pub fn record(mut self, record: Record) -> Self {
        self.record = record;
        self
    }

    /// RK4 with step size `h`.
    pub fn step(h: f64) -> Self {
        Self {
            record: Record::Steps,
            h,
            max_steps: 10_000_000,
        }
    }

    /// Refuses spans that need more than `n` steps (default 10⁷), before starting.
    pub fn max_steps(mut self, n: usize) -> Self {
        self.max_steps = n;
        self
    }

    /// The step size.
    pub fn step_size(&self) -> f64 {
        self.h
    }
}

impl Integrator for Rk4 {
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
        self.max_steps
    }
}

impl Rk4 {
    /// Checks the settings and the problem, then takes the fixed steps.
    fn run<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        (t0, t1): (T, T),
        y0: Pair<T, N, Q>,
        run: &mut Run<T, N, Q>,
    ) -> Result<(), Error> {
        self.record.check_span(t0, t1, Q + N)?;
        if !(self.h.is_finite() && self.h > 0.0) {
            return Err(SettingsError::Value {
                owner: "RK4",
                setting: "step size",
                value: self.h,
                requirement: "positive and finite".into(),
            }
            .into());
        }
        check_problem(t0, t1, &y0.q, &y0.v)?;
        check_orientations(rhs, &y0.q)?;
        let n = fixed_step_count("Rk4", self.h, self.max_steps, t0, t1)?;
        let h = T::lit(self.h);

        let mut y = y0;
        let mut f = y.derivative(rhs, t0, &mut run.stats.evaluations)?;
        run.traj.reserve(n);
        for (t, t_next) in fixed_steps(t0, t1, h, n) {
            let ev = &mut run.stats.evaluations;
            let mut y_next = step(rhs, (t, t_next), &y, &f, ev)?;
            if !y_next.is_finite() {
                // Only a right-hand side that returns NaN or ∞ without an error gets here.
                return Err(Error::non_finite(t_next, &y_next.q, &y_next.v));
            }
            settle(rhs, t_next, &mut y_next.q, &mut y_next.v)?;
            let f_next = y_next.derivative(rhs, t_next, ev)?;
            let segment = DenseSegment::hermite(t, t_next, &y, &f, &y_next, &f_next);
            let stop = run.record(rhs, segment, y_next.q, y_next.v)?;
            run.stats.accepted += 1;
            (y, f) = (y_next, f_next);
            if stop {
                break;
            }
        }
        Ok(())
    }
}

/// One RK4 step from (t, y), with first stage f = y'(t), to t_next.
fn step<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    (t, t_next): (T, T),
    y: &Pair<T, N, Q>,
    f: &Pair<T, N, Q>,
    ev: &mut usize,
) -> Result<Pair<T, N, Q>, Error> {
    let hk = t_next - t;
    let half = T::lit(0.5);
    let two = T::lit(2.0);
    let k2 = y
        .add_combination(hk * half, [T::one()], [f])
        .derivative(rhs, t + hk * half, ev)?;
    let k3 = y
        .add_combination(hk * half, [T::one()], [&k2])
        .derivative(rhs, t + hk * half, ev)?;
    let k4 = y
        .add_combination(hk, [T::one()], [&k3])
        .derivative(rhs, t_next, ev)?;
    Ok(y.add_combination(
        hk / T::lit(6.0),
        [T::one(), two, two, T::one()],
        [f, &k2, &k3, &k4],
    ))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::ode::test_problems::Oscillator;
    use nalgebra::Vector1;

    fn error_at(h: f64, t_end: f64) -> f64 {
        let osc = Oscillator { omega: 1.0 };
        let tr = Rk4::step(h)
            .integrate(&osc, 0.0, t_end, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        let (q, v) = tr.final_state();
        let (qe, ve) = osc.exact(t_end);
        (q[0] - qe).abs().max((v[0] - ve).abs())
    }

    #[test]
    fn fourth_order() {
        let e1 = error_at(0.1, 10.0);
        let e2 = error_at(0.05, 10.0);
        let ratio = e1 / e2;
        assert!((ratio - 16.0).abs() < 0.5, "ratio {ratio}");
    }

    #[test]
    fn lands_on_end_time_and_counts() {
        let osc = Oscillator { omega: 1.0 };
        // 1.0 / 0.3: three full steps and a shortened one.
        let tr = Rk4::step(0.3)
            .integrate(&osc, 0.0, 1.0, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        assert_eq!(tr.times().last(), Some(&1.0));
        assert_eq!(tr.len(), 5);
        assert_eq!(tr.stats().evaluations, 1 + 4 * 4);
        // A span that is a whole number of steps up to rounding: no sliver step.
        let tr = Rk4::step(0.1)
            .integrate(&osc, 0.0, 0.7, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        assert_eq!(tr.len(), 8);
        assert_eq!(tr.times()[7], 0.7);
    }

    /// a = NaN from t = 0.5 on, reported as an acceleration rather than an error.
    pub(crate) struct Poisoned;
    impl SecondOrder<f64, 1> for Poisoned {
        fn acceleration(
            &self,
            t: f64,
            _q: &Vector1<f64>,
            _v: &Vector1<f64>,
        ) -> Result<Vector1<f64>, Error> {
            Ok(Vector1::new(if t < 0.5 { -1.0 } else { f64::NAN }))
        }
    }

    #[test]
    fn silent_nan_is_an_error() {
        let e = Rk4::step(0.1).integrate(&Poisoned, 0.0, 1.0, Vector1::new(1.0), Vector1::new(0.0));
        assert!(
            matches!(e, Err(Failure { error: Error::NonFiniteState { t, .. }, .. }) if (t - 0.5).abs() < 1e-12),
            "{e:?}"
        );
    }

    #[test]
    fn invalid_step() {
        let osc = Oscillator { omega: 1.0 };
        for h in [0.0, -1.0, f64::NAN] {
            let e = Rk4::step(h).integrate(&osc, 0.0, 1.0, Vector1::new(1.0), Vector1::new(0.0));
            assert!(matches!(
                e,
                Err(Failure {
                    error: Error::Settings(_),
                    ..
                })
            ));
        }
        let e = Rk4::step(1e-3).max_steps(10).integrate(
            &osc,
            0.0,
            1.0,
            Vector1::new(1.0),
            Vector1::new(0.0),
        );
        assert!(matches!(
            e,
            Err(Failure {
                error: Error::TooManySteps { max_steps: 10, .. },
                ..
            })
        ));
    }
}
