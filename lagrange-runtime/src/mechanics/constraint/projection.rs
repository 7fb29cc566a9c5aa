//! Projection of a state onto the constraint manifold.
//!
//! Positions: Gauss–Newton on Φ(q, t) = 0 with the *M-weighted* minimum-norm step
//! Δq = −M⁻¹ Φ_qᵀ (Φ_q M⁻¹ Φ_qᵀ)⁻¹ Φ, the correction of least kinetic-energy norm.
//! With free orientations Δq is a tangent vector (Φ_q's columns are the tangent
//! space's) and the step is q ⊕ Δq: the quaternion turns by exp of its three
//! entries, so it stays of unit norm.
//! Weighting by M rather than the identity makes the step independent of how the
//! coordinates are scaled (metres against radians), matches the metric the
//! velocity correction needs anyway, and reuses the Cholesky of M and the
//! range-space solve of the dynamics. M is factorised once, at the starting point:
//! a fixed metric keeps Φ_q Δq = −Φ, so convergence stays quadratic in Φ.
//!
//! Velocities: v ← v − M⁻¹ Gᵀ (G M⁻¹ Gᵀ)⁻¹ (G v + g) over all rows, with M at the
//! projected positions: the M-orthogonal projection, which never increases the
//! kinetic energy ½ vᵀ M v. It is linear, so one step lands on G v + g = 0 to
//! round-off.

use super::{ConstrainedDynamics, holonomic, range_space, redundant};
use crate::error::{Error, to_vec};
use crate::mechanics::dynamics::all_finite;
use crate::numeric::Real;
use crate::numeric::orientation;
use crate::system::Constrained;
use nalgebra::SVector;

impl<S, T: Real, const K: usize, F> ConstrainedDynamics<'_, S, T, K, F> {
    /// Projects (q, v) onto Φ = 0 (holonomic rows) and G v + g = 0 (all rows) to
    /// the absolute tolerance `tol`. Returns whether the state changed.
    pub(crate) fn project_state<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &mut SVector<T, Q>,
        v: &mut SVector<T, N>,
        tol: T,
        max_iter: usize,
    ) -> Result<bool, Error>
    where
        S: Constrained<T, N, K, Q>,
    {
        let sys = self.system;
        let h = holonomic::<S, T, N, K, Q>();
        let finite = |q: &SVector<T, Q>, v: &SVector<T, N>, x: &[T]| {
            if all_finite(q.as_slice()) && all_finite(v.as_slice()) && all_finite(x) {
                Ok(())
            } else {
                Err(Error::non_finite(t, q, v))
            }
        };
        let mut phi = sys.constraint_positions(q, t);
        finite(q, v, phi.as_slice())?;
        let mut residual = max_abs(&phi, h);
        let mut changed = false;
        if residual > tol {
            let m = sys.mass_matrix(q, t);
            finite(q, v, m.as_slice())?;
            let chol = self.factor_mass_matrix(t, q, m)?;
            let mut iterations = 0;
            while residual > tol {
                if iterations == max_iter {
                    return Err(Error::ProjectionFailed {
                        t: t.to_f64(),
                        q: to_vec(q),
                        coordinates: S::COORDINATES.to_vec(),
                        residual: residual.to_f64(),
                        iterations,
                        tolerance: tol.to_f64(),
                    });
                }
                let (g, _) = sys.constraint_jacobian(q, t);
                finite(q, v, g.as_slice())?;
                let (dq, _) = range_space(&chol, &g, h, SVector::zeros(), &-phi, self.schur())
                    .map_err(|d| redundant::<S, T, N, K, Q>(t, q, d))?;
                // q ⊕ Δq: Δq is in the tangent space (an orientation's
                // three entries a rotation vector in body axes).
                let before = *q;
                orientation::integrate(
                    S::ORIENTATIONS,
                    before.as_slice(),
                    dq.as_slice(),
                    q.as_mut_slice(),
                );
                iterations += 1;
                phi = sys.constraint_positions(q, t);
                finite(q, v, phi.as_slice())?;
                residual = max_abs(&phi, h);
            }
            changed = true;
        }
        let (g, g0) = sys.constraint_jacobian(q, t);
        let r = g * *v + g0;
        finite(q, v, r.as_slice())?;
        if max_abs(&r, K) > tol {
            let m = sys.mass_matrix(q, t);
            finite(q, v, m.as_slice())?;
            let chol = self.factor_mass_matrix(t, q, m)?;
            let (dv, _) = range_space(&chol, &g, K, SVector::zeros(), &-r, self.schur())
                .map_err(|d| redundant::<S, T, N, K, Q>(t, q, d))?;
            *v += dv;
            finite(q, v, &[])?;
            changed = true;
        }
        Ok(changed)
    }
}

/// max |x_i| over the first `rows` entries (0 for none).
pub(super) fn max_abs<T: Real, const K: usize>(x: &SVector<T, K>, rows: usize) -> T {
    x.iter()
        .take(rows)
        .fold(T::zero(), |m, &xi| m.max(crate::numeric::func::abs(xi)))
}
