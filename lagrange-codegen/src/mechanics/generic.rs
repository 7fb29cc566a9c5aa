//! The generic route: M = Σ Jᵀ m J (+ Σ Wᵀ I W) by differentiating ξ(q, t), and h
//! three ways — d'Alembert's projection, the Christoffel route through T, and for
//! a scleronomic system the Christoffel symbols of the derived M — of which the
//! cheapest program is kept. The others stay in the model so that tests can
//! check the routes agree.

use lagrange_symbolic::{Context, Expr as Sym, Program};

use super::kinematics::{Kinematics, Spin};
use crate::mat3::{cross, dot, mat_vec};

/// Which derivation of h the emitted code uses.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum BiasRoute {
    /// h = Σ_ν m_ν J_νᵀ κ_ν (d'Alembert's principle).
    Projection,
    /// h = d/dt ∂T/∂q̇ − ∂T/∂q with q̈ = 0 (Christoffel symbols, rheonomic terms).
    Christoffel,
    /// Recursive Newton–Euler over the kinematic tree, with M by composite rigid
    /// bodies ([`crate::tree`]).
    Recursive,
    /// h_i = Σ_jk (∂M_ij/∂q_k − ½ ∂M_jk/∂q_i) q̇_j q̇_k, the Christoffel symbols of
    /// the derived M (scleronomic systems only).
    MassMatrix,
}

/// M and h by the generic route, with the route h was kept from and the h not kept.
pub(super) struct GenericTerms {
    pub mass: Vec<Vec<Sym>>,
    pub route: BiasRoute,
    pub bias: Vec<Sym>,
    pub other: Vec<Sym>,
}

/// The weighted operation count of the program computing `outputs`.
pub(super) fn cost(ctx: &Context, outputs: &[Sym]) -> usize {
    Program::new(ctx, outputs).op_count().weighted()
}

/// M and the cheapest h.
pub(super) fn derive(
    ctx: &mut Context,
    kin: &[Kinematics],
    spin: &[Spin],
    kinetic: Sym,
    rheonomic: bool,
    zero_acc: &[(Sym, Sym)],
) -> GenericTerms {
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let n = q.len();
    let mass = mass_matrix(ctx, kin, spin, n);
    let projection = bias_projection(ctx, kin, spin, n);
    let christoffel = christoffel_bias(ctx, kinetic, &q, &qd, zero_acc);
    let (route, bias, other) = if cost(ctx, &projection) <= cost(ctx, &christoffel) {
        (BiasRoute::Projection, projection, christoffel)
    } else {
        (BiasRoute::Christoffel, christoffel, projection)
    };
    // M's entries come out simplified (sin² + cos² folded, cyclic
    // coordinates gone) where T's velocity products do not: for a
    // scleronomic system h from M's Christoffel symbols keeps that form.
    if !rheonomic {
        let from_mass = bias_from_mass(ctx, &mass, &q, &qd);
        if cost(ctx, &from_mass) < cost(ctx, &bias) {
            return GenericTerms {
                mass,
                route: BiasRoute::MassMatrix,
                bias: from_mass,
                other: bias,
            };
        }
    }
    GenericTerms {
        mass,
        route,
        bias,
        other,
    }
}

/// M_ij = Σ_ν m_ν (J_ν)_·iᵀ (J_ν)_·j + Σ_bodies W_iᵀ I W_j, then factored so common
/// factors are computed once.
fn mass_matrix(ctx: &mut Context, kin: &[Kinematics], spin: &[Spin], n: usize) -> Vec<Vec<Sym>> {
    let mut m = vec![vec![ctx.zero(); n]; n];
    for i in 0..n {
        for j in i..n {
            let mut terms: Vec<Sym> = kin
                .iter()
                .map(|k| {
                    let ci: Vec<Sym> = k.jacobian.iter().map(|row| row[i]).collect();
                    let cj: Vec<Sym> = k.jacobian.iter().map(|row| row[j]).collect();
                    let d = dot(ctx, &ci, &cj);
                    ctx.mul(k.mass, d)
                })
                .collect();
            for s in spin {
                let iw = mat_vec(ctx, &s.inertia, s.jacobian[j]);
                terms.push(dot(ctx, &s.jacobian[i], &iw));
            }
            let s = ctx.sum(&terms);
            let s = ctx.collect(s);
            let s = simplest_entry(ctx, s);
            m[i][j] = s;
            m[j][i] = s;
        }
    }
    m
}

/// Entries up to this DAG size are also tried expanded (see [`simplest_entry`]).
const EXPAND_ENTRIES_UP_TO: usize = 400;

/// The cheapest of an entry as derived, expanded and collected (where
/// sin² + cos² = 1 meets the squares of the Jacobian's sums of products:
/// m₂((l₁ cos a + l₂ cos(a+b))² + (…)²) becomes m₂(l₁² + l₂² + 2 l₁ l₂ cos b)),
/// and that with angle sums folded.
fn simplest_entry(ctx: &mut Context, e: Sym) -> Sym {
    if ctx.node_count(e) > EXPAND_ENTRIES_UP_TO {
        return e;
    }
    let expanded = ctx.expand(e);
    let collected = ctx.collect(expanded);
    let folded = ctx.fold_angle_sums(collected);
    [collected, folded].into_iter().fold(e, |best, c| {
        if entry_cost(ctx, c) < entry_cost(ctx, best) {
            c
        } else {
            best
        }
    })
}

/// Operations of an entry's program, with sines and cosines of bare
/// coordinates free (every program computes those once anyway) and any other
/// call at the weight of a call.
fn entry_cost(ctx: &Context, e: Sym) -> usize {
    let ops = Program::new(ctx, &[e]).op_count();
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![e];
    let mut compound_calls = 0;
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        let node = ctx.node(x);
        if let lagrange_symbolic::Node::Call(_, a) = node
            && ctx.as_symbol(*a).is_none()
        {
            compound_calls += 1;
        }
        stack.extend(node.children());
    }
    ops.add + ops.mul + 4 * ops.div + 20 * compound_calls
}

/// h_i = Σ_ν m_ν (J_ν)_·iᵀ κ_ν + Σ_bodies W_iᵀ (I κ_ω + ω × I ω) (Euler's equations
/// projected onto the coordinates).
fn bias_projection(ctx: &mut Context, kin: &[Kinematics], spin: &[Spin], n: usize) -> Vec<Sym> {
    let euler: Vec<[Sym; 3]> = spin
        .iter()
        .map(|s| {
            let kappa = s.kappa.expect("the generic route derives each body's κ_ω");
            let ik = mat_vec(ctx, &s.inertia, kappa);
            let iw = mat_vec(ctx, &s.inertia, s.omega);
            let gyro = cross(ctx, s.omega, iw);
            [0, 1, 2].map(|c| ctx.add(ik[c], gyro[c]))
        })
        .collect();
    (0..n)
        .map(|i| {
            let mut terms: Vec<Sym> = kin
                .iter()
                .map(|k| {
                    let ci: Vec<Sym> = k.jacobian.iter().map(|row| row[i]).collect();
                    let d = dot(ctx, &ci, &k.kappa);
                    ctx.mul(k.mass, d)
                })
                .collect();
            for (s, e) in spin.iter().zip(&euler) {
                terms.push(dot(ctx, &s.jacobian[i], e));
            }
            let s = ctx.sum(&terms);
            ctx.collect(s)
        })
        .collect()
}

/// h_i = d/dt ∂T/∂q̇_i − ∂T/∂q_i at q̈ = 0.
fn christoffel_bias(
    ctx: &mut Context,
    kinetic: Sym,
    q: &[Sym],
    qd: &[Sym],
    zero_acc: &[(Sym, Sym)],
) -> Vec<Sym> {
    euler_lagrange(ctx, kinetic, (q, qd), Some(zero_acc))
}

/// d/dt ∂L/∂q̇_i − ∂L/∂q_i for every i, with q̈'s symbols where the rates of
/// q̇ appear, or zero for them given `zero_acc`.
pub(super) fn euler_lagrange(
    ctx: &mut Context,
    lagrangian: Sym,
    (q, qd): (&[Sym], &[Sym]),
    zero_acc: Option<&[(Sym, Sym)]>,
) -> Vec<Sym> {
    (0..q.len())
        .map(|i| {
            let p = ctx.diff(lagrangian, qd[i]);
            let dp = ctx.time_derivative(p);
            let dp = zero_acc.map_or(dp, |zero| ctx.substitute(dp, zero));
            let dq = ctx.diff(lagrangian, q[i]);
            let h = ctx.sub(dp, dq);
            ctx.collect(h)
        })
        .collect()
}

/// h_i = Σ_{j≤k} c_ijk q̇_j q̇_k with c_ijk = ∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i
/// (halved on the diagonal j = k): the Christoffel symbols of M, for T = ½ q̇ᵀ M q̇.
fn bias_from_mass(ctx: &mut Context, mass: &[Vec<Sym>], q: &[Sym], qd: &[Sym]) -> Vec<Sym> {
    let n = q.len();
    // d[k][i][j] = ∂M_ij/∂q_k, the same node at (i, j) and (j, i).
    let mut d = vec![vec![vec![ctx.zero(); n]; n]; n];
    for (k, dk) in d.iter_mut().enumerate() {
        for i in 0..n {
            for j in i..n {
                let e = ctx.diff(mass[i][j], q[k]);
                dk[i][j] = e;
                dk[j][i] = e;
            }
        }
    }
    let half = ctx.rational(1, 2);
    (0..n)
        .map(|i| {
            let mut terms = Vec::new();
            for j in 0..n {
                for k in j..n {
                    let c = ctx.sum(&[d[k][i][j], d[j][i][k]]);
                    let c = ctx.sub(c, d[i][j][k]);
                    let c = if j == k { ctx.mul(half, c) } else { c };
                    let c = ctx.collect(c);
                    if ctx.is_zero(c) {
                        continue;
                    }
                    let vv = ctx.mul(qd[j], qd[k]);
                    terms.push(ctx.mul(c, vv));
                }
            }
            let h = ctx.sum(&terms);
            ctx.collect(h)
        })
        .collect()
}
