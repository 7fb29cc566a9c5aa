//! Scalar and small-matrix numerics, the bottom layer: the scalar type, the
//! functions generated code calls (and their four-lane counterparts, `lanes`;
//! the joint angles' sines and cosines in SIMD lanes, `sincos`), the one Cholesky (and a whole small M⁻¹ by L D Lᵀ, `inverse`), the one saddle-point
//! solve, the one elimination with complete pivoting, dense LU for the
//! implicit integrators, products of small dynamically sized matrices that
//! allocate nothing (`products`), root finding on a bracket and a wall clock. Nothing
//! here knows about mechanics or integrators.

pub(crate) mod cholesky;
pub(crate) mod clock;
pub(crate) mod elimination;
pub mod euler;
pub mod func;
pub(crate) mod inverse;
pub mod lanes;
pub(crate) mod lu;
pub mod orientation;
pub(crate) mod products;
mod real;
pub(crate) mod root;
pub(crate) mod saddle;
#[cfg(test)]
pub(crate) mod samples;
pub mod sincos;

pub use real::Real;
