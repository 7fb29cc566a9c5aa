//! A held source's forces for the runs that stop at its samples themselves
//! (the contact runs): the sample taken at each break is kept in a cell and
//! read, within the actuators' limits, at every evaluation between breaks.

use super::{InputSource, check_input};
use crate::error::Error;
use crate::mechanics::Forcing;
use crate::numeric::Real;
use crate::system::Driven;
use nalgebra::SVector;
use std::cell::Cell;

/// The forces of `system`'s inputs from a held (sampled) `source`.
pub(crate) struct HeldForces<'s, S, C, T, const P: usize> {
    system: &'s S,
    source: &'s C,
    held: Cell<SVector<T, P>>,
}

impl<'s, S, C, T: Real, const P: usize> HeldForces<'s, S, C, T, P> {
    /// No sample yet (zeros until the run takes its first).
    pub(crate) fn new(system: &'s S, source: &'s C) -> Self {
        Self {
            system,
            source,
            held: Cell::new(SVector::zeros()),
        }
    }
}

impl<S, C, T, const N: usize, const P: usize, const Q: usize> Forcing<T, N, Q>
    for HeldForces<'_, S, C, T, P>
where
    S: Driven<T, N, P, Q>,
    C: InputSource<T, N, P, Q>,
    T: Real,
{
    #[inline]
    fn force(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        let u = self.source.limit(t, q, v, self.held.get());
        Ok(self.system.input_forces(q, v, &u, t))
    }

    fn next_sample(&self, start: T, after: T) -> Option<T> {
        self.source.next_break(start, after)
    }

    fn take_sample(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<(), Error> {
        let u = self.source.input(t, q, v);
        check_input::<S, T, N, P, Q>(t, q, v, &u)?;
        self.held.set(u);
        Ok(())
    }
}
