//! ∂q̈/∂q and ∂q̈/∂q̇ of a robot read from its URDF (`emit(jacobians)`,
//! `lagrange::acceleration_derivatives`), to set beside Pinocchio's
//! `computeABADerivatives` on the same file (`peer/pinocchio/derivatives.sh`),
//! at the same state; q̈ alone beside its ABA for scale. The floating bases'
//! derivatives are in the `free` bench.
//!
//!     cargo bench -p lagrange-bench --bench derivatives

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::Lagrangian;
use nalgebra::SVector;
use std::hint::black_box;

#[derive(Lagrangian)]
#[lagrange(urdf = "../robots/ur5.urdf", gravity = [0, 0, -9.81], emit(jacobians))]
struct Ur5 {}

fn derivatives(c: &mut Criterion) {
    let q = SVector::<f64, 6>::from_fn(|k, _| 0.3 - 0.17 * k as f64);
    let v = SVector::<f64, 6>::from_fn(|k, _| 0.5 - 0.21 * k as f64);
    let mut group = c.benchmark_group("derivatives_ur5");
    group.bench_function("accelerations", |b| {
        b.iter(|| lagrange::accelerations(&Ur5 {}, black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("acceleration derivatives", |b| {
        b.iter(|| lagrange::acceleration_derivatives(&Ur5 {}, black_box(&q), black_box(&v), 0.0))
    });
    group.finish();
}

criterion_group!(benches, derivatives);
criterion_main!(benches);
