//! Optional outputs over the derived M and Q − h: the Coriolis matrix, the
//! right-hand side's Jacobians, and the momentum and ∂T/∂q of the Hamiltonian
//! methods.

use lagrange_symbolic::{Context, Expr as Sym};

use super::expressions::{Expressions, entries};

/// Hamilton's form (`emit(hamiltonian)`), or the momentum alone of a
/// rheonomic system (where the runtime's default M q̇ would be wrong).
pub struct Hamilton {
    /// p = ∂T/∂q̇.
    pub momentum: Vec<Sym>,
    /// ∂T/∂q at fixed q̇ (with orientations: at fixed ω), with
    /// `emit(hamiltonian)`.
    pub kinetic_gradient: Option<Vec<Sym>>,
}

impl Expressions for Hamilton {
    fn expressions(&self, out: &mut Vec<Sym>) {
        out.extend(&self.momentum);
        out.extend(self.kinetic_gradient.iter().flatten());
    }
}

/// C(q, q̇) with C_ij = Σ_k Γ_ijk q̇_k (`emit(coriolis)`).
pub struct Coriolis {
    /// N × N, row-major.
    pub matrix: Vec<Vec<Sym>>,
}

impl Expressions for Coriolis {
    fn expressions(&self, out: &mut Vec<Sym>) {
        entries(out, [&self.matrix]);
    }
}

/// p = ∂T/∂q̇.
pub(super) fn momentum(ctx: &mut Context, kinetic: Sym) -> Vec<Sym> {
    ctx.velocities()
        .iter()
        .map(|&v| {
            let p = ctx.diff(kinetic, v);
            ctx.collect(p)
        })
        .collect()
}

/// ∂T/∂q at fixed q̇.
pub(super) fn kinetic_gradient(ctx: &mut Context, kinetic: Sym) -> Vec<Sym> {
    ctx.coordinates()
        .iter()
        .map(|&x| {
            let g = ctx.diff(kinetic, x);
            ctx.collect(g)
        })
        .collect()
}

/// What is read off T as written in the orientations' θ (the recursive
/// route builds M at the chart's centre, and T is later rewritten from that
/// M): M, when `emit(coriolis)` needs its derivatives there, and ∂T/∂θ for
/// `emit(hamiltonian)`.
#[allow(clippy::type_complexity)]
pub(super) fn in_chart(
    ctx: &mut Context,
    extras: &[crate::ast::Extra],
    free: bool,
    kinetic: Sym,
) -> (Option<Vec<Vec<Sym>>>, Option<Vec<Sym>>) {
    let wants = |e| free && extras.contains(&e);
    let mass = wants(crate::ast::Extra::Coriolis).then(|| mass_from_kinetic(ctx, kinetic));
    let gradient = wants(crate::ast::Extra::Hamiltonian).then(|| kinetic_gradient(ctx, kinetic));
    (mass, gradient)
}

/// M_ij = ∂²T/∂q̇_i∂q̇_j: the mass matrix read off the kinetic energy, in
/// whatever coordinates T is written (a free orientation's θ chart, where
/// the recursive route builds M at the centre only).
pub(super) fn mass_from_kinetic(ctx: &mut Context, kinetic: Sym) -> Vec<Vec<Sym>> {
    let qd = ctx.velocities();
    let momentum: Vec<Sym> = qd.iter().map(|&v| ctx.diff(kinetic, v)).collect();
    momentum
        .iter()
        .map(|&p| {
            qd.iter()
                .map(|&v| {
                    let m = ctx.diff(p, v);
                    ctx.collect(m)
                })
                .collect()
        })
        .collect()
}

/// C_ij = Σ_k Γ_ijk q̇_k with Γ_ijk = ½(∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i): the
/// factorisation of the Christoffel terms for which Ṁ − 2C is skew-symmetric.
pub(super) fn coriolis_matrix(
    ctx: &mut Context,
    mass: &[Vec<Sym>],
    q: &[Sym],
    qd: &[Sym],
) -> Vec<Vec<Sym>> {
    let n = q.len();
    let half = ctx.rational(1, 2);
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let terms: Vec<Sym> = (0..n)
                        .map(|k| {
                            let a = ctx.diff(mass[i][j], q[k]);
                            let b = ctx.diff(mass[i][k], q[j]);
                            let c = ctx.diff(mass[j][k], q[i]);
                            let g = ctx.add(a, b);
                            let g = ctx.sub(g, c);
                            let g = ctx.mul(half, g);
                            ctx.mul(g, qd[k])
                        })
                        .collect();
                    let s = ctx.sum(&terms);
                    ctx.collect(s)
                })
                .collect()
        })
        .collect()
}

/// p = ∂T/∂q̇ (for Hamilton's form or a rheonomic system) and, for
/// Hamilton's form, ∂T/∂q: with orientations from T in their θ, at fixed ω.
pub(super) fn hamilton_form(
    ctx: &mut Context,
    d: &mut super::Derived,
    hamiltonian: bool,
) -> Option<Hamilton> {
    let kinetic = d.energies.kinetic;
    if !(hamiltonian || d.motion.rheonomic) {
        return None;
    }
    let momentum = momentum(ctx, kinetic);
    let slots = (
        d.variables.coordinates.len(),
        d.variables.orientations.len(),
    );
    let kinetic_gradient = hamiltonian.then(|| match d.chart_gradient.take() {
        Some(g) => super::chart::at_fixed_omega(ctx, g, &momentum, slots),
        None => kinetic_gradient(ctx, kinetic),
    });
    Some(Hamilton {
        momentum,
        kinetic_gradient,
    })
}

/// C: with orientations, the chart's Christoffel factorisation turned along
/// the motion (`super::chart::along_the_motion`); otherwise M's, if wanted.
pub(super) fn coriolis(
    ctx: &mut Context,
    in_theta: Option<Vec<Vec<Sym>>>,
    mass: &[Vec<Sym>],
    wanted: bool,
    (first, orientations): (usize, usize),
) -> Option<Coriolis> {
    let matrix = match in_theta {
        Some(c) => Some(super::chart::along_the_motion(
            ctx,
            c,
            mass,
            first,
            orientations,
        )),
        None => wanted.then(|| {
            let q = ctx.coordinates();
            let qd = ctx.velocities();
            coriolis_matrix(ctx, mass, &q, &qd)
        }),
    };
    matrix.map(|matrix| Coriolis { matrix })
}
