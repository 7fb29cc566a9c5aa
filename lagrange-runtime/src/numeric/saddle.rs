//! The saddle-point system
//!
//! ```text
//! [ M  Gᵀ ] [ x  ]   [ f ]
//! [ G  0  ] [ −ν ] = [ γ ]
//! ```
//!
//! by the range-space method: with M = L Lᵀ, Y = L⁻¹ Gᵀ and z = L⁻¹ f, the Schur
//! complement S = G M⁻¹ Gᵀ = Yᵀ Y gives S ν = γ − Yᵀ z, then x = L⁻ᵀ (z + Y ν).
//! M is symmetric positive definite for a regular chart, so this only needs two
//! Cholesky factorisations, of sizes N and K; a symmetric indefinite factorisation
//! of the whole (N+K)² matrix would cost more and hide which block is singular.
//!
//! The same solve serves the dynamics (f = Q − h) and the projections (f = 0, where
//! x = M⁻¹ Gᵀ S⁻¹ γ is the M-weighted minimum-norm correction).

use crate::numeric::Real;
use crate::numeric::cholesky::{Cholesky, PivotedCholesky};
use nalgebra::{SMatrix, SVector};

/// How the Schur complement is factorised.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Schur<T> {
    /// Pivot ratio of S below which rows count as dependent.
    pub tolerance: T,
    /// Accept dependent rows and return the minimum-norm multipliers.
    pub least_squares: bool,
}

/// Dependent rows of G: the pivot ratio that stopped the factorisation and the
/// row indices.
#[derive(Clone, Debug)]
pub(crate) struct Dependent<T> {
    pub ratio: T,
    pub rows: Vec<usize>,
}

/// The Schur complement S = G M⁻¹ Gᵀ = Yᵀ Y (Y = L⁻¹ Gᵀ) factorised once, for
/// the first `rows` rows of G: solving then costs two triangular solves with
/// M's factor and one with S's, for each right-hand side.
pub(crate) struct SchurFactor<T, const N: usize, const K: usize> {
    y: SMatrix<T, N, K>,
    factor: PivotedCholesky<T, K>,
    rows: usize,
}

impl<T: Real, const N: usize, const K: usize> SchurFactor<T, N, K> {
    /// Factorises S; [`Dependent`] rows unless `schur` accepts least squares.
    #[inline]
    pub(crate) fn new(
        m: &Cholesky<T, N>,
        g: &SMatrix<T, K, N>,
        rows: usize,
        schur: Schur<T>,
    ) -> Result<Self, Dependent<T>> {
        let mut y = SMatrix::<T, N, K>::zeros();
        for j in 0..rows {
            let mut col = g.row(j).transpose();
            m.solve_lower(&mut col);
            y.set_column(j, &col);
        }
        let factor = PivotedCholesky::new(y.tr_mul(&y), rows, schur.tolerance);
        let this = Self { y, factor, rows };
        if !this.factor.is_full_rank() && !schur.least_squares {
            return Err(this.dependent());
        }
        Ok(this)
    }

    fn dependent(&self) -> Dependent<T> {
        Dependent {
            ratio: self.factor.ratio(),
            rows: self.factor.dependent_rows().to_vec(),
        }
    }

    /// (x, ν) for the right-hand sides f and γ (γ's rows past `rows` ignored,
    /// their multipliers zero); `m` is the factor this was built with.
    #[inline]
    pub(crate) fn solve(
        &self,
        m: &Cholesky<T, N>,
        mut f: SVector<T, N>,
        gamma: &SVector<T, K>,
    ) -> Result<(SVector<T, N>, SVector<T, K>), Dependent<T>> {
        m.solve_lower(&mut f);
        let z = f;
        let mut b = *gamma - self.y.tr_mul(&z);
        for x in b.iter_mut().skip(self.rows) {
            *x = T::zero();
        }
        let nu = self
            .factor
            .solve_min_norm(&b)
            .ok_or_else(|| self.dependent())?;
        let mut x = z + self.y * nu;
        m.solve_upper(&mut x);
        Ok((x, nu))
    }
}

/// Solves the saddle-point system restricted to the first `rows` rows of G (the
/// others, and γ's, are ignored and their multipliers are zero). Returns (x, ν).
#[inline]
pub(crate) fn range_space<T: Real, const N: usize, const K: usize>(
    m: &Cholesky<T, N>,
    g: &SMatrix<T, K, N>,
    rows: usize,
    f: SVector<T, N>,
    gamma: &SVector<T, K>,
    schur: Schur<T>,
) -> Result<(SVector<T, N>, SVector<T, K>), Dependent<T>> {
    SchurFactor::new(m, g, rows, schur)?.solve(m, f, gamma)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix2x3, Matrix3, Vector2, Vector3};

    fn schur(least_squares: bool) -> Schur<f64> {
        Schur {
            tolerance: 1e-12,
            least_squares,
        }
    }

    #[test]
    fn solves_the_kkt_system() {
        let m = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let g = Matrix2x3::new(1.0, 2.0, 0.0, 0.0, 1.0, -1.0);
        let f = Vector3::new(1.0, -1.0, 2.0);
        let gamma = Vector2::new(0.5, -0.25);
        let chol = Cholesky::new(m, 1e-12).unwrap();
        let (x, nu) = range_space(&chol, &g, 2, f, &gamma, schur(false)).unwrap();
        assert!((m * x - f - g.transpose() * nu).amax() < 1e-14);
        assert!((g * x - gamma).amax() < 1e-14);
        // Only the first row: the second multiplier is zero and row 2 is ignored.
        let (x, nu) = range_space(&chol, &g, 1, f, &gamma, schur(false)).unwrap();
        assert_eq!(nu[1], 0.0);
        assert!((m * x - f - g.transpose() * nu).amax() < 1e-14);
        assert!(((g * x)[0] - gamma[0]).abs() < 1e-14);
    }

    #[test]
    fn duplicated_row_is_dependent_unless_least_squares() {
        let m = Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0));
        let g = Matrix2x3::new(1.0, 2.0, 0.0, 1.0, 2.0, 0.0);
        let f = Vector3::new(1.0, -1.0, 2.0);
        let gamma = Vector2::new(0.5, 0.5);
        let chol = Cholesky::new(m, 1e-12).unwrap();
        let e = range_space(&chol, &g, 2, f, &gamma, schur(false)).unwrap_err();
        assert_eq!(e.rows, vec![1]);
        let (x, nu) = range_space(&chol, &g, 2, f, &gamma, schur(true)).unwrap();
        // The single-row solution, its multiplier split evenly.
        let (x1, nu1) = range_space(&chol, &g, 1, f, &gamma, schur(false)).unwrap();
        assert!((x - x1).amax() < 1e-14, "{x} {x1}");
        assert!((nu[0] - 0.5 * nu1[0]).abs() < 1e-14 && (nu[1] - nu[0]).abs() < 1e-14);
    }
}
