//! Per-point and per-body kinematics, and the kinetic energy they give.
//!
//! sin/cos of sums of coordinates are expanded into products of sin/cos of the
//! coordinates themselves, so an n-link chain costs ~2n transcendental calls.
//! The Jacobians and κ are only needed by the generic route.

use lagrange_symbolic::{Context, Expr as Sym};

use crate::lowered::{PointModel, SpinModel};
use crate::mat3::{Mat3, dot, mat_vec};

/// Per-point kinematics: ξ, ξ̇, J = ∂ξ/∂q, ∂ξ/∂t and κ = ξ̈ − J q̈.
pub(super) struct Kinematics {
    pub mass: Sym,
    pub velocity: Vec<Sym>,
    pub jacobian: Vec<Vec<Sym>>, // [component][coordinate]
    pub partial_t: Vec<Sym>,
    pub kappa: Vec<Sym>,
    pub position: Vec<Sym>,
}

/// Per-body rotational kinematics: ω = W q̇ + w_t, W = ∂ω/∂q̇, and κ_ω = ω̇ − W q̈.
pub(super) struct Spin {
    pub inertia: Mat3,
    pub omega: [Sym; 3],
    /// W = ∂ω/∂q̇ and κ_ω = ω̇ at q̈ = 0: derived for the generic route only
    /// (empty and `None` otherwise).
    pub jacobian: Vec<[Sym; 3]>, // [coordinate][component]
    pub kappa: Option<[Sym; 3]>,
}

/// The substitution of zero for each of `symbols`.
pub(super) fn at_zero(ctx: &mut Context, symbols: &[Sym]) -> Vec<(Sym, Sym)> {
    let z = ctx.zero();
    symbols.iter().map(|&a| (a, z)).collect()
}

/// The kinematics of every point and body, whether the system is rheonomic,
/// and T.
pub(super) fn derive(
    ctx: &mut Context,
    point_models: &[PointModel],
    spin_models: &[SpinModel],
    generic: bool,
    zero_acc: &[(Sym, Sym)],
) -> (Vec<Kinematics>, Vec<Spin>, bool, Sym) {
    let kin = points(ctx, point_models, generic, zero_acc);
    let qd = ctx.velocities();
    let zero_vel = at_zero(ctx, &qd);
    let spin = spins(ctx, spin_models, generic, zero_acc);
    let rheonomic = is_rheonomic(ctx, &kin, &spin, &zero_vel);
    let kinetic = kinetic_energy(ctx, &kin, &spin);
    (kin, spin, rheonomic, kinetic)
}

/// ξ, ξ̇ and ∂ξ/∂t of every point, with J and κ where the generic route needs them.
fn points(
    ctx: &mut Context,
    points: &[PointModel],
    generic: bool,
    zero_acc: &[(Sym, Sym)],
) -> Vec<Kinematics> {
    let q = ctx.coordinates();
    let t = ctx.time();
    points
        .iter()
        .map(|p| {
            let position: Vec<Sym> = p.position.iter().map(|&x| ctx.expand_trig(x)).collect();
            let velocity: Vec<Sym> = position.iter().map(|&x| ctx.time_derivative(x)).collect();
            let jacobian = if generic {
                position
                    .iter()
                    .map(|&x| q.iter().map(|&qi| ctx.diff(x, qi)).collect())
                    .collect()
            } else {
                Vec::new()
            };
            let partial_t = position.iter().map(|&x| ctx.diff(x, t)).collect();
            let kappa = if generic {
                velocity
                    .iter()
                    .map(|&v| {
                        let a = ctx.time_derivative(v);
                        ctx.substitute(a, zero_acc)
                    })
                    .collect()
            } else {
                Vec::new()
            };
            Kinematics {
                mass: p.mass,
                velocity,
                jacobian,
                partial_t,
                kappa,
                position,
            }
        })
        .collect()
}

/// ω of every body, and W and κ_ω where the generic route needs them.
fn spins(
    ctx: &mut Context,
    spins: &[SpinModel],
    generic: bool,
    zero_acc: &[(Sym, Sym)],
) -> Vec<Spin> {
    let qd = ctx.velocities();
    spins
        .iter()
        .map(|b| {
            let omega = b.omega.map(|w| ctx.expand_trig(w));
            // J_ω and κ_ω serve the generic route only; an explicit matrix's
            // ω = vee(RᵀṘ) is large, and its rate the costliest derivative
            // of a written-out tree.
            if !generic {
                return Spin {
                    inertia: b.inertia,
                    omega,
                    jacobian: Vec::new(),
                    kappa: None,
                };
            }
            let jacobian = qd.iter().map(|&v| omega.map(|w| ctx.diff(w, v))).collect();
            let kappa = omega.map(|w| {
                let a = ctx.time_derivative(w);
                ctx.substitute(a, zero_acc)
            });
            Spin {
                inertia: b.inertia,
                omega,
                jacobian,
                kappa: Some(kappa),
            }
        })
        .collect()
}

/// Whether a point moves, or a body turns, with the velocities at zero.
fn is_rheonomic(
    ctx: &mut Context,
    kin: &[Kinematics],
    spin: &[Spin],
    zero_vel: &[(Sym, Sym)],
) -> bool {
    kin.iter()
        .any(|k| k.partial_t.iter().any(|&x| !ctx.is_zero(x)))
        || spin.iter().any(|s| {
            s.omega.iter().any(|&w| {
                let w0 = ctx.substitute(w, zero_vel);
                !ctx.is_zero(w0)
            })
        })
}

/// T = ½ Σ m |ξ̇|² + ½ Σ ωᵀ I ω.
fn kinetic_energy(ctx: &mut Context, kin: &[Kinematics], spin: &[Spin]) -> Sym {
    let mut terms: Vec<Sym> = kin
        .iter()
        .map(|k| {
            let sq = dot(ctx, &k.velocity, &k.velocity);
            ctx.mul(k.mass, sq)
        })
        .collect();
    for s in spin {
        let iw = mat_vec(ctx, &s.inertia, s.omega);
        terms.push(dot(ctx, &s.omega, &iw));
    }
    let s = ctx.sum(&terms);
    let half = ctx.rational(1, 2);
    let e = ctx.mul(half, s);
    ctx.collect(e)
}
