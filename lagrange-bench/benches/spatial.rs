//! Issue 10's spatial chain (n rods, joint axes alternating z, y) at n = 6, 10,
//! 12, 14, 30: M + (Q − h) and q̈ per call, the figures to set beside Pinocchio's
//! CRBA + NLE and ABA from `peer/pinocchio/run.sh` on the same machine, and
//! the hand-written recursive peer (`lagrange_bench::recursive`) to n = 30.
//!
//!     cargo bench -p lagrange-bench --bench spatial

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::Lagrangian;
use nalgebra::SVector;
use std::hint::black_box;

include!(concat!(env!("OUT_DIR"), "/spatial_chains.rs"));

/// The state the Pinocchio harness uses: q_i = 0.3 + 0.01 i, v_i = 0.2 − 0.01 i.
fn state<const N: usize>() -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_fn(|i, _| 0.3 + 0.01 * i as f64),
        SVector::from_fn(|i, _| 0.2 - 0.01 * i as f64),
    )
}

macro_rules! chain_bench {
    ($c:expr, $module:ident, $articulated:ident, $n:literal) => {{
        let sys = $module::SpatialChain::benchmark();
        let (q, v) = state::<$n>();
        let mut group = $c.benchmark_group(concat!("spatial_chain_", stringify!($n)));
        group.bench_function("M + (Q - h)", |b| {
            b.iter(|| sys.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
        });
        group.bench_function("accelerations", |b| {
            b.iter(|| lagrange::accelerations(&sys, black_box(&q), black_box(&v), 0.0))
        });
        let aba = $articulated::SpatialChain::benchmark();
        group.bench_function("accelerations (articulated)", |b| {
            b.iter(|| lagrange::accelerations(&aba, black_box(&q), black_box(&v), 0.0))
        });
        group.finish();
    }};
}

/// The chain with its poses written out beside the same chain written with
/// `rot_*` factors and points, in one group.
macro_rules! written_bench {
    ($c:expr, $written:ident, $factored:ident, $n:literal) => {{
        let written = $written::SpatialChain::benchmark();
        let factored = $factored::SpatialChain::benchmark();
        let (q, v) = state::<$n>();
        let mut group = $c.benchmark_group(concat!("spatial_chain_written_", stringify!($n)));
        group.bench_function("M + (Q - h), written out", |b| {
            b.iter(|| written.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
        });
        group.bench_function("M + (Q - h), factors", |b| {
            b.iter(|| factored.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
        });
        group.finish();
    }};
}

fn spatial(c: &mut Criterion) {
    chain_bench!(c, n6, a6, 6);
    chain_bench!(c, n10, a10, 10);
    chain_bench!(c, n12, a12, 12);
    chain_bench!(c, n14, a14, 14);
    chain_bench!(c, n30, a30, 30);
    written_bench!(c, w6, n6, 6);
    written_bench!(c, w12, n12, 12);
    // The hand-written recursive Newton–Euler peer (M by n unit-acceleration
    // passes: O(n²), heap-allocated), to n = 30.
    let mut group = c.benchmark_group("spatial_chain_recursive");
    for n in [6, 10, 12, 14, 30] {
        let chain = lagrange_bench::recursive::SerialChain::benchmark(n);
        let q = nalgebra::DVector::from_fn(n, |i, _| 0.3 + 0.01 * i as f64);
        let v = nalgebra::DVector::from_fn(n, |i, _| 0.2 - 0.01 * i as f64);
        group.bench_function(format!("M + (Q - h), n = {n}"), |b| {
            b.iter(|| chain.mass_matrix_and_rhs(black_box(&q), black_box(&v)))
        });
    }
    group.finish();
}

criterion_group!(benches, spatial);
criterion_main!(benches);
