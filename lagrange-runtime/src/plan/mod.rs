//! Planning with the model: optimal control over a horizon and
//! model-predictive control.
//!
//! An [`OptimalControl`] problem takes a [`Transition`](crate::linear::Transition)
//! (one fixed step of the system's dynamics, RK4 or semi-implicit Euler,
//! with its derivatives by the chain rule), a horizon of K steps, quadratic
//! running and terminal costs about a goal state and an input target, and
//! box bounds on the inputs. [`Ddp`] solves it by box-constrained
//! differential dynamic programming and returns a [`Plan`]: states, inputs,
//! feedback gains, and the log of every iteration (cost, stationarity,
//! step, regularisation, gap). From a guess of the states that need not
//! satisfy the dynamics ([`Ddp::solve_from`]) the same solver is
//! feasibility-driven DDP (FDDP): it carries the guess's gaps and closes
//! them. [`Mpc`] re-solves it at every sample of a
//! [`Simulation::sampled`](crate::Simulation::sampled) run, warm-started,
//! within an iteration budget.
//!
//! With the feature `direct`, `Direct` solves the same problem by
//! multiple shooting with an interior-point method (IPOPT's barrier method
//! and filter line search, the Lagrangian's exact Hessian, each Newton
//! system sparse and factorised by Clarabel's LDLᵀ), and also holds
//! constraints on states that DDP cannot: hard
//! [`state_limits`](OptimalControl::state_limits) and a
//! [`final_equality`](OptimalControl::final_equality).
//!
//! The state is x = (q, v). A system with free orientations (unit
//! quaternions in q, `OptimalControl<S, N, P, Q>` with Q = N + 1 per
//! orientation) is planned on the group: the transition steps on it, every
//! derivative and gain is in the tangent space (δ, δv) of
//! [`Linearizer::tangent`](crate::linear::Linearizer::tangent), the cost
//! measures x ⊖ x* (an attitude's error by its rotation angle), FDDP's
//! gaps are tangent vectors and its forward pass retracts (x ⊕ d). The
//! direct method and [`StateBounds`] take systems without orientations
//! (their `OptimalControl<S, N, P>`); constrained systems are not planned
//! for yet.

mod bounds;
mod box_qp;
mod cost;
#[cfg(feature = "direct")]
mod curvature;
mod ddp;
#[cfg(feature = "direct")]
mod direct;
#[cfg(feature = "direct")]
mod direct_qp;
mod expansion;
#[cfg(feature = "direct")]
mod interior;
#[cfg(feature = "direct")]
mod interior_step;
#[cfg(feature = "direct")]
mod kkt;
mod mpc;
mod passes;
mod problem;
mod progress;

pub use bounds::StateBounds;
pub use cost::{Cost, CostFn, CostModel, FramePosition, Waypoint};
pub use ddp::{Ddp, Iteration, Plan};
#[cfg(feature = "direct")]
pub use direct::Direct;
pub use mpc::{Mpc, Sample};
pub use problem::OptimalControl;

#[cfg(all(test, feature = "direct"))]
mod direct_tests;
#[cfg(test)]
mod feasibility_tests;
#[cfg(test)]
mod group_tests;
#[cfg(test)]
mod tests;
