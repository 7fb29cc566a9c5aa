//! Whole integrations: each integrator over a fixed span at a fixed tolerance
//! (or step) on a derived system, so that changes to the shared step loop, the
//! error control, the dense output and the recorder show up as one number per
//! run. The systems are defined here, so the bench compiles against any tree of
//! the workspace with the same public API.
//!
//!     cargo bench -p lagrange-bench --bench integrate

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::prelude::*;
use std::hint::black_box;

/// Planar double pendulum, absolute angles from the downward vertical.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(th1, th2),
    define(x1 = l1 * sin(th1), y1 = -l1 * cos(th1)),
    point(b1, mass = m1, at = [x1, y1]),
    point(b2, mass = m2, at = [x1 + l2 * sin(th2), y1 - l2 * cos(th2)]),
    gravity = [0, -g],
    emit(hamiltonian),
)]
struct DoublePendulum {
    m1: f64,
    m2: f64,
    l1: f64,
    l2: f64,
    g: f64,
}

/// Planar 5-link pendulum in relative angles.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(a1, a2, a3, a4, a5),
    define(
        p1 = a1, p2 = a1 + a2, p3 = a1 + a2 + a3, p4 = a1 + a2 + a3 + a4,
        p5 = a1 + a2 + a3 + a4 + a5,
        x1 = l * sin(p1), y1 = -l * cos(p1),
        x2 = x1 + l * sin(p2), y2 = y1 - l * cos(p2),
        x3 = x2 + l * sin(p3), y3 = y2 - l * cos(p3),
        x4 = x3 + l * sin(p4), y4 = y3 - l * cos(p4),
        x5 = x4 + l * sin(p5), y5 = y4 - l * cos(p5),
    ),
    point(b1, mass = m, at = [x1, y1]),
    point(b2, mass = m, at = [x2, y2]),
    point(b3, mass = m, at = [x3, y3]),
    point(b4, mass = m, at = [x4, y4]),
    point(b5, mass = m, at = [x5, y5]),
    gravity = [0, -g],
)]
struct Chain5 {
    m: f64,
    l: f64,
    g: f64,
}

/// A pendulum whose rod is a stiff spring (k/m = 10⁸): polar coordinates (r, θ).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(r, theta),
    point(bob, mass = m, at = [r * sin(theta), -r * cos(theta)]),
    gravity = [0, -g],
    potential = k * ((r - l0)^2) / 2,
)]
struct SpringPendulum {
    m: f64,
    k: f64,
    l0: f64,
    g: f64,
}

/// The spherical pendulum in Cartesian coordinates, the thread a multiplier.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    point(bob, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    holonomic(thread = (bob.x^2) + (bob.y^2) + (bob.z^2) - (l^2)),
)]
struct CartesianSphericalPendulum {
    m: f64,
    l: f64,
    g: f64,
}

const DOUBLE: DoublePendulum = DoublePendulum {
    m1: 1.0,
    m2: 0.7,
    l1: 1.0,
    l2: 0.8,
    g: 9.81,
};

fn double_pendulum(c: &mut Criterion) {
    let sys = DOUBLE;
    let (q0, v0) = (Vector2::new(1.0, 0.5), Vector2::new(0.0, 0.0));
    let span = 0.0..10.0;
    let mut group = c.benchmark_group("integrate_double_pendulum_10s");
    group.bench_function("dopri5 rtol 1e-8", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Dopri5::tol(1e-8))
                .run(q0, v0, span.clone())
                .unwrap()
                .final_state()
        })
    });
    group.bench_function("dop853 rtol 1e-10", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Dop853::tol(1e-10))
                .run(q0, v0, span.clone())
                .unwrap()
                .final_state()
        })
    });
    group.bench_function("rk4 h 1e-3", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Rk4::step(1e-3))
                .run(q0, v0, span.clone())
                .unwrap()
                .final_state()
        })
    });
    group.bench_function("gauss h 1e-2", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Gauss::step(1e-2))
                .run(q0, v0, span.clone())
                .unwrap()
                .final_state()
        })
    });
    group.bench_function("radau5 rtol 1e-8", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Radau5::tol(1e-8))
                .run(q0, v0, span.clone())
                .unwrap()
                .final_state()
        })
    });
    group.bench_function("dop853 rtol 1e-10, rising event", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Dop853::tol(1e-10))
                .event(Event::new(|_, q: &Vector2<f64>, _| q[0]).rising())
                .run(q0, v0, span.clone())
                .unwrap()
                .occurrences
                .len()
        })
    });
    group.finish();
}

fn chain5(c: &mut Criterion) {
    let sys = Chain5 {
        m: 1.0,
        l: 0.5,
        g: 9.81,
    };
    let q0 = Vector5::new(0.8, 0.3, -0.2, 0.4, 0.1);
    let v0 = Vector5::zeros();
    let mut group = c.benchmark_group("integrate_chain5_5s");
    group.bench_function("dopri5 rtol 1e-8", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Dopri5::tol(1e-8))
                .run(q0, v0, 0.0..5.0)
                .unwrap()
                .final_state()
        })
    });
    group.bench_function("dop853 rtol 1e-10", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Dop853::tol(1e-10))
                .run(q0, v0, 0.0..5.0)
                .unwrap()
                .final_state()
        })
    });
    group.finish();
}

fn stiff(c: &mut Criterion) {
    let sys = SpringPendulum {
        m: 1.0,
        k: 1e8,
        l0: 1.0,
        g: 9.81,
    };
    let th0 = 0.5f64;
    // Static stretch along the rod, so the fast mode starts (nearly) at rest.
    let q0 = [sys.l0 + sys.m * sys.g * th0.cos() / sys.k, th0];
    let mut group = c.benchmark_group("integrate_stiff_spring_pendulum_2s");
    group.bench_function("radau5 rtol 1e-8", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Radau5::tol(1e-8))
                .run(q0, [0.0; 2], 0.0..2.0)
                .unwrap()
                .final_state()
        })
    });
    group.finish();
}

fn constrained(c: &mut Criterion) {
    let sys = CartesianSphericalPendulum {
        m: 1.2,
        l: 0.9,
        g: 9.81,
    };
    // (θ, φ) = (1.1, 0.2), (θ̇, φ̇) = (0.3, 1.7) in Cartesian coordinates.
    let (l, th, ph, thd, phd) = (sys.l, 1.1f64, 0.2f64, 0.3, 1.7);
    let x0 = Vector3::new(
        l * th.sin() * ph.cos(),
        l * th.sin() * ph.sin(),
        -l * th.cos(),
    );
    let xd0 = Vector3::new(
        l * (th.cos() * ph.cos() * thd - th.sin() * ph.sin() * phd),
        l * (th.cos() * ph.sin() * thd + th.sin() * ph.cos() * phd),
        l * th.sin() * thd,
    );
    let mut group = c.benchmark_group("integrate_cartesian_spherical_pendulum_5s");
    group.bench_function("dopri5 rtol 1e-10, projection", |b| {
        b.iter(|| {
            Simulation::new(black_box(&sys))
                .integrator(Dopri5::tol(1e-10))
                .drift(Drift::projection())
                .run_constrained(x0, xd0, 0.0..5.0)
                .unwrap()
                .final_state()
        })
    });
    group.finish();
}

criterion_group!(benches, double_pendulum, chain5, stiff, constrained);
criterion_main!(benches);
