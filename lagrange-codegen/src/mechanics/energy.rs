//! The energies: V with gravity's share, T in its cheaper form, and the integral
//! of the motion (the energy, or Jacobi's integral for a rheonomic system).

use lagrange_symbolic::{Context, Expr as Sym, Program};

use super::kinematics::{Kinematics, at_zero};
use crate::mat3::dot;

/// The potential of uniform gravity, −Σ m g·ξ.
pub(super) fn gravity_potential(
    ctx: &mut Context,
    gravity: Option<&[Sym]>,
    kin: &[Kinematics],
) -> Sym {
    let mut terms = Vec::new();
    if let Some(g) = gravity {
        for k in kin {
            let gx = dot(ctx, g, &k.position);
            let mg = ctx.mul(k.mass, gx);
            terms.push(ctx.neg(mg));
        }
    }
    ctx.sum(&terms)
}

/// The user's V plus gravity's.
pub(super) fn total_potential(ctx: &mut Context, potential: Option<Sym>, gravity: Sym) -> Sym {
    let v = match potential {
        Some(v) => ctx.add(v, gravity),
        None => gravity,
    };
    ctx.collect(v)
}

/// T = ½ q̇ᵀ M q̇ for a scleronomic system, printed and emitted in M's
/// simplified form where that is the cheaper program.
pub(super) fn cheaper_kinetic(
    ctx: &mut Context,
    rheonomic: bool,
    kinetic: Sym,
    mass: &[Vec<Sym>],
) -> Sym {
    if rheonomic {
        return kinetic;
    }
    let qd = ctx.velocities();
    let from_mass = quadratic_form(ctx, mass, &qd);
    let cost = |ctx: &Context, e: Sym| Program::new(ctx, &[e]).op_count().weighted();
    if cost(ctx, from_mass) < cost(ctx, kinetic) {
        from_mass
    } else {
        kinetic
    }
}

/// T + V, or for a rheonomic system Jacobi's integral T2 − T0 + V (Suslov 32.56),
/// with T2 = ½ q̇ᵀ M q̇ and T0 = T at q̇ = 0.
pub(super) fn integral(
    ctx: &mut Context,
    rheonomic: bool,
    kinetic: Sym,
    potential: Sym,
    mass: &[Vec<Sym>],
) -> Sym {
    if !rheonomic {
        let e = ctx.add(kinetic, potential);
        return ctx.collect(e);
    }
    let qd = ctx.velocities();
    let n = qd.len();
    let t2 = {
        let mut terms = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let mv = ctx.mul(mass[i][j], qd[j]);
                terms.push(ctx.mul(qd[i], mv));
            }
        }
        let s = ctx.sum(&terms);
        let half = ctx.rational(1, 2);
        ctx.mul(half, s)
    };
    let zero_vel = at_zero(ctx, &qd);
    let t0 = ctx.substitute(kinetic, &zero_vel);
    let e = ctx.sub(t2, t0);
    let e = ctx.add(e, potential);
    ctx.collect(e)
}

/// ½ q̇ᵀ M q̇, off-diagonal pairs once.
fn quadratic_form(ctx: &mut Context, mass: &[Vec<Sym>], qd: &[Sym]) -> Sym {
    let n = qd.len();
    let mut terms = Vec::new();
    for i in 0..n {
        for j in i..n {
            if ctx.is_zero(mass[i][j]) {
                continue;
            }
            let vv = ctx.mul(qd[i], qd[j]);
            let e = ctx.mul(mass[i][j], vv);
            terms.push(if i == j { e } else { ctx.add(e, e) });
        }
    }
    let s = ctx.sum(&terms);
    let half = ctx.rational(1, 2);
    let e = ctx.mul(half, s);
    ctx.collect(e)
}
