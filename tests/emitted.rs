//! The derive's optional outputs, exercised in compiled code: the Coriolis matrix,
//! the right-hand-side Jacobians (used by Radau5), and Hamilton's form (momentum
//! and ∂T/∂q, used by the symplectic Gauss method) — each against finite
//! differences of what the always-emitted methods compute.

#![allow(clippy::needless_range_loop)] // index loops mirror the formulas

use crate::catalog;

use lagrange::ode::SecondOrder;
use lagrange::prelude::*;
use lagrange::{Dynamics, Gauss, Radau5};
use nalgebra::{Matrix2, Vector2};

/// The catalog's double pendulum, with every optional output asked for.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(th1, th2),
    point(b1, mass = m1, at = [l1 * sin(th1), -l1 * cos(th1)]),
    point(b2, mass = m2, at = [l1 * sin(th1) + l2 * sin(th2), -l1 * cos(th1) - l2 * cos(th2)]),
    gravity = [0, -g],
    dissipation = c * (dot(th1)^2) / 2,
    emit(coriolis, jacobians, hamiltonian, inverse_dynamics),
)]
struct Double {
    m1: f64,
    m2: f64,
    l1: f64,
    l2: f64,
    g: f64,
    c: f64,
}

const SYS: Double = Double {
    m1: 1.0,
    m2: 0.6,
    l1: 1.2,
    l2: 0.8,
    g: 9.81,
    c: 0.3,
};

fn states() -> Vec<(Vector2<f64>, Vector2<f64>)> {
    vec![
        (Vector2::new(0.3, -1.1), Vector2::new(0.7, 2.0)),
        (Vector2::new(2.5, 0.4), Vector2::new(-1.5, 0.1)),
        (Vector2::new(-0.9, 3.0), Vector2::new(0.0, -3.0)),
    ]
}

/// Ṁ − 2C is skew-symmetric and C q̇ equals h (scleronomic, no dissipation in h).
#[test]
fn coriolis_matrix_factorises_the_bias() {
    let h = 1e-6;
    for (q, v) in states() {
        let c = SYS.coriolis_matrix(&q, &v, 0.0);
        let cv = c * v;
        let bias = SYS.bias(&q, &v, 0.0);
        assert!((cv - bias).amax() < 1e-12, "{cv} vs {bias}");
        let mdot =
            (SYS.mass_matrix(&(q + v * h), 0.0) - SYS.mass_matrix(&(q - v * h), 0.0)) / (2.0 * h);
        let s: Matrix2<f64> = mdot - c * 2.0;
        assert!((s + s.transpose()).amax() < 1e-8, "{s}");
    }
}

/// The emitted Jacobians give ∂q̈/∂q and ∂q̈/∂q̇ equal to central differences of
/// the accelerations (dissipation makes ∂q̈/∂q̇ non-trivial).
#[test]
fn rhs_jacobians_match_finite_differences() {
    let dynamics = Dynamics::new(&SYS);
    let acc = |q: Vector2<f64>, v: Vector2<f64>| dynamics.acceleration(0.0, &q, &v).unwrap();
    for (q, v) in states() {
        let (dq, dv) = SecondOrder::jacobian(&dynamics, 0.0, &q, &v)
            .expect("emitted")
            .unwrap();
        let h = 1e-6;
        for k in 0..2 {
            let mut e = Vector2::zeros();
            e[k] = h;
            let fq = (acc(q + e, v) - acc(q - e, v)) / (2.0 * h);
            let fv = (acc(q, v + e) - acc(q, v - e)) / (2.0 * h);
            for i in 0..2 {
                assert!((dq[(i, k)] - fq[i]).abs() < 1e-6 * (1.0 + fq[i].abs()));
                assert!((dv[(i, k)] - fv[i]).abs() < 1e-6 * (1.0 + fv[i].abs()));
            }
        }
    }
}

/// p = ∂T/∂q̇ and ∂T/∂q against central differences of the kinetic energy.
#[test]
fn momentum_and_kinetic_gradient_match_the_energy() {
    let h = 1e-6;
    for (q, v) in states() {
        let p = SYS.momentum(&q, &v, 0.0);
        let g = SYS.kinetic_gradient(&q, &v, 0.0).expect("emitted");
        for k in 0..2 {
            let mut e = Vector2::zeros();
            e[k] = h;
            let dp = (SYS.kinetic_energy(&q, &(v + e), 0.0)
                - SYS.kinetic_energy(&q, &(v - e), 0.0))
                / (2.0 * h);
            let dg = (SYS.kinetic_energy(&(q + e), &v, 0.0)
                - SYS.kinetic_energy(&(q - e), &v, 0.0))
                / (2.0 * h);
            assert!((p[k] - dp).abs() < 1e-8 && (g[k] - dg).abs() < 1e-8);
        }
    }
}

/// A rheonomic system's momentum is M q̇ + a, not M q̇: the derive always emits it.
#[test]
fn rheonomic_momentum_includes_the_t1_term() {
    let sys = catalog::GrowingEllipsoid {
        m: 1.5,
        a: 1.0,
        b: 0.8,
        c: 0.6,
        g: 9.81,
    };
    let (q, v, t) = (Vector2::new(0.9, 0.4), Vector2::new(0.3, -0.2), 1.7);
    let h = 1e-6;
    let p = sys.momentum(&q, &v, t);
    for k in 0..2 {
        let mut e = Vector2::zeros();
        e[k] = h;
        let dp =
            (sys.kinetic_energy(&q, &(v + e), t) - sys.kinetic_energy(&q, &(v - e), t)) / (2.0 * h);
        assert!((p[k] - dp).abs() < 1e-8, "p[{k}] = {} vs {dp}", p[k]);
    }
    assert!((p - sys.mass_matrix(&q, t) * v).amax() > 1e-3);
}

/// The symplectic Gauss method runs on a derived system through Hamilton's form,
/// and keeps the energy bounded where RK4 at the same step drifts.
#[test]
fn gauss_on_a_derived_system_keeps_energy_bounded() {
    let sys = Double { c: 0.0, ..SYS };
    let (q0, v0) = (Vector2::new(1.0, 0.5), Vector2::new(0.0, 0.0));
    let gauss = Simulation::new(&sys)
        .integrator(Gauss::step(0.02))
        .run(q0, v0, 0.0..40.0)
        .unwrap();
    let rk4 = Simulation::new(&sys)
        .integrator(Rk4::step(0.02))
        .run(q0, v0, 0.0..40.0)
        .unwrap();
    let (eg, er) = (gauss.integral_drift(), rk4.integral_drift());
    assert!(eg < 1e-5, "Gauss energy error {eg:e}");
    assert!(eg < er, "Gauss {eg:e} vs RK4 {er:e}");
}

/// Radau5 uses the emitted Jacobians and reaches the same state as with finite
/// differences, with fewer right-hand-side evaluations.
#[test]
fn radau5_uses_emitted_jacobians() {
    let without = catalog::DoublePendulum {
        m1: SYS.m1,
        m2: SYS.m2,
        l1: SYS.l1,
        l2: SYS.l2,
        g: SYS.g,
    };
    let undamped = Double { c: 0.0, ..SYS };
    let (q0, v0) = (Vector2::new(1.0, 0.5), Vector2::new(0.0, 0.0));
    let a = Simulation::new(&undamped)
        .integrator(Radau5::tol(1e-10))
        .run(q0, v0, 0.0..2.0)
        .unwrap();
    let b = Simulation::new(&without)
        .integrator(Radau5::tol(1e-10))
        .run(q0, v0, 0.0..2.0)
        .unwrap();
    let (qa, _) = a.final_state();
    let (qb, _) = b.final_state();
    assert!((qa - qb).amax() < 1e-7, "{:e}", (qa - qb).amax());
    // Same steps; finite differences cost 2N = 4 extra evaluations per Jacobian.
    let (sa, sb) = (a.stats(), b.stats());
    assert!(
        sa.jacobians > 0 && sa.accepted == sb.accepted,
        "{sa:?} vs {sb:?}"
    );
    assert!(sa.evaluations < sb.evaluations, "{sa:?} vs {sb:?}");
}

/// A three-link spatial chain, each link hung at its parent's tip.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(a, b, c),
    body(l1, mass = m, inertia = [i, i, j], at = [0, 0, 0], rotation = rot_z(a)),
    point(t1, on = l1, at = [0, 0, -l]),
    body(l2, mass = m, inertia = [i, i, j], com = [0, 0, -l / 2], at = [t1.x, t1.y, t1.z],
         rotation = rot_z(a) * rot_y(b)),
    point(t2, on = l2, at = [0, 0, -l]),
    body(l3, mass = m, inertia = [i, i, j], com = [0, 0, -l / 2], at = [t2.x, t2.y, t2.z],
         rotation = rot_z(a) * rot_y(b) * rot_x(c)),
    gravity = [0, 0, -g],
)]
struct Chain {
    m: f64,
    i: f64,
    j: f64,
    l: f64,
    g: f64,
}

#[test]
fn the_route_is_a_constant_with_its_reason() {
    use lagrange::Route;
    assert_eq!(
        <Double as Lagrangian<f64, 2>>::ROUTE,
        Route::Generic {
            reason: "it has no rigid bodies (point masses alone)"
        }
    );
    assert!(Double::EQUATIONS.contains("not recursive because it has no rigid bodies"));
    // A tree this small is derived both ways, and the cheaper program kept.
    assert_eq!(
        <Chain as Lagrangian<f64, 3>>::ROUTE,
        Route::Generic {
            reason: "the generic program is the cheaper one on this small tree (3 joints)"
        }
    );
}

/// Off the tree route, the emitted inverse dynamics is M a + h − Q, and the
/// gravity torques the gradient of the potential (gravity is the only one).
#[test]
fn inverse_dynamics_and_gravity_torques_off_the_tree() {
    for (q, v) in states() {
        let a = Vector2::new(0.7 * q[0] - 0.2, 1.1 - v[1]);
        let (m, f) = SYS.mass_matrix_and_rhs(&q, &v, 0.0);
        let expected = m * a - f;
        let tau = SYS.inverse_dynamics(&q, &v, &a, 0.0);
        assert!(
            (tau - expected).amax() < 1e-12 * expected.amax().max(1.0),
            "{tau} vs {expected}"
        );
        let g = SYS.gravity_torques(&q, 0.0).expect("emitted");
        let h = 1e-6;
        for i in 0..2 {
            let mut up = q;
            up[i] += h;
            let mut down = q;
            down[i] -= h;
            let dv =
                (SYS.potential_energy(&up, 0.0) - SYS.potential_energy(&down, 0.0)) / (2.0 * h);
            assert!((g[i] - dv).abs() < 1e-7, "g[{i}] {} vs {dv}", g[i]);
        }
    }
}
