//! A deterministic random generator, central differences, a relative
//! comparison of matrices, and a run's distance from its linear model.

use lagrange::Trajectory;
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// A deterministic pseudo-random sequence in [−1, 1).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }

    /// A vector of components uniform in [−scale, scale).
    pub fn vector<const D: usize>(&mut self, scale: f64) -> SVector<f64, D> {
        SVector::from_fn(|_, _| scale * self.next())
    }
}

/// Asserts |a − b| ≤ tol · max(1, max |b|) entrywise.
pub fn close<const R: usize, const C: usize>(
    a: &SMatrix<f64, R, C>,
    b: &SMatrix<f64, R, C>,
    tol: f64,
) {
    let scale = b.amax().max(1.0);
    assert!((a - b).amax() <= tol * scale, "{a} vs {b}");
}

/// Central differences of `f` at `x`, one column per component of `x`.
pub fn fd<const R: usize, const C: usize>(
    f: impl Fn(&SVector<f64, C>) -> SVector<f64, R>,
    x: &SVector<f64, C>,
) -> SMatrix<f64, R, C> {
    let h = 1e-6;
    SMatrix::from_fn(|i, j| {
        let mut e = SVector::<f64, C>::zeros();
        e[j] = h;
        (f(&(x + e))[i] - f(&(x - e))[i]) / (2.0 * h)
    })
}

/// The largest distance, at `times`, between the state a run reaches (read
/// by `state` as the linear model's states) and the linear model's
/// exp(A t) x₀: how far a closed loop strays from its linearisation.
pub fn apart_from_linear<const N: usize, const Q: usize>(
    traj: &Trajectory<f64, N, Q>,
    state: impl Fn(&SVector<f64, Q>, &SVector<f64, N>) -> DVector<f64>,
    (a, x0): (&DMatrix<f64>, &DVector<f64>),
    times: &[f64],
) -> f64 {
    times
        .iter()
        .map(|&t| {
            let (q, v) = traj.state_at(t).unwrap();
            (state(&q, &v) - (a * t).exp() * x0).norm()
        })
        .fold(0.0, f64::max)
}
