//! Moreau's midpoint time-stepping scheme with a fixed step: the integrator
//! of [`MoreauJean`], and on its own (without contacts) the position form
//! of Störmer–Verlet.

use super::run::{Run, fixed_steps};
use super::verlet::fixed_step_count;
use super::{DenseSegment, Integrator, Pair, SecondOrder, check_orientations, check_problem};
use crate::error::{Error, Failure, SettingsError};
use crate::numeric::Real;
use crate::ode::{Continuation, Record, Trajectory};
use nalgebra::SVector;

/// The Moreau–Jean time-stepping scheme, in Moreau's midpoint form, with a
/// fixed step `h`:
///
/// ```text
/// q_m = q + h/2 · v
/// v₁  = v + h · M(q_m)⁻¹ (Q − h)(t + h/2, q_m, v) + M(q_m)⁻¹ Jᵀ P
/// q₁  = q_m + h/2 · v₁
/// ```
///
/// where P are the contacts' impulses over the step. It is the scheme of
/// *nonsmooth contact dynamics* (Moreau 1988, Jean 1999; Acary and
/// Brogliato, *Numerical Methods for Nonsmooth Dynamical Systems*, §10.1):
/// the contacts whose gap at the midpoint is closed take one impulse
/// problem per step, with Newton's law at the velocity level
/// (uₙ⁺ + e uₙ ≥ 0) and Coulomb's isotropic cone on the impulses, solved by
/// nonsmooth Gauss–Seidel with an exact solution per contact. Impacts,
/// sticking, sliding and lifting off all happen inside that one problem, so
/// the step never stops for an event: many contacts changing often (a box
/// settling on its corners, feet on the ground) cost what a smooth motion
/// costs. The price is accuracy: events fall on the step's grid, the answers
/// are of order one in h across them, and the gaps may close to −O(h·|v|)
/// (the impact is applied at the step after the surface is crossed).
///
/// [`Simulation::run_contacts`](crate::Simulation::run_contacts) runs this
/// scheme when the simulation's integrator is a `MoreauJean`
/// (`.integrator(MoreauJean::step(1e-3))`), and the event-driven one with
/// any other integrator; [`contact`](crate::contact) says which to choose.
///
/// Without contacts (any other run) the step is q_m = q + h/2·v,
/// v₁ = v + h·a(t + h/2, q_m, v), q₁ = q_m + h/2·v₁: the position form of
/// Störmer–Verlet, symplectic and of order 2 for a constant mass matrix and
/// velocity-independent forces, of order 1 otherwise (the acceleration is
/// taken at the step's first velocity). The dense output is the quadratic
/// through both ends with the step's mean acceleration, which the step's
/// trapezoidal relation q₁ − q = h (v + v₁)/2 makes exact at both ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoreauJean {
    h: f64,
    max_steps: usize,
    record: Record,
    sweeps: usize,
    tolerance: f64,
}

impl MoreauJean {
    /// The scheme with step size `h`: at most 1000 Gauss–Seidel sweeps per
    /// step, to a tolerance of 1e-10 on the contacts' velocities.
    pub fn step(h: f64) -> Self {
        Self {
            h,
            max_steps: 10_000_000,
            record: Record::Steps,
            sweeps: 1000,
            tolerance: 1e-10,
        }
    }

    /// What the trajectory keeps of the steps (default: every step with its
    /// dense output); see [`Record`].
    pub fn record(mut self, record: Record) -> Self {
        self.record = record;
        self
    }

    /// Refuses spans that need more than `n` steps (default 10⁷), before
    /// starting.
    pub fn max_steps(mut self, n: usize) -> Self {
        self.max_steps = n;
        self
    }

    /// The most sweeps of nonsmooth Gauss–Seidel over the contacts of one
    /// step (default 1000); a step that needs more stops the run with
    /// [`ContactFault::ImpulsesUnsettled`](crate::error::ContactFault::ImpulsesUnsettled).
    pub fn sweeps(mut self, n: usize) -> Self {
        self.sweeps = n;
        self
    }

    /// The impulses have settled when a sweep changes no contact's local
    /// velocities by more than this (default 1e-10, in the units of the
    /// contacts' velocity rows).
    pub fn tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// The step size.
    pub fn step_size(&self) -> f64 {
        self.h
    }

    /// The most Gauss–Seidel sweeps per step.
    pub fn max_sweeps(&self) -> usize {
        self.sweeps
    }

    /// The velocity tolerance of the impulses.
    pub fn velocity_tolerance(&self) -> f64 {
        self.tolerance
    }

    /// What the trajectory keeps of the steps.
    pub fn recording(&self) -> Record {
        self.record
    }

    /// The number of steps over [t0, t1], after checking the settings.
    pub(crate) fn steps<T: Real>(&self, t0: T, t1: T) -> Result<usize, Error> {
        let owner = "Moreau–Jean";
        if self.sweeps == 0 {
            return Err(SettingsError::ZeroCount {
                owner,
                setting: "sweeps",
            }
            .into());
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(SettingsError::Value {
                owner,
                setting: "tolerance",
                value: self.tolerance,
                requirement: "positive and finite".into(),
            }
            .into());
        }
        fixed_step_count(owner, self.h, self.max_steps, t0, t1)
    }
}

/// The dense output of one step from (q, v) to (q₁, v₁) over [t, t₁]: the
/// cubic Hermite interpolant with the mean acceleration at both ends, which
/// is the quadratic q + s v + s²/2 (v₁ − v)/h when q₁ − q = h (v + v₁)/2.
pub(crate) fn midpoint_segment<T: Real, const N: usize, const Q: usize, F>(
    rhs: &F,
    (t, t1): (T, T),
    (q, v): (&SVector<T, Q>, &SVector<T, N>),
    (q1, v1): (&SVector<T, Q>, &SVector<T, N>),
) -> DenseSegment<T, N, Q>
where
    F: SecondOrder<T, N, Q>,
{
    let mean = (v1 - v) / (t1 - t);
    DenseSegment::hermite(
        t,
        t1,
        &Pair::new(*q, *v),
        &Pair::new(rhs.rate(q, v), mean),
        &Pair::new(*q1, *v1),
        &Pair::new(rhs.rate(q1, v1), mean),
    )
}

impl Integrator for MoreauJean {
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
        let outcome = self.smooth(rhs, (t0, t1), (q0, v0), &mut run);
        run.finish(outcome)
    }

    fn max_steps(&self) -> usize {
        self.max_steps
    }

    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
}

impl MoreauJean {
    /// The steps without contacts: drift, kick, drift.
    fn smooth<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        (t0, t1): (T, T),
        (q0, v0): (SVector<T, Q>, SVector<T, N>),
        run: &mut Run<T, N, Q>,
    ) -> Result<(), Error> {
        self.record.check_span(t0, t1, Q + N)?;
        check_problem(t0, t1, &q0, &v0)?;
        check_orientations(rhs, &q0)?;
        let n = self.steps(t0, t1)?;
        let half = T::lit(0.5);
        let (mut q, mut v) = (q0, v0);
        run.traj.reserve(n);
        for (t, t_next) in fixed_steps(t0, t1, T::lit(self.h), n) {
            let hk = t_next - t;
            let mid = rhs.advance(&q, &(v * (half * hk)));
            run.stats.evaluations += 1;
            let a = rhs.acceleration(t + half * hk, &mid, &v)?;
            let v_next = v + a * hk;
            let q_next = rhs.advance(&mid, &(v_next * (half * hk)));
            if !Pair::new(q_next, v_next).is_finite() {
                return Err(Error::non_finite(t_next, &q_next, &v_next));
            }
            let segment = midpoint_segment(rhs, (t, t_next), (&q, &v), (&q_next, &v_next));
            let stop = run.record(rhs, segment, q_next, v_next)?;
            run.stats.accepted += 1;
            (q, v) = (q_next, v_next);
            if stop {
                break;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::test_problems::Oscillator;
    use nalgebra::Vector1;

    fn error_at(h: f64) -> f64 {
        let osc = Oscillator { omega: 1.0 };
        let traj = MoreauJean::step(h)
            .integrate(&osc, 0.0, 2.0, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        let (q, _) = traj.final_state();
        (q[0] - 2.0f64.cos()).abs()
    }

    #[test]
    fn second_order_on_the_oscillator() {
        let (coarse, fine) = (error_at(0.02), error_at(0.01));
        let order = (coarse / fine).log2();
        assert!((order - 2.0).abs() < 0.05, "order {order}");
    }

    #[test]
    fn dense_output_meets_both_ends() {
        let osc = Oscillator { omega: 1.0 };
        let traj = MoreauJean::step(0.1)
            .integrate(&osc, 0.0, 1.0, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap();
        let seg = &traj.segments()[3];
        let (q, v) = seg.eval(seg.end());
        assert!((q[0] - traj.positions()[4][0]).abs() < 1e-15);
        assert!((v[0] - traj.velocities()[4][0]).abs() < 1e-15);
    }

    #[test]
    fn refuses_no_sweeps() {
        let osc = Oscillator { omega: 1.0 };
        let bad = MoreauJean::step(0.1).sweeps(0);
        assert!(bad.steps(0.0, 1.0).is_err());
        let bad = MoreauJean::step(0.1).tolerance(f64::NAN);
        assert!(bad.steps(0.0, 1.0).is_err());
        assert!(
            MoreauJean::step(-1.0)
                .integrate(&osc, 0.0, 1.0, Vector1::new(1.0), Vector1::new(0.0))
                .is_err()
        );
    }
}
