//! The visitors through which a system picks the form it runs in
//! ([`Lagrangian::visit_form`]): one per builder, each holding the initial
//! state until the system names its form.

use super::{ControlledSimulation, EventSimulation, Simulation};
use crate::control::InputSource;
use crate::error::Failure;
use crate::event::EventRun;
use crate::numeric::Real;
use crate::ode::{Integrator, Trajectory};
use crate::simulation::ControlRun;
use crate::system::{Constrained, Driven, FormVisitor, Lagrangian, Reduced};
use nalgebra::SVector;
use std::ops::Range;

/// A run waiting for its form: the builder, the initial state and the span.
pub(super) struct Start<'r, B, T, const N: usize, const Q: usize = N> {
    pub builder: &'r B,
    pub q0: SVector<T, Q>,
    pub v0: SVector<T, N>,
    pub span: Range<T>,
}

impl<S, I, T, const N: usize, const Q: usize> FormVisitor<T, N, S, Q>
    for Start<'_, Simulation<'_, S, I>, T, N, Q>
where
    S: Lagrangian<T, N, Q>,
    I: Integrator,
    T: Real,
{
    type Output = Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>>;

    fn unconstrained(self, _: &S) -> Self::Output {
        self.builder.run_unconstrained(self.q0, self.v0, self.span)
    }

    fn multipliers<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Constrained<T, N, K, Q>,
    {
        self.builder
            .run_constrained::<T, N, K, Q>(self.q0, self.v0, self.span)
    }

    fn reduced<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Reduced<T, N, K, Q>,
    {
        self.builder
            .run_reduced::<T, N, K, Q>(self.q0, self.v0, self.span)
    }
}

impl<S, I, T, const N: usize, const Q: usize> FormVisitor<T, N, S, Q>
    for Start<'_, EventSimulation<'_, '_, S, I, T, N, Q>, T, N, Q>
where
    S: Lagrangian<T, N, Q>,
    I: Integrator,
    T: Real,
{
    type Output = Result<EventRun<T, N, Q>, Failure<EventRun<T, N, Q>>>;

    fn unconstrained(self, _: &S) -> Self::Output {
        self.builder.run_unconstrained(self.q0, self.v0, self.span)
    }

    fn multipliers<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Constrained<T, N, K, Q>,
    {
        self.builder
            .run_constrained::<K>(self.q0, self.v0, self.span)
    }

    fn reduced<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Reduced<T, N, K, Q>,
    {
        self.builder.run_reduced::<K>(self.q0, self.v0, self.span)
    }
}

impl<S, I, C, T, const N: usize, const P: usize, const Q: usize> FormVisitor<T, N, S, Q>
    for Start<'_, ControlledSimulation<'_, '_, S, I, C, T, N, P, Q>, T, N, Q>
where
    S: Driven<T, N, P, Q>,
    I: Integrator,
    C: InputSource<T, N, P, Q>,
    T: Real,
{
    type Output = Result<ControlRun<T, N, P, Q>, Failure<ControlRun<T, N, P, Q>>>;

    fn unconstrained(self, _: &S) -> Self::Output {
        self.builder.run_unconstrained(self.q0, self.v0, self.span)
    }

    fn multipliers<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Constrained<T, N, K, Q>,
    {
        self.builder
            .run_constrained::<K>(self.q0, self.v0, self.span)
    }

    fn reduced<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Reduced<T, N, K, Q>,
    {
        self.builder.run_reduced::<K>(self.q0, self.v0, self.span)
    }
}
