//! The Hamiltonian view of a mechanical system, for the symplectic integrators.

use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use nalgebra::{SMatrix, SVector};

/// A second-order system that can also be written in Hamilton's form
///
/// ```text
/// p = ∂L/∂q̇ = M(q,t) q̇ + a(q,t),     ṗ = ∂T/∂q + Q(q,q̇,t)
/// ```
///
/// which a symplectic method ([`Gauss`](crate::Gauss)) integrates in (q, p). The
/// velocity is recovered from the momentum by q̇ = M⁻¹(p − a), and a is the
/// momentum at zero velocity (p is affine in q̇).
pub trait Mechanical<T: Real, const N: usize, const Q: usize = N> {
    /// The mass matrix M(q,t).
    ///
    /// # Errors
    /// Whatever prevents its evaluation.
    fn mass_matrix(&self, t: T, q: &SVector<T, Q>) -> Result<SMatrix<T, N, N>, Error>;

    /// The momentum p = ∂L/∂q̇.
    ///
    /// # Errors
    /// Whatever prevents its evaluation.
    fn momentum(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<SVector<T, N>, Error>;

    /// ṗ = ∂T/∂q + Q: the kinetic-energy gradient plus all generalized forces
    /// (a forcing's ΔQ included). For a free orientation, the torque
    /// ∂T/∂θ + Q_θ in body axes at fixed ω (see
    /// [`Lagrangian::kinetic_gradient`](crate::Lagrangian::kinetic_gradient));
    /// the gyroscopic π × ω is not part of it.
    ///
    /// # Errors
    /// Whatever prevents its evaluation, or a system that cannot provide ∂T/∂q.
    fn momentum_rate(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error>;

    /// The velocity q̇ = M⁻¹(p − a) with the momentum p at (t, q).
    ///
    /// # Errors
    /// [`Error::SingularMassMatrix`] if M is not positive definite.
    fn velocity(&self, t: T, q: &SVector<T, Q>, p: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        let a = self.momentum(t, q, &SVector::zeros())?;
        let m = self.mass_matrix(t, q)?;
        // The runtime's one Cholesky; a zero tolerance refuses only a matrix
        // that is not positive definite, as before (the symplectic method has
        // no singular-tolerance setting of its own).
        let chol = Cholesky::new(m, T::zero())
            .map_err(|ratio| Error::singular_mass(t, q, ratio, &m, (&[], false)))?;
        Ok(chol.solve(p - a))
    }
}
