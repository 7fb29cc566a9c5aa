//! The visitor through which a system names the form it runs in.

use super::{Constrained, Lagrangian, Reduced};
use crate::numeric::Real;

/// What runs a system in the form its description asked for (see
/// [`Lagrangian::visit_form`]): one method per form, each with the trait the
/// form needs. Implemented by the simulation builders; not meant to be
/// implemented by users.
#[doc(hidden)]
pub trait FormVisitor<T: Real, const N: usize, S: Lagrangian<T, N, Q>, const Q: usize = N> {
    /// What running the system gives.
    type Output;

    /// The unconstrained equations M q̈ + h = Q.
    fn unconstrained(self, system: &S) -> Self::Output;

    /// The multiplier form with K constraint rows.
    fn multipliers<const K: usize>(self, system: &S) -> Self::Output
    where
        S: Constrained<T, N, K, Q>;

    /// The reduced form with K independent speeds.
    fn reduced<const K: usize>(self, system: &S) -> Self::Output
    where
        S: Reduced<T, N, K, Q>;
}
