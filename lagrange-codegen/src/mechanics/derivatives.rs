//! `emit(jacobians)`: J_q = ∂(Q − h)/∂q − [∂M/∂q_k q̈]_k and J_v = ∂(Q − h)/∂q̇,
//! that is −∂τ/∂q and −∂τ/∂q̇ of the inverse dynamics τ(q, q̇, q̈) at the
//! accelerations' symbols (Pinocchio's RNEA derivatives; the runtime solves
//! ∂q̈/∂q = M⁻¹ J_q).
//!
//! On a tree the derivatives are those of recursive Newton–Euler, O(n) per
//! coordinate, not of M (O(n³) entries each); a description with free
//! orientations takes them from a copy of the tree whose spherical joints
//! are turned by R(θ) (`Tree::perturbed`), so ∂/∂θ at θ = 0 is the derivative
//! along q ⊕ δ at fixed ω — the tangent space's, with no chart.

use lagrange_symbolic::{Context, Expr as Sym};

use super::expressions::{Expressions, entries};
use super::motion::EquationsOfMotion;
use super::{DeriveError, Sources};
use crate::tree::Tree;

/// The right-hand side's Jacobians at the accelerations' symbols q̈, N × N
/// each, row-major (`emit(jacobians)`).
pub struct RhsJacobians {
    /// J_q = ∂(Q − h)/∂q − [∂M/∂q_k q̈]_k.
    pub position: Vec<Vec<Sym>>,
    /// J_v = ∂(Q − h)/∂q̇.
    pub velocity: Vec<Vec<Sym>>,
    /// M and Q − h (at zero input) from the composites the closed form
    /// gathers, for a program that takes both (`solved`); none where the
    /// Jacobians came otherwise or the tree has a spherical joint (whose M
    /// is the motion's, in ω).
    pub dynamics: Option<(Vec<Vec<Sym>>, Vec<Sym>)>,
}

impl Expressions for RhsJacobians {
    fn expressions(&self, out: &mut Vec<Sym>) {
        entries(out, [&self.position, &self.velocity]);
    }
}

/// J_q and J_v from the tree where M and h come from it, or where there are
/// free orientations, else from M and Q − h; an error for orientations
/// without a tree (differentiating the generic form in θ would hold θ̇, not
/// ω, fixed).
pub(super) fn rhs_jacobians(
    ctx: &mut Context,
    tree: Option<&Tree>,
    motion: &EquationsOfMotion,
    sources: &Sources,
    orientations: bool,
) -> Result<RhsJacobians, DeriveError> {
    let tree = tree.filter(|_| sources.recursive || orientations);
    match (tree, orientations) {
        (Some(tree), _) => {
            // Every generalized force but gravity's (a base acceleration to
            // the recursion), at zero input.
            let zero = ctx.zero();
            let rest = (sources.applied).generalized_forces(ctx, sources.potential.unwrap_or(zero));
            let at_zero: Vec<(Sym, Sym)> = ctx.inputs().iter().map(|&u| (u, zero)).collect();
            let rest: Vec<Sym> = rest.iter().map(|&f| ctx.substitute(f, &at_zero)).collect();
            Ok(of_the_tree(ctx, tree, &rest))
        }
        (None, false) => Ok(of_the_generic_form(ctx, &motion.mass, &motion.rhs)),
        (None, true) => Err(DeriveError::JacobiansNeedTree(
            sources.route_reason.clone().unwrap_or_default(),
        )),
    }
}

/// −∂τ/∂q, −∂τ/∂q̇ with τ = RNEA(q, q̇, q̈; gravity) − rest: by the closed-form
/// derivatives of the recursion in world axes or by differentiating its
/// link-axes form, whichever program is cheaper (the closed form wins on
/// arms with general axes; the link-axes form can win on small trees whose
/// axes are aligned, where its products by 0 and 1 vanish).
fn of_the_tree(ctx: &mut Context, tree: &Tree, rest: &[Sym]) -> RhsJacobians {
    let d = crate::tree::inverse_dynamics_derivatives(ctx, tree);
    let mut closed = with_rest(ctx, d.position, d.velocity, rest);
    if !tree.turns_freely() {
        let rhs = rest
            .iter()
            .zip(&d.bias)
            .map(|(&f, &b)| ctx.sub(f, b))
            .collect();
        closed.dynamics = Some((d.mass, rhs));
    }
    let differentiated = of_the_link_axes_form(ctx, tree, rest);
    let cost = |ctx: &Context, j: &RhsJacobians| {
        let mut out = Vec::new();
        j.expressions(&mut out);
        super::generic::cost(ctx, &out)
    };
    #[cfg(test)]
    if let Some(closed_form) = tests::FORCED.get() {
        return if closed_form { closed } else { differentiated };
    }
    if cost(ctx, &differentiated) < cost(ctx, &closed) {
        differentiated
    } else {
        closed
    }
}

/// −∂τ/∂x + ∂rest/∂x from the recursion's ∂τ/∂q and ∂τ/∂q̇.
fn with_rest(
    ctx: &mut Context,
    tq: Vec<Vec<Sym>>,
    tv: Vec<Vec<Sym>>,
    rest: &[Sym],
) -> RhsJacobians {
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let minus = |ctx: &mut Context, m: Vec<Vec<Sym>>, x: &[Sym]| -> Vec<Vec<Sym>> {
        m.into_iter()
            .zip(rest)
            .map(|(row, &f)| {
                row.into_iter()
                    .zip(x)
                    .map(|(e, &xk)| {
                        let d = ctx.diff(f, xk);
                        ctx.sub(d, e)
                    })
                    .collect()
            })
            .collect()
    };
    let position = minus(ctx, tq, &q);
    let velocity = minus(ctx, tv, &qd);
    RhsJacobians {
        position,
        velocity,
        dynamics: None,
    }
}

/// −∂τ/∂q, −∂τ/∂q̇ by differentiating the link-axes recursion coordinate by
/// coordinate; a description with free orientations takes them from a copy
/// of the tree whose spherical joints are turned by R(θ).
fn of_the_link_axes_form(ctx: &mut Context, tree: &Tree, rest: &[Sym]) -> RhsJacobians {
    let turned = tree.perturbed(ctx);
    let inertial = crate::tree::inverse_dynamics_at_accelerations(ctx, &turned, true);
    let tau: Vec<Sym> = inertial
        .iter()
        .zip(rest)
        .map(|(&m, &f)| ctx.sub(m, f))
        .collect();
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let minus_d = |ctx: &mut Context, x: &[Sym]| -> Vec<Vec<Sym>> {
        tau.iter()
            .map(|&t| {
                x.iter()
                    .map(|&xk| {
                        let d = ctx.diff(t, xk);
                        ctx.neg(d)
                    })
                    .collect()
            })
            .collect()
    };
    let position = minus_d(ctx, &q);
    let velocity = minus_d(ctx, &qd);
    RhsJacobians {
        position,
        velocity,
        dynamics: None,
    }
}

/// J_q = ∂(Q − h)/∂q − [∂M/∂q_k q̈]_k and J_v = ∂(Q − h)/∂q̇, with q̈ left as the
/// acceleration symbols (the runtime passes the current q̈).
fn of_the_generic_form(ctx: &mut Context, mass: &[Vec<Sym>], rhs: &[Sym]) -> RhsJacobians {
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    let n = q.len();
    let position = (0..n)
        .map(|i| {
            (0..n)
                .map(|k| {
                    let mut terms = vec![ctx.diff(rhs[i], q[k])];
                    for j in 0..n {
                        let dm = ctx.diff(mass[i][j], q[k]);
                        let t = ctx.mul(dm, qdd[j]);
                        terms.push(ctx.neg(t));
                    }
                    let s = ctx.sum(&terms);
                    ctx.collect(s)
                })
                .collect()
        })
        .collect();
    let velocity = (0..n)
        .map(|i| {
            (0..n)
                .map(|k| {
                    let d = ctx.diff(rhs[i], qd[k]);
                    ctx.collect(d)
                })
                .collect()
        })
        .collect();
    RhsJacobians {
        position,
        velocity,
        dynamics: None,
    }
}

#[cfg(test)]
mod tests;
