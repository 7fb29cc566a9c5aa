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
//! ```
//! # use lagrange_runtime::{Dopri5, Lagrangian, Simulation};
//! # use nalgebra::{Matrix1, Vector1};
//! # struct Pendulum;
//! # impl Lagrangian<f64, 1> for Pendulum {
//! #     const COORDINATES: [&'static str; 1] = ["theta"];
//! #     const RHEONOMIC: bool = false;
//! #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
//! #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-q[0].sin()) }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
//! #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { -q[0].cos() }
//! #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
//! #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
//! #     }
//! # }
//! let sys = Pendulum; // θ'' = −sin θ (by hand here; usually #[derive(Lagrangian)])
//! let traj = Simulation::new(&sys).integrator(Dopri5::tol(1e-10)).run([1.0], [0.0], 0.0..10.0)?;
//! let zeros = traj.crossings(|_, q, _| q[0])?; // θ = 0 every half period
//! assert_eq!(zeros.len(), 3);
//! println!("energy drift {:e}", traj.integral_drift());
//! traj.save_csv(std::env::temp_dir().join("pendulum.csv"), &Pendulum::COORDINATES)?;
//! # Ok::<(), lagrange_runtime::Error>(())
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
//! ```
//! # use lagrange_runtime::{Constrained, Dopri5, Drift, Lagrangian, Simulation};
//! # use nalgebra::{Matrix1x2, Matrix2, Vector1, Vector2};
//! # struct Bob;
//! # impl Lagrangian<f64, 2> for Bob {
//! #     const COORDINATES: [&'static str; 2] = ["x", "y"];
//! #     const RHEONOMIC: bool = false;
//! #     fn mass_matrix(&self, _: &Vector2<f64>, _: f64) -> Matrix2<f64> { Matrix2::identity() }
//! #     fn bias(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> { Vector2::zeros() }
//! #     fn generalized_forces(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> { Vector2::new(0.0, -9.81) }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> (Matrix2<f64>, Vector2<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> f64 { 0.5 * v.norm_squared() }
//! #     fn potential_energy(&self, q: &Vector2<f64>, _: f64) -> f64 { 9.81 * q[1] }
//! #     fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
//! #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
//! #     }
//! # }
//! # impl Constrained<f64, 2, 1> for Bob {
//! #     const CONSTRAINTS: [&'static str; 1] = ["rod"];
//! #     const HOLONOMIC: usize = 1;
//! #     fn constraint_positions(&self, q: &Vector2<f64>, _: f64) -> Vector1<f64> { Vector1::new(q.norm_squared() - 1.0) }
//! #     fn constraint_jacobian(&self, q: &Vector2<f64>, _: f64) -> (Matrix1x2<f64>, Vector1<f64>) {
//! #         (Matrix1x2::new(2.0 * q[0], 2.0 * q[1]), Vector1::zeros())
//! #     }
//! #     fn constraint_rhs(&self, _: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> Vector1<f64> { Vector1::new(-2.0 * v.norm_squared()) }
//! #     fn constrained_system(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64)
//! #         -> (Matrix2<f64>, Vector2<f64>, Matrix1x2<f64>, Vector1<f64>) {
//! #         let (m, f) = self.mass_matrix_and_rhs(q, v, t);
//! #         (m, f, self.constraint_jacobian(q, t).0, self.constraint_rhs(q, v, t))
//! #     }
//! # }
//! // A point (x, y) on a rod x² + y² = 1 (written out in full in `mechanics::constraint`).
//! let (sys, q0, v0) = (Bob, [0.6, -0.8], [0.0, 0.0]);
//! let traj = Simulation::new(&sys)
//!     .integrator(Dopri5::tol(1e-10))
//!     .drift(Drift::projection())
//!     .run_constrained(q0, v0, 0.0..10.0)?;
//! let [phi, vel] = traj.max_residuals();
//! assert!(phi < 1e-12 && vel < 1e-12);
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! Events ([`Event`]: zero crossings of g(t, q, v), located on the dense output,
//! with an optional action such as an impact law, optionally terminal) are
//! watched with [`Simulation::event`]; see [`event`] for the design.
//!
//! ```
//! # use lagrange_runtime::{Event, Lagrangian, Simulation};
//! # use nalgebra::{Matrix1, Vector1};
//! # struct Ball;
//! # impl Lagrangian<f64, 1> for Ball {
//! #     const COORDINATES: [&'static str; 1] = ["z"];
//! #     const RHEONOMIC: bool = false;
//! #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
//! #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-9.81) }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
//! #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { 9.81 * q[0] }
//! #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
//! #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
//! #     }
//! # }
//! let ball = Ball; // z'' = −g, dropped from z = 1
//! let run = Simulation::new(&ball)
//!     .event(Event::new(|_, q, _| q[0]).falling().action(|_, _, v| *v *= -0.9))
//!     .run([1.0], [0.0], 0.0..5.0)?;
//! println!("{} impacts", run.occurrences.len());
//! assert!(run.occurrences.len() > 3);
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! Systems with inputs ([`Driven`]) are driven by a controller or a signal:
//! continuous feedback, sampled feedback with zero-order hold, open-loop
//! closures or [`InputTable`]s, in all three forms; see [`control`].
//!
//! ```
//! # use lagrange_runtime::{Dopri5, Driven, Lagrangian, Simulation};
//! # use nalgebra::{Matrix1, Vector1};
//! # struct Cart;
//! # impl Lagrangian<f64, 1> for Cart {
//! #     const COORDINATES: [&'static str; 1] = ["x"];
//! #     const RHEONOMIC: bool = false;
//! #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
//! #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
//! #     fn potential_energy(&self, _: &Vector1<f64>, _: f64) -> f64 { 0.0 }
//! #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 { self.kinetic_energy(q, v, t) }
//! # }
//! # impl Driven<f64, 1, 1> for Cart {
//! #     const INPUTS: [&'static str; 1] = ["force"];
//! #     fn input_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, u: &Vector1<f64>, _: f64) -> Vector1<f64> { *u }
//! #     fn input_jacobians(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: &Vector1<f64>, _: f64)
//! #         -> (Matrix1<f64>, Matrix1<f64>, Matrix1<f64>) {
//! #         (Matrix1::identity(), Matrix1::zeros(), Matrix1::zeros())
//! #     }
//! # }
//! // A free cart of unit mass pushed by a digital PD controller.
//! let (cart, k1, k2) = (Cart, 4.0, 4.0);
//! let run = Simulation::new(&cart)
//!     .integrator(Dopri5::tol(1e-10))
//!     .sampled(0.01, |_, q, v| [-k1 * q[0] - k2 * v[0]])
//!     .run([1.0], [0.0], 0.0..5.0)?;
//! run.save_csv(std::env::temp_dir().join("cart.csv"))?; // t, coordinates, velocities, inputs
//! assert!(run.trajectory().final_state().0[0].abs() < 0.01);
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! [`Rattle`] integrates holonomic constraints with a constant mass matrix
//! symplectically, keeping Φ = 0 and Φ_q q̇ = 0 to round-off; with free
//! orientations too (a body held by holonomic rows, its inertia constant in
//! body axes), second order.
//!
//! [`Scene`] turns runs of a system into one self-contained HTML page that
//! plays the motion in 3D (the bodies' poses come from [`Posed`], which the
//! derive implements); see [`scene`].
//!
//! [`orientation`] builds and compares the unit quaternions of systems with
//! free orientations: from an axis and an angle or Euler angles, q ⊕ δ and
//! q ⊖ q₀ (the tangent space the linearisations and controllers use), over
//! one quaternion or a system's whole configuration, and a run's error in
//! that tangent space.
//!
//! [`task_space`] holds what robot programs ask of a frame, for any number of
//! joints: damped least-squares inverse kinematics, and the operational-space
//! controller as a feedback law for a run (in `f64`, on the emitted
//! [`Kinematics`]).
//!
//! [`study`] runs work-precision studies: integrators × tolerances or step sizes
//! on one problem, each run's error against a closed form or a DOP853 reference
//! and its cost, as a markdown/CSV table and (feature `plot`) a log-log PNG.
//! With the feature `plot`, `picture` draws a run's columns against t and a
//! scene's still as PNGs.
//!
//! Everything else is generic over the scalar `T: `[`Real`] (f64, f32, ...) and
//! the number of degrees of freedom `N`, a type-level constant.

#![warn(missing_docs)]

// The modules by layer, bottom up: each imports only from its own layer and
// the layers listed before it (ARCHITECTURE.md has the map; the workspace's
// tests/architecture.rs holds it true).

// 0 numerics
pub mod numeric;

// 1 errors
pub mod error;

// 2 integrators
pub mod ode;

// 3 the contract the derive implements
pub mod orientation;
pub mod pose;
mod system;

// 4 mechanical forms
pub mod mechanics;

// 5 services
pub mod atlas;
pub mod contact;
pub mod control;
#[cfg(feature = "parallel")]
pub mod ensemble;
pub mod event;
pub mod identify;
pub mod linear;
#[cfg(feature = "plot")]
pub mod picture;
pub mod plan;
pub mod scene;
pub mod study;
mod table;
pub mod task_space;

// 6 top: the one builder
mod simulation;

pub use atlas::{AtlasRun, ChartSwitch, ChartedTrajectory};
pub use contact::{
    ChangeKind, Compliant, ContactChange, ContactForce, ContactRun, ContactSettings, ContactState,
};
pub use control::{
    Feedback, InputForces, InputSource, InputTable, Interpolation, IntoInput, OpenLoop, Sampled,
    Saturated, Saturation, StateFeedback,
};
pub use error::{
    ContactError, ContactFault, Error, Failure, IdentifyError, LinearError, SettingsError,
};
pub use event::{Direction, Event, EventRun, Events, LimitPolicy, Occurrence};
pub use linear::{
    Linear, Linearizer, OperatingPoint, complete_state, linearize, linearize_constrained,
    linearize_reduced,
};
pub use mechanics::constraint::{
    ConstrainedDynamics, Drift, Solution, check_consistency, project_consistent,
};
#[doc(hidden)]
pub use mechanics::factored_derivatives;
pub use mechanics::{
    AccelerationDerivatives, Batched, BatchedDifferentiable, DEFAULT_SINGULAR_TOLERANCE,
    Differentiable, Dynamics, Forcing, InputDerivatives, LaneDerivatives, NoForcing, Rattle,
    ReducedDynamics, ReducedForm, acceleration_derivatives, accelerations,
    batched_acceleration_derivatives, batched_accelerations,
};
pub use numeric::lanes::F64x4;
pub use numeric::orientation::Orientation;
pub use numeric::{Real, func};
pub use ode::{
    Continuation, DenseSegment, Dop853, Dopri5, Gauss, Integrator, Mechanical, MoreauJean, Radau5,
    Record, Rk4, Sample, SecondOrder, Stats, StormerVerlet, Trajectory,
};
pub use pose::{Kinematics, Posed};
pub use scene::Scene;
pub use simulation::{
    AtlasRunOf, AtlasRuns, Control, ControlRun, NoEvents, Run, Runs, Simulation, Unforced,
};
#[allow(deprecated)]
pub use simulation::{ControlledSimulation, EventSimulation};
pub use study::{Study, Sweep, WorkPrecision};
pub use system::physical;
pub use system::{Atlas, Configuration, DrivenAtlas, EulerRotation, FreeVisitor};
pub use system::{
    Constrained, Driven, FormVisitor, ForwardRoute, JointLimit, Lagrangian, Reduced, Route,
};
pub use system::{ContactKind, ContactLaw, ContactRows, Contacts};
pub use table::Table;
