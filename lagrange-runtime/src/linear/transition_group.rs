//! A step on the rotation group and its chain rule in the tangent space.
//!
//! With free orientations the step is Runge–Kutta–Munthe-Kaas: the
//! configuration is written in the chart at the step's start,
//! q = q₀ ⊕ ξ, and RK4 (or semi-implicit Euler) integrates the chart's
//! coordinates ξ (from 0) with the velocities. An ordinary coordinate's
//! ξ̇ is its velocity; an orientation's is J_r(ξ)⁻¹ ω, taken as its
//! series to second order, ω + ½ ξ × ω + 1/12 ξ × (ξ × ω) (the next term
//! is of fourth order, so RK4 keeps its order: Munthe-Kaas 1999). Without
//! orientations ξ = q − q₀ and the step is plain RK4, number for number.
//! The end is q₀ ⊕ ξ⁺: the quaternions stay unit without a projection.
//!
//! The derivatives are in the tangent space: a start moved to
//! (q₀ ⊕ δ, v₀ + δv) moves a stage at q₀ ⊕ ξ by
//!
//! ```text
//! η = R(ξ)ᵀ δ + J_r(ξ) dξ        (an orientation's block; δ + dξ otherwise)
//! ```
//!
//! in that stage's own tangent space, since exp(−ξ) exp(δ) exp(ξ + dξ) =
//! exp(R(ξ)ᵀ δ + J_r(ξ) dξ) to first order. The stage's q̈ changes by
//! A_q η + A_v dv + A_u du, its ξ̇ by (∂ξ̇/∂ξ) dξ + (∂ξ̇/∂ω) dv, and the
//! end's δ⁺ is the same map at ξ⁺.

use super::chain::{Rows, acceleration_rows, assemble};
use crate::mechanics::InputDerivatives;
use crate::numeric::orientation::{Orientation, exp, right_jacobian, rotation_matrix};
use nalgebra::{DMatrix, Matrix3, SMatrix, SVector, Vector3};

/// ξ̇ at (ξ, v) in the chart at the step's start: an ordinary coordinate's
/// velocity, an orientation's J_r(ξ)⁻¹ ω to second order in ξ.
pub(super) fn chart_rates<const N: usize>(
    layout: &[Orientation],
    xi: &SVector<f64, N>,
    v: &SVector<f64, N>,
) -> SVector<f64, N> {
    let mut rate = *v;
    for o in layout {
        let (x, w) = (block(xi, o), block(v, o));
        let r = w + x.cross(&w) * 0.5 + x.cross(&x.cross(&w)) / 12.0;
        rate.fixed_rows_mut::<3>(o.v).copy_from(&r);
    }
    rate
}

fn block<const N: usize>(x: &SVector<f64, N>, o: &Orientation) -> Vector3<f64> {
    x.fixed_rows::<3>(o.v).into_owned()
}

fn hat(x: &Vector3<f64>) -> Matrix3<f64> {
    x.cross_matrix()
}

/// The chart's linear maps at a stage (ξ, v), N × N, identity (or zero) on
/// the ordinary coordinates' rows.
pub(super) struct Chart<const N: usize> {
    /// R(ξ)ᵀ: a start's δ seen in the stage's tangent space.
    turn: SMatrix<f64, N, N>,
    /// J_r(ξ): a change of ξ in the stage's tangent space.
    jacobian: SMatrix<f64, N, N>,
    /// ∂ξ̇/∂ξ.
    by_xi: SMatrix<f64, N, N>,
    /// ∂ξ̇/∂v.
    by_v: SMatrix<f64, N, N>,
}

impl<const N: usize> Chart<N> {
    /// The maps at (ξ, v).
    pub(super) fn at(layout: &[Orientation], xi: &SVector<f64, N>, v: &SVector<f64, N>) -> Self {
        let mut chart = Self {
            turn: SMatrix::identity(),
            jacobian: SMatrix::identity(),
            by_xi: SMatrix::zeros(),
            by_v: SMatrix::identity(),
        };
        for o in layout {
            let (x, w) = (block(xi, o), block(v, o));
            let (r, jr) = (rotation_matrix(exp(x.into())), right_jacobian(x.into()));
            let (r, jr) = (
                Matrix3::from_fn(|i, j| r[j][i]),
                Matrix3::from_fn(|i, j| jr[i][j]),
            );
            let by_v = Matrix3::identity() + hat(&x) * 0.5 + hat(&x) * hat(&x) / 12.0;
            // ∂(½ ξ × ω + 1/12 ξ × (ξ × ω))/∂ξ, with ξ × (ξ × ω) = ξ (ξ·ω) − ω |ξ|².
            let second =
                Matrix3::identity() * x.dot(&w) + x * w.transpose() - w * x.transpose() * 2.0;
            let by_xi = -hat(&w) * 0.5 + second / 12.0;
            let at = (o.v, o.v);
            chart.turn.fixed_view_mut::<3, 3>(at.0, at.1).copy_from(&r);
            chart
                .jacobian
                .fixed_view_mut::<3, 3>(at.0, at.1)
                .copy_from(&jr);
            chart
                .by_v
                .fixed_view_mut::<3, 3>(at.0, at.1)
                .copy_from(&by_v);
            chart
                .by_xi
                .fixed_view_mut::<3, 3>(at.0, at.1)
                .copy_from(&by_xi);
        }
        chart
    }

    /// The stage's tangent change η = R(ξ)ᵀ δ + J_r(ξ) dξ, rows over
    /// (δ, δv, du).
    fn tangent<const P: usize>(&self, start: &Rows<N, P>, d_xi: &Rows<N, P>) -> Rows<N, P> {
        Rows {
            q: self.turn * start.q + self.jacobian * d_xi.q,
            v: self.turn * start.v + self.jacobian * d_xi.v,
            u: self.turn * start.u + self.jacobian * d_xi.u,
        }
    }

    /// d(ξ̇) = (∂ξ̇/∂ξ) dξ + (∂ξ̇/∂v) dv.
    fn rates<const P: usize>(&self, d_xi: &Rows<N, P>, d_v: &Rows<N, P>) -> Rows<N, P> {
        Rows {
            q: self.by_xi * d_xi.q + self.by_v * d_v.q,
            v: self.by_xi * d_xi.v + self.by_v * d_v.v,
            u: self.by_xi * d_xi.u + self.by_v * d_v.u,
        }
    }
}

/// RK4 in the chart: stage i at ξ = c_i h k^ξ_{i−1}, v = v₀ + c_i h k^v_{i−1};
/// ξ⁺ = h/6 Σ w_i k^ξ_i, v⁺ = v₀ + h/6 Σ w_i k^v_i; δ⁺ through the chart at
/// ξ⁺ (`end`).
pub(super) fn rk4<const N: usize, const P: usize>(
    stages: &[(InputDerivatives<f64, N, P>, Chart<N>); 4],
    end: &Chart<N>,
    nodes: [f64; 4],
    weights: [f64; 4],
    h: f64,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let (x_q, x_v, zero) = (Rows::identity(true), Rows::identity(false), Rows::zero());
    let (mut sum_xi, mut sum_v) = (zero, x_v);
    let mut previous: Option<(Rows<N, P>, Rows<N, P>)> = None;
    for (((d, chart), c), w) in stages.iter().zip(nodes).zip(weights) {
        let (d_xi, d_v) = match &previous {
            None => (zero, x_v),
            Some((k_xi, k_v)) => (zero.plus(c * h, k_xi), x_v.plus(c * h, k_v)),
        };
        let eta = chart.tangent(&x_q, &d_xi);
        let k = (chart.rates(&d_xi, &d_v), acceleration_rows(d, &eta, &d_v));
        sum_xi = sum_xi.plus(w * h / 6.0, &k.0);
        sum_v = sum_v.plus(w * h / 6.0, &k.1);
        previous = Some(k);
    }
    assemble(&end.tangent(&x_q, &sum_xi), &sum_v)
}

/// Semi-implicit Euler on the group: v⁺ = v + h q̈, q⁺ = q ⊕ h v⁺ (an
/// orientation turned at the constant ω⁺ for h); δ⁺ through the chart at
/// ξ⁺ = h v⁺.
pub(super) fn semi_implicit<const N: usize, const P: usize>(
    d: &InputDerivatives<f64, N, P>,
    end: &Chart<N>,
    h: f64,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let (x_q, x_v, zero) = (Rows::identity(true), Rows::identity(false), Rows::zero());
    let dv = x_v.plus(h, &acceleration_rows(d, &x_q, &x_v));
    let d_xi = zero.plus(h, &dv);
    assemble(&end.tangent(&x_q, &d_xi), &dv)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∂ξ̇/∂ξ and ∂ξ̇/∂v against central differences of `chart_rates`.
    #[test]
    fn the_chart_maps_are_the_rates_derivatives() {
        const LAYOUT: [Orientation; 1] = [Orientation { q: 1, v: 1 }];
        let xi = SVector::<f64, 4>::from([0.3, 0.2, -0.4, 0.1]);
        let v = SVector::<f64, 4>::from([1.0, -0.7, 1.3, 0.5]);
        let chart = Chart::at(&LAYOUT, &xi, &v);
        let eps = 1e-6;
        for j in 0..4 {
            let e = SVector::<f64, 4>::from_fn(|i, _| if i == j { eps } else { 0.0 });
            let by_xi = (chart_rates(&LAYOUT, &(xi + e), &v) - chart_rates(&LAYOUT, &(xi - e), &v))
                / (2.0 * eps);
            let by_v = (chart_rates(&LAYOUT, &xi, &(v + e)) - chart_rates(&LAYOUT, &xi, &(v - e)))
                / (2.0 * eps);
            assert!((by_xi - chart.by_xi.column(j)).amax() < 1e-9, "ξ {j}");
            assert!((by_v - chart.by_v.column(j)).amax() < 1e-9, "v {j}");
        }
    }
}
