//! A torque on a body, as the Cartesian forces the generalized forces
//! already take: (direction, force) pairs whose Jacobians give τ · ∂ω/∂q̇.

use lagrange_symbolic::Expr as Sym;

use super::{Lowerer, Mode};
use crate::ast::Torque;

impl Lowerer<'_> {
    /// `torque(body, τ)` as three pairs (e_{k+1}, τ_k e_{k+2}), e_k the body's
    /// axes in world components and τ_k the torque's component about e_k.
    ///
    /// Why this is the torque: the pair is a couple, the force at the tip of
    /// e_{k+1} with its opposite at the origin, so the origin's motion cancels
    /// and its generalized force is ∂e_{k+1}/∂q_i · τ_k e_{k+2} =
    /// (ω_i × e_{k+1}) · e_{k+2} τ_k = ω_i · e_k τ_k, with ω_i = ∂ω/∂q̇_i;
    /// summed over k, ω_i · τ. The generalized forces differentiate each
    /// "position" of a pair, so the direction e_{k+1} stands in for it.
    pub fn torque(&mut self, t: &Torque) -> Option<Vec<(Vec<Sym>, Vec<Sym>)>> {
        let body = self.frame_of(&t.body)?;
        let axes = self.frames[body].axes?;
        // A torque of other than three components is reported by `check`.
        let value = self
            .vector(&t.value, Mode::State)
            .filter(|v| v.len() == 3)?;
        let axis = |k: usize| -> Vec<Sym> { (0..3).map(|i| axes[i][k % 3]).collect() };
        let pairs = (0..3)
            .map(|k| {
                let component = if t.body_axes {
                    value[k]
                } else {
                    let e = axis(k);
                    let terms: Vec<Sym> = (0..3).map(|i| self.ctx.mul(e[i], value[i])).collect();
                    self.ctx.sum(&terms)
                };
                let force = axis(k + 2)
                    .into_iter()
                    .map(|e| self.ctx.mul(component, e))
                    .collect();
                (axis(k + 1), force)
            })
            .collect();
        Some(pairs)
    }
}
