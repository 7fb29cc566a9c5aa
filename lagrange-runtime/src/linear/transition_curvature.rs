//! The curvature of one step in the plane: for multipliers y on x⁺, the
//! Hessian of yᵀF(x, u) over (x, u), which the direct method's Newton
//! steps need (the Lagrangian's −Σ λᵀ∇²F).
//!
//! All of a step's nonlinearity is in q̈ at its stages: each stage point
//! p_s = (q_s, v_s) is affine in the previous stage's rates, so by the
//! second-order chain rule
//!
//! ```text
//! ∇²(yᵀF) = Σ_s W_sᵀ ∇²(μ_sᵀ q̈)(p_s, u) W_s,     W_s = ∂(p_s, u)/∂(x, u),
//! ```
//!
//! μ_s the adjoint of stage s's acceleration (a reverse sweep from y) and
//! W_s its tangent (a forward sweep, as `chain::rk4`'s). Each stage's
//! ∇²(μᵀq̈) is the forward difference of the exact ∂q̈/∂(q, v, u)ᵀ μ, one
//! column per coordinate, velocity and input, skipping the cyclic
//! coordinates, on which q̈ does not depend, and the inputs where they
//! enter affinely (`Driven::INPUTS_AFFINE`): ∂²q̈/∂u² = 0 there, and the
//! mixed terms are in the other columns.

use super::blocks::Square;
use super::chain::{Rows, acceleration_rows, assemble};
use super::{RK4_NODES, RK4_WEIGHTS, StepDerivatives, StepMethod, Transition};
use crate::error::{Error, SettingsError};
use crate::mechanics::{Dynamics, InputDerivatives};
use crate::system::Driven;
use nalgebra::{DMatrix, SVector};

impl<S> Transition<'_, S> {
    /// The step's derivatives (as [`derivatives`](Self::derivatives)) and
    /// ∇²(yᵀF) over (q, v, u), symmetric, 2N + P square, at (q, v, u), for
    /// a system without orientations; y has 2N entries (on q⁺, then v⁺).
    /// One sweep through the stages gives both.
    ///
    /// # Errors
    /// As [`derivatives`](Self::derivatives); [`Error::Settings`] for a
    /// system with orientations.
    pub(crate) fn curvature<const N: usize, const P: usize>(
        &self,
        (q, v, u): (&SVector<f64, N>, &SVector<f64, N>, &SVector<f64, P>),
        t: f64,
        y: &[f64],
    ) -> Result<(StepDerivatives<N>, DMatrix<f64>), Error>
    where
        S: Driven<f64, N, P, N>,
    {
        if !S::ORIENTATIONS.is_empty() {
            return Err(SettingsError::Data {
                owner: "Transition",
                problem: "a step's curvature is for systems without orientations".into(),
            }
            .into());
        }
        let width = 2 * N + P;
        if self.method == StepMethod::SemiImplicitEuler || self.through_linearizer {
            let d = self.derivatives(q, v, u, t)?;
            let hessian = match self.method {
                StepMethod::SemiImplicitEuler => self.euler_curvature((q, v, u), t, y)?,
                StepMethod::Rk4 => self.rk4(q, v, u, t, y)?.1,
            };
            return Ok((d, hessian));
        }
        if y.iter().all(|y| *y == 0.0) {
            return Ok((self.derivatives(q, v, u, t)?, DMatrix::zeros(width, width)));
        }
        self.rk4(q, v, u, t, y)
    }

    /// The difference step relative to each entry: √ε where the stages'
    /// derivatives are the emitted ones, exact to round-off; ∛ε where they
    /// are central differences themselves, whose own error of ~10⁻¹¹ a step
    /// of √ε would magnify to 10⁻³. With the derivatives at (q, v, u).
    fn first_stage<const N: usize, const P: usize>(
        &self,
        (q, v, u): (&SVector<f64, N>, &SVector<f64, N>, &SVector<f64, P>),
        t: f64,
    ) -> Result<(InputDerivatives<f64, N, P>, f64), Error>
    where
        S: Driven<f64, N, P, N>,
    {
        let tolerance = self.linearizer.tolerances.singular;
        let dynamics = Dynamics::new(self.system).with_singular_tolerance(tolerance);
        Ok(match dynamics.input_derivatives(t, q, v, u)? {
            Some(first) => (first, f64::EPSILON.sqrt()),
            None => (self.stage_derivatives(q, v, u, t)?, f64::EPSILON.cbrt()),
        })
    }

    /// Semi-implicit Euler: q⁺ = q + h v + h² q̈, v⁺ = v + h q̈, one stage
    /// at the start, so ∇²(yᵀF) = ∇²((h² y_q + h y_v)ᵀ q̈).
    fn euler_curvature<const N: usize, const P: usize>(
        &self,
        (q, v, u): (&SVector<f64, N>, &SVector<f64, N>, &SVector<f64, P>),
        t: f64,
        y: &[f64],
    ) -> Result<DMatrix<f64>, Error>
    where
        S: Driven<f64, N, P, N>,
    {
        let (first, step) = self.first_stage((q, v, u), t)?;
        let h = self.h;
        let mu = SVector::<f64, N>::from_column_slice(&y[..N]) * (h * h)
            + SVector::<f64, N>::from_column_slice(&y[N..2 * N]) * h;
        let mut g = Square::zero();
        self.stage_hessian(((q, v, u), t), (&first, &mu), step, &mut g)?;
        Ok(g.symmetric())
    }

    /// RK4 in the plane: forward, each stage's point, derivatives and
    /// tangent rows (as `chain::rk4`, whose sums give ∂F/∂(x, u)); back,
    /// the adjoints of each stage's rates, and Σ_s W_sᵀ ∇²(μ_sᵀq̈) W_s.
    fn rk4<const N: usize, const P: usize>(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        u: &SVector<f64, P>,
        t: f64,
        y: &[f64],
    ) -> Result<(StepDerivatives<N>, DMatrix<f64>), Error>
    where
        S: Driven<f64, N, P, N>,
    {
        let h = self.h;
        let (first, step) = self.first_stage((q, v, u), t)?;
        let (x_q, x_v) = (Rows::<N, P>::identity(true), Rows::identity(false));
        let (mut sum_q, mut sum_v) = (x_q, x_v);
        let mut stages = Vec::with_capacity(4);
        let (mut point, mut tangent, mut first) = ((*q, *v), (x_q, x_v), Some(first));
        let (mut q1, mut v1) = (*q, *v);
        for s in 0..4 {
            let d = match first.take() {
                Some(d) => d,
                None => self.stage_derivatives(&point.0, &point.1, u, t + RK4_NODES[s] * h)?,
            };
            let rates = (tangent.1, acceleration_rows(&d, &tangent.0, &tangent.1));
            let w = RK4_WEIGHTS[s] * h / 6.0;
            sum_q = sum_q.plus(w, &rates.0);
            sum_v = sum_v.plus(w, &rates.1);
            (q1, v1) = (q1 + point.1 * w, v1 + d.acceleration * w);
            // The next stage's point x + c k_s and its tangent rows.
            let c = RK4_NODES[(s + 1) % 4] * h;
            let next = (q + point.1 * c, v + d.acceleration * c);
            stages.push((point, tangent, d));
            (point, tangent) = (next, (x_q.plus(c, &rates.0), x_v.plus(c, &rates.1)));
        }
        let (dx, du) = assemble(&sum_q, &sum_v);
        let derivatives = StepDerivatives {
            q: q1,
            v: v1,
            dx,
            du,
        };
        let y = (
            SVector::<f64, N>::from_column_slice(&y[..N]),
            SVector::<f64, N>::from_column_slice(&y[N..2 * N]),
        );
        let (mut hessian, mut g) = (Square::<N, P>::zero(), Square::zero());
        // The adjoint of the next stage's point (q̄, v̄), zero after the last.
        let (mut next_q, mut next_v) = (SVector::<f64, N>::zeros(), SVector::<f64, N>::zeros());
        for s in (0..4).rev() {
            let weight = RK4_WEIGHTS[s] * h / 6.0;
            let c_next = if s < 3 { RK4_NODES[s + 1] * h } else { 0.0 };
            // k̄_s = (h/6) w_s y + c_{s+1} p̄_{s+1}, on the rates (v_s, q̈_s).
            let bar_v = y.0 * weight + next_q * c_next;
            let bar_a = y.1 * weight + next_v * c_next;
            let ((qs, vs), (tq, tv), d) = &stages[s];
            let at = ((qs, vs, u), t + RK4_NODES[s] * h);
            if self.stage_hessian(at, (d, &bar_a), step, &mut g)? {
                hessian.add_congruence(&g, (tq, tv));
            }
            // p̄_s = ∂k_s/∂p_sᵀ k̄_s, k = (v, q̈(q, v)).
            next_q = d.dq.tr_mul(&bar_a);
            next_v = bar_v + d.dv.tr_mul(&bar_a);
        }
        // Σ W_sᵀ G_s W_s with each G_s as differenced: its symmetric part is
        // the curvature, and the sum's is Σ W_sᵀ sym(G_s) W_s.
        Ok((derivatives, hessian.symmetric()))
    }

    /// ∇²(μᵀq̈) over (q, v, u) at one stage into `g` (2N + P square), as
    /// forward differences of [∂q̈/∂q ∂q̈/∂v ∂q̈/∂u]ᵀ μ, each of `relative`
    /// times its entry (at least 1): column j the difference along the j-th
    /// unknown, not yet symmetrised. False (and `g` untouched) when μ = 0.
    fn stage_hessian<const N: usize, const P: usize>(
        &self,
        ((q, v, u), t): StagePoint<N, P>,
        (here, mu): (&InputDerivatives<f64, N, P>, &SVector<f64, N>),
        relative: f64,
        g: &mut Square<N, P>,
    ) -> Result<bool, Error>
    where
        S: Driven<f64, N, P, N>,
    {
        if mu.iter().all(|m| *m == 0.0) {
            return Ok(false);
        }
        // [∂q̈/∂q ∂q̈/∂v ∂q̈/∂u]ᵀ μ, by blocks, on the stack.
        let contracted =
            |d: &InputDerivatives<f64, N, P>| (d.dq.tr_mul(mu), d.dv.tr_mul(mu), d.du.tr_mul(mu));
        let base = contracted(here);
        // Inputs that enter affinely have no curvature of their own: their
        // columns are the other columns' input rows (g is symmetric).
        let differenced = if S::INPUTS_AFFINE { 2 * N } else { 2 * N + P };
        for j in 0..differenced {
            if j < N && S::CYCLIC[j] {
                g.set_column(j, (&SVector::zeros(), &SVector::zeros(), &SVector::zeros()));
                continue;
            }
            let (mut q1, mut v1, mut u1) = (*q, *v, *u);
            let value = match j {
                j if j < N => &mut q1[j],
                j if j < 2 * N => &mut v1[j - N],
                j => &mut u1[j - 2 * N],
            };
            let step = relative * value.abs().max(1.0);
            *value += step;
            let (dq, dv, du) = contracted(&self.stage_derivatives(&q1, &v1, &u1, t)?);
            let column = (
                (dq - base.0) / step,
                (dv - base.1) / step,
                (du - base.2) / step,
            );
            g.set_column(j, (&column.0, &column.1, &column.2));
        }
        if S::INPUTS_AFFINE {
            g.mirror_inputs();
        }
        Ok(true)
    }
}

/// A stage's (q, v, u) and time.
type StagePoint<'a, const N: usize, const P: usize> = (
    (
        &'a SVector<f64, N>,
        &'a SVector<f64, N>,
        &'a SVector<f64, P>,
    ),
    f64,
);

#[cfg(test)]
#[path = "transition_curvature_tests.rs"]
mod tests;
