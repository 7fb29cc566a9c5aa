//! Generalized forces Q and the inputs' share of them.

use lagrange_symbolic::{Context, Expr as Sym};

use super::expressions::{Expressions, entries};
use crate::mat3::dot;

/// What the description applies besides gravity: a dissipation function,
/// Cartesian forces at points and explicit generalized forces.
pub(super) struct Applied<'a> {
    pub dissipation: Option<Sym>,
    /// (position of the point of application, Cartesian force)
    pub forces: &'a [(Vec<Sym>, Vec<Sym>)],
    /// (coordinate index, generalized force)
    pub generalized: &'a [(usize, Sym)],
}

impl Applied<'_> {
    /// Q with the potential `potential`.
    pub(super) fn generalized_forces(&self, ctx: &mut Context, potential: Sym) -> Vec<Sym> {
        let q = ctx.coordinates();
        let qd = ctx.velocities();
        generalized_forces_of(
            ctx,
            &q,
            &qd,
            potential,
            self.dissipation,
            self.forces,
            self.generalized,
        )
    }
}

/// Q = −∂V/∂q + Σ_ν J_νᵀ F_ν − ∂D/∂q̇ + explicit generalized forces (Suslov 32.28–32.31).
fn generalized_forces_of(
    ctx: &mut Context,
    q: &[Sym],
    qd: &[Sym],
    potential: Sym,
    dissipation: Option<Sym>,
    forces: &[(Vec<Sym>, Vec<Sym>)],
    generalized: &[(usize, Sym)],
) -> Vec<Sym> {
    (0..q.len())
        .map(|i| {
            let mut terms = Vec::new();
            let dv = ctx.diff(potential, q[i]);
            terms.push(ctx.neg(dv));
            for (at, f) in forces {
                let ci: Vec<Sym> = at.iter().map(|&x| ctx.diff(x, q[i])).collect();
                terms.push(dot(ctx, &ci, f));
            }
            if let Some(d) = dissipation {
                let dd = ctx.diff(d, qd[i]);
                terms.push(ctx.neg(dd));
            }
            for (c, g) in generalized {
                if *c == i {
                    terms.push(*g);
                }
            }
            let s = ctx.sum(&terms);
            ctx.collect(s)
        })
        .collect()
}

/// Splits Q(u) and V(u) into the unforced Q(0), V(0) and the inputs' part ΔQ
/// with its Jacobians. Without inputs, Q and V are returned untouched.
pub(super) fn split_inputs(
    ctx: &mut Context,
    names: Vec<String>,
    total: Vec<Sym>,
    potential: Sym,
) -> (Vec<Sym>, Sym, Option<InputModel>) {
    let u = ctx.inputs();
    if u.is_empty() {
        return (total, potential, None);
    }
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let zero = ctx.zero();
    let at_zero: Vec<(Sym, Sym)> = u.iter().map(|&x| (x, zero)).collect();
    let unforced = |ctx: &mut Context, e: Sym| {
        let e = ctx.substitute(e, &at_zero);
        ctx.collect(e)
    };
    let q0: Vec<Sym> = total.iter().map(|&e| unforced(ctx, e)).collect();
    let v0 = unforced(ctx, potential);
    let jacobian = |ctx: &mut Context, rows: &[Sym], wrt: &[Sym]| -> Vec<Vec<Sym>> {
        rows.iter()
            .map(|&r| {
                wrt.iter()
                    .map(|&x| {
                        let d = ctx.diff(r, x);
                        ctx.collect(d)
                    })
                    .collect()
            })
            .collect()
    };
    let jacobian_u = jacobian(ctx, &total, &u);
    // Where Q is affine in u (forces proportional to the inputs, set-points in
    // a quadratic potential), ΔQ = Σ u_j ∂Q/∂u_j: the derivatives have already
    // dropped every term without an input, whereas Q(u) − Q(0) would keep them
    // nested in factored sums that only cancel numerically.
    let affine_rows: Vec<bool> = (jacobian_u.iter())
        .map(|row| {
            row.iter()
                .all(|&d| u.iter().all(|&x| !ctx.depends_on(d, x)))
        })
        .collect();
    let forces: Vec<Sym> = (0..total.len())
        .map(|i| {
            let d = if affine_rows[i] {
                let terms: Vec<Sym> = jacobian_u[i]
                    .iter()
                    .zip(&u)
                    .map(|(&d, &x)| ctx.mul(x, d))
                    .collect();
                ctx.sum(&terms)
            } else {
                ctx.sub(total[i], q0[i])
            };
            ctx.collect(d)
        })
        .collect();
    let model = InputModel {
        affine: affine_rows.iter().all(|&a| a),
        names,
        jacobian_q: jacobian(ctx, &forces, &q),
        jacobian_v: jacobian(ctx, &forces, &qd),
        jacobian_u,
        symbols: u,
        forces,
    };
    (q0, v0, Some(model))
}

/// How the inputs u enter: Q(q, q̇, u, t) = Q(q, q̇, 0, t) + ΔQ.
pub struct InputModel {
    /// The inputs' names, in order.
    pub names: Vec<String>,
    /// The input symbols, in order (emitted as `u[i]`).
    pub symbols: Vec<Sym>,
    /// Whether ∂Q/∂u depends on no input (Q affine in u).
    pub affine: bool,
    /// ΔQ = Q(q, q̇, u, t) − Q(q, q̇, 0, t).
    pub forces: Vec<Sym>,
    /// ∂Q/∂u (N × P), row-major.
    pub jacobian_u: Vec<Vec<Sym>>,
    /// ∂ΔQ/∂q (N × N).
    pub jacobian_q: Vec<Vec<Sym>>,
    /// ∂ΔQ/∂q̇ (N × N).
    pub jacobian_v: Vec<Vec<Sym>>,
}

impl Expressions for InputModel {
    fn expressions(&self, out: &mut Vec<Sym>) {
        out.extend(&self.forces);
        entries(out, [&self.jacobian_u, &self.jacobian_q, &self.jacobian_v]);
    }
}
