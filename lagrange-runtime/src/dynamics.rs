//! Forward dynamics: q̈ = M⁻¹ (Q − h).
//!
//! The mass matrix is factorised by a Cholesky decomposition written out here on
//! the stack rather than through `nalgebra::Cholesky`, for one reason: the pivots
//! L_ii² are needed to tell a *near*-singular mass matrix (a chart singularity such
//! as the pole of a spherical pendulum) from a healthy one. nalgebra only reports
//! outright failure, and a mass matrix with a pivot of 1e-30 would silently give
//! accelerations that are pure round-off.

use crate::error::{Error, to_vec};
use crate::func::sqrt;
use crate::ode::SecondOrder;
use crate::real::Real;
use crate::system::Lagrangian;
use nalgebra::{SMatrix, SVector};

/// Default threshold on min_i L_ii² / max_i L_ii² below which the mass matrix is
/// declared singular.
pub const DEFAULT_SINGULAR_TOLERANCE: f64 = 1e-12;

/// The forward dynamics of a [`Lagrangian`] system, as a right-hand side for the
/// integrators.
///
/// The singularity test compares the squared pivots of the Cholesky factor. It is a
/// cheap lower bound on the conditioning, not the condition number itself, and it is
/// not invariant under rescaling a single coordinate: for coordinates with very
/// different units (metres and radians, say) choose the tolerance accordingly.
#[derive(Debug)]
pub struct Dynamics<'a, S, T> {
    system: &'a S,
    singular_tolerance: T,
}

// Manual impls: derive would demand `S: Clone`, but only a reference is held.
impl<S, T: Copy> Clone for Dynamics<'_, S, T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S, T: Copy> Copy for Dynamics<'_, S, T> {}

impl<'a, S, T: Real> Dynamics<'a, S, T> {
    /// Dynamics of `system` with the default singular tolerance (1e-12).
    pub fn new(system: &'a S) -> Self {
        Self {
            system,
            singular_tolerance: T::lit(DEFAULT_SINGULAR_TOLERANCE),
        }
    }

    /// Sets the threshold on min L_ii² / max L_ii² below which the mass matrix is
    /// reported as singular.
    pub fn with_singular_tolerance(mut self, tolerance: T) -> Self {
        self.singular_tolerance = tolerance;
        self
    }

    /// The system.
    pub fn system(&self) -> &'a S {
        self.system
    }

    /// The singular tolerance in use.
    pub fn singular_tolerance(&self) -> T {
        self.singular_tolerance
    }

    /// The generalized accelerations q̈ at (t, q, v).
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] if the state, M, Q − h or the result is not finite;
    /// [`Error::SingularMassMatrix`] if M is not positive definite or its pivot
    /// ratio is below the singular tolerance.
    pub fn acceleration<const N: usize>(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error>
    where
        S: Lagrangian<T, N>,
    {
        if !(t.is_finite() && all_finite(q.as_slice()) && all_finite(v.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        let (m, rhs) = self.system.mass_matrix_and_rhs(q, v, t);
        if !(all_finite(m.as_slice()) && all_finite(rhs.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        let a = cholesky_solve(m, rhs, self.singular_tolerance).map_err(|ratio| {
            Error::SingularMassMatrix {
                t: t.to_f64(),
                q: to_vec(q),
                ratio: ratio.to_f64(),
            }
        })?;
        // Finite M and rhs with acceptable pivots can still overflow.
        if !all_finite(a.as_slice()) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(a)
    }
}

impl<S, T, const N: usize> SecondOrder<T, N> for Dynamics<'_, S, T>
where
    S: Lagrangian<T, N>,
    T: Real,
{
    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        Dynamics::acceleration(self, t, q, v)
    }

    fn integral(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> T {
        self.system.integral(q, v, t)
    }

    fn mechanical(&self) -> Option<&dyn crate::ode::Mechanical<T, N>> {
        Some(self)
    }
}

/// The generalized accelerations of `sys` at (q, v, t) with the default singular
/// tolerance. See [`Dynamics::acceleration`].
///
/// # Errors
/// [`Error::NonFiniteState`] or [`Error::SingularMassMatrix`].
pub fn accelerations<S: Lagrangian<T, N>, T: Real, const N: usize>(
    sys: &S,
    q: &SVector<T, N>,
    v: &SVector<T, N>,
    t: T,
) -> Result<SVector<T, N>, Error> {
    Dynamics::new(sys).acceleration(t, q, v)
}

fn all_finite<T: Real>(xs: &[T]) -> bool {
    xs.iter().all(|x| x.is_finite())
}

/// Solves M x = b for symmetric positive definite M by Cholesky, M = L Lᵀ.
///
/// Only the lower triangle of `m` is read. On failure returns the pivot ratio
/// min L_ii² / max L_ii² (or the offending non-positive pivot divided by the largest
/// diagonal entry seen so far) so that the error can say how singular M was.
fn cholesky_solve<T: Real, const N: usize>(
    mut m: SMatrix<T, N, N>,
    mut b: SVector<T, N>,
    tolerance: T,
) -> Result<SVector<T, N>, T> {
    if N == 0 {
        return Ok(b);
    }
    let mut min_pivot = T::max_value().unwrap_or(T::one() / T::default_epsilon());
    let mut max_pivot = T::zero();
    let mut max_diag = T::zero();
    // Left-looking factorisation in place in the lower triangle of `m`.
    for j in 0..N {
        let mut d = m[(j, j)];
        max_diag = max_diag.max(d);
        for k in 0..j {
            d -= m[(j, k)] * m[(j, k)];
        }
        if d <= T::zero() {
            let denom = max_pivot.max(max_diag);
            return Err(if denom > T::zero() {
                d / denom
            } else {
                T::zero()
            });
        }
        min_pivot = min_pivot.min(d);
        max_pivot = max_pivot.max(d);
        let ljj = sqrt(d);
        m[(j, j)] = ljj;
        for i in j + 1..N {
            let mut s = m[(i, j)];
            for k in 0..j {
                s -= m[(i, k)] * m[(j, k)];
            }
            m[(i, j)] = s / ljj;
        }
    }
    let ratio = min_pivot / max_pivot;
    if ratio < tolerance {
        return Err(ratio);
    }
    // Forward substitution L y = b, then back substitution Lᵀ x = y, in place.
    for i in 0..N {
        let mut s = b[i];
        for k in 0..i {
            s -= m[(i, k)] * b[k];
        }
        b[i] = s / m[(i, i)];
    }
    for i in (0..N).rev() {
        let mut s = b[i];
        for k in i + 1..N {
            s -= m[(k, i)] * b[k];
        }
        b[i] = s / m[(i, i)];
    }
    Ok(b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector3};

    #[test]
    fn cholesky_solves_spd_system() {
        let a = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let x = Vector3::new(1.0, -2.0, 0.5);
        let b = a * x;
        let got = cholesky_solve(a, b, 1e-12).unwrap();
        assert!((got - x).norm() < 1e-14, "{got}");
    }

    #[test]
    fn cholesky_reports_pivot_ratio() {
        let s = 1e-8_f64; // sin θ near the pole
        let m = nalgebra::Matrix2::new(1.0, 0.0, 0.0, s * s);
        let ratio = cholesky_solve(m, nalgebra::Vector2::new(1.0, 0.0), 1e-12).unwrap_err();
        assert!((ratio - 1e-16).abs() < 1e-30);
        // A tolerance below the ratio accepts the same matrix.
        assert!(cholesky_solve(m, nalgebra::Vector2::new(1.0, 0.0), 1e-20).is_ok());
        // Indefinite: the second pivot is negative.
        let m = nalgebra::Matrix2::new(1.0, 2.0, 2.0, 1.0);
        let ratio = cholesky_solve(m, nalgebra::Vector2::new(1.0, 0.0), 1e-12).unwrap_err();
        assert!(ratio < 0.0);
    }
}
