//! Prints, for the generic n-link planar pendulum (n = 1..10), the size of the
//! emitted M + (Q − h) program and how long the derivation took.
//!
//!     cargo run --release -p lagrange-codegen --example opcount

use std::time::Instant;

use lagrange_codegen::chain::n_link_source;
use lagrange_symbolic::Program;

fn main() {
    println!("| n | derive + emit (ms) | ops | add | mul | div | sin/cos/... | route for h |");
    println!("|---|---|---|---|---|---|---|---|");
    for n in 1..=10 {
        let input: syn::DeriveInput = syn::parse_str(&n_link_source(n)).expect("source parses");
        let start = Instant::now();
        let tokens = lagrange_codegen::expand(&input);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        std::hint::black_box(tokens);
        let model = lagrange_codegen::model(&input).expect("derivation succeeds");
        let mut outputs: Vec<_> = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| model.mass[i][j])
            .collect();
        outputs.extend(&model.rhs);
        let ops = Program::new(&model.ctx, &outputs).op_count();
        println!(
            "| {n} | {ms:.1} | {} | {} | {} | {} | {} | {:?} |",
            ops.total(),
            ops.add,
            ops.mul,
            ops.div,
            ops.call,
            model.bias_route
        );
    }
}
