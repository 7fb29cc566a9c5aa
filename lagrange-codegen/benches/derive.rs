//! How long the macro takes to derive and emit the n-link planar pendulum, n = 1..10,
//! and how many operations the emitted M + h program needs (printed once per n,
//! so later work can compare). Reference points (issue 2): SymPy 1.14's
//! LagrangesMethod takes ~22 s to form the 10-link equations and its CSE'd M and
//! forcing count ~2,100 operations.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use lagrange_codegen::chain::n_link_source;
use lagrange_symbolic::Program;
use std::hint::black_box;

fn derive(c: &mut Criterion) {
    let mut group = c.benchmark_group("derive_n_link");
    group.sample_size(10);
    for n in 1..=10 {
        let input: syn::DeriveInput = syn::parse_str(&n_link_source(n)).expect("source parses");
        let model = lagrange_codegen::model(&input).expect("derivation succeeds");
        let mut outputs: Vec<_> = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| model.motion.mass[i][j])
            .collect();
        outputs.extend(&model.motion.rhs);
        let ops = Program::new(&model.ctx, &outputs).op_count();
        println!(
            "n = {n:2}: M + (Q - h) program: {} ops ({} add, {} mul, {} div, {} calls)",
            ops.total(),
            ops.add,
            ops.mul,
            ops.div,
            ops.call
        );
        group.bench_with_input(BenchmarkId::from_parameter(n), &input, |b, input| {
            b.iter(|| lagrange_codegen::expand(black_box(input)))
        });
    }
    group.finish();
}

criterion_group!(benches, derive);
criterion_main!(benches);
