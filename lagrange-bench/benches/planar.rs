//! The planar n-link chain (point masses, absolute angles), derived, against
//! the closed form collected by hand (`lagrange_bench::closed_form`) in the
//! same run, at n = 10, 20, 30: M + (Q − h) per call, with the parameter-only
//! terms computed once (as a run does) and at every call.
//!
//!     cargo bench -p lagrange-bench --bench planar

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::Lagrangian;
use lagrange_bench::closed_form::PlanarChain;
use nalgebra::SVector;
use std::hint::black_box;

include!(concat!(env!("OUT_DIR"), "/planar_chains.rs"));

fn state<const N: usize>() -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_fn(|i, _| 0.3 + 0.01 * i as f64),
        SVector::from_fn(|i, _| 0.2 - 0.01 * i as f64),
    )
}

macro_rules! planar_bench {
    ($c:expr, $module:ident, $n:literal) => {{
        let sys = $module::Chain::sample();
        let terms = sys.parameter_terms();
        let hand = PlanarChain::<$n>::sample();
        let (q, v) = state::<$n>();
        let mut group = $c.benchmark_group(concat!("planar_chain_", stringify!($n)));
        group.bench_function("derived, terms once", |b| {
            b.iter(|| sys.mass_matrix_and_rhs_with(&terms, black_box(&q), black_box(&v), 0.0))
        });
        group.bench_function("derived, terms every call", |b| {
            b.iter(|| sys.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
        });
        group.bench_function("closed form", |b| {
            b.iter(|| hand.mass_matrix_and_rhs(black_box(&q), black_box(&v)))
        });
        group.finish();
    }};
}

fn planar(c: &mut Criterion) {
    planar_bench!(c, planar10, 10);
    planar_bench!(c, planar20, 20);
    planar_bench!(c, planar30, 30);
}

criterion_group!(benches, planar);
criterion_main!(benches);
