//! The mechanical forms: the equations of motion of a [`Lagrangian`](crate::Lagrangian)
//! system solved for the accelerations, as a [`SecondOrder`](crate::ode::SecondOrder)
//! problem the integrators step.
//!
//! - [`Dynamics`]: unconstrained, q̈ = M⁻¹(Q − h) (or the articulated-body q̈),
//!   and its derivatives from the emitted Jacobians (`derivatives`), and both
//!   over four states per call (`batched`, `emit(batched)`);
//! - [`constraint`]: constraints kept with multipliers (the saddle-point system),
//!   drift control and consistent initial conditions; [`Rattle`] integrates the
//!   holonomic case symplectically;
//! - [`ReducedDynamics`]: independent speeds, no multipliers.
//!
//! Each form adds a [`Forcing`] (controllers' input forces, by default none) to
//! Q − h; it imports nothing above the system contract.

mod batched;
pub mod constraint;
pub(crate) mod derivatives;
pub(crate) mod dynamics;
mod forcing;
mod hamilton;
mod rattle;
pub(crate) mod reduced;
mod tolerances;

pub use batched::{
    Batched, BatchedDifferentiable, LaneDerivatives, batched_acceleration_derivatives,
    batched_accelerations,
};
pub use derivatives::{
    AccelerationDerivatives, Differentiable, ForceJacobians, InputDerivatives,
    acceleration_derivatives, factored_derivatives,
};
pub use dynamics::{DEFAULT_SINGULAR_TOLERANCE, Dynamics, accelerations};
pub use forcing::{Forcing, NoForcing};
pub use rattle::Rattle;
pub use reduced::{ReducedDynamics, ReducedForm};
pub use tolerances::Tolerances;
