//! The one step loop of the explicit embedded Runge–Kutta methods, as in
//! Hairer's `dopri5.f` and `dop853.f`, which share it line for line around
//! their own stages: the settings and the start checked, the `hinit` first
//! step, then per attempt the stages, the error norm and the PI controller's
//! verdict ([`stepping`]), and per accepted step the stiffness test
//! ([`stiffness`]), the dense output, the projection back onto the system's
//! manifold and the recording, with the partial trajectory returned on any
//! failure ([`Run`]).
//!
//! A method brings what is its own through [`EmbeddedMethod`]: its stages, its
//! error estimate (DOPRI5's one embedded difference, DOP853's blend of a 5th-
//! and a 3rd-order one), its continuous extension, and the constants of its
//! controller and of its stability region.

mod controller;
mod stepping;
mod stiffness;

pub(crate) use controller::PiController;

use super::run::Run;
use super::settings::StepControl;
use super::{
    Continuation, DenseSegment, Pair, Record, SecondOrder, Trajectory, check_orientations,
    check_problem, settle,
};
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::func::abs;
use nalgebra::SVector;
use stepping::{Stepping, first_step};
use stiffness::StiffnessTest;

/// An explicit embedded Runge–Kutta method as the loop reads it: implemented
/// by the method's coefficients, converted to the system's scalar.
pub(crate) trait EmbeddedMethod<T: Real, const N: usize, const Q: usize> {
    /// The name errors and settings messages carry ("DOPRI5").
    const NAME: &'static str;
    /// The order `hinit` aims the first step at.
    const ORDER: u32;
    /// Where the stability region ends on the negative real axis: h·|λ|
    /// beyond it, again and again, is stiffness.
    const STABILITY_LIMIT: f64;

    /// What one attempt keeps of its stages for the error estimate, the
    /// stiffness test and the dense output.
    type Stages;

    /// Hairer's controller settings for the method.
    fn controller() -> PiController<T>;

    /// The stages of `attempt` after its first, up to the new solution.
    ///
    /// # Errors
    /// Whatever the right-hand side cannot evaluate; the loop retries a
    /// failure of the state with a smaller step.
    fn stages<F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        attempt: &Attempt<'_, T, N, Q>,
        evaluations: &mut usize,
    ) -> Result<Self::Stages, Error>;

    /// The new solution at `t_new`, the one the step keeps if accepted.
    fn solution(stages: &Self::Stages) -> &Pair<T, N, Q>;

    /// The error norm the controller judges: at most 1 accepts the step.
    fn error(
        &self,
        attempt: &Attempt<'_, T, N, Q>,
        stages: &Self::Stages,
        tolerance: &Tolerance<T>,
    ) -> T;

    /// The derivative at the accepted solution, which is also the next
    /// step's first stage.
    ///
    /// # Errors
    /// Whatever the right-hand side cannot evaluate.
    fn end_slope<F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        t_new: T,
        stages: &Self::Stages,
        evaluations: &mut usize,
    ) -> Result<Pair<T, N, Q>, Error>;

    /// The argument and the derivative of the last stage at `t_new`: beside
    /// the solution and its derivative, they give the stiffness test its
    /// estimate of |λ|.
    fn last_stage(stages: &Self::Stages) -> [&Pair<T, N, Q>; 2];

    /// The continuous extension of an accepted step whose end has the
    /// derivative `end_slope`.
    ///
    /// # Errors
    /// Whatever the right-hand side cannot evaluate, for a method whose
    /// extension needs more stages.
    fn dense<F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        attempt: &Attempt<'_, T, N, Q>,
        stages: &Self::Stages,
        end_slope: &Pair<T, N, Q>,
        evaluations: &mut usize,
    ) -> Result<DenseSegment<T, N, Q>, Error>;
}

/// One attempted step: from (t, y), whose derivative is the first stage k1,
/// a step of size h to t_new (t + h, or the span's end itself on the last
/// step, where h was shortened to reach it).
pub(crate) struct Attempt<'a, T: Real, const N: usize, const Q: usize> {
    pub t: T,
    pub h: T,
    pub t_new: T,
    pub y: &'a Pair<T, N, Q>,
    pub k1: &'a Pair<T, N, Q>,
}

/// The settings an explicit method's run reads.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    pub control: StepControl,
    /// Hairer's NSTIFF: test for stiffness every so many accepted steps
    /// (0: never).
    pub stiffness_test: usize,
    pub record: Record,
}

impl Settings {
    /// What a run checks before its first evaluation: the settings of
    /// `method`, the span and the initial state.
    fn check<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        method: &'static str,
        rhs: &F,
        (t0, t1): (T, T),
        y0: &Pair<T, N, Q>,
    ) -> Result<(), Error> {
        self.record.check_span(t0, t1, Q + N)?;
        self.control.validate(method, 0.0, false)?;
        self.control.check_precision::<T>(method)?;
        check_problem(t0, t1, &y0.q, &y0.v)?;
        check_orientations(rhs, &y0.q)
    }
}

/// The tolerances in the system's scalar, and Hairer's weighting of an error
/// by them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tolerance<T> {
    atol: T,
    rtol: T,
}

impl<T: Real> Tolerance<T> {
    fn of(control: &StepControl) -> Self {
        Self {
            atol: T::lit(control.atol),
            rtol: T::lit(control.rtol),
        }
    }

    /// Σ (e_i / sk_i)² over all Q + N components for each of the K error
    /// vectors, with Hairer's scale sk = atol + rtol·max(|y|, |y_new|).
    pub fn scaled_squares<const N: usize, const Q: usize, const K: usize>(
        &self,
        errors: [&Pair<T, N, Q>; K],
        y: &Pair<T, N, Q>,
        y_new: &Pair<T, N, Q>,
    ) -> [T; K] {
        let mut sums = [T::zero(); K];
        let parts = [
            (
                errors.map(|e| e.q.as_slice()),
                y.q.as_slice(),
                y_new.q.as_slice(),
            ),
            (
                errors.map(|e| e.v.as_slice()),
                y.v.as_slice(),
                y_new.v.as_slice(),
            ),
        ];
        for (errors, y, y_new) in parts {
            for i in 0..y.len() {
                let sk = self.atol + self.rtol * abs(y[i]).max(abs(y_new[i]));
                for (sum, e) in sums.iter_mut().zip(&errors) {
                    let r = e[i] / sk;
                    *sum += r * r;
                }
            }
        }
        sums
    }
}

/// A run of `method` from (q0, v0) at t0 to t1, going on from the recording
/// `from`: the trajectory, or the failure with the trajectory up to the last
/// accepted step.
pub(crate) fn continue_run<
    T: Real,
    const N: usize,
    const Q: usize,
    F: SecondOrder<T, N, Q>,
    M: EmbeddedMethod<T, N, Q>,
>(
    method: &M,
    settings: &Settings,
    rhs: &F,
    from: Continuation<T>,
    (t0, t1): (T, T),
    (q0, v0): (SVector<T, Q>, SVector<T, N>),
) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>> {
    let mut run = Run::of(settings.record, from, rhs, t0, q0, v0);
    // Everything computed before a failure goes back with it.
    let outcome = integrate(method, settings, rhs, (t0, t1), Pair::new(q0, v0), &mut run);
    run.finish(outcome)
}

/// Checks the settings and the problem, then steps from y0 at t0 to t1.
fn integrate<
    T: Real,
    const N: usize,
    const Q: usize,
    F: SecondOrder<T, N, Q>,
    M: EmbeddedMethod<T, N, Q>,
>(
    method: &M,
    settings: &Settings,
    rhs: &F,
    (t0, t1): (T, T),
    y0: Pair<T, N, Q>,
    run: &mut Run<T, N, Q>,
) -> Result<(), Error> {
    settings.check(M::NAME, rhs, (t0, t1), &y0)?;
    let control = &settings.control;
    let tolerance = Tolerance::of(control);
    let evaluations = &mut run.stats.evaluations;
    let mut y = y0;
    let mut k1 = y0.derivative(rhs, t0, evaluations)?;
    let h = first_step(control, M::ORDER, rhs, (t0, t1), &y, &k1, evaluations)?;
    let mut steps = Stepping::new(control, M::controller(), t0, t1, h);
    let mut stiffness = StiffnessTest::new(M::NAME, settings.stiffness_test, M::STABILITY_LIMIT);
    loop {
        let (t_new, last) = steps.begin(&run.stats)?;
        let t = steps.t;
        let h = steps.h;
        let attempt = Attempt {
            t,
            h,
            t_new,
            y: &y,
            k1: &k1,
        };
        let stages = match method.stages(rhs, &attempt, &mut run.stats.evaluations) {
            Ok(stages) => stages,
            Err(e) => {
                steps.stage_failed(e, &mut run.stats)?;
                continue;
            }
        };
        let err = method.error(&attempt, &stages, &tolerance);
        let y_new = M::solution(&stages);
        if !steps.judge(err, t_new, y_new, &mut run.stats)? {
            continue;
        }
        let evaluations = &mut run.stats.evaluations;
        let k_new = method.end_slope(rhs, t_new, &stages, evaluations)?;
        // The step is accepted: a stiffness verdict is reported after it is
        // recorded, so the partial trajectory ends where the error says.
        let [y_stage, k_stage] = M::last_stage(&stages);
        let stiff = stiffness.check(
            run.stats.accepted,
            t_new,
            h,
            [y_new, y_stage, &k_new, k_stage],
        );
        let segment = method.dense(rhs, &attempt, &stages, &k_new, evaluations)?;
        // A projection moves the end point by about the local error; the
        // dense output keeps the unprojected polynomial, and the first stage
        // of the next step is re-evaluated at the projected state.
        let mut y_new = *y_new;
        let mut k_new = k_new;
        if settle(rhs, t_new, &mut y_new.q, &mut y_new.v)? {
            k_new = y_new.derivative(rhs, t_new, evaluations)?;
        }
        let stop = run.record(rhs, segment, y_new.q, y_new.v)?;
        stiff?;
        (y, k1) = (y_new, k_new);
        steps.advance(t_new);
        if last || stop {
            return Ok(());
        }
    }
}
