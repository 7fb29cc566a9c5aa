//! Y on the generic route, for a description that is not a kinematic tree
//! (point masses at ξ(q, t), bodies placed by arbitrary ξ(q, t) and
//! rotations, closed chains written in their own coordinates).
//!
//! The Lagrangian is linear in π: L = Σ_k (T_k − V_k) π_k, and so is the
//! Euler–Lagrange operator, so column k of Y is that operator applied to
//! T_k − V_k alone, by the same derivation as the generic route's h from T
//! (`generic::euler_lagrange`), with q̈'s symbols kept. Its cost grows with
//! the number of parameters times the coordinates, not as the recursion's
//! O(n): the recursive route stays the one for trees.

use lagrange_symbolic::{Context, Expr as Sym};

use super::energy::Column;
use crate::mechanics::generic::euler_lagrange;

/// `rows[i][k]` = d/dt ∂L_k/∂q̇_i − ∂L_k/∂q_i with L_k = T_k − V_k.
pub(super) fn rows(ctx: &mut Context, columns: &[Column]) -> Vec<Vec<Sym>> {
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    // Sines and cosines of sums expanded first, as the kinematics' are, so
    // that a chain's columns call ~2n of them.
    let by_column: Vec<Vec<Sym>> = columns
        .iter()
        .map(|c| {
            let l = c.lagrangian(ctx);
            let l = ctx.expand_trig(l);
            euler_lagrange(ctx, l, (&q, &qd), None)
        })
        .collect();
    (0..q.len())
        .map(|i| by_column.iter().map(|column| column[i]).collect())
        .collect()
}
