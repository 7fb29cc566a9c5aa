//! The route of the emitted q̈ (`emit(articulated)`), chosen at build time
//! by operation count: the articulated-body algorithm, or M and Q − h with
//! M factorised in the program (`factor`: Featherstone's LᵀDL, which on a
//! tree fills in nothing). Which is cheaper depends on the robot: the
//! articulated-body algorithm is O(n) but carries 6×6 articulated inertias
//! through every link, while M, h and a tree-sparse factorisation are a
//! handful of operations per entry when the joint axes fold (the UR arms).
//! Both return q̈ at (q, q̇, τ) and the pivots D of M = Lᵀ D L, so the
//! emitted method and the singularity check do not depend on the choice.

use lagrange_symbolic::{Context, Expr as Sym, Program};

use super::factor::factorise;
use super::motion::EquationsOfMotion;
use super::recursive::Articulation;

/// How the emitted q̈ is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ForwardRoute {
    /// Featherstone's articulated-body algorithm.
    ArticulatedBody,
    /// M and Q − h, M = Lᵀ D L factorised in the program, two triangular
    /// solves.
    FactoredMass,
}

/// The route taken and both routes' weighted operation counts
/// ([`lagrange_symbolic::OpCount::weighted`]), for `FORWARD_ROUTE` and the
/// `EQUATIONS` text.
pub struct ForwardChoice {
    /// The route the emitted q̈ takes.
    pub route: ForwardRoute,
    /// The articulated-body program's weighted operations; `None` where the
    /// algorithm does not apply (a coordinate driving two joints).
    pub articulated_body: Option<usize>,
    /// The factored mass matrix program's weighted operations.
    pub factored_mass: usize,
    /// The route not taken, kept for tests (not emitted, and not among the
    /// model's expressions).
    pub other: Option<Articulation>,
}

/// The cheaper of the articulated-body program `a` and q̈ = M⁻¹(Q − h + τ)
/// with M factorised, over the same τ symbols; ties go to the
/// articulated-body algorithm, whose cost grows slower with the tree.
pub(super) fn fastest(
    ctx: &mut Context,
    a: Articulation,
    motion: &EquationsOfMotion,
) -> (Articulation, ForwardChoice) {
    let factored = factored(ctx, &a.extra, motion);
    let articulated_body = cost(ctx, &a);
    let factored_mass = cost(ctx, &factored);
    let (kept, other, route) = if factored_mass < articulated_body {
        (factored, a, ForwardRoute::FactoredMass)
    } else {
        (a, factored, ForwardRoute::ArticulatedBody)
    };
    let choice = ForwardChoice {
        route,
        articulated_body: Some(articulated_body),
        factored_mass,
        other: Some(other),
    };
    (kept, choice)
}

/// The factored route alone, where the articulated-body algorithm does not
/// apply: a coordinate driving two joints (a URDF's `<mimic>`), whose
/// shares M and h sum but the algorithm's one pivot per joint cannot.
pub(super) fn factored_only(
    ctx: &mut Context,
    motion: &EquationsOfMotion,
) -> (Articulation, ForwardChoice) {
    let extra: Vec<Sym> = (0..motion.rhs.len())
        .map(|i| ctx.free_symbol(&format!("tau{i}")))
        .collect();
    let factored = factored(ctx, &extra, motion);
    let choice = ForwardChoice {
        route: ForwardRoute::FactoredMass,
        articulated_body: None,
        factored_mass: cost(ctx, &factored),
        other: None,
    };
    (factored, choice)
}

/// The weighted operations of q̈ and the pivots as one program.
fn cost(ctx: &Context, a: &Articulation) -> usize {
    let outputs: Vec<Sym> = a.accelerations.iter().chain(&a.pivots).copied().collect();
    Program::new(ctx, &outputs).op_count().weighted()
}

/// q̈ = M⁻¹(Q − h + τ) by M = Lᵀ D L, with the pivots D.
fn factored(ctx: &mut Context, extra: &[Sym], motion: &EquationsOfMotion) -> Articulation {
    let factor = factorise(ctx, &motion.mass);
    let forced: Vec<Sym> = (motion.rhs.iter().zip(extra))
        .map(|(&r, &x)| ctx.add(r, x))
        .collect();
    let accelerations = factor.solve(ctx, &forced);
    Articulation {
        accelerations,
        pivots: factor.pivots,
        extra: extra.to_vec(),
    }
}
