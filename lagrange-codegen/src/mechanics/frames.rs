//! `emit(kinematics)`: for every body's frame, the geometric Jacobian at its
//! origin in world-aligned axes (the origin's velocity, then the angular
//! velocity: Pinocchio's `LOCAL_WORLD_ALIGNED`) and J̇ q̇, the frame's
//! classical acceleration at q̈ = 0; and the centre of mass of the moving
//! masses with its Jacobian.
//! All at a fixed time (a rheonomic description's ∂/∂t terms are left out).

use lagrange_symbolic::{Context, Expr as Sym};

use crate::lowered::Poses;
use crate::mat3::Mat3;

/// Per body, J (6 × N, row-major) and J̇ q̇ (6); the centre of mass (3) and its
/// Jacobian (3 × N, row-major).
pub struct Frames {
    /// Per body, J (6 × N, row-major): rows 0–2 the reference point's velocity,
    /// rows 3–5 the angular velocity, world axes.
    pub jacobians: Vec<Vec<Sym>>,
    /// Per body, J̇ q̇ (6), in the rows of J.
    pub biases: Vec<Vec<Sym>>,
    /// The system's centre of mass, world axes.
    pub com: Vec<Sym>,
    /// The centre of mass's Jacobian (3 × N, row-major).
    pub com_jacobian: Vec<Sym>,
}

/// A position padded to three components (planar descriptions have two).
fn three(ctx: &mut Context, x: &[Sym]) -> [Sym; 3] {
    let zero = ctx.zero();
    [0, 1, 2].map(|i| x.get(i).copied().unwrap_or(zero))
}

/// ∂x/∂q as rows of N.
fn jacobian(ctx: &mut Context, x: &[Sym; 3], q: &[Sym]) -> [Vec<Sym>; 3] {
    [0, 1, 2].map(|i| q.iter().map(|&qk| ctx.diff(x[i], qk)).collect())
}

/// The columns vee(∂R/∂q_k Rᵀ): the angular velocity per unit rate of q_k.
fn angular(ctx: &mut Context, r: &Mat3, q: &[Sym]) -> [Vec<Sym>; 3] {
    let mut rows: [Vec<Sym>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    for &qk in q {
        let dr: Mat3 = r.map(|row| row.map(|e| ctx.diff(e, qk)));
        // W = dR Rᵀ is skew; ω = (W₂₁, W₀₂, W₁₀).
        let w = |ctx: &mut Context, a: usize, b: usize| {
            let terms: Vec<Sym> = (0..3).map(|k| ctx.mul(dr[a][k], r[b][k])).collect();
            ctx.sum(&terms)
        };
        let col = [w(ctx, 2, 1), w(ctx, 0, 2), w(ctx, 1, 0)];
        for (row, c) in rows.iter_mut().zip(col) {
            row.push(c);
        }
    }
    rows
}

/// J̇ q̇ as the frame's classical acceleration at q̈ = 0: p̈ = D(D(p)) for the
/// origin, and for the angular part the skew matrix d(Ṙ Rᵀ)/dt = R̈ Rᵀ +
/// Ṙ Ṙᵀ read as a vector, with D the derivative along (q → q̇) in one
/// forward pass each.
fn accelerations(ctx: &mut Context, p: &[Sym; 3], r: &Mat3, q: &[Sym], v: &[Sym]) -> Vec<Sym> {
    let direction: Vec<(Sym, Sym)> = q.iter().copied().zip(v.iter().copied()).collect();
    let d = |ctx: &mut Context, e: Sym| ctx.directional(e, &direction);
    let linear: Vec<Sym> = p
        .iter()
        .map(|&x| {
            let dx = d(ctx, x);
            d(ctx, dx)
        })
        .collect();
    let rd: Mat3 = r.map(|row| row.map(|e| d(ctx, e)));
    let rdd: Mat3 = rd.map(|row| row.map(|e| d(ctx, e)));
    // (R̈ Rᵀ + Ṙ Ṙᵀ)_ab.
    let w = |ctx: &mut Context, a: usize, b: usize| {
        let terms: Vec<Sym> = (0..3)
            .flat_map(|k| [(rdd[a][k], r[b][k]), (rd[a][k], rd[b][k])])
            .map(|(x, y)| ctx.mul(x, y))
            .collect();
        ctx.sum(&terms)
    };
    let angular = [w(ctx, 2, 1), w(ctx, 0, 2), w(ctx, 1, 0)];
    linear.into_iter().chain(angular).collect()
}

/// The frames' Jacobians and biases and the centre of mass of `particles`
/// (mass, position), bodies' centres included.
pub(super) fn frames(ctx: &mut Context, poses: &Poses, particles: &[(Sym, Vec<Sym>)]) -> Frames {
    let q = ctx.coordinates();
    let v = ctx.velocities();
    let mut jacobians = Vec::new();
    let mut biases = Vec::new();
    for body in &poses.bodies {
        let origin = three(ctx, &body.origin);
        let [l0, l1, l2] = jacobian(ctx, &origin, &q);
        let [a0, a1, a2] = angular(ctx, &body.rotation, &q);
        let rows = [l0, l1, l2, a0, a1, a2];
        biases.push(accelerations(ctx, &origin, &body.rotation, &q, &v));
        jacobians.push(rows.concat());
    }
    // The moving masses: a mass fixed in space (a robot's base) moves with
    // nothing, and Pinocchio's centre of mass leaves it out too. A body moves
    // when its origin or its axes do (its centre may stay put on a joint's
    // axis).
    let moves = |ctx: &Context, e: Sym| {
        let free = ctx.free_symbols(e);
        q.iter()
            .any(|&qk| ctx.as_symbol(qk).is_some_and(|s| free.contains(&s)))
    };
    let moving_centres: Vec<&Vec<Sym>> = poses
        .bodies
        .iter()
        .filter(|b| {
            b.origin
                .iter()
                .chain(b.rotation.iter().flatten())
                .any(|&e| moves(ctx, e))
        })
        .map(|b| &b.centre)
        .collect();
    let particles: Vec<&(Sym, Vec<Sym>)> = particles
        .iter()
        .filter(|(_, x)| x.iter().any(|&e| moves(ctx, e)) || moving_centres.contains(&x))
        .collect();
    let masses: Vec<Sym> = particles.iter().map(|(m, _)| *m).collect();
    let total = ctx.sum(&masses);
    let inverse = ctx.powi(total, -1);
    let com: [Sym; 3] = [0, 1, 2].map(|i| {
        let terms: Vec<Sym> = particles
            .iter()
            .map(|(m, x)| {
                let x = x.get(i).copied().unwrap_or_else(|| ctx.zero());
                ctx.mul(*m, x)
            })
            .collect();
        let moment = ctx.sum(&terms);
        ctx.mul(moment, inverse)
    });
    let com_jacobian = jacobian(ctx, &com, &q).concat();
    Frames {
        jacobians,
        biases,
        com: com.to_vec(),
        com_jacobian,
    }
}
