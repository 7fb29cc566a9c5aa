//! The visitor through which a system picks the form [`Simulation::run`]
//! integrates ([`Lagrangian::visit_form`]): it holds the initial state until
//! the system names its form.

use super::{Run, Runs, Simulation};
use crate::error::Failure;
use crate::numeric::Real;
use crate::ode::Integrator;
use crate::system::{Constrained, FormVisitor, Lagrangian, Reduced};
use nalgebra::SVector;
use std::ops::Range;

/// A run waiting for its form: the builder, the initial state and the span.
pub(super) struct Start<'r, B, T, const N: usize, const Q: usize = N> {
    pub builder: &'r B,
    pub q0: SVector<T, Q>,
    pub v0: SVector<T, N>,
    pub span: Range<T>,
}

impl<'a, S, I, C, E, T, const N: usize, const Q: usize> FormVisitor<T, N, S, Q>
    for Start<'_, Simulation<'a, S, I, C, E>, T, N, Q>
where
    S: Lagrangian<T, N, Q>,
    I: Integrator,
    T: Real,
    Simulation<'a, S, I, C, E>: Runs<T, N, Q>,
{
    type Output = Result<
        Run<Simulation<'a, S, I, C, E>, T, N, Q>,
        Failure<Run<Simulation<'a, S, I, C, E>, T, N, Q>>,
    >;

    fn unconstrained(self, _: &S) -> Self::Output {
        self.builder.run_unconstrained(self.q0, self.v0, self.span)
    }

    fn multipliers<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Constrained<T, N, K, Q>,
    {
        (self.builder).run_constrained::<T, N, K, Q>(self.q0, self.v0, self.span)
    }

    fn reduced<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Reduced<T, N, K, Q>,
    {
        (self.builder).run_reduced::<T, N, K, Q>(self.q0, self.v0, self.span)
    }
}
