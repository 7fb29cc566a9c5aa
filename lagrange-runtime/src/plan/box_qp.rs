//! The box-constrained quadratic program of each step of the backward pass,
//!
//! ```text
//! minimise ½ δuᵀ H δu + gᵀ δu   over   lower ≤ δu ≤ upper,
//! ```
//!
//! by projected Newton (Bertsekas 1982), as Tassa, Mansard and Todorov's
//! control-limited DDP (2014) solves it: the inputs at a bound whose gradient
//! pushes outward are clamped, Newton's step is taken on the others with an
//! Armijo line search along the projection. The free block's Cholesky factor
//! comes back for the feedback gains (zero on the clamped inputs).
//!
//! `solve_step` is what a step of the backward pass calls: where H is
//! positive definite and its unconstrained minimiser −H⁻¹g lies in the box
//! (no bound binds, the common case) that minimiser is the answer, found
//! by a Cholesky factorisation on the stack with no iteration; otherwise
//! projected Newton. Either way the free block's inverse comes back, which
//! the gains K = −H_ff⁻¹ Q_ux read.

use crate::numeric::cholesky::Cholesky as StackCholesky;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn, SMatrix, SVector};

/// The minimiser, which inputs are free at it, and the inverse of H on the
/// free ones (`None` when none is free).
pub(super) struct StepSolution {
    pub x: DVector<f64>,
    pub free: Vec<usize>,
    pub inverse: Option<DMatrix<f64>>,
}

/// The box QP of one step of P inputs (see the module notes), projected
/// Newton starting from `start` (zero if none); `None` if H is not positive
/// definite on the free inputs.
pub(super) fn solve_step<const P: usize>(
    h: &DMatrix<f64>,
    g: &DVector<f64>,
    lower: &DVector<f64>,
    upper: &DVector<f64>,
    start: Option<&DVector<f64>>,
) -> Option<StepSolution> {
    if let Some(interior) = interior::<P>(h, g, lower, upper) {
        return Some(interior);
    }
    let solution = match start {
        Some(start) => solve(h, g, lower, upper, start)?,
        None => solve(h, g, lower, upper, &DVector::zeros(P))?,
    };
    Some(StepSolution {
        inverse: solution.factor.map(|chol| chol.inverse()),
        x: solution.x,
        free: solution.free,
    })
}

/// −H⁻¹g with every input free, if H is positive definite and that point
/// lies in the box.
fn interior<const P: usize>(
    h: &DMatrix<f64>,
    g: &DVector<f64>,
    lower: &DVector<f64>,
    upper: &DVector<f64>,
) -> Option<StepSolution> {
    let chol =
        StackCholesky::new(SMatrix::<f64, P, P>::from_column_slice(h.as_slice()), 0.0).ok()?;
    let x = -chol.solve(SVector::<f64, P>::from_column_slice(g.as_slice()));
    let inside = (0..P).all(|i| lower[i] <= x[i] && x[i] <= upper[i]);
    if !inside {
        return None;
    }
    let inverse = chol.solve_columns(SMatrix::<f64, P, P>::identity());
    Some(StepSolution {
        x: DVector::from_column_slice(x.as_slice()),
        free: (0..P).collect(),
        inverse: Some(DMatrix::from_column_slice(P, P, inverse.as_slice())),
    })
}

/// The minimiser, which inputs are free at it, and the Cholesky factor of H
/// on the free ones (`None` when none is free).
pub(super) struct BoxSolution {
    pub x: DVector<f64>,
    pub free: Vec<usize>,
    pub factor: Option<Cholesky<f64, Dyn>>,
}

/// A free set and the Cholesky factor of H on it.
type FreeFactor = (Vec<usize>, Option<Cholesky<f64, Dyn>>);

/// Solves the box QP from `start` (clamped into the box); `None` if H is not
/// positive definite on the free inputs (the caller raises the
/// regularisation).
pub(super) fn solve(
    h: &DMatrix<f64>,
    g: &DVector<f64>,
    lower: &DVector<f64>,
    upper: &DVector<f64>,
    start: &DVector<f64>,
) -> Option<BoxSolution> {
    let n = g.len();
    let clamp = |x: &DVector<f64>| DVector::from_fn(n, |i, _| x[i].clamp(lower[i], upper[i]));
    let value = |x: &DVector<f64>| 0.5 * x.dot(&(h * x)) + g.dot(x);
    // The last iterate's free set and factor, kept while the set stays.
    let mut held: Option<FreeFactor> = None;
    let mut x = clamp(start);
    for _ in 0..100 {
        let grad = g + h * &x;
        let free = free_at(&grad, lower, upper, &x);
        let factor = match held.take() {
            Some((last, factor)) if last == free => factor,
            _ => factor_free(h, &free)?,
        };
        let Some(chol) = &factor else {
            return Some(BoxSolution { x, free, factor });
        };
        let grad_free = DVector::from_fn(free.len(), |i, _| grad[free[i]]);
        if grad_free.amax() <= 1e-12 * (1.0 + g.amax()) {
            return Some(BoxSolution { x, free, factor });
        }
        let newton = -chol.solve(&grad_free);
        let mut direction = DVector::zeros(n);
        free.iter()
            .enumerate()
            .for_each(|(i, &j)| direction[j] = newton[i]);
        let f0 = value(&x);
        let mut alpha = 1.0;
        let accepted = loop {
            let candidate = clamp(&(&x + &direction * alpha));
            if value(&candidate) <= f0 + 0.1 * grad.dot(&(&candidate - &x)) {
                break Some(candidate);
            }
            alpha *= 0.5;
            if alpha < 1e-20 {
                break None;
            }
        };
        let Some(next) = accepted else {
            return Some(BoxSolution { x, free, factor });
        };
        let improvement = f0 - value(&next);
        x = next;
        if improvement <= 1e-14 * (1.0 + f0.abs()) {
            let free_now = free_at(&(g + h * &x), lower, upper, &x);
            let factor = match free_now == free {
                true => factor,
                false => factor_free(h, &free_now)?,
            };
            return Some(BoxSolution {
                x,
                free: free_now,
                factor,
            });
        }
        held = Some((free, factor));
    }
    let free = free_at(&(g + h * &x), lower, upper, &x);
    let factor = factor_free(h, &free)?;
    Some(BoxSolution { x, free, factor })
}

/// The inputs not held at a bound by the gradient `grad` at x.
fn free_at(
    grad: &DVector<f64>,
    lower: &DVector<f64>,
    upper: &DVector<f64>,
    x: &DVector<f64>,
) -> Vec<usize> {
    (0..grad.len())
        .filter(|&i| !(x[i] <= lower[i] && grad[i] > 0.0 || x[i] >= upper[i] && grad[i] < 0.0))
        .collect()
}

/// The Cholesky factor of H on `free` (`Some(None)` for no free input;
/// `None` if that block is not positive definite).
fn factor_free(h: &DMatrix<f64>, free: &[usize]) -> Option<Option<Cholesky<f64, Dyn>>> {
    if free.is_empty() {
        return Some(None);
    }
    let block = DMatrix::from_fn(free.len(), free.len(), |i, j| h[(free[i], free[j])]);
    block.cholesky().map(Some)
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
        let s = solve(&h, &g, &-&inf, &inf, &vector(&[0.0, 0.0])).unwrap();
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
        let s = solve(&h, &g, &lo, &hi, &vector(&[0.0; 3])).unwrap();
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
        let s = solve(&h, &g, &lo, &hi, &vector(&[0.0; 3])).unwrap();
        let grad = &g + &h * &s.x;
        for i in 0..3 {
            let ok = match () {
                _ if s.x[i] >= hi[i] => grad[i] <= 1e-12,
                _ if s.x[i] <= lo[i] => grad[i] >= -1e-12,
                _ => grad[i].abs() <= 1e-12,
            };
            assert!(ok, "input {i}: x = {}, gradient {}", s.x[i], grad[i]);
        }
    }

    /// A step's QP: inside the box the stack factorisation's minimiser and
    /// inverse; a binding bound goes to projected Newton, whose free block's
    /// inverse comes back; both as `solve` finds them.
    #[test]
    fn a_step_s_qp_is_the_same_inside_and_at_the_bounds() {
        let h = DMatrix::from_row_slice(3, 3, &[4.0, 1.0, 0.5, 1.0, 3.0, -1.0, 0.5, -1.0, 2.0]);
        let g = vector(&[-1.0, 0.5, 0.2]);
        let zero = vector(&[0.0; 3]);
        for bound in [10.0, 0.43] {
            let (lo, hi) = (vector(&[-bound; 3]), vector(&[bound; 3]));
            let step = solve_step::<3>(&h, &g, &lo, &hi, Some(&zero)).unwrap();
            let general = solve(&h, &g, &lo, &hi, &zero).unwrap();
            assert!((&step.x - &general.x).amax() < 1e-14, "bound {bound}");
            assert_eq!(step.free, general.free, "bound {bound}");
            let free = &step.free;
            let clamped = 3 - free.len();
            assert_eq!(
                clamped,
                usize::from(bound < 1.0),
                "bound {bound}: free {free:?}"
            );
            let block = DMatrix::from_fn(free.len(), free.len(), |i, j| h[(free[i], free[j])]);
            let inverse = step.inverse.unwrap();
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
        assert!(solve(&h, &g, &-&inf, &inf, &vector(&[0.0, 0.0])).is_none());
    }
}
