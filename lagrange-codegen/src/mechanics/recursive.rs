//! The recursive route: M by composite rigid bodies and h − Q_gravity by
//! recursive Newton–Euler over a detected kinematic tree ([`crate::tree`]), and
//! the articulated-body q̈; here the tree is found and the route chosen.

use lagrange_symbolic::{Context, Expr as Sym};

use super::expressions::Expressions;
use super::generic::{GenericTerms, cost};
use crate::lowered::{PointModel, Skeleton, SpinModel};
use crate::mat3::Mat3;
use crate::tree::NotATree;
use crate::tree::Tree;

/// M, h − Q_gravity (the right-hand side's share) and h by the recursions.
pub(super) struct RecursiveTerms {
    pub mass: Vec<Vec<Sym>>,
    pub with_gravity: Vec<Sym>,
    pub bias: Vec<Sym>,
}

/// The kinematic tree the points and bodies span, if they span one and the
/// route may use it.
pub(super) fn detect(
    ctx: &mut Context,
    route: super::Route,
    (points, spins, skeleton): (&[PointModel], &[SpinModel], &Skeleton),
    gravity: Option<&[Sym]>,
) -> Result<Tree, NotATree> {
    if route == super::Route::Generic {
        return Err(NotATree::GenericAsked);
    }
    let point_masses: Vec<Sym> = points.iter().map(|p| p.mass).collect();
    let point_names: Vec<String> = points.iter().map(|p| p.name.clone()).collect();
    let body_names: Vec<String> = spins.iter().map(|s| s.name.clone()).collect();
    let point_positions: Vec<Vec<Sym>> = points.iter().map(|p| p.position.clone()).collect();
    let inertias: Vec<Mat3> = spins.iter().map(|s| s.inertia).collect();
    let masses = crate::tree::Masses {
        body_names: &body_names,
        point_names: &point_names,
        point_masses: &point_masses,
        point_positions: &point_positions,
        inertias: &inertias,
        gravity,
    };
    crate::tree::detect(ctx, skeleton, &masses)
}

/// The recursive terms, if there is a tree and (where the generic route was
/// derived too) they make the cheaper program.
pub(super) fn cheaper(
    ctx: &mut Context,
    tree: Option<&Tree>,
    generic: Option<&GenericTerms>,
) -> Option<RecursiveTerms> {
    // M by CRBA, and h − Q_gravity in one RNEA pass for the right-hand side (h
    // alone for the `bias` output).
    let recursive = tree.map(|tree| RecursiveTerms {
        mass: crate::tree::mass_matrix(ctx, tree),
        with_gravity: crate::tree::inverse_dynamics(ctx, tree, true),
        bias: crate::tree::inverse_dynamics(ctx, tree, false),
    });
    let flat =
        |m: &[Vec<Sym>], v: &[Sym]| -> Vec<Sym> { m.iter().flatten().chain(v).copied().collect() };
    match (generic, recursive) {
        (Some(g), Some(r)) => {
            let generic_cost = cost(ctx, &flat(&g.mass, &g.bias));
            (cost(ctx, &flat(&r.mass, &r.with_gravity)) < generic_cost).then_some(r)
        }
        (_, r) => r,
    }
}

/// q̈ by the articulated-body algorithm with `rest`, every generalized force
/// but gravity's (which the algorithm takes as a base acceleration), at zero
/// input, plus the runtime's extra forces `tau[i]`.
pub(super) fn articulation(
    ctx: &mut Context,
    tree: &crate::tree::Tree,
    rest: &[Sym],
) -> Articulation {
    let zero = ctx.zero();
    let at_zero: Vec<(Sym, Sym)> = ctx.inputs().iter().map(|&u| (u, zero)).collect();
    let extra: Vec<Sym> = (0..rest.len())
        .map(|i| ctx.free_symbol(&format!("tau{i}")))
        .collect();
    let tau: Vec<Sym> = rest
        .iter()
        .zip(&extra)
        .map(|(&r, &x)| {
            let r = ctx.substitute(r, &at_zero);
            ctx.add(r, x)
        })
        .collect();
    let fd = crate::tree::forward_dynamics(ctx, tree, &tau);
    Articulation {
        accelerations: fd.accelerations,
        pivots: fd.pivots,
        extra,
    }
}

/// q̈(q, q̇, τ) by the articulated-body algorithm (`emit(articulated)`).
pub struct Articulation {
    /// q̈, with the extra generalized forces as the free symbols `extra`.
    pub accelerations: Vec<Sym>,
    /// The articulated pivots D_i, for the singularity check.
    pub pivots: Vec<Sym>,
    /// Free symbols for the extra generalized forces (emitted as `tau[i]`).
    pub extra: Vec<Sym>,
}

impl Expressions for Articulation {
    fn expressions(&self, out: &mut Vec<Sym>) {
        out.extend(&self.accelerations);
        out.extend(&self.pivots);
    }
}
