//! Fixtures shared by the runtime's integration tests, one module per kind:
//! `minimal` (pendulums and the oscillator in minimal coordinates),
//! `constrained` (holonomic and nonholonomic systems with their constraints),
//! `driven` (systems with inputs), `second_order` (plain q̈ = f(t, q, q̇)
//! reference problems), `closed_form` (exact answers to check against), `numeric` (random
//! states, finite differences).
#![allow(dead_code)] // each test binary uses a different subset

pub mod closed_form;
pub mod constrained;
pub mod driven;
pub mod minimal;
pub mod numeric;
pub mod rigid;
pub mod second_order;

// The names most tests use, at the top (each binary uses some of them).
#[allow(unused_imports)]
pub use closed_form::{agm, pendulum_period};
#[allow(unused_imports)]
pub use minimal::{Ball, Oscillator, Pendulum, SphericalPendulum};

use nalgebra::SVector;

/// A state vector from a slice of the right size.
pub fn sv<const N: usize>(x: [f64; N]) -> SVector<f64, N> {
    SVector::from(x)
}
