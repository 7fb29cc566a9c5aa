//! Forces added to the right-hand side of the forward dynamics: the seam
//! through which controllers (and any other force law) reach the mechanics
//! without the mechanics knowing about controllers.

use crate::error::Error;
use crate::numeric::Real;
use nalgebra::SVector;

/// A generalized force ΔQ(t, q, q̇) added to the right-hand side Q − h of the
/// forward dynamics.
///
/// Implemented by [`NoForcing`] (nothing, the default of every dynamics type)
/// and [`InputForces`](crate::InputForces) (the forces of a [`Driven`](crate::Driven) system's inputs); implement
/// it for any other force law.
pub trait Forcing<T: Real, const N: usize, const Q: usize = N> {
    /// Whether [`force`](Self::force) is called at all. `false` only for
    /// [`NoForcing`]: the dynamics test it as a constant, so an unforced system
    /// pays nothing.
    const ACTIVE: bool = true;

    /// ΔQ at (t, q, q̇).
    ///
    /// # Errors
    /// Whatever prevents its evaluation, such as [`Error::NonFiniteInput`].
    fn force(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<SVector<T, N>, Error>;
}

/// No forcing: the default forcing parameter of [`Dynamics`](crate::Dynamics),
/// [`ConstrainedDynamics`](crate::ConstrainedDynamics) and
/// [`ReducedDynamics`](crate::ReducedDynamics).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoForcing;

impl<T: Real, const N: usize, const Q: usize> Forcing<T, N, Q> for NoForcing {
    const ACTIVE: bool = false;

    #[inline(always)]
    fn force(&self, _: T, _: &SVector<T, Q>, _: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        Ok(SVector::zeros())
    }
}

/// A borrowed forcing is the same forcing.
impl<T: Real, const N: usize, const Q: usize, F: Forcing<T, N, Q>> Forcing<T, N, Q> for &F {
    const ACTIVE: bool = F::ACTIVE;

    #[inline(always)]
    fn force(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        (**self).force(t, q, v)
    }
}
