//! The unconstrained dynamics in Hamilton's form, for the symplectic
//! integrators ([`Mechanical`]).

use super::Forcing;
use super::dynamics::{Dynamics, refuse_constrained};
use crate::error::Error;
use crate::error::SettingsError;
use crate::numeric::Real;
use crate::ode::Mechanical;
use crate::system::Lagrangian;
use nalgebra::{SMatrix, SVector};

impl<S, T, F, const N: usize, const Q: usize> Mechanical<T, N, Q> for Dynamics<'_, S, T, F>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
    F: Forcing<T, N, Q>,
{
    fn mass_matrix(&self, t: T, q: &SVector<T, Q>) -> Result<SMatrix<T, N, N>, Error> {
        refuse_constrained::<S, T, N, Q>();
        Ok(self.system().mass_matrix(q, t))
    }

    fn momentum(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        Ok(self.system().momentum(q, v, t))
    }

    fn momentum_rate(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        let sys = self.system();
        let grad = sys.kinetic_gradient(q, v, t).ok_or_else(|| {
            Error::from(SettingsError::Unsupported {
                owner: "the symplectic integrator (Gauss)",
                needs: "Hamilton's form, ∂T/∂q".into(),
                remedy: "this system's Lagrangian::kinetic_gradient returns None: for a \
                         #[derive(Lagrangian)] description add `emit(hamiltonian)`; for a \
                         hand-written system implement Lagrangian::kinetic_gradient (and \
                         Lagrangian::momentum if it is rheonomic); or choose another \
                         integrator"
                    .into(),
            })
        })?;
        let q_total = sys.generalized_forces(q, v, t);
        if F::ACTIVE {
            return Ok(grad + q_total + self.forcing().force(t, q, v)?);
        }
        Ok(grad + q_total)
    }
}
