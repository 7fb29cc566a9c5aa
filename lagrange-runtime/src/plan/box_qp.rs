//! The box-constrained quadratic program of each step of the backward pass,
//!
//! ```text
//! minimise ½ δuᵀ H δu + gᵀ δu   over   lower ≤ δu ≤ upper,
//! ```
//!
//! by projected Newton (Bertsekas 1982), as Tassa, Mansard and Todorov's
//! control-limited DDP (2014) solves it: the inputs at a bound whose gradient
//! pushes outward are clamped, Newton's step is taken on the others with an
//! Armijo line search along the projection. The inverse of H on the free
//! inputs comes back for the feedback gains (zero on the clamped inputs).
//!
//! Everything is on the stack, in P × P matrices (P the inputs, a const
//! generic): the free block is factorised as the leading block of H with
//! the free inputs permuted first. Where H is positive definite and its
//! unconstrained minimiser −H⁻¹g lies in the box (no bound binds, the common
//! case) that minimiser is the answer, with no iteration.

use crate::numeric::cholesky::Cholesky;
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// The minimiser, which inputs are free at it, and the inverse of H on the
/// free ones (`None` when none is free).
pub(super) struct StepSolution {
    pub x: DVector<f64>,
    pub free: Vec<usize>,
    pub inverse: Option<DMatrix<f64>>,
}

/// The problem, on the stack.
struct BoxQp<const P: usize> {
    h: SMatrix<f64, P, P>,
    g: SVector<f64, P>,
    lower: SVector<f64, P>,
    upper: SVector<f64, P>,
}

/// A minimiser, its free inputs and, where at hand, H's factor on them.
type Minimiser<const P: usize> = (SVector<f64, P>, Inputs<P>, Option<Cholesky<f64, P>>);

/// A set of inputs, in increasing order in `index[..len]`.
#[derive(Clone, Copy, PartialEq)]
struct Inputs<const P: usize> {
    index: [usize; P],
    len: usize,
}

impl<const P: usize> Inputs<P> {
    fn all() -> Self {
        Self {
            index: std::array::from_fn(|i| i),
            len: P,
        }
    }

    fn as_slice(&self) -> &[usize] {
        &self.index[..self.len]
    }
}

/// Solves the box QP from `start` (zero if none; clamped into the box);
/// `None` if H is not positive definite on the free inputs (the caller
/// raises the regularisation).
pub(super) fn solve_step<const P: usize>(
    h: &DMatrix<f64>,
    g: &DVector<f64>,
    lower: &DVector<f64>,
    upper: &DVector<f64>,
    start: Option<&DVector<f64>>,
) -> Option<StepSolution> {
    let stacked = |v: &DVector<f64>| SVector::<f64, P>::from_column_slice(v.as_slice());
    let qp = BoxQp::<P> {
        h: SMatrix::from_column_slice(h.as_slice()),
        g: stacked(g),
        lower: stacked(lower),
        upper: stacked(upper),
    };
    let (x, free, chol) = match interior(&qp) {
        Some((x, chol)) => (x, Inputs::all(), Some(chol)),
        None => qp.projected_newton(start.map_or_else(SVector::zeros, stacked))?,
    };
    let inverse = match (free.len, chol) {
        (0, _) => None,
        (n, chol) => {
            // The factor of the last iterate's free set, or of the final one.
            let chol = match chol {
                Some(chol) => chol,
                None => factor(&qp.h, &free)?,
            };
            let inverse = chol.solve_columns(SMatrix::<f64, P, P>::identity());
            Some(DMatrix::from_fn(n, n, |i, j| inverse[(i, j)]))
        }
    };
    Some(StepSolution {
        x: DVector::from_column_slice(x.as_slice()),
        free: free.as_slice().to_vec(),
        inverse,
    })
}

/// −H⁻¹g and H's factor, if H is positive definite and that point lies in
/// the box.
fn interior<const P: usize>(qp: &BoxQp<P>) -> Option<(SVector<f64, P>, Cholesky<f64, P>)> {
    let chol = factor(&qp.h, &Inputs::all())?;
    let x = -chol.solve(qp.g);
    (0..P)
        .all(|i| qp.lower[i] <= x[i] && x[i] <= qp.upper[i])
        .then_some((x, chol))
}

/// The Cholesky factor of H on `free`, as the leading block of H with those
/// rows and columns first; `None` if that block is not positive definite.
fn factor<const P: usize>(h: &SMatrix<f64, P, P>, free: &Inputs<P>) -> Option<Cholesky<f64, P>> {
    let f = free.as_slice();
    let mut block = SMatrix::<f64, P, P>::zeros();
    for (j, &c) in f.iter().enumerate() {
        for (i, &r) in f.iter().enumerate() {
            block[(i, j)] = h[(r, c)];
        }
    }
    Cholesky::leading(block, f.len(), 0.0).ok()
}

impl<const P: usize> BoxQp<P> {
    fn value(&self, x: &SVector<f64, P>) -> f64 {
        0.5 * x.dot(&(self.h * x)) + self.g.dot(x)
    }

    fn clamp(&self, x: &SVector<f64, P>) -> SVector<f64, P> {
        SVector::from_fn(|i, _| x[i].clamp(self.lower[i], self.upper[i]))
    }

    fn gradient(&self, x: &SVector<f64, P>) -> SVector<f64, P> {
        self.g + self.h * x
    }

    /// The inputs not held at a bound by the gradient `grad` at x.
    fn free_at(&self, x: &SVector<f64, P>, grad: &SVector<f64, P>) -> Inputs<P> {
        let mut free = Inputs {
            index: [0; P],
            len: 0,
        };
        for i in 0..P {
            let held =
                x[i] <= self.lower[i] && grad[i] > 0.0 || x[i] >= self.upper[i] && grad[i] < 0.0;
            if !held {
                free.index[free.len] = i;
                free.len += 1;
            }
        }
        free
    }

    /// The minimiser and its free inputs by projected Newton from `start`,
    /// with H's factor on them where the last iterate had it; `None` if H
    /// is not positive definite on a free set met on the way.
    fn projected_newton(&self, start: SVector<f64, P>) -> Option<Minimiser<P>> {
        let mut x = self.clamp(&start);
        // The last iterate's free set and factor, kept while the set stays.
        let mut held: Option<(Inputs<P>, Cholesky<f64, P>)> = None;
        for _ in 0..100 {
            let grad = self.gradient(&x);
            let free = self.free_at(&x, &grad);
            if free.len == 0 {
                return Some((x, free, None));
            }
            let chol = match held.take() {
                Some((last, chol)) if last == free => chol,
                _ => factor(&self.h, &free)?,
            };
            let f = free.as_slice();
            let mut grad_free = SVector::<f64, P>::zeros();
            f.iter()
                .enumerate()
                .for_each(|(i, &j)| grad_free[i] = grad[j]);
            if grad_free.amax() <= 1e-12 * (1.0 + self.g.amax()) {
                return Some((x, free, Some(chol)));
            }
            let newton = chol.solve(grad_free);
            let mut direction = SVector::<f64, P>::zeros();
            f.iter()
                .enumerate()
                .for_each(|(i, &j)| direction[j] = -newton[i]);
            let f0 = self.value(&x);
            let Some((next, f1)) = self.armijo((&x, f0), &grad, &direction) else {
                return Some((x, free, Some(chol)));
            };
            x = next;
            if f0 - f1 <= 1e-14 * (1.0 + f0.abs()) {
                let free_now = self.free_at(&x, &self.gradient(&x));
                let chol = (free_now == free).then_some(chol);
                return Some((x, free_now, chol));
            }
            held = Some((free, chol));
        }
        Some((x, self.free_at(&x, &self.gradient(&x)), None))
    }

    /// The Armijo step along the projection of x + α d, halving α from 1,
    /// with the value there; f0 is the value at x.
    fn armijo(
        &self,
        (x, f0): (&SVector<f64, P>, f64),
        grad: &SVector<f64, P>,
        direction: &SVector<f64, P>,
    ) -> Option<(SVector<f64, P>, f64)> {
        let mut alpha = 1.0;
        while alpha >= 1e-20 {
            let candidate = self.clamp(&(x + direction * alpha));
            let f1 = self.value(&candidate);
            if f1 <= f0 + 0.1 * grad.dot(&(candidate - x)) {
                return Some((candidate, f1));
            }
            alpha *= 0.5;
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vector(x: &[f64]) -> DVector<f64> {
        DVector::from_column_slice(x)
    }

    /// Unbounded: the Newton point −H⁻¹g in one step.
    #[test]
    fn unbounded_is_newtons_point() {
        let h = DMatrix::from_row_slice(2, 2, &[2.0, 0.5, 0.5, 1.0]);
        let g = vector(&[1.0, -1.0]);
        let inf = vector(&[f64::INFINITY; 2]);
        let s = solve_step::<2>(&h, &g, &-&inf, &inf, None).unwrap();
        let expected = -h.clone().lu().solve(&g).unwrap();
        assert!((&s.x - expected).amax() < 1e-14);
        assert_eq!(s.free, vec![0, 1]);
    }

    /// A separable QP: each coordinate is its own 1-D problem, the
    /// unconstrained minimiser −g_i/h_i clamped into its interval.
    #[test]
    fn separable_problems_clamp_coordinatewise() {
        let h = DMatrix::from_diagonal(&vector(&[1.0, 2.0, 4.0]));
        let g = vector(&[-3.0, 1.0, 0.4]);
        let (lo, hi) = (vector(&[-1.0, -1.0, -1.0]), vector(&[1.0, 1.0, 1.0]));
        let s = solve_step::<3>(&h, &g, &lo, &hi, None).unwrap();
        assert!(
            (&s.x - vector(&[1.0, -0.5, -0.1])).amax() < 1e-14,
            "{}",
            s.x
        );
        assert_eq!(s.free, vec![1, 2]);
    }

    /// A coupled QP against its KKT conditions: a clamped input's gradient
    /// points out of the box, a free one's is zero.
    #[test]
    fn coupled_problem_meets_its_optimality_conditions() {
        let h = DMatrix::from_row_slice(3, 3, &[4.0, 1.0, 0.5, 1.0, 3.0, -1.0, 0.5, -1.0, 2.0]);
        let g = vector(&[-8.0, 3.0, -1.0]);
        let (lo, hi) = (vector(&[-0.5, -0.5, -0.5]), vector(&[0.5, 0.5, 0.5]));
        let s = solve_step::<3>(&h, &g, &lo, &hi, None).unwrap();
        assert_optimal((&h, &g), (&lo, &hi), &s.x);
    }

    /// A clamped input's gradient points out of the box, a free one's is
    /// zero.
    fn assert_optimal(
        (h, g): (&DMatrix<f64>, &DVector<f64>),
        (lo, hi): (&DVector<f64>, &DVector<f64>),
        x: &DVector<f64>,
    ) {
        let grad = g + h * x;
        for i in 0..x.len() {
            let ok = match () {
                _ if x[i] >= hi[i] => grad[i] <= 1e-12,
                _ if x[i] <= lo[i] => grad[i] >= -1e-12,
                _ => grad[i].abs() <= 1e-12,
            };
            assert!(ok, "input {i}: x = {}, gradient {}", x[i], grad[i]);
        }
    }

    /// Inside the box the minimiser is −H⁻¹g at once; with a bound binding,
    /// projected Newton's, from a start away from it, meets the optimality
    /// conditions; either way the inverse of H's free block comes back.
    #[test]
    fn the_free_block_s_inverse_comes_back_inside_and_at_the_bounds() {
        let h = DMatrix::from_row_slice(3, 3, &[4.0, 1.0, 0.5, 1.0, 3.0, -1.0, 0.5, -1.0, 2.0]);
        let g = vector(&[-1.0, 0.5, 0.2]);
        // −H⁻¹g = (0.415, −0.448, −0.428): a bound of 0.43 holds input 1 only.
        for bound in [10.0, 0.43] {
            let (lo, hi) = (vector(&[-bound; 3]), vector(&[bound; 3]));
            let start = vector(&[0.3, 0.3, -0.3]);
            let s = solve_step::<3>(&h, &g, &lo, &hi, Some(&start)).unwrap();
            assert_optimal((&h, &g), (&lo, &hi), &s.x);
            let free = &s.free;
            let clamped = 3 - free.len();
            assert_eq!(
                clamped,
                usize::from(bound < 1.0),
                "bound {bound}: free {free:?}"
            );
            let block = DMatrix::from_fn(free.len(), free.len(), |i, j| h[(free[i], free[j])]);
            let inverse = s.inverse.unwrap();
            let identity = DMatrix::identity(free.len(), free.len());
            assert!((block * inverse - identity).amax() < 1e-14, "bound {bound}");
        }
    }

    /// Not convex on the free inputs: refused, so the caller regularises.
    #[test]
    fn an_indefinite_block_is_refused() {
        let h = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, -1.0]);
        let g = vector(&[0.0, 0.1]);
        let inf = vector(&[f64::INFINITY; 2]);
        assert!(solve_step::<2>(&h, &g, &-&inf, &inf, None).is_none());
    }
}
