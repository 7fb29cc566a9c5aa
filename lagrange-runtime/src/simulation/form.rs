//! The visitors through which a system picks the form it runs in
//! ([`Lagrangian::visit_form`]): one per builder, each holding the initial
//! state until the system names its form.

use super::{ControlledSimulation, EventSimulation, Simulation};
use crate::control::InputSource;
use crate::error::{Error, Failure};
use crate::event::EventRun;
use crate::numeric::Real;
use crate::ode::{Integrator, Sample, Trajectory};
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
        S: Reduced<T, N, K>,
    {
        // A system with a reduced form has Q = N (`Reduced` extends
        // `Lagrangian<T, N>`): the casts only restate that to the compiler.
        let Some(q0) = same::<_, SVector<T, N>>(self.q0) else {
            return Err(self.mismatch());
        };
        let run = self.builder.run_reduced::<T, N, K>(q0, self.v0, self.span);
        same(run).expect("the run's type is the output's when q0's was")
    }
}

impl<B, T: Real, const N: usize, const Q: usize> Start<'_, B, T, N, Q> {
    /// The failure of a system whose `visit_form` names the reduced form
    /// for a configuration with orientations, which it does not take (only a
    /// hand-written `visit_form` can).
    fn mismatch(self) -> Failure<Trajectory<T, N, Q>> {
        let zero = T::zero();
        let sample = Sample {
            integral: zero,
            residuals: [zero; 2],
            unit_error: zero,
        };
        Failure::new(
            Error::InvalidSettings(
                "the reduced form takes no orientations (Q = N): this system's \
                 visit_form names it for a configuration with quaternions"
                    .into(),
            ),
            Trajectory::start(self.span.start, self.q0, self.v0, sample),
        )
    }
}

/// `a` as a `B` when `A` and `B` are the same type: the witness that Q = N,
/// which the const generics of stable Rust cannot state.
fn same<A: 'static, B: 'static>(a: A) -> Option<B> {
    let boxed: Box<dyn std::any::Any> = Box::new(a);
    boxed.downcast::<B>().ok().map(|b| *b)
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
        S: Reduced<T, N, K>,
    {
        let Some(q0) = same::<_, SVector<T, N>>(self.q0) else {
            return Err(self.mismatch().map(EventRun::unstarted));
        };
        self.builder.run_reduced::<K>(q0, self.v0, self.span)
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
        S: Reduced<T, N, K>,
    {
        self.builder.run_reduced::<K>(self.q0, self.v0, self.span)
    }
}
