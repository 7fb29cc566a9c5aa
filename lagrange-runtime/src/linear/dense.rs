//! Dense f64 linear algebra for the linearisation: conversions from the
//! system's stack matrices, rank tests and column pivoting. (Its solves use the
//! dynamics' own factorisations: see `solve`.)

use crate::numeric::Real;
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// A stack matrix in any scalar as a dense f64 matrix.
pub(crate) fn dm<T: Real, const R: usize, const C: usize>(m: &SMatrix<T, R, C>) -> DMatrix<f64> {
    DMatrix::from_fn(R, C, |i, j| m[(i, j)].to_f64())
}

/// A stack vector in any scalar as a dense f64 vector.
pub(crate) fn dv<T: Real, const R: usize>(x: &SVector<T, R>) -> DVector<f64> {
    DVector::from_fn(R, |i, _| x[i].to_f64())
}

pub(crate) fn finite(m: &DMatrix<f64>) -> bool {
    m.iter().all(|x| x.is_finite())
}

/// σ_min / σ_max of a matrix (1 for an empty one), and the right singular vector
/// of σ_min (the direction it nearly annihilates) when the matrix is square or
/// wide, else the left one.
pub(crate) fn condition(m: &DMatrix<f64>) -> (f64, DVector<f64>) {
    if m.is_empty() {
        return (1.0, DVector::zeros(0));
    }
    let svd = m.clone().svd(true, true);
    let s = &svd.singular_values;
    let (imin, smin) = s.argmin();
    let smax = s.max();
    let ratio = if smax > 0.0 { smin / smax } else { 0.0 };
    let vec = if m.ncols() >= m.nrows() {
        svd.v_t.as_ref().map(|vt| vt.row(imin).transpose())
    } else {
        svd.u.as_ref().map(|u| u.column(imin).into_owned())
    };
    (ratio, vec.unwrap_or_else(|| DVector::zeros(m.ncols())))
}

/// Columns chosen by QR with column pivoting (Businger–Golub): `count` times, the
/// column of largest norm after orthogonalising against the columns already
/// chosen (the later column on ties). Returns the chosen column indices in
/// order and the ratio of the last chosen norm to the largest initial one (how
/// far from rank deficient the choice is).
pub(crate) fn pivot_columns(m: &DMatrix<f64>, count: usize) -> (Vec<usize>, f64) {
    let mut cols: Vec<DVector<f64>> = (0..m.ncols()).map(|j| m.column(j).into_owned()).collect();
    let first = cols.iter().map(|c| c.norm()).fold(0.0, f64::max);
    let mut chosen = Vec::with_capacity(count);
    let mut ratio = 1.0;
    for _ in 0..count {
        let mut best: Option<(usize, f64)> = None;
        for (j, c) in cols.iter().enumerate() {
            if chosen.contains(&j) {
                continue;
            }
            let n = c.norm();
            if best.is_none_or(|(_, b)| n >= b) {
                best = Some((j, n));
            }
        }
        let Some((j, n)) = best else { break };
        chosen.push(j);
        ratio = if first > 0.0 { n / first } else { 0.0 };
        if n > 0.0 {
            let e = &cols[j] / n;
            for c in cols.iter_mut() {
                let p = e.dot(c);
                c.axpy(-p, &e, 1.0);
            }
        }
    }
    (chosen, ratio)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pivoting_picks_the_best_conditioned_columns() {
        // Column 2 is largest; after removing its direction, column 0 is left
        // with more than the nearly parallel column 1.
        let m = DMatrix::from_row_slice(2, 3, &[1.0, 0.1, 3.0, 0.0, 0.0, 1.0]);
        let (chosen, ratio) = pivot_columns(&m, 2);
        assert_eq!(chosen[0], 2);
        assert_eq!(chosen[1], 0);
        // Left of column 0: (1, 0) − 0.3 (3, 1) = (0.1, −0.3), against |column 2| = √10.
        assert!((ratio - 0.1).abs() < 1e-15, "{ratio}");
        // Rank one: the second pivot vanishes.
        let r1 = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        let (_, ratio) = pivot_columns(&r1, 2);
        assert!(ratio < 1e-15, "{ratio}");
    }
}
