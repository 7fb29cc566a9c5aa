//! Our side of the IPOPT peer (`peer/ipopt/`): the catalog's cart-pole swung
//! up from hanging to upright at rest exactly (a final equality), the force
//! within ±5 N and the cart within ±0.5 m of the rail's centre (state
//! limits), 50 RK4 steps of 50 ms, cost ½ Σ 0.01 F² (and, with
//! `--state-weight w`, ½ Σ w (x² + θ² + 0.1 ẋ² + 0.1 θ̇²)), from the rollout of
//! F = 0 — solved by `plan::Direct` (multiple shooting, an interior point
//! with Clarabel's sparse LDLᵀ) as `cart_pole.py` solves it by IPOPT
//! through CasADi, both to a tolerance of 1e-10. Prints one line in the
//! script's format (the median of `--repeats` solves; `iterations` counts
//! the log's records, one per Newton step and one at the plan) and writes
//! the forces to `--out`. `--steps K` takes K steps of 2.5 s / K.
//!
//!     cargo run --release -p lagrange-bench --features direct --example cart_pole_direct -- [--state-weight w] [--steps K] [--repeats R] [--out u.csv] [--iterations n] [--guess u.csv]

// The catalog's file holds other systems this example does not use.
#[allow(dead_code)]
#[path = "../../examples/catalog/control.rs"]
mod control;

use control::CartPole;
use lagrange::linear::Transition;
use lagrange::nalgebra::{DMatrix, DVector, Vector1, Vector2};
use lagrange::plan::{Direct, OptimalControl};
use std::f64::consts::PI;
use std::time::Instant;

/// `--name value` from the command line, or `default`.
fn option(name: &str, default: &str) -> String {
    let args: Vec<String> = std::env::args().collect();
    (args.iter().position(|a| a == name))
        .and_then(|i| args.get(i + 1).cloned())
        .unwrap_or_else(|| default.to_string())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let repeats: usize = option("--repeats", "10").parse()?;
    let w: f64 = option("--state-weight", "0").parse()?;
    // K steps of 2.5 s / K, as the script's `--steps`.
    let steps: usize = option("--steps", "50").parse()?;
    let cart_pole = CartPole::standard();
    let inf = f64::INFINITY;
    let problem = OptimalControl::new(
        Transition::new(&cart_pole, 2.5 / steps as f64)?,
        steps,
        (Vector2::new(0.0, PI), Vector2::zeros()),
        DMatrix::from_diagonal(&DVector::from_column_slice(&[1.0, 1.0, 0.1, 0.1])) * w,
        DMatrix::from_element(1, 1, 0.01),
    )
    .final_weight(DMatrix::zeros(4, 4))
    .final_equality()
    .input_bounds(Vector1::new(-5.0), Vector1::new(5.0))
    .state_limits(
        (Vector2::new(-0.5, -inf), Vector2::new(-inf, -inf)),
        (Vector2::new(0.5, inf), Vector2::new(inf, inf)),
    );
    let solver = Direct::new()
        .tolerance(1e-10)
        .max_iterations(option("--iterations", "3000").parse()?)
        .verbose(option("--verbose", "no") == "yes");
    // `--guess u.csv`: the rollout of these forces instead of F = 0.
    let guess: Vec<Vector1<f64>> = match option("--guess", "").as_str() {
        "" => Vec::new(),
        file => std::fs::read_to_string(file)?
            .lines()
            .map(|l| l.trim().parse().map(Vector1::new))
            .collect::<Result<_, _>>()?,
    };
    let mut times = Vec::with_capacity(repeats);
    let mut plan = None;
    let mut status = "converged".to_string();
    for _ in 0..repeats.max(1) {
        let clock = Instant::now();
        let solved = solver.solve(&problem, &guess);
        times.push(clock.elapsed().as_secs_f64());
        plan = Some(solved.unwrap_or_else(|failure| {
            // Reported, not hidden: the failure's best plan is timed and
            // printed with the reason.
            status = format!("{:?}", failure.error).replace(' ', "");
            *failure.partial
        }));
    }
    times.sort_by(f64::total_cmp);
    let plan = plan.ok_or("no solve")?;
    println!(
        "lagrange status {status} iterations {} cost {:.12e} per_solve {:.6e} kkt {:.1e} gap {:.1e}",
        plan.log.len(),
        plan.cost,
        times[times.len() / 2],
        plan.log.last().map_or(f64::NAN, |i| i.stationarity),
        plan.gap
    );
    let out = option("--out", "");
    if !out.is_empty() {
        let rows: Vec<String> = plan.u.iter().map(|u| format!("{:.17e}", u[0])).collect();
        std::fs::write(out, rows.join("\n") + "\n")?;
    }
    Ok(())
}
