//! Which columns of a stacked regressor are independent of the ones before
//! them: the one rank decision that both the base parameters and the
//! identification make.

use nalgebra::{DMatrix, DVector};

/// A column is a combination of the kept ones before it when less than this
/// fraction of its norm is left once they are projected out. Round-off
/// leaves about 1e-15 of a column that is an exact combination (double
/// precision, projected out twice; at most 3e-13 on the arms shipped with
/// the project), while every genuine column of those arms keeps more than
/// 0.4 of its norm at random states: 1e-9 lies far from both.
pub(super) const RANK_TOLERANCE: f64 = 1e-9;

/// For each column of `w`, whether it is kept: its residual after the kept
/// columns before it are projected out (Gram–Schmidt, twice for
/// orthogonality in floating point) is more than [`RANK_TOLERANCE`] of its
/// norm. A column within [`RANK_TOLERANCE`] of zero, beside the largest, is
/// never kept. Taken left to right, this keeps a
/// body's parameters and drops the later ones that only act through them,
/// which is the classical regrouping (Khalil and Dombre): the mass of link j
/// regrouped into link j − 1's inertia, Iyy into Ixx, and so on.
pub(super) fn independent(w: &DMatrix<f64>) -> Vec<bool> {
    let mut basis: Vec<DVector<f64>> = Vec::new();
    // A column this small beside the largest is round-off of a zero (a
    // constant turn's cos(π/2) = 6e-17 in a URDF's placements), not an
    // effect: its residual would be all noise and large beside it.
    let largest = w.column_iter().map(|c| c.norm()).fold(0.0, f64::max);
    w.column_iter()
        .map(|column| {
            let norm = column.norm();
            if norm <= RANK_TOLERANCE * largest {
                return false;
            }
            let mut r = column.clone_owned();
            for _ in 0..2 {
                for b in &basis {
                    let along = b.dot(&r);
                    r.axpy(-along, b, 1.0);
                }
            }
            let left = r.norm();
            let kept = left > RANK_TOLERANCE * norm;
            if kept {
                basis.push(r / left);
            }
            kept
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combinations_zeros_and_round_off_are_dropped() {
        let a = DVector::from_vec(vec![1.0, 2.0, -1.0, 0.5]);
        let b = DVector::from_vec(vec![0.0, 1.0, 3.0, -2.0]);
        let combination = &a * 2.0 - &b * 0.25;
        // A zero written as round-off: 1e-17 against columns of order 1.
        let noise = DVector::from_vec(vec![1e-17, -2e-17, 0.0, 3e-17]);
        let weak = &a + DVector::from_vec(vec![0.0, 0.0, 1e-6, 0.0]);
        let w = DMatrix::from_columns(&[a, b, combination, DVector::zeros(4), noise, weak]);
        assert_eq!(independent(&w), [true, true, false, false, false, true]);
    }
}
