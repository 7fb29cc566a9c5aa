//! Free orientations (`orientation(..)`): the heavy top's M + (Q − h) derived
//! against Euler's equations written by hand, and floating bases to set
//! beside Pinocchio's free flyer (`peer/pinocchio/free_flyer.sh`, the same
//! models and states): a hub with a two-joint arm, and the quadruped and the
//! satellite of `examples/catalog/floating.rs` at state 0 of
//! `tests/data/floating_pinocchio.txt`, which the peer reads too.
//!
//!     cargo bench -p lagrange-bench --bench free

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::prelude::{Dopri5, Lagrangian, Simulation};
use nalgebra::{Matrix3, SVector, Vector3, Vector4};
use std::hint::black_box;

#[path = "../../examples/catalog/floating.rs"]
mod floating;

const REFERENCE: &str = include_str!("../../tests/data/floating_pinocchio.txt");

/// The numbers of `key` at `model`'s state 0 in the reference file.
fn reference(model: &str, key: &str) -> Vec<f64> {
    let head = format!("{model} 0 {key} ");
    let line = REFERENCE.lines().find(|l| l.starts_with(&head));
    let line = line.unwrap_or_else(|| panic!("no {head:?} in the reference file"));
    line[head.len()..]
        .split(' ')
        .map(|x| x.parse().expect("a number"))
        .collect()
}

/// M + (Q − h), the articulated q̈, τ by recursive Newton–Euler (at q̈ = 0.1
/// in every joint, as the peer) and the tangent-space A of a floating base.
fn floating_base<S, const N: usize, const Q: usize>(c: &mut Criterion, name: &str, sys: &S)
where
    S: lagrange::Differentiable<f64, N, Q>,
{
    let q = SVector::<f64, Q>::from_column_slice(&reference(name, "q"));
    let v = SVector::<f64, N>::from_column_slice(&reference(name, "v"));
    let a = SVector::<f64, N>::repeat(0.1);
    let tau = SVector::<f64, N>::zeros();
    let mut group = c.benchmark_group(format!("free_{name}"));
    group.bench_function("M + (Q - h)", |b| {
        b.iter(|| sys.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("accelerations", |b| {
        b.iter(|| lagrange::accelerations(sys, black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("inverse dynamics", |b| {
        b.iter(|| sys.inverse_dynamics(black_box(&q), black_box(&v), black_box(&a), 0.0))
    });
    let accel = lagrange::accelerations(sys, &q, &v, 0.0).expect("a positive definite M");
    group.bench_function("rhs Jacobians", |b| {
        b.iter(|| sys.rhs_jacobians(black_box(&q), black_box(&v), black_box(&accel), 0.0))
    });
    group.bench_function("acceleration derivatives", |b| {
        b.iter(|| {
            lagrange::acceleration_derivatives(
                sys,
                black_box(&q),
                black_box(&v),
                black_box(&tau),
                0.0,
            )
        })
    });
    let linearizer = lagrange::prelude::Linearizer::new();
    group.bench_function("tangent A (emitted derivatives)", |b| {
        b.iter(|| linearizer.tangent(sys, black_box(&q), black_box(&v), 0.0))
    });
    group.finish();
}

#[derive(Lagrangian)]
#[lagrange(
    orientation(spin),
    body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
         at = [0, 0, 0], rotation = spin),
    gravity = [0, 0, -g],
)]
struct Top {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// Euler's equations of the same top by hand: M = diag(A, A, C), Q − h =
/// l e₃ × Rᵀ(−m g e_z) − ω × I ω, R's third row from the quaternion.
fn by_hand(top: &Top, q: &Vector4<f64>, w: &Vector3<f64>) -> (Matrix3<f64>, Vector3<f64>) {
    let (qw, qx, qy, qz) = (q[0], q[1], q[2], q[3]);
    let r31 = 2.0 * (qx * qz - qw * qy);
    let r32 = 2.0 * (qy * qz + qw * qx);
    let mgl = top.m * top.g * top.l;
    let iw = Vector3::new(top.a * w[0], top.a * w[1], top.c * w[2]);
    let gyro = w.cross(&iw);
    let rhs = Vector3::new(mgl * r32 - gyro[0], -mgl * r31 - gyro[1], -gyro[2]);
    (
        Matrix3::from_diagonal(&Vector3::new(top.a, top.a, top.c)),
        rhs,
    )
}

/// The same top in Euler angles z-x-z with an atlas.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
         at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -g],
    emit(atlas),
)]
struct EulerTop {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// A swing over the top through θ = 0 for 2 s: the atlas run (the user's
/// program in the user's chart, the twin's in the second) against the
/// quaternion top's run of the same motion, both DOPRI5 at 1e-10.
fn atlas(c: &mut Criterion, top: &Top) {
    let euler = EulerTop {
        m: top.m,
        a: top.a,
        c: top.c,
        l: top.l,
        g: top.g,
    };
    let (q0, v0) = ([0.2, 0.6, -0.4], [0.0, -6.0, 2.0]);
    let chart = lagrange::numeric::euler::EulerChart::new([2, 0, 2]).expect("z-x-z");
    let w = chart.rates(q0) * Vector3::from(v0);
    let r = chart.matrix(q0);
    let quaternion = lagrange::numeric::orientation::from_rotation_matrix(&r);
    let mut group = c.benchmark_group("atlas_top");
    group.bench_function("swing 2 s, run_atlas (Euler angles)", |b| {
        b.iter(|| {
            Simulation::new(&euler)
                .integrator(Dopri5::tol(1e-10))
                .run_atlas(black_box(q0), v0, 0.0..2.0)
                .map(|run| run.switches().len())
        })
    });
    group.bench_function("swing 2 s, run (quaternion)", |b| {
        b.iter(|| {
            Simulation::new(top)
                .integrator(Dopri5::tol(1e-10))
                .run(black_box(quaternion), [w[0], w[1], w[2]], 0.0..2.0)
                .map(|traj| traj.len())
        })
    });
    group.finish();
}

fn free(c: &mut Criterion) {
    let top = Top {
        m: 1.5,
        a: 0.8,
        c: 0.5,
        l: 0.4,
        g: 9.81,
    };
    let n = (0.8_f64 * 0.8 + 0.2 * 0.2 + 0.4 * 0.4 + 0.3 * 0.3).sqrt();
    let q = Vector4::new(0.8 / n, 0.2 / n, -0.4 / n, 0.3 / n);
    let w = Vector3::new(0.4, -0.6, 9.0);
    let mut group = c.benchmark_group("free_top");
    group.bench_function("M + (Q - h) derived", |b| {
        b.iter(|| top.mass_matrix_and_rhs(black_box(&q), black_box(&w), 0.0))
    });
    group.bench_function("M + (Q - h) by hand", |b| {
        b.iter(|| by_hand(&top, black_box(&q), black_box(&w)))
    });
    group.finish();
    atlas(c, &top);
    let arm = floating::FloatingArm { g: 9.81 };
    let q = SVector::<f64, 9>::from([
        0.1,
        -0.2,
        0.3,
        0.7,
        -0.4,
        0.8 / n,
        0.2 / n,
        -0.4 / n,
        0.3 / n,
    ]);
    let v = SVector::<f64, 8>::from([0.3, -0.1, 0.2, 0.5, -0.8, 0.4, -0.6, 0.9]);
    let mut group = c.benchmark_group("free_floating_arm");
    group.bench_function("M + (Q - h)", |b| {
        b.iter(|| arm.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("accelerations", |b| {
        b.iter(|| lagrange::accelerations(&arm, black_box(&q), black_box(&v), 0.0))
    });
    group.finish();
    floating_base::<_, 18, 19>(c, "quadruped", &floating::Quadruped { g: 9.81 });
    floating_base::<_, 12, 13>(c, "satellite", &floating::ArmedSatellite { g: 9.81 });
}

criterion_group!(benches, free);
criterion_main!(benches);
