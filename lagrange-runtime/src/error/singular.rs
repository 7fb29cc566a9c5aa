//! What a singular mass matrix has no inertia along, in the coordinates'
//! names: the report of [`Error::SingularMassMatrix`].

use super::{Error, to_vec};
use crate::numeric::Real;
use nalgebra::{DMatrix, SMatrix, SVector};

/// The direction of least inertia of M (the eigenvector of its smallest
/// eigenvalue), its components of at least a tenth of the largest, named by
/// `names` (v's: M's rows): "0.707 psi + 0.707 phi". Empty for a
/// non-finite M or names that do not fit.
pub(crate) fn null_direction<T: Real, const N: usize>(
    m: &SMatrix<T, N, N>,
    names: &[&str],
) -> String {
    if names.len() != N || N == 0 || m.iter().any(|x| !x.is_finite()) {
        return String::new();
    }
    let m = DMatrix::from_fn(N, N, |i, j| 0.5 * (m[(i, j)] + m[(j, i)]).to_f64());
    let eigen = m.symmetric_eigen();
    let smallest = eigen.eigenvalues.imin();
    let x = eigen.eigenvectors.column(smallest);
    let big = x.amax();
    let named: Vec<usize> = (0..N).filter(|&i| x[i].abs() >= 0.1 * big).collect();
    // The sign that makes the first named component positive, so the report
    // is the same whichever sign the eigen-solver returns.
    let sign = if x[named[0]] < 0.0 { -1.0 } else { 1.0 };
    let parts: Vec<String> = (named.iter())
        .map(|&i| format!("{:.3} {}", sign * x[i], names[i]))
        .collect();
    parts.join(" + ").replace("+ -", "- ")
}

impl Error {
    /// [`Error::SingularMassMatrix`] at (t, q) with the pivot ratio and the
    /// direction M has no inertia along, named by `names` (v's); `atlas`:
    /// the system has `emit(atlas)`.
    pub(crate) fn singular_mass<T: Real, const N: usize, const Q: usize>(
        t: T,
        q: &SVector<T, Q>,
        ratio: T,
        m: &SMatrix<T, N, N>,
        (names, atlas): (&[&str], bool),
    ) -> Self {
        Error::SingularMassMatrix {
            t: t.to_f64(),
            q: to_vec(q),
            ratio: ratio.to_f64(),
            direction: null_direction(m, names),
            atlas,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    #[test]
    fn the_direction_of_no_inertia_is_named() {
        // The z-x-z top at θ = 0: ψ and φ turn about the same axis.
        let m = Matrix3::new(0.5, 0.0, 0.5, 0.0, 0.8, 0.0, 0.5, 0.0, 0.5);
        let d = null_direction(&m, &["psi", "theta", "phi"]);
        assert_eq!(d, "0.707 psi - 0.707 phi");
        // A massless coordinate.
        let m = Matrix3::from_diagonal(&nalgebra::Vector3::new(1.0, 0.0, 2.0));
        assert_eq!(null_direction(&m, &["x", "y", "z"]), "1.000 y");
    }
}
