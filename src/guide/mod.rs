//! The guide: chapters to read in order, from a first model to what to do when
//! a run fails. Each is one page with examples that `cargo test` compiles and
//! runs, and ends in a complete program.
//!
//! 1. [A first model](first_model): a pendulum, its equations, a run, a plot.
//! 2. [The description language](description), item by item.
//! 3. [Constraints](constraints): holonomic, nonholonomic, multipliers and the
//!    reduced form.
//! 4. [Rigid bodies and rotations](rotations): Euler angles and their charts,
//!    free orientations, the atlas.
//! 5. [Robots from URDF](robots): dynamics, kinematics, frames, inverse
//!    dynamics.
//! 6. [Inputs and control](control): controllers, linearisation, LQR.
//! 7. [Seeing results](results): tables, scenes, CSV and serde.
//! 8. [Speed and accuracy](accuracy): choosing an integrator, work-precision
//!    studies.
//! 9. [When things go wrong](errors): the errors and what each means.
//! 10. [Planning](planning): equilibria, discrete time, optimal control and
//!     MPC.
//! 11. [Identification](identification): the regressor, base parameters and
//!     the estimation of a robot's masses and inertias from its motion.
//! 12. [Contact](contact): bodies that land, bounce, slide, stick and roll;
//!     joint stops.

#[doc = include_str!("1-first-model.md")]
pub mod first_model {}

#[doc = include_str!("2-description.md")]
pub mod description {}

#[doc = include_str!("3-constraints.md")]
pub mod constraints {}

#[doc = include_str!("4-rotations.md")]
pub mod rotations {}

#[doc = include_str!("5-robots.md")]
pub mod robots {}

#[doc = include_str!("6-control.md")]
pub mod control {}

#[doc = include_str!("7-results.md")]
pub mod results {}

#[doc = include_str!("8-accuracy.md")]
pub mod accuracy {}

#[doc = include_str!("9-errors.md")]
pub mod errors {}

#[doc = include_str!("10-planning.md")]
pub mod planning {}

#[doc = include_str!("11-identification.md")]
pub mod identification {}
#[doc = include_str!("12-contact.md")]
pub mod contact {}
