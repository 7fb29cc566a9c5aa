//! Whether an eigenvalue on the imaginary axis is semisimple, and if not, how
//! fast it grows: the index of λ (the size of its largest Jordan block).
//!
//! A perturbation along a Jordan block of size ν at λ = iω grows like
//! t^(ν−1): a chain of integrators (the double integrator, a quadrotor's
//! position ← velocity ← attitude ← rate at hover) is unstable in Lyapunov's
//! sense though no eigenvalue leaves the axis. The index is read from the
//! dimensions of the nested kernels ker B ⊂ ker B² ⊂ …, B = A − λI, which
//! stop growing at k = ν. Each kernel is found without forming a power of
//! B (whose entries would spread over ‖A‖^k): ker B^(k+1) = ker((I − Z Zᴴ) B)
//! with Z an orthonormal basis of ker B^k, by an SVD whose singular values
//! at most [`RANK_TOLERANCE`] · max(1, ‖A‖₂) count as zero.

use nalgebra::{Complex, DMatrix};

/// The relative size below which a singular value counts as zero when
/// counting kernel dimensions: a computed eigenvalue of a Jordan block of
/// size m is off by about ε^(1/m) ‖A‖ (1.5e-8 for m = 2), which B = A − λI
/// must still see as singular; a coupling smaller than this (relative to
/// ‖A‖) is taken for round-off.
pub const RANK_TOLERANCE: f64 = 1e-7;

/// An orthonormal basis of ker(P B) (P = I − Z Zᴴ, or I when `z` has no
/// column), its columns the right singular vectors of singular value at most
/// `tol`.
fn kernel(b: &DMatrix<Complex<f64>>, z: &DMatrix<Complex<f64>>, tol: f64) -> DMatrix<Complex<f64>> {
    let n = b.nrows();
    let projected = if z.ncols() == 0 {
        b.clone()
    } else {
        b - z * (z.adjoint() * b)
    };
    let svd = projected.svd(false, true);
    let v_t = svd.v_t.expect("asked for");
    let columns: Vec<_> = (0..n)
        .filter(|&i| svd.singular_values[i] <= tol)
        .map(|i| v_t.row(i).adjoint())
        .collect();
    if columns.is_empty() {
        DMatrix::zeros(n, 0)
    } else {
        DMatrix::from_columns(&columns)
    }
}

/// The index of λ in A: 1 if λ is semisimple, ν for a largest Jordan block
/// of size ν; 0 if λ is not an eigenvalue (to the tolerance).
pub(crate) fn index(a: &DMatrix<f64>, lambda: Complex<f64>) -> usize {
    let n = a.nrows();
    let scale = a.map(|x| Complex::new(x, 0.0)).norm().max(1.0);
    let tol = RANK_TOLERANCE * scale;
    let mut b = a.map(|x| Complex::new(x, 0.0));
    for i in 0..n {
        b[(i, i)] -= lambda;
    }
    let mut z = DMatrix::zeros(n, 0);
    for k in 0..=n {
        let next = kernel(&b, &z, tol);
        if next.ncols() == z.ncols() {
            return k;
        }
        z = next;
    }
    n
}

/// The degree of polynomial growth of ẋ = A x along its eigenvalues on the
/// imaginary axis (`on_axis`, one of each conjugate pair suffices; the zero
/// eigenvalue included if A has one): max(ν − 1) over them, 0 when all are
/// semisimple.
pub(crate) fn growth_degree(a: &DMatrix<f64>, on_axis: &[Complex<f64>]) -> usize {
    on_axis
        .iter()
        .map(|&lambda| index(a, lambda).saturating_sub(1))
        .max()
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain(n: usize) -> DMatrix<f64> {
        DMatrix::from_fn(n, n, |i, j| if j == i + 1 { 1.0 } else { 0.0 })
    }

    #[test]
    fn chains_of_integrators_have_their_length_as_index() {
        let zero = Complex::new(0.0, 0.0);
        assert_eq!(index(&chain(2), zero), 2);
        assert_eq!(index(&chain(3), zero), 3);
        assert_eq!(index(&DMatrix::zeros(3, 3), zero), 1);
        // An undamped oscillator: ±iω semisimple; its square a Jordan block.
        let w = 3.0;
        let osc = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, 0.0]);
        assert_eq!(index(&osc, Complex::new(0.0, w)), 1);
        assert_eq!(index(&osc, zero), 0);
        let mut twice = DMatrix::zeros(4, 4);
        twice.view_mut((0, 0), (2, 2)).copy_from(&osc);
        twice.view_mut((2, 2), (2, 2)).copy_from(&osc);
        twice[(0, 2)] = 1.0;
        assert_eq!(index(&twice, Complex::new(0.0, w)), 2);
        // A damped cyclic coordinate: x' = v, v' = −v: the zero is simple.
        let damped = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, -1.0]);
        assert_eq!(index(&damped, zero), 1);
    }
}
