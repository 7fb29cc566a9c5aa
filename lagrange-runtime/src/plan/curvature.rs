//! The dynamics' curvature in the direct method's Lagrangian: for step k
//! with multipliers y = λ_{k+1}, the Hessian of yᵀF_k(x, u) over (x, u),
//! by forward differences of its gradient [∂F/∂x ∂F/∂u]ᵀ y, which the
//! emitted step derivatives give exactly. One step derivative per state
//! and input; the differences' error, about √ε of the curvature, slows
//! the Newton steps' last digits only, since the gradients that decide
//! the optimum are exact.

use super::problem::{OptimalControl, split};
use crate::error::Error;
use crate::system::Driven;
use nalgebra::{DMatrix, DVector, SVector};

/// ∇²(yᵀF_k) at (x, u), symmetric, 2N + P square; `jacobian` is
/// (∂F/∂x, ∂F/∂u) there. Zero when y is.
pub(super) fn curvature<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    k: usize,
    (x, u): (&DVector<f64>, &DVector<f64>),
    y: &[f64],
    jacobian: (&DMatrix<f64>, &DMatrix<f64>),
) -> Result<DMatrix<f64>, Error>
where
    S: Driven<f64, N, P>,
{
    let width = 2 * N + P;
    let mut h = DMatrix::zeros(width, width);
    if y.iter().all(|y| *y == 0.0) {
        return Ok(h);
    }
    let y = DVector::from_column_slice(y);
    let gradient = |(a, b): (&DMatrix<f64>, &DMatrix<f64>)| {
        let mut g = DVector::zeros(width);
        g.rows_mut(0, 2 * N).copy_from(&a.tr_mul(&y));
        g.rows_mut(2 * N, P).copy_from(&b.tr_mul(&y));
        g
    };
    let here = gradient(jacobian);
    let mut z = DVector::zeros(width);
    z.rows_mut(0, 2 * N).copy_from(x);
    z.rows_mut(2 * N, P).copy_from(u);
    for j in 0..width {
        let step = f64::EPSILON.sqrt() * z[j].abs().max(1.0);
        let mut moved = z.clone();
        moved[j] += step;
        let (q, v) = split::<N, N>(&moved.rows(0, 2 * N).into_owned());
        let input = SVector::<f64, P>::from_column_slice(moved.rows(2 * N, P).as_slice());
        let d = problem.transition.derivatives(&q, &v, &input, problem.time(k))?;
        h.set_column(j, &((gradient((&d.dx, &d.du)) - &here) / step));
    }
    Ok((&h + h.transpose()) * 0.5)
}
