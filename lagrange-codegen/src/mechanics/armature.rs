//! A rotor's reflected inertia (`joint(q, armature = Ia)`, MuJoCo's
//! `armature`): ½ Ia q̇² in T and Ia on M's diagonal entry (q, q). It turns
//! with its coordinate alone, so h, Q and every derivative in q and q̇ are
//! unchanged; the tree's recursions take it through `Tree::with_armature`.

use lagrange_symbolic::{Context, Expr as Sym};

/// T + ½ Σ Ia q̇² (T itself without armature, so its nodes are unchanged).
pub(super) fn kinetic(ctx: &mut Context, kinetic: Sym, armature: &[(usize, Sym)]) -> Sym {
    if armature.is_empty() {
        return kinetic;
    }
    let qd = ctx.velocities();
    let half = ctx.rational(1, 2);
    let mut terms = vec![kinetic];
    for &(i, ia) in armature {
        let sq = ctx.powi(qd[i], 2);
        let e = ctx.mul(ia, sq);
        terms.push(ctx.mul(half, e));
    }
    ctx.sum(&terms)
}

/// M's diagonal entries (q, q) + Ia.
pub(super) fn add_to_mass(ctx: &mut Context, mass: &mut [Vec<Sym>], armature: &[(usize, Sym)]) {
    for &(i, ia) in armature {
        mass[i][i] = ctx.add(mass[i][i], ia);
    }
}
