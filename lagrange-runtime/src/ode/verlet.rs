//! Störmer–Verlet in its velocity form, with a fixed step.

use super::run::{Run, fixed_steps};
use super::{
    DenseSegment, Integrator, Pair, SecondOrder, check_orientations, check_problem, settle,
};
use crate::error::SettingsError;
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::ode::{Continuation, Record, Trajectory};
use nalgebra::SVector;

/// Velocity Verlet with a fixed step `h`:
///
/// ```text
/// v½ = v + h/2 · a(t, q, v)
/// q₁ = q + h · v½
/// v₁ = v½ + h/2 · a(t + h, q₁, v½)
/// ```
///
/// One evaluation per step: the acceleration at the end of a step is the next
/// step's first one.
///
/// **Assumption.** The method is symplectic, time-reversible and of order 2 —
/// hence its energy error stays bounded (O(h²)) over very long runs instead of
/// drifting — for systems q̈ = −M⁻¹∇V(q) with a *constant* mass matrix and
/// *velocity-independent* forces (particles in Cartesian coordinates, a pendulum
/// in its angle, a chain of springs). It runs on any [`SecondOrder`] system, but
/// with a configuration-dependent mass matrix (so Coriolis terms in the
/// acceleration) or velocity-dependent forces (damping, gyroscopic terms) the
/// end-of-step acceleration is evaluated at the half-step velocity v½, and the
/// method is then neither symplectic nor guaranteed to be second order. For a
/// general M(q) use [`Gauss`](crate::Gauss), which is symplectic in (q, p).
///
/// **With orientations** (quaternions in q, body-axis ω in v) the gyroscopic
/// terms always make a depend on v, so the first kick is implicit,
/// v½ = v + h/2 · a(t, q, v½) (fixed-point iteration, a few evaluations per
/// step), and the drift turns each quaternion by exp(h ω½): the step is
/// symmetric and of order 2, and on a free body's Euler equations it is the
/// implicit midpoint rule, keeping its kinetic energy and |I ω|.
///
/// Like [`Rk4`](crate::Rk4), step k ends at t₀ + k·h and the last step is shortened
/// to land on the end time; the dense output is the cubic Hermite interpolant
/// through (q, v, a) at both ends of each step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StormerVerlet {
    h: f64,
    max_steps: usize,
    /// What the trajectory keeps of the steps.
    record: Record,
}

impl StormerVerlet {
    /// What the trajectory keeps of the steps (default: every step with its
    /// dense output); see [`Record`].
    pub fn record(mut self, record: Record) -> Self {
        self.record = record;
        self
    }

    /// Velocity Verlet with step size `h`.
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

/// The number of fixed steps of size `h` covering [t0, t1], refusing more than
/// `max_steps`. A span that is a whole number of steps up to rounding is not
/// followed by a sliver of a step.
pub(crate) fn fixed_step_count<T: Real>(
    name: &'static str,
    h: f64,
    max_steps: usize,
    t0: T,
    t1: T,
) -> Result<usize, Error> {
    if !(h.is_finite() && h > 0.0) {
        return Err(SettingsError::Value {
            owner: name,
            setting: "step size",
            value: h,
            requirement: "positive and finite".into(),
        }
        .into());
    }
    let ratio = ((t1 - t0) / T::lit(h)).to_f64();
    let n = (ratio - 1e-9 * ratio.max(1.0)).ceil().max(1.0);
    if n > max_steps as f64 {
        return Err(Error::TooManySteps {
            t: t0.to_f64(),
            max_steps,
            needed: Some(n as usize),
        });
    }
    Ok(n as usize)
}

impl Integrator for StormerVerlet {
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
        let outcome = self.run(rhs, (t0, t1), (q0, v0), &mut run);
        run.finish(outcome)
    }

    fn max_steps(&self) -> usize {
        self.max_steps
    }
}

impl StormerVerlet {
    /// Checks the settings and the problem, then takes the fixed steps.
    fn run<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        (t0, t1): (T, T),
        (q0, v0): (SVector<T, Q>, SVector<T, N>),
        run: &mut Run<T, N, Q>,
    ) -> Result<(), Error> {
        self.record.check_span(t0, t1, Q + N)?;
        check_problem(t0, t1, &q0, &v0)?;
        check_orientations(rhs, &q0)?;
        let n = fixed_step_count("Störmer–Verlet", self.h, self.max_steps, t0, t1)?;
        let h = T::lit(self.h);
        let half = T::lit(0.5);

        let mut q = q0;
        let mut v = v0;
        let stats = &mut run.stats;
        stats.evaluations += 1;
        let mut a = rhs.acceleration(t0, &q, &v)?;
        run.traj.reserve(n);
        for (t, t_next) in fixed_steps(t0, t1, h, n) {
            let hk = t_next - t;
            let v_half = if F::ORIENTATIONS.is_empty() {
                v + a * (half * hk)
            } else {
                implicit_kick(rhs, (t, hk), (&q, &v), a, &mut run.stats)?
            };
            let mut q_next = rhs.advance(&q, &(v_half * hk));
            run.stats.evaluations += 1;
            let mut a_next = rhs.acceleration(t_next, &q_next, &v_half)?;
            let mut v_next = v_half + a_next * (half * hk);
            if !Pair::new(q_next, v_next).is_finite() {
                return Err(Error::non_finite(t_next, &q_next, &v_next));
            }
            let segment = DenseSegment::hermite(
                t,
                t_next,
                &Pair::new(q, v),
                &Pair::new(rhs.rate(&q, &v), a),
                &Pair::new(q_next, v_next),
                &Pair::new(rhs.rate(&q_next, &v_next), a_next),
            );
            if settle(rhs, t_next, &mut q_next, &mut v_next)? {
                run.stats.evaluations += 1;
                a_next = rhs.acceleration(t_next, &q_next, &v_next)?;
            }
            let stop = run.record(rhs, segment, q_next, v_next)?;
            run.stats.accepted += 1;
            (q, v, a) = (q_next, v_next, a_next);
            if stop {
                break;
            }
        }
        Ok(())
    }
}

/// Most fixed-point iterations of the implicit half kick.
const KICK_ITERATIONS: usize = 50;

/// v½ = v + h/2 · a(t, q, v½), by fixed-point iteration from the guess
/// `a` (the last acceleration known): the first kick of a system with
/// orientations, whose gyroscopic terms make a depend on v. With the
/// explicit end kick the step is symmetric and of order 2 (Hairer, Lubich
/// and Wanner, *Geometric Numerical Integration*, §VI.3), and on Euler's
/// equations it is the implicit midpoint rule, which keeps the kinetic
/// energy and |I ω| of a free body; the explicit kick, a(t, q, v), made it
/// first order, and a tumbling body's energy grew until it overflowed.
///
/// # Errors
/// [`Error::NewtonFailure`] if the iteration does not settle (h |∂a/∂v| / 2
/// too large: take a smaller step); whatever the system reports.
fn implicit_kick<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    (t, h): (T, T),
    (q, v): (&SVector<T, Q>, &SVector<T, N>),
    mut a: SVector<T, N>,
    stats: &mut super::Stats,
) -> Result<SVector<T, N>, Error> {
    let half = T::lit(0.5) * h;
    let mut w = v + a * half;
    for iteration in 1..=KICK_ITERATIONS {
        stats.evaluations += 1;
        // a is finite at the start of the step: an iterate where it is not
        // has diverged (h too large), which a smaller step answers.
        a = match rhs.acceleration(t, q, &w) {
            Err(Error::NonFiniteState { .. }) => {
                return Err(Error::NewtonFailure {
                    t: t.to_f64(),
                    h: h.to_f64(),
                    iterations: iteration,
                });
            }
            a => a?,
        };
        let next = v + a * half;
        let change = (next - w).amax();
        let scale = T::one() + next.amax();
        w = next;
        if !change.is_finite() {
            return Err(Error::NewtonFailure {
                t: t.to_f64(),
                h: h.to_f64(),
                iterations: iteration,
            });
        }
        if change <= T::lit(4.0) * T::default_epsilon() * scale {
            return Ok(w);
        }
    }
    Err(Error::NewtonFailure {
        t: t.to_f64(),
        h: h.to_f64(),
        iterations: KICK_ITERATIONS,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::test_problems::Oscillator;
    use nalgebra::Vector1;

    fn error_at(h: f64) -> f64 {
        let osc = Oscillator { omega: 1.0 };
        let tr = StormerVerlet::step(h)
            .integrate(&osc, 0.0, 10.0, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        let (q, v) = tr.final_state();
        let (qe, ve) = osc.exact(10.0);
        (q[0] - qe).abs().max((v[0] - ve).abs())
    }

    #[test]
    fn second_order() {
        let ratio = error_at(0.02) / error_at(0.01);
        assert!((ratio - 4.0).abs() < 0.1, "ratio {ratio}");
    }

    #[test]
    fn one_evaluation_per_step_and_lands_on_end() {
        let osc = Oscillator { omega: 1.0 };
        let tr = StormerVerlet::step(0.3)
            .integrate(&osc, 0.0, 1.0, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        assert_eq!(tr.times().last(), Some(&1.0));
        assert_eq!(tr.len(), 5);
        assert_eq!(tr.stats().evaluations, 1 + 4);
        for h in [0.0, -1.0, f64::INFINITY] {
            let e = StormerVerlet::step(h).integrate(
                &osc,
                0.0,
                1.0,
                Vector1::new(1.0),
                Vector1::new(0.0),
            );
            assert!(
                matches!(
                    e,
                    Err(Failure {
                        error: Error::Settings(_),
                        ..
                    })
                ),
                "{e:?}"
            );
        }
        let e = StormerVerlet::step(1e-3).max_steps(10).integrate(
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

    #[test]
    fn silent_nan_is_an_error() {
        let e = StormerVerlet::step(0.1).integrate(
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
}
