//! Failures of trajectory optimisation ([`crate::plan`]).

/// Why a plan was not found. The best plan reached is kept beside it, in the
/// [`Failure`](super::Failure) that carries this error.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PlanError {
    /// The iteration budget ran out before the plan was stationary.
    #[error(
        "the plan did not converge in {iterations} iteration(s): stationarity {stationarity:e} \
         against the tolerance {tolerance:e}, largest gap {gap:e} (cost {cost}); raise \
         `max_iterations`, or accept the best plan, kept in the failure"
    )]
    NotConverged {
        /// Iterations done.
        iterations: usize,
        /// The largest feed-forward input change the last backward pass asked for.
        stationarity: f64,
        /// The tolerance on it.
        tolerance: f64,
        /// The best plan's cost.
        cost: f64,
        /// The best plan's largest gap F(x_k, u_k) − x_{k+1}: nonzero only
        /// for a solve from a guess of the states that never took a full
        /// step.
        gap: f64,
    },

    /// No iteration could improve the plan: the regularisation reached its
    /// limit (the quadratic model of the cost is not convex in the inputs
    /// however damped) or no step of the line search lowered the cost.
    #[error(
        "the plan stalled at iteration {iteration}: {reason} (cost {cost}, stationarity \
         {stationarity:e}, regularisation {regularization:e}); the best plan is kept in the \
         failure"
    )]
    Stalled {
        /// The iteration that failed.
        iteration: usize,
        /// What failed.
        reason: String,
        /// The best plan's cost.
        cost: f64,
        /// The largest feed-forward input change asked for.
        stationarity: f64,
        /// The regularisation μ reached.
        regularization: f64,
    },
}
