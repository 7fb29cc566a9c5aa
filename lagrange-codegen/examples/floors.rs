//! Operation counts of the programs the derive emits for the robots in
//! `robots/`, beside the algorithmic floors Featherstone and Orin tabulate
//! for revolute chains of n joints (*Robot dynamics: equations and
//! algorithms*, ICRA 2000, Table 1): RNEA 93n − 108 multiplications and
//! 81n − 100 additions, CRBA 10n² + 22n − 32 and 6n² + 37n − 43, ABA
//! 224n − 174 and 205n − 181. Our counts are after common subexpressions
//! and constant folding (a robot's zero offsets and quarter turns vanish);
//! theirs count a general chain, so a count below the floor is the file's
//! structure, not a better algorithm. The UR5 and the Kinova are counted
//! also with `snap = 0` (their quarter turns, written to twelve digits, as
//! written; by default they are made exact), and every robot's regressor
//! Y beside.
//!
//!     cargo run --release -p lagrange-codegen --example floors

use std::time::Instant;

use lagrange_codegen::mechanics::{Model, Route};
use lagrange_symbolic::{Expr, OpCount, Program};

fn count(model: &Model, outputs: &[Expr]) -> OpCount {
    Program::new(&model.ctx, outputs).op_count()
}

/// `mul + add (floor mul + add)`.
fn beside(c: OpCount, floor: Option<(i64, i64)>) -> String {
    let ours = format!("{} + {}", c.mul, c.add);
    match floor {
        Some((m, a)) => format!("{ours} ({m} + {a})"),
        None => ours,
    }
}

/// The outputs of ∂τ/∂(q, q̇), of the one program of q̈ and ∂q̈/∂(q, q̇, τ),
/// and of Y.
fn derivatives_and_regressor(model: &Model) -> (Vec<Expr>, Vec<Expr>, Vec<Expr>) {
    let j = model.outputs.jacobians.as_ref().expect("emitted");
    let jac: Vec<Expr> = j
        .position
        .iter()
        .chain(&j.velocity)
        .flatten()
        .copied()
        .collect();
    let s = model.outputs.solved.as_ref().expect("emitted");
    let mut solved: Vec<Expr> = s.acceleration.clone();
    for m in [&s.position, &s.velocity, &s.inverse_mass] {
        solved.extend(m.iter().flatten());
    }
    let regressor = model.outputs.regressor.as_ref().expect("emitted");
    let y: Vec<Expr> = regressor.rows.iter().flatten().copied().collect();
    (jac, solved, y)
}

fn main() {
    println!(
        "| robot | n | derive (ms) | τ by RNEA (floor) | M by CRBA (floor) | q̈ by ABA (floor) | ∂τ/∂(q, q̇) | q̈ and ∂q̈/∂(q, q̇, τ), one program | Y |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut depths = Vec::new();
    for (file, options) in [
        ("ur5.urdf", ""),
        ("ur5.urdf", ", snap = 0"),
        ("ur10.urdf", ""),
        ("kinova.urdf", ""),
        ("kinova.urdf", ", snap = 0"),
        ("z1.urdf", ", dynamics = ignore"),
        ("xarm7.urdf", ", dynamics = ignore"),
        ("solo12.urdf", ", base = floating"),
    ] {
        let src = format!(
            "#[lagrange(urdf(\"{}/../robots/{file}\"{options}), gravity = [0, 0, -9.81], emit(jacobians, articulated, inverse_dynamics, regressor))] struct Robot {{}}",
            env!("CARGO_MANIFEST_DIR")
        );
        let input: syn::DeriveInput = syn::parse_str(&src).expect("source parses");
        let start = Instant::now();
        let model = lagrange_codegen::model_by(&input, Route::Recursive).expect("derives");
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let n = model.dof() as i64;
        // The floors are for chains of revolute joints: not a floating base.
        let chain = !options.contains("base = floating");
        let floor = |f: (i64, i64)| chain.then_some(f);
        let rnea = count(
            &model,
            &model.outputs.inverse.as_ref().expect("emitted").torques,
        );
        let mass: Vec<Expr> = model.motion.mass.iter().flatten().copied().collect();
        let crba = count(&model, &mass);
        let aba = count(
            &model,
            &model
                .outputs
                .articulated
                .as_ref()
                .expect("emitted")
                .accelerations,
        );
        let (jac, solved, y) = derivatives_and_regressor(&model);
        let depth = |outputs: &[Expr]| Program::new(&model.ctx, outputs).latency_depth();
        depths.push(format!(
            "| {file}{options} | {} | {} |",
            depth(&jac),
            depth(&solved)
        ));
        println!(
            "| {file}{options} | {n} | {ms:.0} | {} | {} | {} | {} | {} | {} |",
            beside(rnea, floor((93 * n - 108, 81 * n - 100))),
            beside(
                crba,
                floor((10 * n * n + 22 * n - 32, 6 * n * n + 37 * n - 43))
            ),
            beside(aba, floor((224 * n - 174, 205 * n - 181))),
            beside(count(&model, &jac), None),
            beside(count(&model, &solved), None),
            beside(count(&model, &y), None),
        );
    }
    // The longest chain of dependent operations, in cycles of latency
    // (`Program::latency_depth`): what no width of processor runs faster.
    println!("\n| robot | ∂τ/∂(q, q̇), latency depth | the one program, latency depth |");
    println!("|---|---|---|");
    for line in depths {
        println!("{line}");
    }
}
