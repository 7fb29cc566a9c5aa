//! Dense LU with partial pivoting, in place, for the implicit integrators.
//!
//! The iteration matrices of the implicit methods have sizes such as 2sN or 4N
//! that const generics cannot name on stable Rust, so they live in a `DMatrix`
//! allocated once per run. `nalgebra::LU` would allocate its permutation at every
//! factorisation; this one writes the factors over the matrix and the pivots into
//! a slice owned by the caller, so stepping allocates nothing.

// Index loops mirror the block-matrix formulas they implement.
#![allow(clippy::needless_range_loop)]

use crate::numeric::Real;
use crate::numeric::func::abs;
use nalgebra::DMatrix;

/// Factorises the square matrix `a` as P A = L U in place (L unit lower, U upper)
/// and records the row interchanges in `pivots`.
///
/// Returns `Err(column)` if a pivot is exactly zero or not finite (the matrix is
/// singular to working precision, or holds a NaN).
pub(crate) fn lu_factor<T: Real>(a: &mut DMatrix<T>, pivots: &mut [usize]) -> Result<(), usize> {
    let n = a.nrows();
    debug_assert!(a.ncols() == n && pivots.len() == n);
    for k in 0..n {
        let mut p = k;
        let mut best = abs(a[(k, k)]);
        for i in k + 1..n {
            let x = abs(a[(i, k)]);
            if x > best {
                best = x;
                p = i;
            }
        }
        if best == T::zero() || !best.is_finite() {
            return Err(k);
        }
        pivots[k] = p;
        if p != k {
            a.swap_rows(k, p);
        }
        let inv = T::one() / a[(k, k)];
        for i in k + 1..n {
            a[(i, k)] *= inv;
        }
        for j in k + 1..n {
            let akj = a[(k, j)];
            if akj != T::zero() {
                for i in k + 1..n {
                    let lik = a[(i, k)];
                    a[(i, j)] -= lik * akj;
                }
            }
        }
    }
    Ok(())
}

/// Solves A x = b in place (`b` becomes x) with the factors from [`lu_factor`].
pub(crate) fn lu_solve<T: Real>(lu: &DMatrix<T>, pivots: &[usize], b: &mut [T]) {
    let n = lu.nrows();
    for k in 0..n {
        b.swap(k, pivots[k]);
    }
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= lu[(i, k)] * b[k];
        }
        b[i] = s;
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= lu[(i, k)] * b[k];
        }
        b[i] = s / lu[(i, i)];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_with_pivoting_and_reports_singularity() {
        // A zero leading entry needs a row interchange.
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0]);
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| a[(i, j)] * x[j]).sum())
            .collect();
        let mut lu = a.clone();
        let mut piv = [0; 3];
        lu_factor(&mut lu, &mut piv).unwrap();
        lu_solve(&lu, &piv, &mut b);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
        }
        let mut s = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert_eq!(lu_factor(&mut s, &mut [0; 2]), Err(1));
    }
}
