//! ∂q̈/∂q and ∂q̈/∂q̇ from the system's right-hand-side Jacobians
//! ([`Lagrangian::rhs_jacobians`], `emit(jacobians)`): M⁻¹ J_q and M⁻¹ J_v,
//! and ∂q̈/∂τ = M⁻¹ from the same factorisation, on the stack (the
//! counterpart of Pinocchio's `computeABADerivatives`: `ddq_dq`, `ddq_dv`,
//! `Minv`).
//! With orientations the derivatives are in the tangent space: ∂/∂δ along
//! q ⊕ δ, an orientation's δ the rotation vector in body axes, at fixed ω.

use nalgebra::{SMatrix, SVector};

use super::dynamics::{Dynamics, all_finite};
use super::forcing::{Forcing, NoForcing};
use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::system::Lagrangian;

/// The derivatives of q̈ = M⁻¹(Q − h + τ) at a state, N × N each.
#[derive(Clone, Debug, PartialEq)]
pub struct AccelerationDerivatives<T, const N: usize> {
    /// ∂q̈/∂δ: along q ⊕ δ (∂q̈/∂q without orientations), at fixed q̇.
    pub dq: SMatrix<T, N, N>,
    /// ∂q̈/∂q̇.
    pub dv: SMatrix<T, N, N>,
    /// ∂q̈/∂τ = M⁻¹, for generalized forces τ added to Q (joint torques of
    /// a robot; for an orientation, a torque in its body axes).
    pub dtau: SMatrix<T, N, N>,
}

/// A forcing's own Jacobians (∂ΔQ/∂δ, ∂ΔQ/∂q̇), N × N each.
pub type ForceJacobians<T, const N: usize> = (SMatrix<T, N, N>, SMatrix<T, N, N>);

impl<S, T, F> Dynamics<'_, S, T, F>
where
    T: Real,
{
    /// ∂q̈/∂δ, ∂q̈/∂q̇ and ∂q̈/∂τ at (q, v, t), with the forcing's own
    /// Jacobians (∂ΔQ/∂δ, ∂ΔQ/∂v) added when it has any; `Ok(None)` when the
    /// system does not emit its Jacobians.
    ///
    /// # Errors
    /// As [`acceleration`](Self::acceleration); [`Error::NonFiniteState`] for
    /// a non-finite derivative.
    pub fn acceleration_derivatives<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        forced: Option<ForceJacobians<T, N>>,
    ) -> Result<Option<AccelerationDerivatives<T, N>>, Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let Some((chol, dq, dv)) = self.derivatives(t, q, v, forced)? else {
            return Ok(None);
        };
        let dtau = chol.solve_columns(SMatrix::identity());
        if !all_finite(dtau.as_slice()) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(Some(AccelerationDerivatives { dq, dv, dtau }))
    }

    /// ∂q̈/∂δ and ∂q̈/∂q̇ alone: what a linearisation without inputs reads,
    /// without forming M⁻¹.
    ///
    /// # Errors
    /// As [`acceleration_derivatives`](Self::acceleration_derivatives).
    pub(crate) fn state_derivatives<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        forced: Option<ForceJacobians<T, N>>,
    ) -> Result<Option<ForceJacobians<T, N>>, Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let found = self.derivatives(t, q, v, forced)?;
        Ok(found.map(|(_, dq, dv)| (dq, dv)))
    }

    /// M's factorisation (the one q̈ takes), M⁻¹ J_q and M⁻¹ J_v.
    #[allow(clippy::type_complexity)]
    fn derivatives<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        forced: Option<ForceJacobians<T, N>>,
    ) -> Result<Option<(Cholesky<T, N>, SMatrix<T, N, N>, SMatrix<T, N, N>)>, Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let (unit, tau) = self.checked(t, q, v)?;
        let (chol, accel) = self.factorised(t, &unit, v, tau)?;
        let Some((mut jq, mut jv)) = self.system().rhs_jacobians(&unit, v, &accel, t) else {
            return Ok(None);
        };
        if let Some((fq, fv)) = forced {
            jq += fq;
            jv += fv;
        }
        let dq = chol.solve_columns(jq);
        let dv = chol.solve_columns(jv);
        if !(all_finite(dq.as_slice()) && all_finite(dv.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(Some((chol, dq, dv)))
    }
}

/// ∂q̈/∂δ, ∂q̈/∂q̇ and ∂q̈/∂τ = M⁻¹ of `sys` at (q, v, t) with the default
/// singular tolerance, or `None` when it does not emit its Jacobians. See
/// [`Dynamics::acceleration_derivatives`].
///
/// # Errors
/// [`Error::NonFiniteState`] or [`Error::SingularMassMatrix`].
pub fn acceleration_derivatives<S, T, const N: usize, const Q: usize>(
    sys: &S,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
    t: T,
) -> Result<Option<AccelerationDerivatives<T, N>>, Error>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    Dynamics::<S, T, NoForcing>::new(sys).acceleration_derivatives(t, q, v, None)
}
