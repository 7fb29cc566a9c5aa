//! The dynamics' own factorisations, applied to the dense right-hand sides of a
//! linearisation: the stack Cholesky of M (or M*) and the range-space saddle
//! solve with the pivoted Cholesky of the Schur complement. Using the very
//! factorisations the forward dynamics use means a linearisation calls a mass
//! matrix singular, or constraints redundant, exactly when a run would.

use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::saddle::{Schur, SchurFactor};
use nalgebra::{DMatrix, SMatrix, SVector};

/// A stack vector from a column of a dense f64 matrix.
fn column<T: Real, const R: usize>(m: &DMatrix<f64>, j: usize) -> SVector<T, R> {
    SVector::from_fn(|i, _| T::lit(m[(i, j)]))
}

/// Writes a stack vector into a column of a dense f64 matrix.
fn set_column<T: Real, const R: usize>(m: &mut DMatrix<f64>, j: usize, x: &SVector<T, R>) {
    for i in 0..R {
        m[(i, j)] = x[i].to_f64();
    }
}

/// The Cholesky factor of a mass matrix, with the dynamics' pivot-ratio test.
pub(super) struct MassFactor<T, const N: usize>(Cholesky<T, N>);

impl<T: Real, const N: usize> MassFactor<T, N> {
    /// Factorises `m`; `Err(ratio)` when its pivot ratio is below `tolerance`.
    pub(super) fn new(m: &SMatrix<T, N, N>, tolerance: f64) -> Result<Self, f64> {
        Cholesky::new(*m, T::lit(tolerance))
            .map(Self)
            .map_err(|ratio| ratio.to_f64())
    }

    /// M⁻¹ `rhs`, column by column.
    pub(super) fn solve(&self, rhs: &DMatrix<f64>) -> DMatrix<f64> {
        let mut out = DMatrix::zeros(N, rhs.ncols());
        for j in 0..rhs.ncols() {
            set_column(&mut out, j, &self.0.solve(column::<T, N>(rhs, j)));
        }
        out
    }
}

/// Why a saddle-point system cannot be factorised.
pub(super) enum SaddleError {
    /// M singular: the pivot ratio.
    Mass(f64),
    /// G's rows dependent: the pivot ratio of S = G M⁻¹ Gᵀ and the rows.
    Redundant(f64, Vec<usize>),
}

/// The saddle-point system M x − Gᵀ y = f, G x = r of the multiplier form,
/// factorised as the constrained dynamics factorise it.
pub(super) struct SaddleFactor<T, const N: usize, const K: usize> {
    mass: Cholesky<T, N>,
    schur: SchurFactor<T, N, K>,
}

impl<T: Real, const N: usize, const K: usize> SaddleFactor<T, N, K> {
    /// Factorises M and checks the Schur complement's rank with the same
    /// tolerances as [`ConstrainedDynamics`](crate::ConstrainedDynamics).
    pub(super) fn new(
        m: &SMatrix<T, N, N>,
        g: &SMatrix<T, K, N>,
        singular_tolerance: f64,
        redundant_tolerance: f64,
    ) -> Result<Self, SaddleError> {
        let mass = Cholesky::new(*m, T::lit(singular_tolerance))
            .map_err(|ratio| SaddleError::Mass(ratio.to_f64()))?;
        let schur = Schur {
            tolerance: T::lit(redundant_tolerance),
            least_squares: false,
        };
        let schur = SchurFactor::new(&mass, g, K, schur)
            .map_err(|d| SaddleError::Redundant(d.ratio.to_f64(), d.rows))?;
        Ok(Self { mass, schur })
    }

    /// Solves for the columns of `f` (N rows) and `r` (K rows) at once:
    /// returns x (N rows) and y (K rows).
    pub(super) fn solve(&self, f: &DMatrix<f64>, r: &DMatrix<f64>) -> (DMatrix<f64>, DMatrix<f64>) {
        let mut x = DMatrix::zeros(N, f.ncols());
        let mut y = DMatrix::zeros(K, f.ncols());
        for j in 0..f.ncols() {
            let (fj, rj) = (column::<T, N>(f, j), column::<T, K>(r, j));
            match self.schur.solve(&self.mass, fj, &rj) {
                Ok((xj, yj)) => {
                    set_column(&mut x, j, &xj);
                    set_column(&mut y, j, &yj);
                }
                // The rank was checked in `new`; a NaN right-hand side lands here.
                Err(_) => {
                    x.column_mut(j).fill(f64::NAN);
                    y.column_mut(j).fill(f64::NAN);
                }
            }
        }
        (x, y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix2x3, Matrix3};

    #[test]
    fn saddle_solves_and_detects_dependent_rows() {
        let m = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let g = Matrix2x3::new(1.0, 2.0, 0.0, 0.0, 1.0, -1.0);
        let f = DMatrix::from_column_slice(3, 1, &[1.0, -1.0, 2.0]);
        let r = DMatrix::from_column_slice(2, 1, &[0.5, -0.25]);
        let s = SaddleFactor::new(&m, &g, 1e-12, 1e-12).ok().unwrap();
        let (x, y) = s.solve(&f, &r);
        let (md, gd) = (
            DMatrix::from_fn(3, 3, |i, j| m[(i, j)]),
            DMatrix::from_fn(2, 3, |i, j| g[(i, j)]),
        );
        assert!((&md * &x - gd.transpose() * &y - &f).amax() < 1e-14);
        assert!((&gd * &x - &r).amax() < 1e-14);
        let twice = Matrix2x3::new(1.0, 2.0, 0.0, 1.0, 2.0, 0.0);
        assert!(matches!(
            SaddleFactor::new(&m, &twice, 1e-12, 1e-12),
            Err(SaddleError::Redundant(_, rows)) if rows == vec![1]
        ));
        assert!(matches!(
            SaddleFactor::new(&Matrix3::zeros(), &g, 1e-12, 1e-12),
            Err(SaddleError::Mass(_))
        ));
        let chol = MassFactor::new(&m, 1e-12).ok().unwrap();
        assert!((&md * chol.solve(&f) - &f).amax() < 1e-14);
    }
}
