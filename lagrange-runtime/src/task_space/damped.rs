//! The damped least-squares inverse of a task Jacobian, on the stack for any
//! number of rows and joints.

use nalgebra::SMatrix;

/// How far J⁺ is damped, and where: below a smallest singular value
/// `threshold` the inverse is damped with λ² = `damping`² (1 − (σ_min /
/// `threshold`)²), growing from zero at the threshold to `damping`² at a
/// singularity (Nakamura and Hanafusa's variable damping).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Damping {
    /// Below this smallest singular value of J the inverse is damped.
    pub threshold: f64,
    /// The damping λ at a singularity.
    pub damping: f64,
}

impl Default for Damping {
    /// Damped below σ_min = 0.01, with λ up to 0.05.
    fn default() -> Self {
        Damping {
            threshold: 0.01,
            damping: 0.05,
        }
    }
}

impl Damping {
    /// λ² at smallest singular value `smallest`.
    pub fn lambda2(&self, smallest: f64) -> f64 {
        if smallest < self.threshold {
            self.damping * self.damping * (1.0 - (smallest / self.threshold).powi(2))
        } else {
            0.0
        }
    }
}

/// The damped least-squares inverse of an R × N Jacobian J and its smallest
/// singular value σ_min (the min(R, N)-th largest).
#[derive(Clone, Copy, Debug)]
pub struct DampedInverse<const R: usize, const N: usize> {
    /// J⁺ = V diag(σ / (σ² + λ²)) Uᵀ over the min(R, N) largest singular
    /// values: Jᵀ (J Jᵀ + λ² I)⁻¹ for N ≥ R, (Jᵀ J + λ² I)⁻¹ Jᵀ for N ≤ R.
    pub inverse: SMatrix<f64, N, R>,
    /// σ_min of J.
    pub smallest: f64,
    /// The λ² used (zero where σ_min is at least the threshold).
    pub lambda2: f64,
}

/// The inverse of J where its smallest singular value σ_min is at least
/// `damping.threshold`; below it the damped least-squares inverse
/// Jᵀ (J Jᵀ + λ² I)⁻¹ = V diag(σ / (σ² + λ²)) Uᵀ with λ² from
/// [`Damping::lambda2`]: exact away from singularities, its norm at most
/// 1 / `threshold` near one (for `damping` ≥ `threshold`) and 1 / (2
/// `damping`) at one. For a redundant J (N > R) it is the minimum-norm
/// inverse, for a tall one (N < R) the least-squares inverse. The singular
/// values come from a one-sided Jacobi SVD on the stack (no allocation), to
/// round-off relative to the largest. `None` if J is not finite.
///
/// ```
/// use lagrange_runtime::task_space::{Damping, damped_inverse};
/// use nalgebra::Matrix2;
/// let j = Matrix2::new(2.0, 0.0, 0.0, 1e-9); // nearly singular
/// let d = damped_inverse(&j, &Damping { threshold: 0.01, damping: 0.05 }).unwrap();
/// assert!((d.inverse[(0, 0)] - 0.5).abs() < 1e-3);
/// assert!(d.inverse[(1, 1)].abs() < 1e-6); // not 1e9
/// ```
pub fn damped_inverse<const R: usize, const N: usize>(
    j: &SMatrix<f64, R, N>,
    damping: &Damping,
) -> Option<DampedInverse<R, N>> {
    damped_with(j, |smallest| damping.lambda2(smallest))
}

/// [`damped_inverse`] with λ² a function of σ_min.
pub(super) fn damped_with<const R: usize, const N: usize>(
    j: &SMatrix<f64, R, N>,
    lambda2: impl Fn(f64) -> f64,
) -> Option<DampedInverse<R, N>> {
    if !j.iter().all(|x| x.is_finite()) {
        return None;
    }
    let (w, v) = jacobi(j);
    let mut order: [usize; N] = std::array::from_fn(|i| i);
    let norms: [f64; N] = std::array::from_fn(|i| w.column(i).norm());
    order.sort_by(|&a, &b| norms[b].total_cmp(&norms[a]));
    let rank = R.min(N);
    let smallest = if rank == 0 {
        0.0
    } else {
        norms[order[rank - 1]]
    };
    let lambda2 = lambda2(smallest);
    let mut inverse = SMatrix::<f64, N, R>::zeros();
    for &i in order.iter().take(rank) {
        // v_i (σ_i / (σ_i² + λ²)) u_iᵀ with u_i = w_i / σ_i.
        let denominator = norms[i] * norms[i] + lambda2;
        if denominator > 0.0 {
            inverse += v.column(i) * w.column(i).transpose() / denominator;
        }
    }
    Some(DampedInverse {
        inverse,
        smallest,
        lambda2,
    })
}

/// One-sided Jacobi (Hestenes): plane rotations V of J's columns until they
/// are orthogonal, giving W = J V whose column norms are the singular values
/// (W's columns are σ_i u_i).
fn jacobi<const R: usize, const N: usize>(
    j: &SMatrix<f64, R, N>,
) -> (SMatrix<f64, R, N>, SMatrix<f64, N, N>) {
    let mut w = *j;
    let mut v = SMatrix::<f64, N, N>::identity();
    for _ in 0..60 {
        let mut rotated = false;
        for a in 0..N {
            for b in a + 1..N {
                let alpha = w.column(a).norm_squared();
                let beta = w.column(b).norm_squared();
                let gamma = w.column(a).dot(&w.column(b));
                if gamma == 0.0 || gamma.abs() <= f64::EPSILON * (alpha * beta).sqrt() {
                    continue;
                }
                rotated = true;
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                rotate(&mut w, a, b, c, s);
                rotate(&mut v, a, b, c, s);
            }
        }
        if !rotated {
            break;
        }
    }
    (w, v)
}

/// Columns a and b of m turned by the plane rotation (c, s).
fn rotate<const R: usize, const C: usize>(
    m: &mut SMatrix<f64, R, C>,
    a: usize,
    b: usize,
    c: f64,
    s: f64,
) {
    for r in 0..R {
        let (x, y) = (m[(r, a)], m[(r, b)]);
        m[(r, a)] = c * x - s * y;
        m[(r, b)] = s * x + c * y;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix6, SMatrix};

    /// A fixed pseudo-random matrix.
    fn sample<const R: usize, const N: usize>(seed: u64) -> SMatrix<f64, R, N> {
        let mut next = crate::numeric::samples::uniform(seed);
        SMatrix::from_fn(|_, _| next())
    }

    /// Undamped, the inverse is the Moore–Penrose pseudo-inverse (nalgebra's
    /// SVD), square, wide and tall.
    #[test]
    fn the_undamped_inverse_is_the_pseudo_inverse() {
        let none = Damping {
            threshold: 1e-6,
            damping: 1e-3,
        };
        let square: Matrix6<f64> = sample(1);
        let d = damped_inverse(&square, &none).unwrap();
        assert_eq!(d.lambda2, 0.0);
        let off = (d.inverse - square.try_inverse().unwrap()).amax();
        assert!(off < 1e-11, "square: {off:e}");
        let wide: SMatrix<f64, 6, 7> = sample(2);
        let d = damped_inverse(&wide, &none).unwrap();
        let off = (d.inverse - wide.pseudo_inverse(1e-14).unwrap()).amax();
        assert!(off < 1e-11, "wide: {off:e}");
        let tall: SMatrix<f64, 6, 2> = sample(3);
        let d = damped_inverse(&tall, &none).unwrap();
        let off = (d.inverse - tall.pseudo_inverse(1e-14).unwrap()).amax();
        assert!(off < 1e-12, "tall: {off:e}");
        let smallest = wide.svd(false, false).singular_values.min();
        assert!((d.smallest - tall.svd(false, false).singular_values.min()).abs() < 1e-14);
        let d = damped_inverse(&wide, &none).unwrap();
        assert!((d.smallest - smallest).abs() < 1e-14);
    }

    /// Damped, it is Jᵀ (J Jᵀ + λ² I)⁻¹, computed here by a linear solve.
    #[test]
    fn the_damped_inverse_is_the_regularised_solve() {
        let mut j: SMatrix<f64, 6, 7> = sample(4);
        // Make the last row nearly a copy of the first: σ_min ≈ 1e-8.
        let first = j.row(0).into_owned();
        j.set_row(5, &(first * (1.0 + 1e-8)));
        let damping = Damping {
            threshold: 0.01,
            damping: 0.05,
        };
        let d = damped_inverse(&j, &damping).unwrap();
        assert!(d.smallest < 1e-7 && d.lambda2 > 0.0);
        let gram = j * j.transpose() + Matrix6::identity() * d.lambda2;
        let direct = j.transpose() * gram.try_inverse().unwrap();
        let off = (d.inverse - direct).amax();
        assert!(off < 1e-11, "{off:e}");
        assert!(damped_inverse(&(j * f64::NAN), &damping).is_none());
    }
}
