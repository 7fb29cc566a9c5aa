//! Box-constrained differential dynamic programming (Gauss–Newton DDP, or
//! iLQR, with the control limits of Tassa, Mansard and Todorov 2014, the
//! algorithm of Crocoddyl's `SolverBoxDDP`): a backward pass builds a
//! quadratic model of the cost-to-go along the current plan and solves a
//! box QP per step for the input change and its feedback gain; a forward
//! pass rolls the system out under them with a line search on the cost.
//! Levenberg–Marquardt regularisation μ on the value function's Hessian
//! (V_xx + μI in Q_uu and Q_ux) grows when a step's Q_uu is not positive
//! definite or no step lowers the cost, and shrinks after a success.

use super::box_qp;
use super::problem::{OptimalControl, split, state};
use crate::error::{Error, Failure, PlanError, Progress, SettingsError};
use crate::linear::StepDerivatives;
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
    verbose: bool,
}

/// One iteration's record: the log a solve keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration {
    /// The cost after the iteration.
    pub cost: f64,
    /// The largest feed-forward input change the backward pass asked for.
    pub stationarity: f64,
    /// The line search's step α taken (0 if none was).
    pub step: f64,
    /// The regularisation μ the backward pass used.
    pub regularization: f64,
    /// The decrease of the cost the quadratic model predicted for the step.
    pub expected: f64,
}

/// A plan: the states and inputs along the horizon, the feedback gains that
/// track it (u = u_k + K_k (x − x_k) near it) and the solve's log.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan<const N: usize, const P: usize> {
    /// The times t₀ … t_K.
    pub t: Vec<f64>,
    /// The configurations q₀ … q_K.
    pub q: Vec<SVector<f64, N>>,
    /// The velocities v₀ … v_K.
    pub v: Vec<SVector<f64, N>>,
    /// The inputs u₀ … u_{K−1}, each held over its step.
    pub u: Vec<SVector<f64, P>>,
    /// The feedback gains K₀ … K_{K−1} (P × 2N, on x = (q, v); zero rows for
    /// inputs at a bound), from the last backward pass.
    pub gains: Vec<DMatrix<f64>>,
    /// The plan's cost.
    pub cost: f64,
    /// One record per iteration.
    pub log: Vec<Iteration>,
}

impl<const N: usize, const P: usize> Progress for Plan<N, P> {
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

/// The plan being improved: states, inputs, cost.
struct Nominal {
    xs: Vec<DVector<f64>>,
    us: Vec<DVector<f64>>,
    cost: f64,
}

/// What a backward pass gives: per step the feed-forward change and the
/// gain, and the model's predicted decrease terms (Σ kᵀQ_u, Σ ½ kᵀQ_uu k).
struct Backward {
    feedforward: Vec<DVector<f64>>,
    gains: Vec<DMatrix<f64>>,
    expected: (f64, f64),
}

const MU_MIN: f64 = 1e-9;
const MU_MAX: f64 = 1e10;

impl Ddp {
    /// The default settings.
    pub fn new() -> Self {
        Self {
            max_iterations: 200,
            tolerance: 1e-6,
            regularization: 1e-6,
            verbose: false,
        }
    }

    /// At most this many iterations (at least one).
    pub fn max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// Converged when no backward pass asks any input to change by more than
    /// this (positive and finite).
    pub fn tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// The initial regularisation μ (non-negative and finite).
    pub fn regularization(mut self, mu: f64) -> Self {
        self.regularization = mu;
        self
    }

    /// Prints one line per iteration (cost, stationarity, step,
    /// regularisation) to standard error.
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
    pub fn solve<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        guess: &[SVector<f64, P>],
    ) -> Result<Plan<N, P>, Failure<Plan<N, P>>>
    where
        S: Driven<f64, N, P>,
    {
        let unstarted = |e: Error| Failure::new(e, empty_plan(problem));
        self.check(guess.len(), problem.steps).map_err(unstarted)?;
        problem.check().map_err(unstarted)?;
        let us: Vec<DVector<f64>> = (0..problem.steps)
            .map(|k| match guess.get(k) {
                Some(u) => problem.clamp(&DVector::from_column_slice(u.as_slice())),
                None => problem.clamp(&problem.input_target),
            })
            .collect();
        let mut nominal = rollout(problem, &us, None).map_err(unstarted)?;
        let mut mu = self.regularization;
        let mut log = Vec::new();
        let mut last: Option<Backward> = None;
        for iteration in 1..=self.max_iterations {
            let derivatives = linearise(problem, &nominal);
            let derivatives =
                derivatives.map_err(|e| self.fail(problem, &nominal, &last, &log, e))?;
            let backward = loop {
                let pass = backward_pass(problem, &nominal, &derivatives, mu, last.as_ref());
                match pass.map_err(|e| self.fail(problem, &nominal, &last, &log, e))? {
                    Some(b) => break b,
                    None if mu * 10.0 > MU_MAX => {
                        let why = "Q_uu is not positive definite at the largest regularisation";
                        let e = self.stalled(iteration, why, &nominal, &last, mu);
                        return Err(self.fail(problem, &nominal, &last, &log, e));
                    }
                    None => mu = (mu * 10.0).max(1e-6),
                }
            };
            let stationarity = largest(&backward.feedforward);
            if stationarity <= self.tolerance {
                log.push(self.record(nominal.cost, stationarity, 0.0, mu, 0.0));
                // The gains without the regularisation's bias where Q_uu allows.
                let exact = (mu > 0.0)
                    .then(|| backward_pass(problem, &nominal, &derivatives, 0.0, Some(&backward)))
                    .and_then(Result::ok)
                    .flatten();
                let gains = exact.map_or(backward.gains, |b| b.gains);
                return Ok(plan(problem, nominal, gains, log));
            }
            match line_search(problem, &nominal, &backward) {
                Some((next, alpha, expected)) => {
                    nominal = next;
                    log.push(self.record(nominal.cost, stationarity, alpha, mu, expected));
                    mu = if mu / 10.0 < MU_MIN { 0.0 } else { mu / 10.0 };
                }
                None if mu * 10.0 > MU_MAX => {
                    let why = "no step of the line search lowers the cost";
                    let e = self.stalled(iteration, why, &nominal, &Some(backward), mu);
                    return Err(self.fail(problem, &nominal, &None, &log, e));
                }
                None => {
                    log.push(self.record(nominal.cost, stationarity, 0.0, mu, 0.0));
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
        };
        Err(self.fail(problem, &nominal, &last, &log, e.into()))
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

    fn record(&self, cost: f64, stationarity: f64, step: f64, mu: f64, expected: f64) -> Iteration {
        let it = Iteration {
            cost,
            stationarity,
            step,
            regularization: mu,
            expected,
        };
        if self.verbose {
            eprintln!(
                "ddp: cost {cost:.9e}  stationarity {stationarity:.2e}  step {step:.3}  μ {mu:.1e}"
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

    fn fail<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        nominal: &Nominal,
        last: &Option<Backward>,
        log: &[Iteration],
        error: Error,
    ) -> Failure<Plan<N, P>>
    where
        S: Driven<f64, N, P>,
    {
        let gains = last.as_ref().map_or_else(Vec::new, |b| b.gains.clone());
        let nominal = Nominal {
            xs: nominal.xs.clone(),
            us: nominal.us.clone(),
            cost: nominal.cost,
        };
        Failure::new(error, plan(problem, nominal, gains, log.to_vec()))
    }
}

/// The largest |entry| over a sequence of vectors.
fn largest(xs: &[DVector<f64>]) -> f64 {
    xs.iter().map(|x| x.amax()).fold(0.0, f64::max)
}

/// The states under `us` from the start, each input clamped and, with
/// `track = (nominal, feedforward, gains, α)`, shifted by α k + K (x − x̄).
fn rollout<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    us: &[DVector<f64>],
    track: Option<(&Nominal, &Backward, f64)>,
) -> Result<Nominal, Error>
where
    S: Driven<f64, N, P>,
{
    let mut xs = vec![problem.start.clone()];
    let mut applied = Vec::with_capacity(us.len());
    for (k, u) in us.iter().enumerate() {
        let x = &xs[k];
        let u = match track {
            None => u.clone(),
            Some((nominal, b, alpha)) => {
                problem.clamp(&(u + &b.feedforward[k] * alpha + &b.gains[k] * (x - &nominal.xs[k])))
            }
        };
        let (q, v) = split::<N>(x);
        let (q1, v1) = problem.transition.step(
            &q,
            &v,
            &SVector::from_column_slice(u.as_slice()),
            problem.time(k),
        )?;
        xs.push(state(&q1, &v1));
        applied.push(u);
    }
    let cost = problem.cost(&xs, &applied);
    Ok(Nominal {
        xs,
        us: applied,
        cost,
    })
}

/// ∂F/∂x and ∂F/∂u at every step of the plan.
fn linearise<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    nominal: &Nominal,
) -> Result<Vec<StepDerivatives<N>>, Error>
where
    S: Driven<f64, N, P>,
{
    (0..problem.steps)
        .map(|k| {
            let (q, v) = split::<N>(&nominal.xs[k]);
            let u = SVector::from_column_slice(nominal.us[k].as_slice());
            problem.transition.derivatives(&q, &v, &u, problem.time(k))
        })
        .collect()
}

/// The backward pass with regularisation μ, warm-starting each box QP from
/// the last pass's feed-forward; `Ok(None)` if some Q_uu is not positive
/// definite on its free inputs.
fn backward_pass<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    nominal: &Nominal,
    derivatives: &[StepDerivatives<N>],
    mu: f64,
    last: Option<&Backward>,
) -> Result<Option<Backward>, Error>
where
    S: Driven<f64, N, P>,
{
    let steps = problem.steps;
    let n2 = 2 * N;
    let terminal = problem.final_model(&nominal.xs[steps])?;
    let (mut vx, mut vxx) = (terminal.lx, terminal.lxx);
    let mut feedforward = vec![DVector::zeros(P); steps];
    let mut gains = vec![DMatrix::zeros(P, n2); steps];
    let mut expected = (0.0, 0.0);
    for k in (0..steps).rev() {
        let (fx, fu) = (&derivatives[k].dx, &derivatives[k].du);
        let l = problem.running_model(k, &nominal.xs[k], &nominal.us[k])?;
        let qx = &l.lx + fx.transpose() * &vx;
        let qu = &l.lu + fu.transpose() * &vx;
        let v_reg = &vxx + DMatrix::identity(n2, n2) * mu;
        let qxx = &l.lxx + fx.transpose() * &vxx * fx;
        let quu = &l.luu + fu.transpose() * &v_reg * fu;
        let qux = &l.lux + fu.transpose() * &v_reg * fx;
        let start = last.map_or_else(|| DVector::zeros(P), |b| b.feedforward[k].clone());
        let lower = &problem.lower - &nominal.us[k];
        let upper = &problem.upper - &nominal.us[k];
        let Some(qp) = box_qp::solve(&quu, &qu, &lower, &upper, &start) else {
            return Ok(None);
        };
        let mut gain = DMatrix::zeros(P, n2);
        if let Some(chol) = &qp.factor {
            let rows = DMatrix::from_fn(qp.free.len(), n2, |i, j| qux[(qp.free[i], j)]);
            let free_gain = -chol.solve(&rows);
            qp.free
                .iter()
                .enumerate()
                .for_each(|(i, &r)| gain.set_row(r, &free_gain.row(i)));
        }
        let kff = qp.x;
        expected.0 += kff.dot(&qu);
        expected.1 += 0.5 * kff.dot(&(&quu * &kff));
        vx = &qx + gain.transpose() * (&quu * &kff + &qu) + qux.transpose() * &kff;
        let cross = gain.transpose() * &qux;
        vxx = &qxx + gain.transpose() * &quu * &gain + &cross + cross.transpose();
        vxx = (&vxx + vxx.transpose()) * 0.5;
        feedforward[k] = kff;
        gains[k] = gain;
    }
    Ok(Some(Backward {
        feedforward,
        gains,
        expected,
    }))
}

/// The first step α of 1, ½, … 2⁻¹⁰ whose rollout lowers the cost by at
/// least 10⁻⁴ of the decrease the model predicts, −(α ΔV₁ + α² ΔV₂), with
/// that α and the predicted decrease.
fn line_search<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    nominal: &Nominal,
    backward: &Backward,
) -> Option<(Nominal, f64, f64)>
where
    S: Driven<f64, N, P>,
{
    let (d1, d2) = backward.expected;
    let mut alpha = 1.0;
    for _ in 0..=10 {
        let expected = -(alpha * d1 + alpha * alpha * d2);
        if let Ok(next) = rollout(problem, &nominal.us, Some((nominal, backward, alpha)))
            && next.cost < nominal.cost
            && (nominal.cost - next.cost) >= 1e-4 * expected
        {
            return Some((next, alpha, expected));
        }
        alpha *= 0.5;
    }
    None
}

/// The plan of a nominal trajectory.
fn plan<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    nominal: Nominal,
    gains: Vec<DMatrix<f64>>,
    log: Vec<Iteration>,
) -> Plan<N, P>
where
    S: Driven<f64, N, P>,
{
    let (q, v) = nominal.xs.iter().map(split::<N>).unzip();
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
        log,
    }
}

/// The plan of a problem that did not start: its start alone.
fn empty_plan<S, const N: usize, const P: usize>(problem: &OptimalControl<S, N, P>) -> Plan<N, P>
where
    S: Driven<f64, N, P>,
{
    let start = Nominal {
        xs: vec![problem.start.clone()],
        us: Vec::new(),
        cost: f64::NAN,
    };
    let mut p = plan(problem, start, Vec::new(), Vec::new());
    p.t.truncate(1);
    p
}
