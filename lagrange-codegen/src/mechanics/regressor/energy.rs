//! Each inertial parameter's share of the energies, T_k and V_k with
//! T = Σ T_k π_k and V_gravity = Σ V_k π_k: the energy regressor's entries
//! T_k + V_k, the momentum regressor's columns ∂T_k/∂q̇, and the Lagrangian
//! T_k − V_k whose Euler–Lagrange operator is Y's column on the generic
//! route.

use lagrange_symbolic::{Context, Expr as Sym};

use crate::mat3::{Mat3, cross, dot, mat_vec, transpose};

/// One parameter's share of the energies.
#[derive(Clone, Copy)]
pub(super) struct Column {
    /// T_k.
    pub kinetic: Sym,
    /// g·(what π_k weighs) = −V_k: zero without gravity, and for the
    /// parameters of rotational inertia.
    pub lift: Sym,
    /// T_k + V_k, Y_E's entry.
    pub energy: Sym,
}

impl Column {
    /// The column's Lagrangian T_k − V_k.
    pub fn lagrangian(&self, ctx: &mut Context) -> Sym {
        ctx.add(self.kinetic, self.lift)
    }
}

/// A point mass's column: T = ½ |ṗ|², V = −g·p.
pub(super) fn point(ctx: &mut Context, p: &[Sym], gravity: Option<&[Sym]>) -> Column {
    let rate: Vec<Sym> = p.iter().map(|&x| ctx.time_derivative(x)).collect();
    let squared = dot(ctx, &rate, &rate);
    let half = ctx.rational(1, 2);
    let kinetic = ctx.mul(half, squared);
    match gravity {
        Some(g) => {
            let lift = dot(ctx, g, p);
            Column {
                kinetic,
                lift,
                energy: ctx.sub(kinetic, lift),
            }
        }
        None => Column {
            kinetic,
            lift: ctx.zero(),
            energy: kinetic,
        },
    }
}

/// A body's ten columns, from its reference point o (world), its rotation R
/// and ω in its axes: T = ½ m |v_o|² + (m c)·(v × ω) + ½ ωᵀ I ω with
/// v = Rᵀ v_o, and V = −m g·o − (m c)·(Rᵀ g).
pub(super) fn body(
    ctx: &mut Context,
    (origin, rotation): (&[Sym], &Mat3),
    w: [Sym; 3],
    gravity: Option<&[Sym]>,
) -> [Column; 10] {
    let mass = point(ctx, origin, gravity);
    let rate: Vec<Sym> = origin.iter().map(|&x| ctx.time_derivative(x)).collect();
    let body_axes = transpose(rotation);
    let v = mat_vec(ctx, &body_axes, [rate[0], rate[1], rate[2]]);
    let moving = cross(ctx, v, w);
    let zero = ctx.zero();
    let mut first = moving.map(|kinetic| Column {
        kinetic,
        lift: zero,
        energy: kinetic,
    });
    if let Some(g) = gravity {
        let down = mat_vec(ctx, &body_axes, [g[0], g[1], g[2]]);
        for (c, lift) in first.iter_mut().zip(down) {
            c.lift = lift;
            c.energy = ctx.sub(c.kinetic, lift);
        }
    }
    let half = ctx.rational(1, 2);
    let mut product = |a: usize, b: usize| {
        let p = ctx.mul(w[a], w[b]);
        let kinetic = if a == b { ctx.mul(half, p) } else { p };
        Column {
            kinetic,
            lift: zero,
            energy: kinetic,
        }
    };
    let [xx, xy, yy, xz, yz, zz] =
        [(0, 0), (0, 1), (1, 1), (0, 2), (1, 2), (2, 2)].map(|(a, b)| product(a, b));
    [mass, first[0], first[1], first[2], xx, xy, yy, xz, yz, zz]
}

/// The momentum regressor: `rows[i][k]` = ∂T_k/∂q̇_i, so that
/// p = ∂T/∂q̇ = Y_p π. T_k's sines and cosines of sums are expanded first,
/// as the kinematics' are, so a chain's rows call ~2n of them.
pub(super) fn momentum(ctx: &mut Context, columns: &[Column]) -> Vec<Vec<Sym>> {
    let qd = ctx.velocities();
    let kinetic: Vec<Sym> = columns.iter().map(|c| ctx.expand_trig(c.kinetic)).collect();
    qd.iter()
        .map(|&v| kinetic.iter().map(|&t| ctx.diff(t, v)).collect())
        .collect()
}
