//! Derive + emit time of one chain model:
//! `cargo run --release -p lagrange-codegen --example expand_time -- planar 50`.
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(14);
    let source = match args.get(1).map(String::as_str) {
        Some("planar") => lagrange_codegen::chain::n_link_source(n),
        _ => lagrange_codegen::chain::spatial_chain_source(n),
    };
    let input: syn::DeriveInput = syn::parse_str(&source).expect("source parses");
    let start = Instant::now();
    let tokens = lagrange_codegen::expand(&input);
    let ms = start.elapsed().as_secs_f64() * 1e3;
    println!("{ms:.0} ms, {} KiB", tokens.to_string().len() / 1024);
}
