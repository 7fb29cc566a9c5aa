//! `emit(jacobians)` on an unconstrained system: q̈ = M⁻¹(Q − h + τ) and
//! its derivatives ∂q̈/∂δ = M⁻¹ J_q, ∂q̈/∂q̇ = M⁻¹ J_v and ∂q̈/∂τ = M⁻¹ as one
//! straight-line program over (q, q̇, τ): M factorised in it (`factor`), J_q
//! and J_v taken at that q̈, so the dynamics, the factorisation and the
//! derivatives share their subexpressions and nothing is left to the run.

use lagrange_symbolic::{Context, Expr as Sym};

use super::derivatives::RhsJacobians;
use super::expressions::{Expressions, entries};
use super::factor::factorise;

/// q̈ and its derivatives in (q, q̇, τ), N × N row-major each.
pub struct SolvedDerivatives {
    /// q̈ = M⁻¹(Q − h + τ).
    pub acceleration: Vec<Sym>,
    /// ∂q̈/∂δ (∂q̈/∂q without orientations).
    pub position: Vec<Vec<Sym>>,
    /// ∂q̈/∂q̇.
    pub velocity: Vec<Vec<Sym>>,
    /// ∂q̈/∂τ = M⁻¹.
    pub inverse_mass: Vec<Vec<Sym>>,
    /// The pivots D of M = Lᵀ D L, for the singularity check.
    pub pivots: Vec<Sym>,
    /// The free symbols of τ (emitted as `tau[i]`).
    pub extra: Vec<Sym>,
}

impl Expressions for SolvedDerivatives {
    fn expressions(&self, out: &mut Vec<Sym>) {
        out.extend(&self.acceleration);
        entries(out, [&self.position, &self.velocity, &self.inverse_mass]);
        out.extend(&self.pivots);
    }
}

/// The program from M, Q − h (at zero input) and the right-hand side's
/// Jacobians at the accelerations' symbols. Where the Jacobians' composites
/// also give M and Q − h (`RhsJacobians::dynamics`) and the three together
/// cost less than with the motion's own, it takes those: the program then
/// gathers the subtree inertias and forces once, for the dynamics and the
/// derivatives alike (the xArm7's whole program 10,587 → 9,642 operations).
pub(super) fn solved(
    ctx: &mut Context,
    mass: &[Vec<Sym>],
    rhs: &[Sym],
    jacobians: &RhsJacobians,
) -> SolvedDerivatives {
    let (mass, rhs) = cheaper_dynamics(ctx, (mass, rhs), jacobians);
    let n = rhs.len();
    let extra: Vec<Sym> = (0..n)
        .map(|i| ctx.free_symbol(&format!("tau{i}")))
        .collect();
    let factor = factorise(ctx, &mass);
    let forced: Vec<Sym> = rhs
        .iter()
        .zip(&extra)
        .map(|(&r, &x)| ctx.add(r, x))
        .collect();
    let acceleration = factor.solve(ctx, &forced);
    let at: Vec<(Sym, Sym)> = ctx
        .accelerations()
        .into_iter()
        .zip(acceleration.iter().copied())
        .collect();
    let columns = |ctx: &mut Context, m: &[Vec<Sym>]| -> Vec<Vec<Sym>> {
        let flat: Vec<Sym> = m.iter().flatten().copied().collect();
        let at_q = ctx.substitute_all(&flat, &at);
        let solved: Vec<Vec<Sym>> = (0..n)
            .map(|k| {
                let column: Vec<Sym> = (0..n).map(|i| at_q[i * n + k]).collect();
                factor.solve(ctx, &column)
            })
            .collect();
        (0..n)
            .map(|i| (0..n).map(|k| solved[k][i]).collect())
            .collect()
    };
    let position = columns(ctx, &jacobians.position);
    let velocity = columns(ctx, &jacobians.velocity);
    let zero = ctx.zero();
    let one = ctx.one();
    let identity: Vec<Vec<Sym>> = (0..n)
        .map(|i| (0..n).map(|k| if i == k { one } else { zero }).collect())
        .collect();
    let solved = columns(ctx, &identity);
    let inverse_mass = symmetric_half(ctx, solved);
    SolvedDerivatives {
        acceleration,
        position,
        velocity,
        inverse_mass,
        pivots: factor.pivots,
        extra,
    }
}

/// The motion's M and Q − h or the Jacobians' own, whichever program with
/// the Jacobians is cheaper.
fn cheaper_dynamics(
    ctx: &Context,
    (mass, rhs): (&[Vec<Sym>], &[Sym]),
    jacobians: &RhsJacobians,
) -> (Vec<Vec<Sym>>, Vec<Sym>) {
    let motion = (mass.to_vec(), rhs.to_vec());
    let Some(shared) = &jacobians.dynamics else {
        return motion;
    };
    let mut derivatives = Vec::new();
    jacobians.expressions(&mut derivatives);
    let cost = |(m, r): &(Vec<Vec<Sym>>, Vec<Sym>)| {
        let mut outputs: Vec<Sym> = m.iter().flatten().chain(r).copied().collect();
        outputs.extend(&derivatives);
        super::generic::cost(ctx, &outputs)
    };
    if cost(shared) < cost(&motion) {
        shared.clone()
    } else {
        motion
    }
}

/// M⁻¹ from one triangle of its solved columns, mirrored: M⁻¹ is symmetric,
/// and the triangle a column's back substitution reaches first needs none of
/// the other's entries, which the program then leaves out (the cheaper
/// triangle, by operation count).
fn symmetric_half(ctx: &Context, full: Vec<Vec<Sym>>) -> Vec<Vec<Sym>> {
    let n = full.len();
    let mirrored = |upper: bool| -> Vec<Vec<Sym>> {
        (0..n)
            .map(|i| {
                (0..n)
                    .map(|k| {
                        let (a, b) = (i.min(k), i.max(k));
                        if upper { full[a][b] } else { full[b][a] }
                    })
                    .collect()
            })
            .collect()
    };
    let cost = |m: &[Vec<Sym>]| {
        let outputs: Vec<Sym> = m.iter().flatten().copied().collect();
        super::generic::cost(ctx, &outputs)
    };
    let (upper, lower) = (mirrored(true), mirrored(false));
    if cost(&lower) < cost(&upper) {
        lower
    } else {
        upper
    }
}
