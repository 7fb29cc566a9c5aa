//! Many states per call (`emit(batched)`) against one state per call: q̈ (the
//! articulated-body program) and q̈ with its derivatives (the `jacobians`
//! program) of the UR5 and the xArm7 read from their URDF, over 64 states,
//! each state checked as the scalar reading checks it; and the unchecked
//! programs alone over four states (one batched call, four scalar ones).
//! Throughput is states per second; the ratios in `BENCHMARKS.md` are
//! batched over scalar in one run.
//!
//!     cargo bench -p lagrange-bench --bench batched
//!     RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR=target/native \
//!         cargo bench -p lagrange-bench --bench batched

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use lagrange::{Batched, BatchedDifferentiable, F64x4, Lagrangian};
use nalgebra::SVector;
use std::hint::black_box;

macro_rules! arm {
    ($name:ident, $file:tt) => {
        #[derive(Lagrangian, Default)]
        #[lagrange(urdf($file, dynamics = ignore), gravity = [0, 0, -9.81], emit(articulated, jacobians, batched))]
        struct $name {}
    };
}

arm!(Ur5, "../robots/ur5.urdf");
arm!(Xarm7, "../robots/xarm7.urdf");

const STATES: usize = 64;

/// 64 states about q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k, τ_k = 0.1 k.
#[allow(clippy::type_complexity)]
fn states<const N: usize>() -> (
    Vec<SVector<f64, N>>,
    Vec<SVector<f64, N>>,
    Vec<SVector<f64, N>>,
) {
    let at = |s: usize, f: fn(usize) -> f64| {
        SVector::from_fn(|k, _| f(k) + 0.01 * s as f64 * (k as f64 - 2.0))
    };
    let q = (0..STATES)
        .map(|s| at(s, |k| 0.3 - 0.17 * k as f64))
        .collect();
    let v = (0..STATES)
        .map(|s| at(s, |k| 0.5 - 0.21 * k as f64))
        .collect();
    let tau = (0..STATES).map(|s| at(s, |k| 0.1 * k as f64)).collect();
    (q, v, tau)
}

/// One group per arm, `batched_<name>`: the checked readers over 64 states.
fn checked<S, const N: usize>(c: &mut Criterion, name: &str)
where
    S: Batched<N> + BatchedDifferentiable<N> + Default,
{
    let sys = S::default();
    let (q, v, tau) = states::<N>();
    let mut group = c.benchmark_group(format!("batched_{name}"));
    group.throughput(Throughput::Elements(STATES as u64));
    group.bench_function("q'' scalar", |b| {
        b.iter(|| {
            let dynamics = lagrange::Dynamics::new(&sys);
            for s in 0..STATES {
                black_box(dynamics.acceleration(0.0, black_box(&q[s]), black_box(&v[s]))).ok();
            }
        })
    });
    group.bench_function("q'' batched", |b| {
        b.iter(|| lagrange::batched_accelerations(&sys, black_box(&q), black_box(&v), &tau, 0.0))
    });
    group.bench_function("derivatives scalar", |b| {
        b.iter(|| {
            for s in 0..STATES {
                let (q, v) = (black_box(&q[s]), black_box(&v[s]));
                black_box(lagrange::acceleration_derivatives(&sys, q, v, &tau[s], 0.0)).ok();
            }
        })
    });
    group.bench_function("derivatives batched", |b| {
        b.iter(|| {
            lagrange::batched_acceleration_derivatives(
                &sys,
                black_box(&q),
                black_box(&v),
                &tau,
                0.0,
            )
        })
    });
    group.finish();
}

/// One group per arm, `lanes_<name>`: the unchecked programs, four states.
fn unchecked<S, const N: usize>(c: &mut Criterion, name: &str)
where
    S: Batched<N> + BatchedDifferentiable<N> + Default,
{
    let sys = S::default();
    let (q, v, tau) = states::<N>();
    let pack = |xs: &[SVector<f64, N>]| -> [F64x4; N] {
        std::array::from_fn(|i| F64x4::from_array(std::array::from_fn(|k| xs[k][i])))
    };
    let (ql, vl, taul) = (pack(&q), pack(&v), pack(&tau));
    let mut group = c.benchmark_group(format!("lanes_{name}"));
    group.throughput(Throughput::Elements(F64x4::LANES as u64));
    group.bench_function("q'' scalar", |b| {
        b.iter(|| {
            for s in 0..F64x4::LANES {
                black_box(sys.forward_dynamics(black_box(&q[s]), &v[s], &tau[s], 0.0));
            }
        })
    });
    group.bench_function("q'' lanes", |b| {
        b.iter(|| sys.acceleration_lanes_unchecked(black_box(&ql), &vl, &taul, F64x4::splat(0.0)))
    });
    group.bench_function("derivatives scalar", |b| {
        b.iter(|| {
            for s in 0..F64x4::LANES {
                let (q, v) = (black_box(&q[s]), &v[s]);
                black_box(sys.acceleration_derivatives_unchecked(q, v, &tau[s], 0.0));
            }
        })
    });
    group.bench_function("derivatives lanes", |b| {
        b.iter(|| {
            sys.acceleration_derivatives_lanes_unchecked(
                black_box(&ql),
                &vl,
                &taul,
                F64x4::splat(0.0),
            )
        })
    });
    group.finish();
}

fn batched(c: &mut Criterion) {
    checked::<Ur5, 6>(c, "ur5");
    checked::<Xarm7, 7>(c, "xarm7");
    unchecked::<Ur5, 6>(c, "ur5");
    unchecked::<Xarm7, 7>(c, "xarm7");
}

criterion_group!(benches, batched);
criterion_main!(benches);
