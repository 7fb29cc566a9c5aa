//! The direct method: multiple shooting. Every state and input of the
//! horizon is an unknown and the dynamics x_{k+1} = F(x_k, u_k) are
//! equality constraints, beside the bounds on inputs and states and a final
//! equality.
//!
//! The iteration is an interior point (`interior`: IPOPT's primal–dual
//! barrier method and filter line search, with the Lagrangian's exact
//! Hessian, the dynamics' curvature included, and its Newton matrix
//! factorised by Clarabel's sparse LDLᵀ, `kkt`). It converges as IPOPT
//! does, iteration for iteration on the IPOPT peer's cart-pole (see
//! `BENCHMARKS.md`, "The direct method against IPOPT").
//!
//! Where the interior point finds no acceptable step (the constraints
//! cannot all be met: a final equality out of reach), or its steps stall
//! (ten in a row cut below 5 %), the elastic SQP below takes over from its
//! point, as IPOPT's feasibility restoration would:
//! each iteration solves the quadratic program of the cost's Gauss–Newton
//! model and the constraints linearised at the current plan (`direct_qp`,
//! by Clarabel), the final equality and the state limits elastic, and
//! takes a step along it chosen by a line search on the ℓ₁ merit function
//! φ = cost + ν Σ |constraint violations|, ν above the largest multiplier
//! of the programs that meet their constraints (Nocedal and Wright,
//! §18.3). It either finds the constraints again and converges, or settles
//! on the plan that misses them least and says by how much.
//!
//! A plan is converged when IPOPT's optimality error (the Lagrangian's
//! gradient and the complementarity, scaled as IPOPT scales them) is below
//! the tolerance and every constraint holds within the gap tolerance; the
//! state limits hold at every iterate.

use super::ddp::{Iteration, Plan};
use super::direct_qp::{self, Linearised, Unsolved, offsets};
use super::interior::{self, Interior, Outcome};
use super::passes::{
    Nominal, backward_pass, from_guess, guessed, jacobians, largest, linearise, rollout,
};
use super::problem::OptimalControl;
use crate::error::{Error, Failure, PlanError, SettingsError};
use crate::system::Driven;
use nalgebra::{DVector, SVector};

/// The direct method's settings: at most 100 iterations, tolerance 1e-8 on
/// the optimality error (IPOPT's default), 1e-9 on the constraints, quiet.
#[derive(Clone, Debug, PartialEq)]
pub struct Direct {
    max_iterations: usize,
    tolerance: f64,
    gap_tolerance: f64,
    verbose: bool,
}

impl Default for Direct {
    fn default() -> Self {
        Self::new()
    }
}

/// The elastic constraints' price per unit of violation to begin with.
const ELASTIC_PRICE: f64 = 1e3;

/// The largest damping under which a program's small step is taken as
/// stationarity (it starts at 1e-8).
const STATIONARY_DAMPING: f64 = 1e-6;

/// A trial point of the line search, with what the merit function reads.
struct Point {
    nominal: Nominal,
    /// Σ |violations| of the constraints on states (the gaps, x_K − x* if
    /// held, the state limits).
    violation: f64,
    /// The largest |violation|.
    largest: f64,
}

impl Direct {
    /// The default settings.
    pub fn new() -> Self {
        Self {
            max_iterations: 100,
            tolerance: 1e-8,
            gap_tolerance: 1e-9,
            verbose: false,
        }
    }

    /// At most this many iterations (at least one).
    pub fn max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// The tolerance on the optimality error: converged when the largest
    /// entry of the Lagrangian's gradient and of the bounds' complementarity
    /// (each scaled down where the multipliers are large, as IPOPT's `tol`)
    /// is below it, and the constraints hold within the gap tolerance.
    pub fn tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// The tolerance on the constraints (the gaps F(x_k, u_k) − x_{k+1},
    /// the final equality).
    pub fn gap_tolerance(mut self, tolerance: f64) -> Self {
        self.gap_tolerance = tolerance;
        self
    }

    /// Prints each iteration's record to standard error.
    pub fn verbose(mut self, verbose: bool) -> Self {
        self.verbose = verbose;
        self
    }

    /// The plan from a rollout of `u` (all K inputs, or none for zeros).
    ///
    /// # Errors
    /// As [`solve_from`](Self::solve_from).
    pub fn solve<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        u: &[SVector<f64, P>],
    ) -> Result<Plan<N, P>, Failure<Plan<N, P>>>
    where
        S: Driven<f64, N, P>,
    {
        let unstarted = |e: Error| Failure::new(e, super::ddp::empty_plan(problem));
        self.check(problem).map_err(unstarted)?;
        if !u.is_empty() && u.len() != problem.steps {
            let problem = format!("{} guessed inputs for {} steps", u.len(), problem.steps);
            return Err(unstarted(data(problem)));
        }
        let us: Vec<DVector<f64>> = match u.is_empty() {
            true => vec![DVector::zeros(P); problem.steps],
            false => u
                .iter()
                .map(|u| DVector::from_column_slice(u.as_slice()))
                .collect(),
        };
        let nominal = rollout(problem, &us).map_err(unstarted)?;
        self.iterate(problem, nominal)
    }

    /// The plan from a guess of every state and input (K + 1 configurations
    /// and velocities, K inputs), which need not satisfy the dynamics, start
    /// at the start, nor keep the state limits.
    ///
    /// # Errors
    /// [`Error::Settings`] for bad settings, a bad problem or guess;
    /// [`PlanError::NotConverged`] when the iterations run out,
    /// [`PlanError::Stalled`] when the restoration that takes over from
    /// the interior point (where it finds no acceptable step) finds no step
    /// either: the constraints cannot be met together (a final equality out
    /// of reach within the input bounds: it converges to the plan that
    /// misses them least, and says by how much), or a quadratic program
    /// has no solution; the dynamics' errors (a singular mass matrix, a
    /// non-finite state) as they arise; each with the best plan reached in
    /// the failure.
    pub fn solve_from<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        q: &[SVector<f64, N>],
        v: &[SVector<f64, N>],
        u: &[SVector<f64, P>],
    ) -> Result<Plan<N, P>, Failure<Plan<N, P>>>
    where
        S: Driven<f64, N, P>,
    {
        let unstarted = |e: Error| Failure::new(e, super::ddp::empty_plan(problem));
        self.check(problem).map_err(unstarted)?;
        let nominal = from_guess(problem, (q, v, u), "Direct").map_err(unstarted)?;
        self.iterate(problem, nominal)
    }

    fn check<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
    ) -> Result<(), Error>
    where
        S: Driven<f64, N, P>,
    {
        for (setting, value) in [
            ("tolerance", self.tolerance),
            ("gap_tolerance", self.gap_tolerance),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(SettingsError::Value {
                    owner: "Direct",
                    setting,
                    value,
                    requirement: "positive and finite".into(),
                }
                .into());
            }
        }
        if self.max_iterations == 0 {
            return Err(SettingsError::ZeroCount {
                owner: "Direct",
                setting: "max_iterations",
            }
            .into());
        }
        problem.check()
    }

    /// The interior point's iterations from a nominal, then the elastic
    /// SQP's if it finds no acceptable step.
    fn iterate<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        nominal: Nominal,
    ) -> Result<Plan<N, P>, Failure<Plan<N, P>>>
    where
        S: Driven<f64, N, P>,
    {
        let settings = interior::Settings {
            tolerance: self.tolerance,
            gap_tolerance: self.gap_tolerance,
            max_iterations: self.max_iterations,
            verbose: self.verbose,
        };
        let mut log = Vec::new();
        let outcome = Interior::new(problem).run(&settings, &nominal, &mut log);
        match outcome {
            Ok(Outcome::Converged(nominal)) => Ok(finish(problem, &nominal, log, true)),
            Ok(Outcome::OutOfIterations(nominal, stationarity)) => {
                let point = measured(problem, nominal);
                Err(self.out_of_iterations(problem, &point, log, stationarity))
            }
            Ok(Outcome::Restore(nominal, why)) => {
                if self.verbose {
                    eprintln!("direct: {why}; the elastic SQP takes over");
                }
                self.elastic(problem, nominal, log)
            }
            Err(e) => Err(Failure::new(e, finish(problem, &nominal, log, false))),
        }
    }

    /// The elastic SQP's iterations from a nominal, after those in `log`.
    fn elastic<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        nominal: Nominal,
        mut log: Vec<Iteration>,
    ) -> Result<Plan<N, P>, Failure<Plan<N, P>>>
    where
        S: Driven<f64, N, P>,
    {
        let mut point = measured(problem, nominal);
        // The merit function's penalty ν, also the elastic constraints'
        // price: it only grows (`raised`).
        let (mut penalty, mut damping) = (ELASTIC_PRICE, 1e-8);
        let mut last_step = f64::NAN;
        for iteration in log.len() + 1..=self.max_iterations {
            let fail = |e: Error, point: &Point, log: &[Iteration]| {
                Failure::new(e, finish(problem, &point.nominal, log.to_vec(), false))
            };
            let step = match self.program(problem, &point, (damping, penalty)) {
                Ok(Ok(step)) => step,
                // Clarabel found no solution, which a Gauss–Newton Hessian
                // singular along the states can make it report: damp the
                // step and build the program again.
                Ok(Err(unsolved)) if damping < 1e6 => {
                    damping *= 100.0;
                    log.push(self.unsolved(&point, &unsolved, damping));
                    continue;
                }
                Ok(Err(Unsolved(status))) => {
                    let why = format!("the quadratic program has no solution ({status:?})");
                    let e = stalled(iteration, &why, &point, f64::NAN);
                    return Err(fail(e, &point, &log));
                }
                Err(e) => return Err(fail(e, &point, &log)),
            };
            let size = step.delta.iter().fold(0.0f64, |m, d| m.max(d.abs()));
            last_step = size;
            let kkt = step.kkt;
            penalty = self.raised(penalty, &step);
            let slope = cost_slope(problem, &point.nominal, &step.delta)
                + penalty * (step.slack - point.violation);
            let merit = point.nominal.cost + penalty * point.violation;
            // Stationary: no step asked for, or nothing along it can lower
            // the merit function, feasible or not. A step the damping held
            // back says neither (a program damped by 1e2 asks for nothing
            // wherever it is): the damping is lowered and the program built
            // again.
            let small = size <= self.tolerance || slope >= -1e-10 * merit.max(1.0);
            if small && damping > STATIONARY_DAMPING {
                damping = (damping / 100.0).max(1e-8);
                log.push(self.record(&point, kkt, 0.0, damping));
                continue;
            }
            if small {
                log.push(self.record(&point, kkt, 0.0, damping));
                return self.stationary(problem, point, log, iteration, size);
            }
            match search(problem, &point, &step.delta, penalty, slope) {
                Ok(Some((next, alpha))) => {
                    point = next;
                    damping = (damping / 10.0).max(1e-8);
                    log.push(self.record(&point, kkt, alpha, damping));
                }
                Ok(None) if damping < 1e6 => {
                    damping *= 100.0;
                    log.push(self.record(&point, kkt, 0.0, damping));
                }
                Ok(None) => {
                    let e = stalled(iteration, "no step lowers the merit function", &point, size);
                    return Err(fail(e, &point, &log));
                }
                Err(e) => return Err(fail(e, &point, &log)),
            }
        }
        Err(self.out_of_iterations(problem, &point, log, last_step))
    }

    /// `NotConverged`, with the plan reached.
    fn out_of_iterations<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        point: &Point,
        log: Vec<Iteration>,
        last_step: f64,
    ) -> Failure<Plan<N, P>>
    where
        S: Driven<f64, N, P>,
    {
        let e = PlanError::NotConverged {
            iterations: self.max_iterations,
            stationarity: last_step,
            tolerance: self.tolerance,
            cost: point.nominal.cost,
            gap: point.largest,
        };
        Failure::new(e.into(), finish(problem, &point.nominal, log, false))
    }

    /// The merit function's penalty after `step`'s program: raised to twice
    /// its hard rows' largest multiplier, but only by a program that meets
    /// its constraints. While elastic slacks are in use the multipliers are
    /// the slacks' price ν carried back through the dynamics, and raising ν
    /// with them doubled it at every such program (to 7e10 within 26
    /// iterations on the cart-pole's swing-up, where Clarabel then reported
    /// every program dual infeasible).
    fn raised(&self, penalty: f64, step: &direct_qp::Step) -> f64 {
        match step.slack <= self.gap_tolerance {
            true => penalty.max(2.0 * step.largest_multiplier + 1e-6),
            false => penalty,
        }
    }

    /// The record of an iteration whose program had no solution.
    fn unsolved(&self, point: &Point, Unsolved(status): &Unsolved, damping: f64) -> Iteration {
        if self.verbose {
            eprintln!("direct: the program has no solution ({status:?})");
        }
        self.record(point, f64::NAN, 0.0, damping)
    }

    /// At a stationary point: the plan if it meets the constraints, else
    /// the error that says by how much the nearest plan misses them.
    fn stationary<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        point: Point,
        log: Vec<Iteration>,
        iteration: usize,
        size: f64,
    ) -> Result<Plan<N, P>, Failure<Plan<N, P>>>
    where
        S: Driven<f64, N, P>,
    {
        if point.largest <= self.gap_tolerance {
            return Ok(finish(problem, &point.nominal, log, true));
        }
        let why = format!(
            "the constraints cannot all be met: the nearest plan misses them by {:e}",
            point.largest
        );
        let e = stalled(iteration, &why, &point, size);
        Err(Failure::new(e, finish(problem, &point.nominal, log, false)))
    }

    /// The quadratic program at `point` and its step, or why Clarabel has
    /// none.
    fn program<S, const N: usize, const P: usize>(
        &self,
        problem: &OptimalControl<S, N, P>,
        point: &Point,
        (damping, elastic): (f64, f64),
    ) -> Result<Result<direct_qp::Step, Unsolved>, Error>
    where
        S: Driven<f64, N, P>,
    {
        let nominal = &point.nominal;
        let derivatives = linearise(problem, nominal)?;
        let mut models = Vec::with_capacity(problem.steps + 1);
        for k in 0..problem.steps {
            models.push(problem.running_model(k, &nominal.xs[k], &nominal.us[k])?);
        }
        models.push(problem.final_model(&nominal.xs[problem.steps])?);
        let room = |x: &DVector<f64>, (lower, upper): (&DVector<f64>, &DVector<f64>)| {
            (lower - x, upper - x)
        };
        let limits = problem.state_limits.as_ref();
        let lin = Linearised {
            models: &models,
            derivatives: &derivatives,
            gaps: &nominal.gaps,
            final_equality: problem
                .final_equality
                .then(|| &problem.goal - &nominal.xs[problem.steps]),
            input_room: (nominal.us.iter())
                .map(|u| room(u, (&problem.lower, &problem.upper)))
                .collect(),
            state_room: limits.map_or_else(Vec::new, |(lower, upper)| {
                (nominal.xs[1..].iter())
                    .map(|x| room(x, (lower, upper)))
                    .collect()
            }),
            damping,
            elastic,
        };
        Ok(direct_qp::solve(&lin, P, problem.steps))
    }

    /// The record of an iteration: `kkt` is the Lagrangian's gradient at
    /// the plan before the step, with the program's multipliers.
    fn record(&self, point: &Point, kkt: f64, alpha: f64, damping: f64) -> Iteration {
        let (cost, gap) = (point.nominal.cost, point.largest);
        if self.verbose {
            eprintln!(
                "direct: cost {cost:.9e}  KKT {kkt:.2e}  α {alpha:.3}  damping {damping:.1e}  \
                 violation {gap:.2e}"
            );
        }
        Iteration {
            cost,
            stationarity: kkt,
            step: alpha,
            regularization: damping,
            expected: f64::NAN,
            gap,
        }
    }
}

/// A nominal with the violations the merit function reads.
fn measured<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    nominal: Nominal,
) -> Point
where
    S: Driven<f64, N, P>,
{
    let mut violation: f64 = nominal.gaps.iter().map(|g| g.lp_norm(1)).sum();
    let mut worst = largest(&nominal.gaps);
    if problem.final_equality {
        let off = &nominal.xs[problem.steps] - &problem.goal;
        violation += off.lp_norm(1);
        worst = worst.max(off.amax());
    }
    if let Some((lower, upper)) = &problem.state_limits {
        for x in &nominal.xs[1..] {
            let outside = (x - upper).sup(&(lower - x)).map(|e| e.max(0.0));
            violation += outside.sum();
            worst = worst.max(outside.amax());
        }
    }
    Point {
        nominal,
        violation,
        largest: worst,
    }
}

/// The first step α of 1, ½, … 2⁻¹² along δ that lowers the ℓ₁ merit
/// function by at least 10⁻⁴ of the decrease its model predicts, `slope`
/// per unit of α (the cost's derivative along δ, and the penalty on what
/// the program's slacks leave of the violation less the violation now).
fn search<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    point: &Point,
    delta: &[f64],
    penalty: f64,
    slope: f64,
) -> Result<Option<(Point, f64)>, Error>
where
    S: Driven<f64, N, P>,
{
    let (n2, steps) = (2 * N, problem.steps);
    let nominal = &point.nominal;
    let merit = |p: &Point| p.nominal.cost + penalty * p.violation;
    let here = merit(point);
    let mut alpha = 1.0;
    for _ in 0..=12 {
        let xs = (0..=steps)
            .map(|k| {
                let (x, _) = offsets(n2, P, k);
                &nominal.xs[k] + DVector::from_column_slice(&delta[x..x + n2]) * alpha
            })
            .collect();
        let us: Vec<_> = (0..steps)
            .map(|k| {
                let (_, u) = offsets(n2, P, k);
                &nominal.us[k] + DVector::from_column_slice(&delta[u..u + P]) * alpha
            })
            .collect();
        let trial = measured(problem, guessed(problem, xs, &us)?);
        if merit(&trial) <= here + 1e-4 * alpha * slope {
            return Ok(Some((trial, alpha)));
        }
        alpha *= 0.5;
    }
    Ok(None)
}

/// The cost's derivative along δ, Σ l_x·δx + l_u·δu.
fn cost_slope<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    nominal: &Nominal,
    delta: &[f64],
) -> f64
where
    S: Driven<f64, N, P>,
{
    let (n2, steps) = (2 * N, problem.steps);
    let mut slope = 0.0;
    for k in 0..=steps {
        let (x, u) = offsets(n2, P, k);
        let model = match k < steps {
            true => problem.running_model(k, &nominal.xs[k], &nominal.us[k]),
            false => problem.final_model(&nominal.xs[k]),
        };
        let Ok(m) = model else { return f64::NAN };
        slope += m.lx.dot(&DVector::from_column_slice(&delta[x..x + n2]));
        if k < steps {
            slope += m.lu.dot(&DVector::from_column_slice(&delta[u..u + P]));
        }
    }
    slope
}

/// The plan of a nominal, with the feedback gains of the cost's quadratic
/// model about it when it is converged and no constraint on states is
/// active in them (they would not know the limits nor the final equality):
/// otherwise none.
fn finish<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    nominal: &Nominal,
    log: Vec<Iteration>,
    converged: bool,
) -> Plan<N, P>
where
    S: Driven<f64, N, P>,
{
    let gains = (converged && !problem.constrains_states())
        .then(|| {
            let mut d = Vec::new();
            jacobians(problem, nominal, &mut d).ok().map(|()| d)
        })
        .flatten()
        .and_then(|d| {
            backward_pass(problem, nominal, &d, 0.0, None)
                .ok()
                .flatten()
        })
        .map_or_else(Vec::new, |b| b.gains);
    super::ddp::plan(problem, nominal.clone(), gains, log)
}

fn stalled(iteration: usize, reason: &str, point: &Point, size: f64) -> Error {
    PlanError::Stalled {
        iteration,
        reason: reason.into(),
        cost: point.nominal.cost,
        stationarity: size,
        regularization: f64::NAN,
    }
    .into()
}

fn data(problem: String) -> Error {
    SettingsError::Data {
        owner: "Direct",
        problem,
    }
    .into()
}
