//! `inputs(...)`: signals supplied at run time. A cart on a rail with a pendulum,
//! driven by a force on the cart, a torque at the pivot, a set-point of the
//! cart's spring, a gust on the bob and an adjustable damping. The derive must
//! give ΔQ = Q(u) − Q(0) as written by hand, Jacobians that match central
//! differences, and `Lagrangian` methods that are those of the unforced system.

#![allow(clippy::needless_range_loop)] // index loops mirror the formulas

use crate::common;

use common::numeric::{Lcg, close, fd};
use lagrange::Driven;
use lagrange::prelude::*;
use nalgebra::{SVector, Vector2};

#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, theta),
    inputs(force, torque, xs, wind, damp),
    define(gust = wind * cos(theta)),
    point(cart, mass = mc, at = [x, 0]),
    point(bob, mass = mb, at = [x + l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    generalized_force(x = force, theta = torque),
    force(bob, [gust - cw * dot(bob.x), 0]),
    potential = k / 2 * ((x - xs)^2),
    dissipation = (c + damp) * (dot(theta)^2) / 2,
    emit(jacobians),
)]
struct Driven5 {
    mc: f64,
    mb: f64,
    l: f64,
    g: f64,
    k: f64,
    c: f64,
    cw: f64,
}

/// The same system with every input removed (at zero).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, theta),
    point(cart, mass = mc, at = [x, 0]),
    point(bob, mass = mb, at = [x + l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    force(bob, [-cw * dot(bob.x), 0]),
    potential = k / 2 * (x^2),
    dissipation = c * (dot(theta)^2) / 2,
    emit(jacobians),
)]
struct Unforced {
    mc: f64,
    mb: f64,
    l: f64,
    g: f64,
    k: f64,
    c: f64,
    cw: f64,
}

const SYS: Driven5 = Driven5 {
    mc: 2.0,
    mb: 0.7,
    l: 1.3,
    g: 9.81,
    k: 3.0,
    c: 0.4,
    cw: 0.25,
};

const BASE: Unforced = Unforced {
    mc: 2.0,
    mb: 0.7,
    l: 1.3,
    g: 9.81,
    k: 3.0,
    c: 0.4,
    cw: 0.25,
};

type U = SVector<f64, 5>;

fn states() -> Vec<(Vector2<f64>, Vector2<f64>, U, f64)> {
    let mut rng = Lcg(7);
    (0..6)
        .map(|_| {
            let q = Vector2::new(2.0 * rng.next(), 3.0 * rng.next());
            let v = Vector2::new(2.0 * rng.next(), 2.0 * rng.next());
            let u = U::from_fn(|_, _| 3.0 * rng.next());
            (q, v, u, rng.next())
        })
        .collect()
}

/// Q(u) − Q(0) by hand: the generalized forces themselves, the gust through the
/// bob's Jacobian [1, l cos θ], the spring's set-point k·xs and the extra damping.
fn by_hand(q: &Vector2<f64>, v: &Vector2<f64>, u: &U) -> Vector2<f64> {
    let (force, torque, xs, wind, damp) = (u[0], u[1], u[2], u[3], u[4]);
    let (c, l, k) = (q[1].cos(), SYS.l, SYS.k);
    Vector2::new(
        force + wind * c + k * xs,
        torque + l * c * wind * c - damp * v[1],
    )
}

#[test]
fn input_forces_are_q_of_u_minus_q_of_zero() {
    for (q, v, u, t) in states() {
        let dq = SYS.input_forces(&q, &v, &u, t);
        close(&dq, &by_hand(&q, &v, &u), 1e-13);
        // Zero inputs add nothing; the full Q is the unforced Q plus ΔQ.
        let zero = SYS.input_forces(&q, &v, &U::zeros(), t);
        assert_eq!(zero, Vector2::zeros());
    }
}

#[test]
fn input_jacobians_match_central_differences() {
    for (q, v, u, t) in states() {
        let (du, dq, dv) = SYS.input_jacobians(&q, &v, &u, t);
        close(&du, &fd(|u| SYS.input_forces(&q, &v, u, t), &u), 1e-7);
        close(&dq, &fd(|q| SYS.input_forces(q, &v, &u, t), &q), 1e-7);
        close(&dv, &fd(|v| SYS.input_forces(&q, v, &u, t), &v), 1e-7);
        // ∂ΔQ/∂q̇ is the extra damping alone: only (θ, θ̇) is nonzero.
        assert_eq!(dv[(1, 1)], -u[4]);
        assert_eq!(dv[(0, 0)], 0.0);
    }
}

#[test]
fn lagrangian_methods_are_the_unforced_system() {
    for (q, v, _, t) in states() {
        let a = Vector2::new(0.3, -1.7);
        close(&SYS.mass_matrix(&q, t), &BASE.mass_matrix(&q, t), 1e-14);
        close(&SYS.bias(&q, &v, t), &BASE.bias(&q, &v, t), 1e-14);
        close(
            &SYS.generalized_forces(&q, &v, t),
            &BASE.generalized_forces(&q, &v, t),
            1e-14,
        );
        let (m1, r1) = SYS.mass_matrix_and_rhs(&q, &v, t);
        let (m2, r2) = BASE.mass_matrix_and_rhs(&q, &v, t);
        close(&m1, &m2, 1e-14);
        close(&r1, &r2, 1e-14);
        let e = |a: f64, b: f64| assert!((a - b).abs() <= 1e-13 * b.abs().max(1.0), "{a} vs {b}");
        e(
            SYS.kinetic_energy(&q, &v, t),
            BASE.kinetic_energy(&q, &v, t),
        );
        e(SYS.potential_energy(&q, t), BASE.potential_energy(&q, t));
        e(SYS.integral(&q, &v, t), BASE.integral(&q, &v, t));
        let (jq1, jv1) = SYS.rhs_jacobians(&q, &v, &a, t).expect("emitted");
        let (jq2, jv2) = BASE.rhs_jacobians(&q, &v, &a, t).expect("emitted");
        close(&jq1, &jq2, 1e-14);
        close(&jv1, &jv2, 1e-14);
    }
}

/// The names, in order, and the blanket P = 0 impl for a system without inputs.
#[test]
fn driven_trait_constants() {
    assert_eq!(
        <Driven5 as Driven<f64, 2, 5>>::INPUTS,
        ["force", "torque", "xs", "wind", "damp"]
    );
    assert_eq!(<Unforced as Driven<f64, 2, 0>>::INPUTS.len(), 0);
    assert!(Driven5::EQUATIONS.contains("u = (force, torque, xs, wind, damp)"));
    assert!(Driven5::EQUATIONS.contains("dQ[0]/dforce = 1"));
    assert!(!Unforced::EQUATIONS.contains("dQ"));
}

/// Driving the system through the runtime's trait: with Q(u) = Q(0) + ΔQ the
/// accelerations under a constant push differ from the unforced ones by
/// M⁻¹ ΔQ, and ∂q̈/∂u = M⁻¹ ∂Q/∂u.
#[test]
fn driven_accelerations() {
    fn acceleration<S: Driven<f64, 2, 5>>(
        sys: &S,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        u: &U,
    ) -> Vector2<f64> {
        let (m, rhs) = sys.mass_matrix_and_rhs(q, v, 0.0);
        m.cholesky()
            .unwrap()
            .solve(&(rhs + sys.input_forces(q, v, u, 0.0)))
    }
    for (q, v, u, _) in states() {
        let (m, _) = SYS.mass_matrix_and_rhs(&q, &v, 0.0);
        let (du, _, _) = SYS.input_jacobians(&q, &v, &u, 0.0);
        let b = m.cholesky().unwrap().solve(&du);
        close(&b, &fd(|u| acceleration(&SYS, &q, &v, u), &u), 1e-7);
    }
}

/// A pendulum in a wind of speed `wind`, with quadratic drag on the relative
/// velocity: Q is not affine in the input, so ΔQ is Q(u) − Q(0) itself.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(theta),
    inputs(wind),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    force(bob, [cd * (wind - dot(bob.x)) * abs(wind - dot(bob.x)), 0]),
)]
struct Windy {
    m: f64,
    l: f64,
    g: f64,
    cd: f64,
}

#[test]
fn nonlinear_input() {
    let sys = Windy {
        m: 0.5,
        l: 0.9,
        g: 9.81,
        cd: 0.3,
    };
    let drag = |w: f64| sys.cd * w * w.abs();
    let mut rng = Lcg(11);
    for _ in 0..6 {
        let q = SVector::<f64, 1>::new(2.0 * rng.next());
        let v = SVector::<f64, 1>::new(2.0 * rng.next());
        let u = SVector::<f64, 1>::new(3.0 * rng.next());
        // The bob's ẋ = l cos θ θ̇, and its Jacobian in θ is l cos θ.
        let (c, xd) = (q[0].cos(), sys.l * q[0].cos() * v[0]);
        let expected = SVector::<f64, 1>::new(sys.l * c * (drag(u[0] - xd) - drag(-xd)));
        close(&sys.input_forces(&q, &v, &u, 0.0), &expected, 1e-13);
        let (du, dq, dv) = sys.input_jacobians(&q, &v, &u, 0.0);
        close(&du, &fd(|u| sys.input_forces(&q, &v, u, 0.0), &u), 1e-7);
        close(&dq, &fd(|q| sys.input_forces(q, &v, &u, 0.0), &q), 1e-7);
        close(&dv, &fd(|v| sys.input_forces(&q, v, &u, 0.0), &v), 1e-7);
        // The unforced Q: gravity and the drag in still air.
        let unforced = sys.generalized_forces(&q, &v, 0.0)[0];
        let gravity = -sys.m * sys.g * sys.l * q[0].sin();
        assert!((unforced - gravity - sys.l * c * drag(-xd)).abs() < 1e-13);
    }
}

/// A generic scalar: the `Driven` impl carries the struct's type parameter.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x),
    inputs(push),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = push * x),
)]
struct Generic<T> {
    m: T,
}

#[test]
fn generic_scalar() {
    let sys = Generic { m: 2.0f32 };
    let (q, v) = (SVector::<f32, 1>::new(0.5), SVector::<f32, 1>::new(1.0));
    let u = SVector::<f32, 1>::new(4.0);
    assert_eq!(sys.input_forces(&q, &v, &u, 0.0)[0], 2.0);
    let (du, dq, _) = sys.input_jacobians(&q, &v, &u, 0.0);
    assert_eq!((du[(0, 0)], dq[(0, 0)]), (0.5, 4.0));
}

/// An operating point without inputs linearises a driven system with its
/// inputs at zero, with no annotation; the inputs, when given, must be as
/// many as the system's (a compile-time check).
#[test]
fn operating_point_inputs_default_to_zero() {
    let (q, v) = (Vector2::new(0.2, 0.4), Vector2::new(-0.1, 0.3));
    let op = OperatingPoint::new(q, v);
    let zero = Linearizer::new().unconstrained(&SYS, &op).unwrap();
    let given = Linearizer::new()
        .unconstrained(&SYS, &op.input(SVector::<f64, 5>::zeros()))
        .unwrap();
    assert_eq!(zero.a(), given.a());
    assert_eq!(zero.b(), given.b());
    assert_eq!(zero.inputs().len(), 5);
    let pushed = op.input(SVector::<f64, 5>::from([1.0, 0.0, 0.0, 0.0, 0.0]));
    assert_eq!(pushed.u[0], 1.0);
}
