//! The reduced form of a controlled run typed with Q configuration entries
//! when Q = N: the reduced form takes no orientations, so its dynamics (over
//! q of N entries) and the inputs' forces (over q of Q entries) meet through
//! these two retypings, each an entry-by-entry copy. The caller checks Q = N
//! before building either.

use crate::error::Error;
use crate::mechanics::Forcing;
use crate::numeric::Real;
use crate::ode::SecondOrder;
use nalgebra::SVector;

/// q read as the other configuration type of the same length.
fn cast<T: Real, const A: usize, const B: usize>(q: &SVector<T, A>) -> SVector<T, B> {
    SVector::from_fn(|i, _| q[i])
}

/// A forcing over q of Q entries as one over q of N entries (Q = N).
#[derive(Clone, Copy, Debug)]
pub(super) struct Narrowed<F, const Q: usize>(pub F);

impl<T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize> Forcing<T, N>
    for Narrowed<F, Q>
{
    const ACTIVE: bool = F::ACTIVE;

    #[inline]
    fn force(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        self.0.force(t, &cast(q), v)
    }
}

/// Dynamics over q of N entries (no orientations) as dynamics over q of Q
/// entries (Q = N).
#[derive(Clone, Copy, Debug)]
pub(super) struct Widened<D>(pub D);

impl<T: Real, D: SecondOrder<T, N>, const N: usize, const Q: usize> SecondOrder<T, N, Q>
    for Widened<D>
{
    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        self.0.acceleration(t, &cast(q), v)
    }

    fn rate(&self, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, Q> {
        cast(&self.0.rate(&cast(q), v))
    }

    fn advance(&self, q: &SVector<T, Q>, delta: &SVector<T, N>) -> SVector<T, Q> {
        cast(&self.0.advance(&cast(q), delta))
    }

    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        self.0.integral(t, &cast(q), v)
    }

    fn residuals(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> [T; 2] {
        self.0.residuals(t, &cast(q), v)
    }

    fn project(&self, t: T, q: &mut SVector<T, Q>, v: &mut SVector<T, N>) -> Result<bool, Error> {
        let mut narrow = cast::<T, Q, N>(q);
        let changed = self.0.project(t, &mut narrow, v)?;
        *q = cast(&narrow);
        Ok(changed)
    }
}
