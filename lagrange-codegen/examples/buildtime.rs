//! The derive's own share of a robot crate's build time (BENCHMARKS.md,
//! "Build time"): for Solo 12 on a free root (plain and with `articulated`),
//! the A1 if its URDF is given, and the Panda with every output, how long
//! the derivation (`model`) and the whole expansion (`expand`) take, the size
//! of the expansion, and the operation counts of M + (Q − h) and of the
//! articulated-body q̈.
//!
//!     cargo run --release -p lagrange-codegen --example buildtime [-- path/to/a1.urdf]
//!
//! With `DUMP=dir` set, each expansion is written to `dir/<robot>.rs` (to
//! check that a change leaves the emitted code as it was).

use std::time::Instant;

use lagrange_codegen::mechanics::Model;
use lagrange_symbolic::{Expr, Program};

fn ops(model: &Model, outputs: &[Expr]) -> usize {
    Program::new(&model.ctx, outputs).op_count().total()
}

fn row(name: &str, urdf: &str, emit: &str) {
    let src = format!("#[lagrange(urdf({urdf}), gravity = [0, 0, -9.81]{emit})] struct Robot {{}}");
    let input: syn::DeriveInput = syn::parse_str(&src).expect("source parses");
    let start = Instant::now();
    let model = lagrange_codegen::model(&input).expect("derivation succeeds");
    let derive = start.elapsed().as_secs_f64() * 1e3;
    let start = Instant::now();
    let tokens = lagrange_codegen::expand(&input);
    let expand = start.elapsed().as_secs_f64() * 1e3;
    let kib = tokens.to_string().len() as f64 / 1024.0;
    if let Ok(dir) = std::env::var("DUMP") {
        std::fs::write(format!("{dir}/{name}.rs"), tokens.to_string()).expect("written");
    }
    let mut core: Vec<Expr> = model.motion.mass.iter().flatten().copied().collect();
    core.extend(&model.motion.rhs);
    let aba = (model.hoisted_articulated()).map_or("—".into(), |a| ops(&model, a).to_string());
    println!(
        "| {name} | {derive:.0} | {expand:.0} | {kib:.0} | {} | {aba} |",
        ops(&model, &core)
    );
}

fn main() {
    println!("| robot | model (ms) | expand (ms) | expansion (KiB) | M, Q − h (ops) | ABA (ops) |");
    println!("|---|---|---|---|---|---|");
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../robots");
    let solo = format!("\"{dir}/solo12.urdf\", base = floating");
    row("Solo 12", &solo, "");
    row("Solo 12 articulated", &solo, ", emit(articulated)");
    if let Some(a1) = std::env::args().nth(1) {
        let a1 = format!("\"{a1}\", base = floating");
        row("A1", &a1, "");
        row("A1 articulated", &a1, ", emit(articulated)");
    }
    let panda = format!("\"{dir}/panda.urdf\", dynamics = ignore");
    row(
        "Panda all",
        &panda,
        ", emit(inverse_dynamics, kinematics, jacobians)",
    );
    jacobians(&panda);
}

/// The operation counts of `emit(jacobians)`'s program: ∂/∂q and ∂/∂q̇ in
/// one program, and each in its own (what sharing between them saves).
fn jacobians(urdf: &str) {
    let src = format!(
        "#[lagrange(urdf({urdf}), gravity = [0, 0, -9.81], emit(jacobians))] struct Robot {{}}"
    );
    let input: syn::DeriveInput = syn::parse_str(&src).expect("source parses");
    let model = lagrange_codegen::model(&input).expect("derivation succeeds");
    let Some(j) = &model.outputs.jacobians else {
        return;
    };
    let q: Vec<Expr> = j.position.iter().flatten().copied().collect();
    let v: Vec<Expr> = j.velocity.iter().flatten().copied().collect();
    let both: Vec<Expr> = q.iter().chain(&v).copied().collect();
    println!(
        "\njacobians: one program {} ops; apart {} (∂/∂q) + {} (∂/∂q̇)",
        ops(&model, &both),
        ops(&model, &q),
        ops(&model, &v)
    );
}
