//! M⁻¹ of a whole small symmetric positive definite matrix, with its pivots'
//! ratio, and products of small fixed-size matrices: what the factored
//! derivatives (`mechanics::derivatives::factored_derivatives`) run, where
//! [`Cholesky`](super::cholesky::Cholesky) serves leading blocks and solves.

use crate::numeric::Real;
use crate::numeric::func::{mul_add, pivot_ratio};
use nalgebra::SMatrix;

/// M⁻¹ of a symmetric M (its lower triangle read) by M = L D Lᵀ, L unit
/// lower triangular, with the pivots' ratio min d / max d beside it
/// ([`pivot_ratio`]: −1 where a pivot is not finite). Where the ratio is not
/// positive, M is not positive definite and the inverse is NaN throughout.
///
/// Written for speed on a whole small matrix, where `Cholesky` serves
/// leading blocks and many right-hand sides: no square roots, one division
/// per pivot, and every step a scaled column added to another over all N
/// rows (whole vector registers, no index checked, nothing summed across a
/// register). L⁻¹ is formed by rows, so that M⁻¹ = L⁻ᵀ D⁻¹ L⁻¹ is again a sum
/// of scaled rows; its lower triangle is mirrored, so it is symmetric to the
/// bit.
pub(crate) fn spd_inverse<T: Real, const N: usize>(m: &SMatrix<T, N, N>) -> (SMatrix<T, N, N>, T) {
    let (l, d) = ldl(&m.data.0);
    let ratio = pivot_ratio(&d);
    if ratio <= T::zero() {
        let nan = T::zero() / T::zero();
        return (SMatrix::from_element(nan), ratio);
    }
    let recip = d.map(|d| T::one() / d);
    // Row i of L⁻¹: e_iᵀ − Σ_{k<i} L_ik (row k of L⁻¹).
    let mut rows = [[T::zero(); N]; N];
    for i in 0..N {
        let mut row = [T::zero(); N];
        row[i] = T::one();
        for k in 0..i {
            axpy(&mut row, -l[k][i], &rows[k]);
        }
        rows[i] = row;
    }
    // Column j of M⁻¹: Σ_k (row k of L⁻¹)ᵀ (L⁻¹)_kj / d_k, from k = j on
    // (L⁻¹ is lower triangular).
    let mut inverse = [[T::zero(); N]; N];
    for (j, column) in inverse.iter_mut().enumerate() {
        for k in j..N {
            axpy(column, rows[k][j] * recip[k], &rows[k]);
        }
    }
    let mut inverse = SMatrix::from_data(nalgebra::ArrayStorage(inverse));
    inverse.fill_upper_triangle_with_lower_triangle();
    (inverse, ratio)
}

/// L (unit lower, by columns: what lies on and above the diagonal is left
/// over and never read) and D of A = L D Lᵀ, from A's columns;
/// right-looking: each pivot's column, once scaled, is taken from the
/// columns after it at once, so that the next pivot waits for one division
/// and two products, not for a sum over every column before it. Every step
/// runs over whole columns (rows that are never read again included): a
/// partial column is written with masked stores, which the next load cannot
/// take over, and ran 1.7× slower.
fn ldl<T: Real, const N: usize>(a: &[[T; N]; N]) -> ([[T; N]; N], [T; N]) {
    let mut a = *a;
    let mut l = [[T::zero(); N]; N];
    let mut d = [T::zero(); N];
    for j in 0..N {
        d[j] = a[j][j];
        let recip = T::one() / d[j];
        l[j] = a[j].map(|x| x * recip);
        // Column i ← column i − L_j (d_j L_ij), with d_j L_ij = A_ij.
        let (done, rest) = a.split_at_mut(j + 1);
        for (offset, column) in rest.iter_mut().enumerate() {
            axpy(column, -done[j][j + 1 + offset], &l[j]);
        }
    }
    (l, d)
}

/// y ← y + a x over whole arrays, four entries to a step (a vector
/// register's worth; `factored_derivatives` ran some 13 % faster so than
/// with one loop over all N).
#[inline(always)]
fn axpy<T: Real, const N: usize>(y: &mut [T; N], a: T, x: &[T; N]) {
    let (ys, y_rest) = y.as_chunks_mut::<4>();
    let (xs, x_rest) = x.as_chunks::<4>();
    for (y, x) in ys.iter_mut().zip(xs) {
        for i in 0..4 {
            y[i] = mul_add(a, x[i], y[i]);
        }
    }
    for (y, &x) in y_rest.iter_mut().zip(x_rest) {
        *y = mul_add(a, x, *y);
    }
}

/// A B for B's C columns: each column of the product a sum of A's columns
/// scaled by B's entries, held in registers across them (see
/// [`spd_inverse`]).
pub(crate) fn product<T: Real, const N: usize, const C: usize>(
    a: &SMatrix<T, N, N>,
    b: &SMatrix<T, N, C>,
) -> SMatrix<T, N, C> {
    let mut out = [[T::zero(); N]; C];
    for (column, b) in out.iter_mut().zip(&b.data.0) {
        let mut sum = [T::zero(); N];
        for (a, &b) in a.data.0.iter().zip(b) {
            axpy(&mut sum, b, a);
        }
        *column = sum;
    }
    SMatrix::from_data(nalgebra::ArrayStorage(out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, SVector};

    /// M⁻¹ by L D Lᵀ is M's inverse, symmetric to the bit, on a 3 × 3 and
    /// on an 8 × 8 whose pivots spread over more than three decades; the
    /// pivot ratio is the smallest d over the largest (the 3 × 3's by hand);
    /// a matrix that is not positive definite gives a ratio ≤ 0 and NaN, a
    /// NaN one −1 and NaN.
    #[test]
    fn spd_inverse_and_its_pivot_ratio() {
        let a: Matrix3<f64> = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let (inv, ratio) = spd_inverse(&a);
        assert!((inv * a - Matrix3::identity()).amax() < 1e-15, "{inv}");
        assert_eq!(inv, inv.transpose());
        // The pivots of this M: 4, 3 − 1/4 and what is left of 2.
        let d2: f64 = 3.0 - 0.25;
        let d3: f64 = 2.0 - 0.0625 - (0.2_f64 - 0.125).powi(2) / d2;
        assert!(
            (ratio - d3.min(d2) / 4.0).abs() < 1e-15 && ratio < 1.0,
            "{ratio}"
        );

        let g = SMatrix::<f64, 8, 8>::from_fn(|i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0);
        let scale = SMatrix::<f64, 8, 8>::from_diagonal(&SVector::from_fn(|i, _| {
            10f64.powi(-(i as i32) / 2)
        }));
        let m = scale * (g.transpose() * g + SMatrix::identity()) * scale;
        let (inv, ratio) = spd_inverse(&m);
        let exact = m.try_inverse().unwrap();
        assert!(
            (inv - exact).amax() < 1e-9 * exact.amax(),
            "{}",
            (inv - exact).amax()
        );
        assert_eq!(inv, inv.transpose());
        assert!(ratio > 0.0 && ratio < 1e-3, "{ratio}");

        let indefinite: Matrix3<f64> = Matrix3::new(1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0);
        let (inv, ratio) = spd_inverse(&indefinite);
        assert!(ratio <= 0.0 && inv.iter().all(|x| x.is_nan()), "{ratio}");
        let (inv, ratio) = spd_inverse(&(a * f64::NAN));
        assert!(ratio == -1.0 && inv.iter().all(|x| x.is_nan()));
    }

    /// A B column by column equals nalgebra's product to round-off.
    #[test]
    fn product_by_scaled_columns() {
        let a = SMatrix::<f64, 5, 5>::from_fn(|i, j| (i as f64 - 1.3 * j as f64).sin());
        let b = SMatrix::<f64, 5, 3>::from_fn(|i, j| (0.7 * i as f64 + j as f64).cos());
        assert!((product(&a, &b) - a * b).amax() < 1e-15);
    }
}
