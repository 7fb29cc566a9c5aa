//! The dynamics regressor Y(q, q̇, q̈) (`emit(regressor)`) beside the same
//! arm's inverse dynamics, per call, on five arms read from their URDF files
//! (`robots/`): the figures to set beside Pinocchio's
//! `computeJointTorqueRegressor` and `rnea` on the same files from
//! `peer/pinocchio/regressor.sh`, run on the same machine in one session.
//! The bar is a ratio of ratios: Y against Pinocchio's regressor at least as
//! fast as τ against `rnea`. Pinocchio writes Y into its `Data`, allocated
//! once; `regressor_into` writes into a matrix the caller holds, the fair
//! comparison, and `regressor` allocates its matrix on every call.
//!
//! Before timing, each arm prints τ[0] at the bench's state, as the peer
//! does, so that a reader sees both sides run the same model at the same
//! state; Y itself is checked against Pinocchio's column by column in
//! `tests/regressor_pinocchio.rs`.
//!
//!     cargo bench -p lagrange-bench --bench regressor

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::Lagrangian;
use nalgebra::SVector;
use std::hint::black_box;

macro_rules! arm {
    ($name:ident, $file:tt $(, $option:ident = $value:tt)?) => {
        #[derive(Lagrangian, Default)]
        #[lagrange(urdf($file, dynamics = ignore $(, $option = $value)?), gravity = [0, 0, -9.81], emit(regressor, inverse_dynamics))]
        struct $name {}
    };
}

arm!(Ur5, "../robots/ur5.urdf");
// The same files with their quarter turns, written to twelve digits, kept as
// written (by default they are made exact): the model Pinocchio reads.
arm!(Ur5AsWritten, "../robots/ur5.urdf", snap = 0);
arm!(KinovaAsWritten, "../robots/kinova.urdf", snap = 0);
arm!(Ur10, "../robots/ur10.urdf");
arm!(Kinova, "../robots/kinova.urdf");
arm!(Z1, "../robots/z1.urdf");
arm!(Xarm7, "../robots/xarm7.urdf");

/// The peer's state: q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k,
/// q̈_k = 0.1 + 0.05 k.
fn state<const N: usize>() -> [SVector<f64, N>; 3] {
    [
        SVector::from_fn(|k, _| 0.3 - 0.17 * k as f64),
        SVector::from_fn(|k, _| 0.5 - 0.21 * k as f64),
        SVector::from_fn(|k, _| 0.1 + 0.05 * k as f64),
    ]
}

/// One criterion group per arm: `regressor_<name>`.
fn time<S: Lagrangian<f64, N> + Default, const N: usize>(c: &mut Criterion, name: &str) {
    let sys = S::default();
    let [q, v, a] = state::<N>();
    let tau = sys.inverse_dynamics(&q, &v, &a, 0.0);
    eprintln!("{name}: tau[0] = {:.15e}", tau[0]);
    let mut group = c.benchmark_group(format!("regressor_{name}"));
    group.bench_function("regressor", |b| {
        b.iter(|| sys.regressor(black_box(&q), black_box(&v), black_box(&a), 0.0))
    });
    group.bench_function("inverse dynamics", |b| {
        b.iter(|| sys.inverse_dynamics(black_box(&q), black_box(&v), black_box(&a), 0.0))
    });
    let mut y = nalgebra::DMatrix::<f64>::zeros(N, S::REGRESSOR_PARAMETERS.len());
    group.bench_function("regressor into a held matrix", |b| {
        b.iter(|| {
            sys.regressor_into(
                black_box(&q),
                black_box(&v),
                black_box(&a),
                0.0,
                y.as_view_mut(),
            )
        })
    });
    group.finish();
}

fn arms(c: &mut Criterion) {
    time::<Ur5, 6>(c, "ur5");
    time::<Ur10, 6>(c, "ur10");
    time::<Kinova, 6>(c, "kinova");
    time::<Ur5AsWritten, 6>(c, "ur5_as_written");
    time::<KinovaAsWritten, 6>(c, "kinova_as_written");
    time::<Z1, 7>(c, "z1");
    time::<Xarm7, 7>(c, "xarm7");
}

criterion_group!(benches, arms);
criterion_main!(benches);
