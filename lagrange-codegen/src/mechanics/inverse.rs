//! Inverse dynamics τ = M q̈ + h − Q at the accelerations' symbols, and the
//! gravity torques ∂V_gravity/∂q (what holds the system still against gravity
//! alone, Pinocchio's generalized gravity): by recursive Newton–Euler on a
//! kinematic tree (O(n), no mass matrix), else from M, h and Q.

use lagrange_symbolic::{Context, Expr as Sym};

use super::motion::EquationsOfMotion;
use crate::tree::Tree;

/// τ(q, q̇, q̈, t) and the gravity torques g(q, t).
pub struct InverseDynamics {
    /// τ = M q̈ + h − Q, one per velocity.
    pub torques: Vec<Sym>,
    /// The gravity torques g(q, t) = ∂V_g/∂q.
    pub gravity: Vec<Sym>,
}

/// From the tree where there is one, else from M, h and Q (with gravity's
/// share) of the generic route. `rest`, Q without gravity's share when the
/// caller has it, lets the tree take gravity as its base acceleration, so
/// that τ is the recursion's alone (with free orientations: built at the
/// chart's centre, with nothing left to expand there).
pub(super) fn inverse_dynamics(
    ctx: &mut Context,
    tree: Option<&Tree>,
    motion: &EquationsOfMotion,
    gravity_potential: Sym,
    rest: Option<&[Sym]>,
) -> InverseDynamics {
    let mass = &motion.mass;
    let bias = &motion.bias;
    let forces = &motion.forces;
    let q = ctx.coordinates();
    let Some(tree) = tree else {
        let a = ctx.accelerations();
        let torques = (0..q.len())
            .map(|i| {
                let mut terms: Vec<Sym> = (0..q.len()).map(|j| ctx.mul(mass[i][j], a[j])).collect();
                terms.push(bias[i]);
                terms.push(ctx.neg(forces[i]));
                ctx.sum(&terms)
            })
            .collect();
        let gravity = q
            .iter()
            .map(|&qi| ctx.diff(gravity_potential, qi))
            .collect();
        return InverseDynamics { torques, gravity };
    };
    // τ = M q̈ + h − Q: the recursion with gravity less Q without it, or
    // without gravity less Q with it.
    let with_gravity = rest.is_some();
    let inertial = crate::tree::inverse_dynamics_at_accelerations(ctx, tree, with_gravity);
    let torques = inertial
        .iter()
        .zip(rest.unwrap_or(forces))
        .map(|(&m, &f)| ctx.sub(m, f))
        .collect();
    // Gravity alone: the recursion at rest with gravity as a base acceleration.
    let at_rest = crate::tree::inverse_dynamics(ctx, tree, true);
    let zero = ctx.zero();
    let still: Vec<(Sym, Sym)> = ctx.velocities().into_iter().map(|v| (v, zero)).collect();
    let gravity = at_rest.iter().map(|&e| ctx.substitute(e, &still)).collect();
    InverseDynamics { torques, gravity }
}
