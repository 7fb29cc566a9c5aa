//! Model-predictive control: re-plan at every sample from the state
//! measured, warm-started from the last plan shifted by one step, within an
//! iteration budget, and apply the plan's first input.
//!
//! The warm start is the whole shifted plan, states and inputs, solved
//! from by feasibility-driven DDP ([`Ddp::solve_from`]): the measured state
//! differs from the plan's (a disturbance, a model that is wrong), and the
//! old inputs rolled out from it drift away from the plan on an unstable
//! system (a cart-pole's swing-up), where the states' guess keeps the
//! iteration near it and only the gap at the start is new. Warm-started
//! from the inputs alone, the gallery's MPC (a 2.5 s horizon at 20 Hz, ten
//! iterations a sample) did not swing up a cart-pole whose pole is 20 %
//! heavier than its model's; from the states it swings up and holds one
//! 50 % heavier (`tests/planning.rs`).

use super::ddp::{Ddp, Plan};
use super::problem::{OptimalControl, state};
use crate::system::Driven;
use nalgebra::SVector;

/// A receding-horizon controller over an [`OptimalControl`] problem, for
/// [`Simulation::sampled`](crate::Simulation::sampled): its
/// [`control`](Self::control) is the sampled controller k(t, q, v). The
/// problem's horizon recedes with the samples (its start becomes each
/// measured state and time); the solver's `max_iterations` is the budget of
/// each sample.
pub struct Mpc<'a, S, const N: usize, const P: usize, const Q: usize = N> {
    problem: OptimalControl<'a, S, N, P, Q>,
    solver: Ddp,
    warm: Option<Plan<N, P, Q>>,
    samples: Vec<Sample>,
}

/// What one sample's solve did.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// The sample's time.
    pub t: f64,
    /// Iterations used.
    pub iterations: usize,
    /// Whether the plan met the solver's tolerance within the budget.
    pub converged: bool,
    /// The plan's cost.
    pub cost: f64,
    /// Why the solve stopped short (the budget ran out, it stalled), as its
    /// message; the best plan's first input was applied all the same.
    pub stopped: Option<String>,
}

impl<'a, S, const N: usize, const P: usize, const Q: usize> Mpc<'a, S, N, P, Q>
where
    S: Driven<f64, N, P, Q>,
{
    /// The controller re-solving `problem` with `solver` at each sample.
    pub fn new(problem: OptimalControl<'a, S, N, P, Q>, solver: Ddp) -> Self {
        Self {
            problem,
            solver,
            warm: None,
            samples: Vec::new(),
        }
    }

    /// The input at the sample (t, q, v): the first of the plan from there.
    /// A solve that stops short of its tolerance (the budget hit) still gives
    /// its best plan's first input, and is recorded in
    /// [`samples`](Self::samples); one that produced no input at all gives
    /// NaN, so that the run stops with `Error::NonFiniteInput` at that
    /// sample rather than apply a made-up input.
    pub fn control(&mut self, t: f64, q: &SVector<f64, Q>, v: &SVector<f64, N>) -> SVector<f64, P> {
        self.problem.start = state(q, v);
        self.problem.t0 = t;
        let solved = match &self.warm {
            Some(w) => self.solver.solve_from(&self.problem, &w.q, &w.v, &w.u),
            None => self.solver.solve(&self.problem, &[]),
        };
        let (plan, stopped) = match solved {
            Ok(plan) => (plan, None),
            Err(failure) => {
                let (error, plan) = failure.into_parts();
                (plan, Some(error.to_string()))
            }
        };
        self.samples.push(Sample {
            t,
            iterations: plan.log.len(),
            converged: stopped.is_none(),
            cost: plan.cost,
            stopped,
        });
        let Some(first) = plan.u.first().copied() else {
            self.warm = None;
            return SVector::repeat(f64::NAN);
        };
        self.warm = Some(shifted(plan));
        first
    }

    /// Every sample's record, in time order.
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// How many samples stopped short of the tolerance.
    pub fn budget_hits(&self) -> usize {
        self.samples.iter().filter(|s| !s.converged).count()
    }
}

/// The plan one step on, its last state and input repeated: the next
/// sample's warm start.
fn shifted<const N: usize, const P: usize, const Q: usize>(
    mut plan: Plan<N, P, Q>,
) -> Plan<N, P, Q> {
    fn shift<T: Copy>(xs: &mut Vec<T>) {
        if let Some(&last) = xs.last() {
            xs.remove(0);
            xs.push(last);
        }
    }
    shift(&mut plan.q);
    shift(&mut plan.v);
    shift(&mut plan.u);
    plan
}
