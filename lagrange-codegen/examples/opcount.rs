//! Prints, for the generic n-link planar pendulum (n = 1..10), the size of the
//! emitted M + (Q − h) program and how long the derivation took; then the same for
//! every system of the catalog (read from `examples/catalog/*.rs` and derived
//! here), with the sizes of the constrained and reduced programs.
//!
//!     cargo run --release -p lagrange-codegen --example opcount

use std::time::Instant;

use lagrange_codegen::chain::{n_link_source, spatial_chain_source, spatial_chain_written_source};
use lagrange_codegen::mechanics::{Model, Route};
use lagrange_symbolic::{Expr, Program};

const CATALOG: [(&str, &str); 6] = [
    ("mod.rs", include_str!("../../examples/catalog/mod.rs")),
    (
        "constrained.rs",
        include_str!("../../examples/catalog/constrained.rs"),
    ),
    (
        "cavity.rs",
        include_str!("../../examples/catalog/cavity.rs"),
    ),
    (
        "extremes.rs",
        include_str!("../../examples/catalog/extremes.rs"),
    ),
    (
        "control.rs",
        include_str!("../../examples/catalog/control.rs"),
    ),
    (
        "bicycle.rs",
        include_str!("../../examples/catalog/bicycle.rs"),
    ),
];

fn ops(model: &Model, outputs: &[Expr]) -> usize {
    Program::new(&model.ctx, outputs).op_count().total()
}

/// Every `#[derive(Lagrangian)]` struct of the catalog: derivation time and the
/// operation counts of the programs the impls evaluate per step.
fn catalog() {
    println!(
        "\n| system | N | derive + emit (ms) | expansion (KiB) | M, Q − h | + G, γ (multipliers) | + A, b, c (reduced) | route for M, h |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (file, src) in CATALOG {
        let Ok(parsed) = syn::parse_file(src) else {
            println!("| {file}: does not parse |");
            continue;
        };
        for item in parsed.items {
            let syn::Item::Struct(s) = item else { continue };
            let derives = s.attrs.iter().any(|a| {
                a.path().is_ident("derive") && quote::quote!(#a).to_string().contains("Lagrangian")
            });
            if !derives {
                continue;
            }
            let input: syn::DeriveInput = s.into();
            let start = Instant::now();
            let tokens = std::hint::black_box(lagrange_codegen::expand(&input));
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let kib = tokens.to_string().len() as f64 / 1024.0;
            let Ok(model) = lagrange_codegen::model(&input) else {
                println!("| {} | derivation failed |", input.ident);
                continue;
            };
            let n = model.dof();
            let mut core: Vec<Expr> = model.motion.mass.iter().flatten().copied().collect();
            core.extend(&model.motion.rhs);
            let multipliers = model.constraints.multipliers.as_ref().map(|c| {
                let mut all = core.clone();
                all.extend(c.jacobian.iter().flatten());
                all.extend(&c.gamma);
                ops(&model, &all).to_string()
            });
            let reduced = model.constraints.reduced.as_ref().map(|r| {
                // M, Q − h and the rows the runtime solves (A, b, c).
                let mut all = core.clone();
                all.extend(r.matrix.iter().flatten());
                all.extend(&r.free);
                all.extend(&r.rates);
                ops(&model, &all).to_string()
            });
            println!(
                "| {} | {n} | {ms:.1} | {kib:.0} | {} | {} | {} | {:?} |",
                input.ident,
                ops(&model, &core),
                multipliers.unwrap_or_else(|| "—".into()),
                reduced.unwrap_or_else(|| "—".into()),
                model.motion.derivation.route,
            );
        }
    }
}

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
            .map(|(i, j)| model.motion.mass[i][j])
            .collect();
        outputs.extend(&model.motion.rhs);
        let ops = Program::new(&model.ctx, &outputs).op_count();
        println!(
            "| {n} | {ms:.1} | {} | {} | {} | {} | {} | {:?} |",
            ops.total(),
            ops.add,
            ops.mul,
            ops.div,
            ops.call,
            model.motion.derivation.route
        );
    }
    spatial();
    written();
    robots();
    catalog();
}

/// The robots in `robots/`, read from their URDF files: the operation count
/// of M and Q − h by each route, and how long each derivation took.
fn robots() {
    println!(
        "\n| robot (URDF) | dof | recursive: derive (ms), ops | generic: derive (ms), ops | emitted: ops, route (`ROUTE`) |"
    );
    println!("|---|---|---|---|---|");
    for (file, snap) in [
        ("ur5.urdf", ""),
        ("ur5.urdf", ", snap = 1e-6"),
        ("panda.urdf", ", dynamics = ignore"),
        ("ur10.urdf", ""),
        ("kinova.urdf", ""),
        ("kinova.urdf", ", snap = 1e-6"),
        ("z1.urdf", ", dynamics = ignore"),
        ("xarm7.urdf", ", dynamics = ignore"),
    ] {
        let src = format!(
            "#[lagrange(urdf(\"{}/../robots/{file}\"{snap}), gravity = [0, 0, -9.81])] struct Robot {{}}",
            env!("CARGO_MANIFEST_DIR")
        );
        let file = format!("{file}{snap}");
        let input: syn::DeriveInput = syn::parse_str(&src).expect("source parses");
        let by = |route| {
            let start = Instant::now();
            let model = lagrange_codegen::model_by(&input, route).expect("derivation succeeds");
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let mut outputs: Vec<Expr> = model.motion.mass.iter().flatten().copied().collect();
            outputs.extend(&model.motion.rhs);
            (ms, ops(&model, &outputs), model)
        };
        let (rm, rops, model) = by(Route::Recursive);
        let (gm, gops, _) = by(Route::Generic);
        let auto = lagrange_codegen::model_by(&input, Route::Auto).expect("derivation succeeds");
        let mut outputs: Vec<Expr> = auto.motion.mass.iter().flatten().copied().collect();
        outputs.extend(&auto.motion.rhs);
        let route = auto
            .motion
            .derivation
            .reason
            .as_deref()
            .map_or("recursive".into(), |why| format!("generic: {why}"));
        println!(
            "| {file} | {} | {rm:.0}, {rops} | {gm:.0}, {gops} | {}, {route} |",
            model.dof(),
            ops(&auto, &outputs),
        );
    }
}

/// The spatial chain (issue 10's robot-arm shape): derivation time, operation
/// count of M and Q − h, and the size of the expansion, by n.
fn spatial() {
    println!(
        "\n| spatial n | derive + emit (ms) | ops (M, Q − h) | generic route: derive (ms), ops | expansion (KiB) | EQUATIONS (KiB) |"
    );
    println!("|---|---|---|---|---|---|");
    let sizes: Vec<usize> = std::env::args()
        .nth(1)
        .map(|a| a.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| vec![2, 4, 6, 8]);
    for n in sizes {
        let input: syn::DeriveInput =
            syn::parse_str(&spatial_chain_source(n)).expect("source parses");
        let start = Instant::now();
        let tokens = lagrange_codegen::expand(&input);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let kib = tokens.to_string().len() as f64 / 1024.0;
        let model = lagrange_codegen::model(&input).expect("derivation succeeds");
        let mut outputs: Vec<Expr> = model.motion.mass.iter().flatten().copied().collect();
        outputs.extend(&model.motion.rhs);
        let ops = Program::new(&model.ctx, &outputs).op_count().total();
        let eq = lagrange_codegen::doc::equations(&model).len() as f64 / 1024.0;
        // The generic route (differentiating ξ(q)) for comparison, while it is quick.
        let generic = if n <= 14 {
            let start = Instant::now();
            let g =
                lagrange_codegen::model_by(&input, Route::Generic).expect("derivation succeeds");
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let mut outputs: Vec<Expr> = g.motion.mass.iter().flatten().copied().collect();
            outputs.extend(&g.motion.rhs);
            format!(
                "{ms:.0}, {}",
                Program::new(&g.ctx, &outputs).op_count().total()
            )
        } else {
            "—".into()
        };
        println!("| {n} | {ms:.0} | {ops} | {generic} | {kib:.0} | {eq:.0} |");
    }
}

/// The spatial chain with its poses written out (explicit matrices of
/// `define`s, ξ(q) as sums): the route its tree is read back onto, against
/// the same chain written with `rot_*` factors and points.
fn written() {
    println!(
        "\n| spatial n, written out | derive + emit (ms) | ops (M, Q − h) | route | ops with factors | generic: ops |"
    );
    println!("|---|---|---|---|---|---|");
    let sizes: Vec<usize> = std::env::args()
        .nth(1)
        .map(|a| a.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| vec![2, 4, 6, 8]);
    let count = |model: &Model| {
        let mut outputs: Vec<Expr> = model.motion.mass.iter().flatten().copied().collect();
        outputs.extend(&model.motion.rhs);
        Program::new(&model.ctx, &outputs).op_count().total()
    };
    for n in sizes {
        let input: syn::DeriveInput =
            syn::parse_str(&spatial_chain_written_source(n)).expect("source parses");
        let start = Instant::now();
        std::hint::black_box(lagrange_codegen::expand(&input));
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let model = lagrange_codegen::model(&input).expect("derivation succeeds");
        let factors: syn::DeriveInput =
            syn::parse_str(&spatial_chain_source(n)).expect("source parses");
        let factored = lagrange_codegen::model(&factors).expect("derivation succeeds");
        let generic = if n <= 14 {
            let g =
                lagrange_codegen::model_by(&input, Route::Generic).expect("derivation succeeds");
            count(&g).to_string()
        } else {
            "—".into()
        };
        println!(
            "| {n} | {ms:.0} | {} | {:?} | {} | {generic} |",
            count(&model),
            model.motion.derivation.route,
            count(&factored)
        );
    }
}
