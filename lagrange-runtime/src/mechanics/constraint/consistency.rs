//! Constraint residuals and consistent initial conditions.
//!
//! An initial state must satisfy Φ(q0, t0) = 0 and G q̇0 + g = 0: the dynamics only
//! impose G q̈ = γ, so an initial violation is never corrected (without drift
//! control) and the motion is that of a different constraint.

use super::projection::max_abs;
use super::{ConstrainedDynamics, holonomic};
use crate::error::{Error, to_vec};
use crate::mechanics::dynamics::all_finite;
use crate::numeric::Real;
use crate::system::Constrained;
use nalgebra::SVector;

impl<S, T: Real, const K: usize, F> ConstrainedDynamics<'_, S, T, K, F> {
    /// The residual vectors: Φ(q, t) on the holonomic rows (zero on the others) and
    /// G v + g on all rows.
    pub fn constraint_residuals<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> (SVector<T, K>, SVector<T, K>)
    where
        S: Constrained<T, N, K, Q>,
    {
        let mut phi = self.system.constraint_positions(q, t);
        for x in phi.iter_mut().skip(holonomic::<S, T, N, K, Q>()) {
            *x = T::zero();
        }
        let (g, g0) = self.system.constraint_jacobian(q, t);
        (phi, g * v + g0)
    }

    /// [max |Φ_i| over the holonomic rows, max |(G v + g)_i|], what trajectories
    /// record.
    pub fn residuals<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> [T; 2]
    where
        S: Constrained<T, N, K, Q>,
    {
        let (phi, vel) = self.constraint_residuals(t, q, v);
        [max_abs(&phi, K), max_abs(&vel, K)]
    }

    /// Checks that (q, v) satisfies the constraints to the absolute tolerance `tol`
    /// at both levels; returns the residuals [max |Φ|, max |G v + g|].
    ///
    /// # Errors
    /// [`Error::InconsistentInitialConditions`] naming the worst constraint;
    /// [`Error::NonFiniteState`] if the state or the residuals are not finite.
    pub fn check_consistency<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        tol: T,
    ) -> Result<[T; 2], Error>
    where
        S: Constrained<T, N, K, Q>,
    {
        if !(t.is_finite() && all_finite(q.as_slice()) && all_finite(v.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        let (phi, vel) = self.constraint_residuals(t, q, v);
        if !(all_finite(phi.as_slice()) && all_finite(vel.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        let res = [max_abs(&phi, K), max_abs(&vel, K)];
        let worst = if res[0] > tol {
            phi.iamax()
        } else if res[1] > tol {
            vel.iamax()
        } else {
            return Ok(res);
        };
        Err(Error::InconsistentInitialConditions {
            t: t.to_f64(),
            q: to_vec(q),
            coordinates: S::COORDINATES.to_vec(),
            position_residual: res[0].to_f64(),
            velocity_residual: res[1].to_f64(),
            tolerance: tol.to_f64(),
            constraint: S::CONSTRAINTS[worst],
        })
    }

    /// The state projected onto the constraints: Gauss–Newton onto Φ = 0, then the
    /// M-weighted velocity correction, to the tolerance and iteration limit of
    /// [`Drift::projection_settings`](super::Drift::projection_settings).
    ///
    /// # Errors
    /// [`Error::ProjectionFailed`] if Gauss–Newton does not converge;
    /// [`Error::SingularMassMatrix`], [`Error::RedundantConstraints`] (without
    /// least squares) or [`Error::NonFiniteState`] as in the dynamics.
    pub fn consistent_state<const N: usize, const Q: usize>(
        &self,
        t: T,
        mut q: SVector<T, Q>,
        mut v: SVector<T, N>,
    ) -> Result<(SVector<T, Q>, SVector<T, N>), Error>
    where
        S: Constrained<T, N, K, Q>,
    {
        if !(t.is_finite() && all_finite(q.as_slice()) && all_finite(v.as_slice())) {
            return Err(Error::non_finite(t, &q, &v));
        }
        let (tol, max_iter) = self.drift.projection_settings();
        self.project_state(t, &mut q, &mut v, T::lit(tol), max_iter)?;
        Ok((q, v))
    }
}

/// Checks the constraints at (q, v, t) to the absolute tolerance `tol`; see
/// [`ConstrainedDynamics::check_consistency`].
///
/// # Errors
/// [`Error::InconsistentInitialConditions`] or [`Error::NonFiniteState`].
pub fn check_consistency<S, T, const N: usize, const K: usize, const Q: usize>(
    sys: &S,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
    t: T,
    tol: T,
) -> Result<[T; 2], Error>
where
    S: Constrained<T, N, K, Q>,
    T: Real,
{
    ConstrainedDynamics::new(sys).check_consistency(t, q, v, tol)
}

/// (q, v) projected onto the constraints with the default settings (tolerance
/// 1e-12, 10 Gauss–Newton iterations, redundant constraints an error); see
/// [`ConstrainedDynamics::consistent_state`] for other settings.
///
/// # Errors
/// As [`ConstrainedDynamics::consistent_state`].
pub fn project_consistent<S, T, const N: usize, const K: usize, const Q: usize>(
    sys: &S,
    q: SVector<T, Q>,
    v: SVector<T, N>,
    t: T,
) -> Result<(SVector<T, Q>, SVector<T, N>), Error>
where
    S: Constrained<T, N, K, Q>,
    T: Real,
{
    ConstrainedDynamics::new(sys).consistent_state(t, q, v)
}
