//! The linearisation derivatives `emit(jacobians)` adds to the constrained forms:
//! `Constrained::constraint_derivatives` and `Reduced::row_derivatives`, each
//! against central differences of what the always-emitted methods compute, at
//! random states (which need not satisfy the constraints: the derivatives are
//! identities in q, q̇), and the reduced linearisation composed from them.

#![allow(clippy::needless_range_loop)] // index loops mirror the formulas

use crate::common;

use common::numeric::{Lcg, close, fd};
use lagrange::prelude::*;
use nalgebra::{SMatrix, SVector};

/// A spherical pendulum in Cartesian coordinates whose thread length oscillates
/// (so g = Φ_t ≠ 0 and γ has time terms), with some damping.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    point(bob, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    dissipation = c * ((dot(x)^2) + (dot(y)^2)) / 2,
    holonomic(thread = (bob.x^2) + (bob.y^2) + (bob.z^2) - ((l + a * sin(w * t))^2)),
    emit(jacobians),
)]
struct Bob {
    m: f64,
    g: f64,
    c: f64,
    l: f64,
    a: f64,
    w: f64,
}

const BOB: Bob = Bob {
    m: 1.3,
    g: 9.81,
    c: 0.2,
    l: 1.1,
    a: 0.15,
    w: 2.0,
};

/// The Chaplygin sleigh in a harmonic well, with a damped turn: nonholonomic,
/// in both forms.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, theta),
    body(sled, mass = m, inertia = [0, 0, i], at = [x + b * cos(theta), y + b * sin(theta), 0],
         rotation = rot_z(theta)),
    point(blade, on = sled, at = [-b, 0, 0]),
    potential = k * (sled.x^2) / 2 + k * (sled.y^2) / 2,
    dissipation = c * (dot(theta)^2) / 2,
    nonholonomic(sideways = -sin(theta) * dot(blade.x) + cos(theta) * dot(blade.y)),
    speeds(forward = cos(theta) * dot(blade.x) + sin(theta) * dot(blade.y), turn = dot(theta)),
    formulation(reduced, multipliers),
    emit(jacobians),
)]
struct Sleigh {
    m: f64,
    i: f64,
    b: f64,
    k: f64,
    c: f64,
}

const SLEIGH: Sleigh = Sleigh {
    m: 2.0,
    i: 0.4,
    b: 0.3,
    k: 1.5,
    c: 0.1,
};

/// The same pendulum without `emit(jacobians)`: the runtime's default, `None`.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    point(bob, mass = m, at = [x, y, z]),
    holonomic(thread = (bob.x^2) + (bob.y^2) + (bob.z^2) - 1),
)]
struct Plain {
    m: f64,
}

/// Gᵀν, γ − G a, γ and G q̇ + g from `constraint_jacobian` and `constraint_rhs`,
/// differentiated numerically, against `constraint_derivatives`.
fn check_constraint_derivatives<S, const N: usize, const K: usize>(sys: &S, seed: u64)
where
    S: Constrained<f64, N, K>,
{
    let mut rng = Lcg(seed);
    for _ in 0..8 {
        let q: SVector<f64, N> = rng.vector(1.5);
        let v: SVector<f64, N> = rng.vector(2.0);
        let a: SVector<f64, N> = rng.vector(3.0);
        let nu: SVector<f64, K> = rng.vector(2.0);
        let t = rng.next();
        let (d_gnu, d_res, d_gamma, d_vel) = sys
            .constraint_derivatives(&q, &v, &a, &nu, t)
            .expect("emitted with emit(jacobians)");
        let g = |q: &SVector<f64, N>| sys.constraint_jacobian(q, t);
        close(&d_gnu, &fd(|q| g(q).0.transpose() * nu, &q), 1e-6);
        close(
            &d_res,
            &fd(|q| sys.constraint_rhs(q, &v, t) - g(q).0 * a, &q),
            1e-6,
        );
        close(&d_gamma, &fd(|v| sys.constraint_rhs(&q, v, t), &v), 1e-6);
        close(
            &d_vel,
            &fd(
                |q| {
                    let (gm, g0) = g(q);
                    gm * v + g0
                },
                &q,
            ),
            1e-6,
        );
    }
}

#[test]
fn holonomic_constraint_derivatives() {
    check_constraint_derivatives(&BOB, 1);
}

#[test]
fn nonholonomic_constraint_derivatives() {
    check_constraint_derivatives(&SLEIGH, 2);
}

#[test]
fn without_emit_jacobians_there_are_none() {
    let p = Plain { m: 1.0 };
    let (q, v) = (SVector::<f64, 3>::new(1.0, 0.0, 0.0), SVector::zeros());
    let nu = SVector::<f64, 1>::zeros();
    assert!(p.constraint_derivatives(&q, &v, &v, &nu, 0.0).is_none());
}

/// Aᵀν, c − A a, c and A q̇ + b from `velocity_rows` and `row_rates`,
/// differentiated numerically, against `row_derivatives`.
#[test]
fn reduced_row_derivatives_match_central_differences() {
    let sys = SLEIGH;
    let mut rng = Lcg(3);
    for _ in 0..8 {
        let q: SVector<f64, 3> = rng.vector(1.5);
        let v: SVector<f64, 3> = rng.vector(2.0);
        let a: SVector<f64, 3> = rng.vector(3.0);
        let nu: SVector<f64, 3> = rng.vector(2.0);
        let t = rng.next();
        let (d_anu, d_res, d_rate, d_vel) = sys
            .row_derivatives(&q, &v, &a, &nu, t)
            .expect("emitted with emit(jacobians)");
        let rows = |q: &SVector<f64, 3>| sys.velocity_rows(q, t);
        close(&d_anu, &fd(|q| rows(q).0.transpose() * nu, &q), 1e-6);
        close(
            &d_res,
            &fd(|q| sys.row_rates(q, &v, t) - rows(q).0 * a, &q),
            1e-6,
        );
        close(&d_rate, &fd(|v| sys.row_rates(&q, v, t), &v), 1e-6);
        close(
            &d_vel,
            &fd(
                |q| {
                    let (am, b) = rows(q);
                    am * v + b
                },
                &q,
            ),
            1e-6,
        );
    }
}

/// The reduced linearisation, composed at run time from `rhs_jacobians` and
/// `row_derivatives` through the pivoted solve of the rows, against central
/// differences of (q, u) ↦ (q̇, u̇) away from equilibrium, at headings that
/// include θ = 0, π/2 and π (where a symbolic solve for ẋ or ẏ divides by zero).
#[test]
fn reduced_linearisation_matches_central_differences() {
    let sys = SLEIGH;
    let dynamics = ReducedDynamics::<_, f64, 2>::new(&sys);
    let mut rng = Lcg(5);
    let headings = [
        0.0,
        std::f64::consts::FRAC_PI_2,
        std::f64::consts::PI,
        0.7,
        -2.1,
    ];
    for theta in headings {
        let q = SVector::<f64, 3>::new(rng.next(), rng.next(), theta);
        let u: SVector<f64, 2> = rng.vector(2.0);
        let v = dynamics.velocities(0.0, &q, &u).unwrap();
        let lin = Linearizer::new()
            .reduced(&sys, &OperatingPoint::<f64, 3>::new(q, v))
            .unwrap();
        let flow = |x: &SVector<f64, 5>| {
            let (q, u) = (
                x.fixed_rows::<3>(0).into_owned(),
                x.fixed_rows::<2>(3).into_owned(),
            );
            let v = dynamics.velocities(0.0, &q, &u).unwrap();
            let (du, _) = dynamics.solve(0.0, &q, &v).unwrap();
            let mut out = SVector::<f64, 5>::zeros();
            out.fixed_rows_mut::<3>(0).copy_from(&v);
            out.fixed_rows_mut::<2>(3).copy_from(&du);
            out
        };
        let x = SVector::<f64, 5>::new(q[0], q[1], q[2], u[0], u[1]);
        let a = SMatrix::<f64, 5, 5>::from_fn(|i, j| lin.a()[(i, j)]);
        close(&a, &fd(flow, &x), 1e-6);
    }
}
