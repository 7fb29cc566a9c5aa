//! ∂q̈/∂q and ∂q̈/∂q̇ of robots read from their URDF (`emit(jacobians)`,
//! `lagrange::acceleration_derivatives`), to set beside Pinocchio's
//! `computeABADerivatives` on the same files (`peer/pinocchio/derivatives.sh`),
//! at the same state; q̈ alone beside its ABA for scale. The arms: the UR5,
//! UR10, Kinova, Z1 and xArm7 (not the Panda: its mimic finger is a second
//! joint to Pinocchio). The floating bases' derivatives are in the `free`
//! bench.
//!
//!     cargo bench -p lagrange-bench --bench derivatives

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::{Differentiable, Lagrangian};
use nalgebra::SVector;
use std::hint::black_box;

macro_rules! arm {
    ($name:ident, $file:tt) => {
        #[derive(Lagrangian, Default)]
        #[lagrange(urdf($file, dynamics = ignore), gravity = [0, 0, -9.81], emit(jacobians))]
        struct $name {}
    };
}

arm!(Ur5, "../robots/ur5.urdf");
arm!(Ur10, "../robots/ur10.urdf");
arm!(Kinova, "../robots/kinova.urdf");
arm!(Z1, "../robots/z1.urdf");
arm!(Xarm7, "../robots/xarm7.urdf");

/// One group per arm, `derivatives_<name>`, at q_k = 0.3 − 0.17 k,
/// q̇_k = 0.5 − 0.21 k.
fn time<S: Differentiable<f64, N, N> + Default, const N: usize>(c: &mut Criterion, name: &str) {
    let sys = S::default();
    let q = SVector::<f64, N>::from_fn(|k, _| 0.3 - 0.17 * k as f64);
    let v = SVector::<f64, N>::from_fn(|k, _| 0.5 - 0.21 * k as f64);
    let tau = SVector::<f64, N>::zeros();
    let mut group = c.benchmark_group(format!("derivatives_{name}"));
    group.bench_function("accelerations", |b| {
        b.iter(|| lagrange::accelerations(&sys, black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("acceleration derivatives", |b| {
        b.iter(|| {
            lagrange::acceleration_derivatives(
                &sys,
                black_box(&q),
                black_box(&v),
                black_box(&tau),
                0.0,
            )
        })
    });
    group.finish();
}

fn derivatives(c: &mut Criterion) {
    time::<Ur5, 6>(c, "ur5");
    time::<Ur10, 6>(c, "ur10");
    time::<Kinova, 6>(c, "kinova");
    time::<Z1, 7>(c, "z1");
    time::<Xarm7, 7>(c, "xarm7");
}

criterion_group!(benches, derivatives);
criterion_main!(benches);
