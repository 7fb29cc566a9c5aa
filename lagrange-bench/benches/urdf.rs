//! Robots read from their URDF files (`robots/`): M + (Q − h), q̈ and the
//! inverse dynamics per call,
//! the figures to set beside Pinocchio's CRBA + NLE and ABA on the same files
//! from `peer/pinocchio/urdf.sh`, run on the same machine in one session.
//!
//!     cargo bench -p lagrange-bench --bench urdf

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::Lagrangian;
use nalgebra::SVector;
use std::hint::black_box;

#[derive(Lagrangian)]
#[lagrange(urdf = "../robots/ur5.urdf", gravity = [0, 0, -9.81], emit(inverse_dynamics))]
struct Ur5 {}

#[derive(Lagrangian)]
#[lagrange(urdf = "../robots/ur5.urdf", gravity = [0, 0, -9.81], emit(articulated))]
struct Ur5Articulated {}

#[derive(Lagrangian)]
#[lagrange(urdf = "../robots/panda.urdf", gravity = [0, 0, -9.81], emit(inverse_dynamics))]
struct Panda {}

/// The state the peer uses: q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k.
fn state<const N: usize>() -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_fn(|k, _| 0.3 - 0.17 * k as f64),
        SVector::from_fn(|k, _| 0.5 - 0.21 * k as f64),
    )
}

fn arms(c: &mut Criterion) {
    let mut group = c.benchmark_group("urdf_ur5");
    let (q, v) = state::<6>();
    group.bench_function("M + (Q - h)", |b| {
        b.iter(|| Ur5 {}.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("accelerations", |b| {
        b.iter(|| lagrange::accelerations(&Ur5 {}, black_box(&q), black_box(&v), 0.0))
    });
    let a = SVector::<f64, 6>::from_fn(|k, _| 0.1 + 0.05 * k as f64);
    group.bench_function("inverse dynamics", |b| {
        b.iter(|| Ur5 {}.inverse_dynamics(black_box(&q), black_box(&v), black_box(&a), 0.0))
    });
    group.bench_function("accelerations (articulated)", |b| {
        b.iter(|| lagrange::accelerations(&Ur5Articulated {}, black_box(&q), black_box(&v), 0.0))
    });
    group.finish();
    let mut group = c.benchmark_group("urdf_panda");
    let (q, v) = state::<8>();
    group.bench_function("M + (Q - h)", |b| {
        b.iter(|| Panda {}.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("accelerations", |b| {
        b.iter(|| lagrange::accelerations(&Panda {}, black_box(&q), black_box(&v), 0.0))
    });
    let a = SVector::<f64, 8>::from_fn(|k, _| 0.1 + 0.05 * k as f64);
    group.bench_function("inverse dynamics", |b| {
        b.iter(|| Panda {}.inverse_dynamics(black_box(&q), black_box(&v), black_box(&a), 0.0))
    });
    group.finish();
}

criterion_group!(benches, arms);
criterion_main!(benches);
