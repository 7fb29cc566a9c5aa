//! Box-constrained differential dynamic programming (Gauss–Newton DDP, or
//! iLQR, with the control limits of Tassa, Mansard and Todorov 2014, the
//! algorithm of Crocoddyl's `SolverBoxDDP`): a backward pass builds a
//! quadratic model of the cost-to-go along the current plan and solves a
//! box QP per step for the input change and its feedback gain; a forward
//! pass rolls the system out under them with a line search on the cost.
//! Levenberg–Marquardt regularisation μ on the value function's Hessian
//! (V_xx + μI in Q_uu and Q_ux) grows when a step's Q_uu is not positive
//! definite or no step lowers the cost, and shrinks after a success.
//!
//! From a guess of the states as well as the inputs
//! ([`Ddp::solve_from`]) the same iteration is feasibility-driven DDP
//! (FDDP, Mastalli et al. 2020, Crocoddyl's `SolverBoxFDDP`): the guess
//! need not satisfy the dynamics, and the passes carry its gaps until a
//! full step closes them (see `passes`).

use super::expansion::StepJacobian;
use super::passes::{
    Backward, Nominal, backward_pass, forward, from_guess, jacobians, largest, predicted_decrease,
    rollout,
};
use super::problem::{OptimalControl, split};
use super::progress::Ticker;
use crate::error::{Error, Failure, PlanError, Progress, SettingsError};
use crate::system::Driven;
use nalgebra::{DMatrix, DVector, SVector};

/// The solver's settings: at most 200 iterations, stationarity tolerance
/// 1e-6 (the largest input change a backward pass asks for, in the inputs'
/// units), initial regularisation 1e-6, quiet.
#[derive(Clone, Debug, PartialEq)]
pub struct Ddp {
    max_iterations: usize,
    tolerance: f64,
    regularization: f64,
    gap_tolerance: f64,
    verbose: bool,
    progress: bool,
}

/// One iteration's record: the log a solve keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration {
    /// The cost after the iteration.
    pub cost: f64,
    /// How far from stationary the plan is. For [`Ddp`], the largest
    /// feed-forward input change the backward pass asked for; for the
    /// direct method (`plan::Direct`), the largest entry of the
    /// Lagrangian's gradient ∇J + Jᵀλ − z_L + z_U at the plan before the
    /// step (the KKT conditions' stationarity; in its last record, at the
    /// plan returned).
    pub stationarity: f64,
    /// The line search's step α taken (0 if none was).
    pub step: f64,
    /// The regularisation: for [`Ddp`], the μ the backward pass used; for
    /// the direct method, the shift δ_w of the Hessian that gave its Newton
    /// matrix a minimum's inertia (0 where none was needed), or, in the
    /// elastic SQP's iterations, the program's damping.
    pub regularization: f64,
    /// The decrease of the cost the quadratic model predicted for the step
    /// (DDP; NaN for the direct method, whose line search reads a filter
    /// or a merit function instead).
    pub expected: f64,
    /// Feasibility after the iteration: the largest |entry| of the gaps
    /// F(x_k, u_k) − x_{k+1} (and x₀ less the plan's first state). Zero
    /// throughout a solve from inputs; from a guess of the states, it
    /// shrinks by 1 − α with each step α and is zero after a full step.
    /// For the direct method, the largest violation of any constraint (the
    /// gaps, the final equality, the state limits).
    pub gap: f64,
}

/// A plan: the states and inputs along the horizon, the feedback gains that
/// track it (u = u_k + K_k (x − x_k) near it) and the solve's log.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan<const N: usize, const P: usize, const Q: usize = N> {
    /// The times t₀ … t_K.
    pub t: Vec<f64>,
    /// The configurations q₀ … q_K.
    pub q: Vec<SVector<f64, Q>>,
    /// The velocities v₀ … v_K.
    pub v: Vec<SVector<f64, N>>,
    /// The inputs u₀ … u_{K−1}, each held over its step.
    pub u: Vec<SVector<f64, P>>,
    /// The feedback gains K₀ … K_{K−1} (P × 2N, on x − x_k = (q − q_k,
    /// v − v_k), with orientations on x ⊖ x_k, the tangent vector from the
    /// plan's state; zero rows for inputs at a bound), from the last
    /// backward pass.
    pub gains: Vec<DMatrix<f64>>,
    /// The plan's cost.
    pub cost: f64,
    /// The largest |entry| of the plan's gaps F(x_k, u_k) − x_{k+1}: zero
    /// for a plan that satisfies the dynamics (every converged plan, and
    /// every plan of a solve from inputs), else the infeasibility of the
    /// best iterate a failure kept.
    pub gap: f64,
    /// One record per iteration.
    pub log: Vec<Iteration>,
}

impl<const N: usize, const P: usize, const Q: usize> Progress for Plan<N, P, Q> {
    fn progress(&self) -> (usize, Option<f64>) {
        (
            self.q.len(),
            self.t.get(self.q.len().wrapping_sub(1)).copied(),
        )
    }

    fn describe(&self) -> String {
        format!(
            "the plan stopped short after {} iteration(s) at cost {}; the best plan is in \
             `Failure::partial`",
            self.log.len(),
            self.cost
        )
    }
}

impl Default for Ddp {
    fn default() -> Self {
        Self::new()
    }
}

const MU_MIN: f64 = 1e-9;
const MU_MAX: f64 = 1e10;

/// Below this fraction of the cost (and of 1) a change of the cost is
/// round-off (see [`Ddp::tolerance`]).
const COST_ROUND_OFF: f64 = 1e-13;

impl Ddp {
    /// The default settings.
    pub fn new() -> Self {
        Self {
            max_iterations: 200,
            tolerance: 1e-6,
            regularization: 1e-6,
            gap_tolerance: 1e-9,
            verbose: false,
            progress: false,
        }
    }

    /// At most this many iterations (at least one).
    pub fn max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// Converged when no backward pass asks any input to change by more than
    /// this (positive and finite), or when a full step is predicted to
    /// change the cost by no more than its round-off (10⁻¹³ of it; with the
    /// gaps closed and the regularisation at most its initial value): that
    /// step is taken without a line search, which could not tell it from
    /// round-off, and the plan ends there. A tolerance tighter than the cost
    /// can resolve ends at the cost's optimum this way, rather than in steps
    /// accepted or refused by round-off, or in regularisation raised until
    /// the steps vanish.
    pub fn tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// The initial regularisation μ (non-negative and finite).
    pub fn regularization(mut self, mu: f64) -> Self {
        self.regularization = mu;
        self
    }

    /// A plan from a guess of the states counts as feasible once no gap
    /// exceeds this (in the state's units; 1e-9 by default; positive and
    /// finite). A full step closes the gaps exactly.
    pub fn gap_tolerance(mut self, tolerance: f64) -> Self {
        self.gap_tolerance = tolerance;
        self
    }

    /// Draws a progress bar on standard error while solving (the
    /// iterations against the budget, the cost and the gap), cleared when
    /// the solve returns. Off by default; feature `progress`.
    #[cfg(feature = "progress")]
    pub fn progress(mut self, show: bool) -> Self {
        self.progress = show;
        self
    }

    /// Prints one line per iteration (cost, stationarity, step,
    /// regularisation, gap) to standard error.
    pub fn verbose(mut self, verbose: bool) -> Self {
        self.verbose = verbose;
        self
    }

    /// The plan for `problem` from the inputs `guess` (K of them, or none
    /// for the input target u*), clamped into the bounds: a warm start is
    /// the previous plan's inputs.
    ///
    /// # Errors
    /// A [`Failure`] holding the best plan: [`Error::Settings`] for bad
    /// settings, weights or guess; the dynamics' errors on the first
    /// rollout; [`PlanError::NotConverged`] when the budget runs out,
    /// [`PlanError::Stalled`] when no iteration can improve the plan.
    pub fn solve<S, const N: usize, const P: usize, const Q: usize>(
        &self,
        problem: &OptimalControl<S, N, P, Q>,
        guess: &[SVector<f64, P>],
    ) -> Result<Plan<N, P, Q>, Failure<Plan<N, P, Q>>>
    where
        S: Driven<f64, N, P, Q>,
    {
        let unstarted = |e: Error| Failure::new(e, empty_plan(problem));
        self.check(guess.len(), problem.steps).map_err(unstarted)?;
        problem.check().map_err(unstarted)?;
        unconstrained(problem).map_err(unstarted)?;
        let us: Vec<DVector<f64>> = (0..problem.steps)
            .map(|k| match guess.get(k) {
                Some(u) => DVector::from_column_slice(u.as_slice()),
                None => problem.input_target.clone(),
            })
            .collect();
        let nominal = rollout(problem, &us).map_err(unstarted)?;
        self.iterate(problem, nominal)
    }

    /// The plan for `problem` from a guess of the whole trajectory: the
    /// states (q₀ … q_K, v₀ … v_K) need not satisfy the dynamics nor start
    /// at the problem's start (a straight line to the goal, a previous
    /// plan shifted, a demonstration), the inputs u₀ … u_{K−1} are clamped
    /// into the bounds. The solver is then feasibility-driven (FDDP): it
    /// keeps the gaps F(x_k, u_k) − x_{k+1} in its passes, closes them by
    /// the step α it takes (all of them at α = 1), and converges only to a
    /// plan without gaps. From a guess that is a rollout it is the iteration
    /// of [`solve`](Self::solve).
    ///
    /// # Errors
    /// As [`solve`](Self::solve); [`Error::Settings`] for a guess of the
    /// wrong length or not finite. A failure keeps the best iterate, whose
    /// [`Plan::gap`] says how far it is from satisfying the dynamics.
    pub fn solve_from<S, const N: usize, const P: usize, const Q: usize>(
        &self,
        problem: &OptimalControl<S, N, P, Q>,
        q: &[SVector<f64, Q>],
        v: &[SVector<f64, N>],
        u: &[SVector<f64, P>],
    ) -> Result<Plan<N, P, Q>, Failure<Plan<N, P, Q>>>
    where
        S: Driven<f64, N, P, Q>,
    {
        let unstarted = |e: Error| Failure::new(e, empty_plan(problem));
        self.check(u.len(), problem.steps).map_err(unstarted)?;
        problem.check().map_err(unstarted)?;
        unconstrained(problem).map_err(unstarted)?;
        let nominal = from_guess(problem, (q, v, u), "Ddp").map_err(unstarted)?;
        self.iterate(problem, nominal)
    }

    /// The iterations from a nominal plan (with or without gaps).
    fn iterate<S, const N: usize, const P: usize, const Q: usize>(
        &self,
        problem: &OptimalControl<S, N, P, Q>,
        mut nominal: Nominal,
    ) -> Result<Plan<N, P, Q>, Failure<Plan<N, P, Q>>>
    where
        S: Driven<f64, N, P, Q>,
    {
        let ticker = Ticker::new(self.progress, self.max_iterations);
        let mut mu = self.regularization;
        let mut log = Vec::new();
        let mut last: Option<Backward> = None;
        let mut derivatives = Vec::new();
        // The line search's trials, in buffers of the nominal's shape.
        let mut trial = nominal.clone();
        for iteration in 1..=self.max_iterations {
            let fail = |e, last: &Option<Backward>, log: &[Iteration], nominal: &Nominal| {
                self.fail(problem, nominal, last, log, e)
            };
            jacobians(problem, &nominal, &mut derivatives)
                .map_err(|e| fail(e, &last, &log, &nominal))?;
            let backward = loop {
                let pass = backward_pass(problem, &nominal, &derivatives, mu, last.as_ref());
                match pass.map_err(|e| fail(e, &last, &log, &nominal))? {
                    Some(b) => break b,
                    None if mu * 10.0 > MU_MAX => {
                        let why = "Q_uu is not positive definite at the largest regularisation";
                        let e = self.stalled(iteration, why, &nominal, &last, mu);
                        return Err(fail(e, &last, &log, &nominal));
                    }
                    None => mu = (mu * 10.0).max(1e-6),
                }
            };
            let stationarity = largest(&backward.feedforward);
            let feasible = nominal.gap() <= self.gap_tolerance;
            if feasible && stationarity <= self.tolerance {
                log.push(self.record(&ticker, &nominal, stationarity, 0.0, mu, 0.0));
                return Ok(finish(problem, nominal, (&derivatives, backward, mu), log));
            }
            if feasible && self.settled(&nominal, &backward, mu) {
                // The cost cannot judge a step this small, so no line search
                // can: the model's full step is taken, and the plan ends.
                let alpha = match full_step(problem, &nominal, &backward) {
                    Some(next) => {
                        nominal = next;
                        1.0
                    }
                    None => 0.0,
                };
                log.push(self.record(&ticker, &nominal, stationarity, alpha, mu, 0.0));
                return Ok(finish(problem, nominal, (&derivatives, backward, mu), log));
            }
            match line_search(problem, &nominal, &backward, &mut trial) {
                Some((alpha, expected)) => {
                    std::mem::swap(&mut nominal, &mut trial);
                    log.push(self.record(&ticker, &nominal, stationarity, alpha, mu, expected));
                    mu = if mu / 10.0 < MU_MIN { 0.0 } else { mu / 10.0 };
                }
                None if mu * 10.0 > MU_MAX => {
                    let why = "no step of the line search lowers the cost";
                    let e = self.stalled(iteration, why, &nominal, &Some(backward), mu);
                    return Err(fail(e, &None, &log, &nominal));
                }
                None => {
                    log.push(self.record(&ticker, &nominal, stationarity, 0.0, mu, 0.0));
                    mu = (mu * 10.0).max(1e-6);
                }
            }
            last = Some(backward);
        }
        let e = PlanError::NotConverged {
            iterations: self.max_iterations,
            stationarity: last.as_ref().map_or(f64::NAN, |b| largest(&b.feedforward)),
            tolerance: self.tolerance,
            cost: nominal.cost,
            gap: nominal.gap(),
        };
        Err(self.fail(problem, &nominal, &last, &log, e.into()))
    }

    /// Whether a full step is predicted to change the cost by its round-off
    /// only (see [`Ddp::tolerance`]), the regularisation at most its initial
    /// value.
    fn settled(&self, nominal: &Nominal, backward: &Backward, mu: f64) -> bool {
        let (along, curvature) = backward.expected;
        let full_step = -(along + curvature);
        mu <= self.regularization && full_step.abs() <= COST_ROUND_OFF * (1.0 + nominal.cost.abs())
    }

    fn check(&self, guesses: usize, steps: usize) -> Result<(), Error> {
        let positive = |setting, value: f64| match value.is_finite() && value > 0.0 {
            true => Ok(()),
            false => Err(SettingsError::Value {
                owner: "Ddp",
                setting,
                value,
                requirement: "positive and finite".into(),
            }),
        };
        positive("tolerance", self.tolerance)?;
        positive("gap_tolerance", self.gap_tolerance)?;
        if !(self.regularization.is_finite() && self.regularization >= 0.0) {
            return Err(SettingsError::Value {
                owner: "Ddp",
                setting: "regularization",
                value: self.regularization,
                requirement: "non-negative and finite".into(),
            }
            .into());
        }
        if self.max_iterations == 0 {
            return Err(SettingsError::ZeroCount {
                owner: "Ddp",
                setting: "max_iterations",
            }
            .into());
        }
        if guesses != 0 && guesses != steps {
            return Err(SettingsError::Data {
                owner: "Ddp",
                problem: format!("{guesses} guessed inputs for {steps} steps (give all or none)"),
            }
            .into());
        }
        Ok(())
    }

    fn record(
        &self,
        ticker: &Ticker,
        nominal: &Nominal,
        stationarity: f64,
        step: f64,
        mu: f64,
        expected: f64,
    ) -> Iteration {
        let (cost, gap) = (nominal.cost, nominal.gap());
        let it = Iteration {
            cost,
            stationarity,
            step,
            regularization: mu,
            expected,
            gap,
        };
        ticker.tick(&it);
        if self.verbose {
            eprintln!(
                "ddp: cost {cost:.9e}  stationarity {stationarity:.2e}  step {step:.3}  \
                 μ {mu:.1e}  gap {gap:.2e}"
            );
        }
        it
    }

    fn stalled(
        &self,
        iteration: usize,
        why: &str,
        nominal: &Nominal,
        last: &Option<Backward>,
        mu: f64,
    ) -> Error {
        PlanError::Stalled {
            iteration,
            reason: why.into(),
            cost: nominal.cost,
            stationarity: last.as_ref().map_or(f64::NAN, |b| largest(&b.feedforward)),
            regularization: mu,
        }
        .into()
    }

    fn fail<S, const N: usize, const P: usize, const Q: usize>(
        &self,
        problem: &OptimalControl<S, N, P, Q>,
        nominal: &Nominal,
        last: &Option<Backward>,
        log: &[Iteration],
        error: Error,
    ) -> Failure<Plan<N, P, Q>>
    where
        S: Driven<f64, N, P, Q>,
    {
        let gains = last.as_ref().map_or_else(Vec::new, |b| b.gains.clone());
        let nominal = Nominal {
            xs: nominal.xs.clone(),
            us: nominal.us.clone(),
            gaps: nominal.gaps.clone(),
            cost: nominal.cost,
        };
        Failure::new(error, plan(problem, nominal, gains, log.to_vec()))
    }
}

/// The first step α of 1, ½, … 2⁻¹⁰ whose forward pass the model accepts,
/// with that α and the predicted decrease: where the model predicts a
/// decrease, the cost must fall by at least 10⁻⁴ of it; where closing the
/// gaps is predicted to raise the cost, it may rise by at most twice the
/// prediction (Crocoddyl's rule).
fn line_search<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    nominal: &Nominal,
    backward: &Backward,
    trial: &mut Nominal,
) -> Option<(f64, f64)>
where
    S: Driven<f64, N, P, Q>,
{
    let mut alpha = 1.0;
    for _ in 0..=10 {
        if forward(problem, (nominal, backward), alpha, trial).is_ok() {
            let expected = predicted_decrease(problem, nominal, backward, trial, alpha);
            let decrease = nominal.cost - trial.cost;
            let accepted = match expected >= 0.0 {
                true => decrease > 0.0 && decrease >= 1e-4 * expected,
                false => decrease >= 2.0 * expected,
            };
            if accepted && trial.cost.is_finite() {
                return Some((alpha, expected));
            }
        }
        alpha *= 0.5;
    }
    None
}

/// The full step of a settled plan, if it stays finite and leaves the cost
/// within its round-off of the nominal's.
fn full_step<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    nominal: &Nominal,
    backward: &Backward,
) -> Option<Nominal>
where
    S: Driven<f64, N, P, Q>,
{
    let mut next = nominal.clone();
    forward(problem, (nominal, backward), 1.0, &mut next).ok()?;
    let round_off = COST_ROUND_OFF * (1.0 + nominal.cost.abs());
    (next.cost.is_finite() && next.cost <= nominal.cost + round_off).then_some(next)
}

/// The converged plan, with the gains of a backward pass without the
/// regularisation's bias where Q_uu allows.
fn finish<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    nominal: Nominal,
    (derivatives, backward, mu): (&[StepJacobian], Backward, f64),
    log: Vec<Iteration>,
) -> Plan<N, P, Q>
where
    S: Driven<f64, N, P, Q>,
{
    let exact = (mu > 0.0)
        .then(|| backward_pass(problem, &nominal, derivatives, 0.0, Some(&backward)))
        .and_then(Result::ok)
        .flatten();
    let gains = exact.map_or(backward.gains, |b| b.gains);
    plan(problem, nominal, gains, log)
}

/// The plan of a nominal trajectory.
pub(super) fn plan<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    nominal: Nominal,
    gains: Vec<DMatrix<f64>>,
    log: Vec<Iteration>,
) -> Plan<N, P, Q>
where
    S: Driven<f64, N, P, Q>,
{
    let (q, v) = nominal.xs.iter().map(split::<N, Q>).unzip();
    Plan {
        t: (0..=problem.steps).map(|k| problem.time(k)).collect(),
        q,
        v,
        u: nominal
            .us
            .iter()
            .map(|u| SVector::from_column_slice(u.as_slice()))
            .collect(),
        gains,
        cost: nominal.cost,
        gap: nominal.gap(),
        log,
    }
}

/// The plan of a problem that did not start: its start alone.
pub(super) fn empty_plan<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
) -> Plan<N, P, Q>
where
    S: Driven<f64, N, P, Q>,
{
    let start = Nominal {
        xs: vec![problem.start.clone()],
        us: Vec::new(),
        gaps: Vec::new(),
        cost: f64::NAN,
    };
    let mut p = plan(problem, start, Vec::new(), Vec::new());
    p.t.truncate(1);
    p
}

/// DDP keeps the states on the dynamics and the inputs in their box, and
/// nothing else: a problem that constrains states is refused with what to
/// use instead.
fn unconstrained<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
) -> Result<(), Error>
where
    S: Driven<f64, N, P, Q>,
{
    if !problem.constrains_states() {
        return Ok(());
    }
    Err(SettingsError::Data {
        owner: "Ddp",
        problem: "the problem constrains states (`final_equality` or `state_limits`), which \
                  DDP cannot hold: solve it with `plan::Direct` (feature `direct`), or give \
                  DDP the same wishes as costs (a large `final_weight`, `StateBounds`)"
            .into(),
    }
    .into())
}
