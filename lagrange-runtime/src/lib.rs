//! Runtime of `lagrange`: the trait the derive macro implements, forward
//! dynamics, integrators and trajectories.
//!
//! A system implements [`Lagrangian`] (the macro writes this; a hand-written
//! implementation works the same), which gives the equations of motion
//! M(q,t) q̈ + h(q,q̇,t) = Q(q,q̇,t). [`Dynamics`] solves them for q̈ by a
//! Cholesky factorisation on the stack and reports a singular mass matrix (a chart
//! singularity) or a non-finite state as a typed [`Error`], never as a silent NaN.
//! The integrators in [`ode`] step the second-order system without allocating per
//! step, and [`Simulation`] ties it together:
//!
//! ```text
//! let traj = Simulation::new(&sys).integrator(Dopri5::tol(1e-10)).run(q0, v0, 0.0..10.0)?;
//! let periods = traj.crossings(|_, q, _| q[0]);
//! println!("energy drift {:e}", traj.integral_drift());
//! traj.save_csv("out.csv", &Pendulum::COORDINATES)?;
//! ```
//!
//! Constrained systems come in two forms. A [`Constrained`] system keeps its
//! constraints with multipliers: [`ConstrainedDynamics`] solves the saddle-point
//! system for q̈ and ν (redundant constraints are a typed error, or least squares
//! on request), [`Drift`] chooses the drift control (none, Baumgarte, projection),
//! and initial conditions are checked or projected ([`check_consistency`],
//! [`project_consistent`]). A [`Reduced`] system is written in independent speeds
//! and needs no multipliers: [`ReducedDynamics`].
//!
//! ```text
//! let traj = Simulation::new(&sys)
//!     .integrator(Dopri5::tol(1e-10))
//!     .drift(Drift::projection())
//!     .run_constrained(q0, v0, 0.0..10.0)?;
//! let [phi, vel] = traj.max_residuals();
//! ```
//!
//! Events ([`Event`]: zero crossings of g(t, q, v), located on the dense output,
//! with an optional action such as an impact law, optionally terminal) are
//! watched with [`Simulation::event`]; see [`event`] for the design.
//!
//! ```text
//! let run = Simulation::new(&ball)
//!     .event(Event::new(|_, q, _| q[0]).falling().action(|_, _, v| *v *= -0.9))
//!     .run(q0, v0, 0.0..5.0)?;
//! println!("{} impacts", run.occurrences.len());
//! ```
//!
//! Systems with inputs ([`Driven`]) are driven by a controller or a signal:
//! continuous feedback, sampled feedback with zero-order hold, open-loop
//! closures or [`InputTable`]s, in all three forms; see [`control`].
//!
//! ```text
//! let run = Simulation::new(&cart)
//!     .integrator(Dopri5::tol(1e-10))
//!     .sampled(0.01, |_, q, v| [-k1 * q[0] - k2 * v[0]])
//!     .run(q0, v0, 0.0..5.0)?;
//! run.save_csv("cart.csv")?;   // t, coordinates, velocities, inputs
//! ```
//!
//! [`Rattle`] integrates holonomic constraints with a constant mass matrix
//! symplectically, keeping Φ = 0 and Φ_q q̇ = 0 to round-off.
//!
//! [`study`] runs work-precision studies: integrators × tolerances or step sizes
//! on one problem, each run's error against a closed form or a DOP853 reference
//! and its cost, as a markdown/CSV table and (feature `plot`) a log-log PNG.
//!
//! Everything is generic over the scalar `T: `[`Real`] (f64, f32, ...) and the
//! number of degrees of freedom `N`, a type-level constant.

// The layers, bottom to top; each imports only from the layers above it in
// this list (ARCHITECTURE.md has the map, tests/layers.rs holds it true).
pub mod control;
#[cfg(feature = "parallel")]
pub mod ensemble;
pub mod error;
pub mod event;
pub mod linear;
pub mod mechanics;
pub mod numeric;
pub mod ode;
mod simulation;
pub mod study;
mod system;
mod table;

pub use control::{
    Feedback, InputForces, InputSource, InputTable, Interpolation, IntoInput, OpenLoop, Sampled,
    StateFeedback,
};
pub use error::{Error, Failure, LinearError};
pub use event::{Direction, Event, EventRun, Events, Occurrence};
pub use linear::{
    Linear, Linearizer, OperatingPoint, complete_state, linearize, linearize_constrained,
    linearize_reduced,
};
pub use mechanics::constraint::{
    ConstrainedDynamics, Drift, Solution, check_consistency, project_consistent,
};
pub use mechanics::{
    DEFAULT_SINGULAR_TOLERANCE, Dynamics, Forcing, NoForcing, Rattle, ReducedDynamics, ReducedForm,
    accelerations,
};
pub use numeric::{Real, func};
pub use ode::{
    DenseSegment, Dop853, Dopri5, Gauss, Integrator, Mechanical, Radau5, Record, Rk4, Sample,
    SecondOrder, Stats, StormerVerlet, Trajectory,
};
pub use simulation::{ControlRun, ControlledSimulation, EventSimulation, Simulation};
pub use study::{Study, Sweep, WorkPrecision};
pub use system::{Constrained, Driven, FormVisitor, Lagrangian, Reduced};
pub use table::Table;
