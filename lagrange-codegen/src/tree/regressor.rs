//! The dynamics regressor Y on the tree, by the joints' axes carried outward
//! rather than the bodies' forces carried inward.
//!
//! τ_i is the share of joint i in the forces every body below it needs:
//! τ_i = Σ_j u_ij · f_j over the links j of i's subtree, f_j = (moment about
//! j's origin, force) from Newton–Euler in j's axes and u_ij joint i's
//! motion subspace S_i seen from link j — the unit rotation about (or slide
//! along) i's axis as a spatial motion at j's origin in j's axes. Each f_j is
//! linear in link j's ten inertial numbers (m, h = m c, I_o), so
//! u_ij · f_j = r_ij · (m, h, I_o) with r_ij = B_jᵀ u_ij, B_j the body's
//! regressor; and those ten numbers are linear in π (a link holds its own
//! body's and those fixed to it), so column k of row i is Σ_j r_ij · ∂(m, h,
//! I_o)_j/∂π_k.
//!
//! The alternative, differentiating RNEA's τ by each of π's symbols, carries
//! every one of a body's ten columns inward through each of its ancestors as
//! a spatial force (as Pinocchio's `computeJointTorqueRegressor` carries the
//! 6×10 body regressor); here one motion vector per (joint, descendant) pair
//! goes outward and meets B_j in ten short dot products, most of whose
//! factors are the zeros and ones of a unit joint axis. On the UR5 it takes
//! Y's multiplications from 1884 to 713 (635 since quarter turns are read
//! exact).

use lagrange_symbolic::{Context, Expr as Sym};

use super::link::{add3, origin, to_link, trig};
use super::rnea::accelerations;
use super::{Inertia, Link, Tree};
use crate::mat3::cross;

/// Y row by row (`rows[coordinate][k]` = ∂τ/∂π_k, `parameters[k]` = π_k),
/// τ = M q̈ + h − Q_gravity at the accelerations' symbols.
pub fn regressor(ctx: &mut Context, tree: &Tree, parameters: &[Sym]) -> Vec<Vec<Sym>> {
    let zero = ctx.zero();
    let massive: Vec<bool> = tree.links.iter().map(|l| l.inertia.is_some()).collect();
    let by_link = link_regressor(ctx, tree, &massive);
    let shares: Vec<Option<Share>> = (tree.links.iter())
        .map(|link| Some(Share::of(ctx, &link.inertia?, parameters)))
        .collect();
    let mut rows = Vec::with_capacity(by_link.len());
    for links in &by_link {
        let mut terms = vec![Vec::new(); parameters.len()];
        for (r, share) in links.iter().zip(&shares) {
            let (Some(r), Some(share)) = (r, share) else {
                continue;
            };
            for (k, d) in &share.columns {
                let products: Vec<Sym> = (0..10).map(|c| ctx.mul(r[c], d[c])).collect();
                terms[*k].push(ctx.sum(&products));
            }
        }
        rows.push(
            (terms.iter())
                .map(|t| if t.is_empty() { zero } else { ctx.sum(t) })
                .collect(),
        );
    }
    rows
}

/// The regressor by link: `rows[coordinate][j]`, where asked for by
/// `wanted[j]`, holds the coefficients of link j's ten numbers (m, h, I_o in
/// its axes, π's order) in τ at that coordinate, None where no joint of the
/// coordinate is above j.
pub fn link_regressor(
    ctx: &mut Context,
    tree: &Tree,
    wanted: &[bool],
) -> Vec<Vec<Option<[Sym; 10]>>> {
    let n = tree.links.len();
    let motion = accelerations(ctx, tree, true, true);
    let bodies: Vec<Option<[[Sym; 10]; 6]>> = (motion.iter().zip(wanted))
        .map(|(&m, &w)| w.then(|| body_regressor(ctx, m)))
        .collect();
    let mut rows: Vec<Vec<Option<[Sym; 10]>>> = vec![vec![None; n]; ctx.coordinates().len()];
    for (i, joint) in tree.links.iter().enumerate() {
        let mut seen: Vec<Option<[[Sym; 3]; 2]>> = vec![None; n];
        seen[i] = Some(axis(ctx, joint));
        // Links are ordered parents first: i's subtree is among those after
        // it, each reached from its parent's u.
        for j in i..n {
            let link = &tree.links[j];
            if j > i {
                let Some(up) = link.parent.and_then(|p| seen[p]) else {
                    continue;
                };
                seen[j] = Some(motion_to_link(ctx, link, up));
            }
            let (Some(u), Some(b)) = (seen[j], &bodies[j]) else {
                continue;
            };
            let r = body_row(ctx, u, b);
            // A coordinate that drives several joints (a mimic joint) takes
            // the sum of their shares, as in `rnea`.
            let sum = match rows[joint.coordinate][j] {
                None => r,
                Some(before) => [0, 1, 2, 3, 4, 5, 6, 7, 8, 9].map(|c| ctx.add(before[c], r[c])),
            };
            rows[joint.coordinate][j] = Some(sum);
        }
    }
    rows
}

/// How a link's ten inertial numbers depend on π: for each parameter that
/// moves them, ∂(m, h, I_o)/∂π_k — constants, mostly zeros and ones (a
/// body's own parameters map onto its link's numbers one to one).
struct Share {
    columns: Vec<(usize, [Sym; 10])>,
}

impl Share {
    fn of(ctx: &mut Context, inertia: &Inertia, parameters: &[Sym]) -> Share {
        let numbers = ten(inertia);
        let columns = (parameters.iter().enumerate())
            .filter_map(|(k, &p)| {
                let d = numbers.map(|x| ctx.diff(x, p));
                (!d.iter().all(|&x| ctx.is_zero(x))).then_some((k, d))
            })
            .collect();
        Share { columns }
    }
}

/// (m, h, I_o) in π's order for a body: m, hx, hy, hz, Ixx, Ixy, Iyy, Ixz,
/// Iyz, Izz.
pub(super) fn ten(i: &Inertia) -> [Sym; 10] {
    let [h0, h1, h2] = i.first;
    let r = &i.rot;
    [
        i.mass, h0, h1, h2, r[0][0], r[0][1], r[1][1], r[0][2], r[1][2], r[2][2],
    ]
}

/// S of a link's joint in its own axes: (e_axis, 0) for a revolute joint (or
/// an axis of a spherical one), (0, slide) for a sliding joint, whose link
/// keeps its parent's axes.
fn axis(ctx: &mut Context, link: &Link) -> [[Sym; 3]; 2] {
    let zero = ctx.zero();
    match link.slide {
        Some(dir) => [[zero; 3], dir],
        None => {
            let mut e = [zero; 3];
            e[link.axis] = ctx.one();
            [e, [zero; 3]]
        }
    }
}

/// A spatial motion (ω, v at the parent's origin, parent axes) at the link's
/// origin d in link axes: (Eᵀ ω, Eᵀ (v + ω × d)). The dual of
/// `force_to_parent`, so that u · f is the same number on either side.
fn motion_to_link(ctx: &mut Context, link: &Link, [w, v]: [[Sym; 3]; 2]) -> [[Sym; 3]; 2] {
    let cs = trig(ctx, link);
    let d = origin(ctx, link);
    let wd = cross(ctx, w, d);
    let at = add3(ctx, v, wd);
    [to_link(ctx, link, cs, w), to_link(ctx, link, cs, at)]
}

/// The body's regressor B (6 × 10) in its axes at (ω, α, a): the force
/// (moment about the origin, force) of `rnea::body_force`,
/// u_ω·(I α + ω × I ω + h × a) + u_v·(m a + α × h + ω × (ω × h)) for a
/// motion u = (u_ω, u_v), is uᵀ B (m, h, I_o). Read off that form:
/// m: u_v·a; h: a × u_ω + u_v × α + ω × (ω × u_v); I_ab (a ≤ b): p_a α_b +
/// s_a ω_b and its mirror, p = u_ω, s = u_ω × ω. Built once per link, so
/// that each (joint, link) pair costs one product per nonzero entry.
fn body_regressor(ctx: &mut Context, [w, al, a]: [[Sym; 3]; 3]) -> [[Sym; 10]; 6] {
    let zero = ctx.zero();
    let mut b = [[zero; 10]; 6];
    for l in 0..3 {
        let e = unit(ctx, l);
        // Row l of the moment rows is the coefficient of u_ω = e_l, row l
        // of the force rows that of u_v = e_l.
        let a_u = cross(ctx, a, e);
        let s = cross(ctx, e, w);
        let u_al = cross(ctx, e, al);
        let w_u = cross(ctx, w, e);
        let w_w_u = cross(ctx, w, w_u);
        b[3 + l][0] = a[l];
        for k in 0..3 {
            b[l][1 + k] = a_u[k];
            b[3 + l][1 + k] = ctx.add(u_al[k], w_w_u[k]);
        }
        for (c, (x, y)) in [(0, 0), (0, 1), (1, 1), (0, 2), (1, 2), (2, 2)]
            .into_iter()
            .enumerate()
        {
            let mut t = vec![ctx.mul(e[x], al[y]), ctx.mul(s[x], w[y])];
            if x != y {
                t.push(ctx.mul(e[y], al[x]));
                t.push(ctx.mul(s[y], w[x]));
            }
            b[l][4 + c] = ctx.sum(&t);
        }
    }
    b
}

/// e_l.
fn unit(ctx: &mut Context, l: usize) -> [Sym; 3] {
    let mut e = [ctx.zero(); 3];
    e[l] = ctx.one();
    e
}

/// r = Bᵀ u, skipping u's zeros (most of a joint axis's).
fn body_row(ctx: &mut Context, [uw, uv]: [[Sym; 3]; 2], b: &[[Sym; 10]; 6]) -> [Sym; 10] {
    let u = [uw[0], uw[1], uw[2], uv[0], uv[1], uv[2]];
    let mut r = [ctx.zero(); 10];
    for (c, out) in r.iter_mut().enumerate() {
        let mut products = Vec::new();
        for l in 0..6 {
            if !ctx.is_zero(u[l]) && !ctx.is_zero(b[l][c]) {
                products.push(ctx.mul(u[l], b[l][c]));
            }
        }
        *out = ctx.sum(&products);
    }
    r
}
