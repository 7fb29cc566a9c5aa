//! The dynamics' derivatives and curvature for the direct method's Newton
//! steps: for each step k, ∂F_k/∂(x, u) and, with multipliers y =
//! λ_{k+1}, the Hessian of yᵀF_k over (x, u), from one sweep through the
//! step's stages (`Transition::curvature`: the second-order chain rule,
//! each stage's ∇²(μᵀq̈) by forward differences of the emitted
//! ∂q̈/∂(q, v, u)). The differences' error, about √ε of the curvature,
//! touches the Newton steps' last digits only: the gradients that decide
//! the optimum are exact.

use super::passes::Nominal;
use super::problem::{OptimalControl, split};
use crate::error::Error;
use crate::linear::StepDerivatives;
use crate::system::Driven;
use nalgebra::{DMatrix, SVector};

/// Each step's derivatives and ∇²(λ_{k+1}ᵀF_k), 2N + P square, at the
/// nominal; `lambda` holds the rows' multipliers (the start's first).
#[allow(clippy::type_complexity)]
pub(super) fn linearised<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    nominal: &Nominal,
    lambda: &[f64],
) -> Result<(Vec<StepDerivatives<N>>, Vec<DMatrix<f64>>), Error>
where
    S: Driven<f64, N, P>,
{
    let (mut derivatives, mut curvatures) = (Vec::new(), Vec::new());
    for k in 0..problem.steps {
        let (q, v) = split::<N, N>(&nominal.xs[k]);
        let u = SVector::<f64, P>::from_column_slice(nominal.us[k].as_slice());
        let y = &lambda[(k + 1) * 2 * N..][..2 * N];
        let (d, c) = problem
            .transition
            .curvature((&q, &v, &u), problem.time(k), y)?;
        derivatives.push(d);
        curvatures.push(c);
    }
    Ok((derivatives, curvatures))
}
