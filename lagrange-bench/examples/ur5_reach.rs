//! Our side of the Crocoddyl peer (`peer/crocoddyl/`): the UR5's tool
//! drawn 20 cm in 0.6 s under torques within ±40 N·m (the problem of
//! `tests/planning.rs`), solved by `plan::Ddp` from gravity compensation,
//! timed as `ur5_reach.py` times Crocoddyl's `SolverBoxFDDP`: the median of
//! `--repeats` solves, per solve and per iteration. Prints one line in the
//! Python script's format and writes the plan's inputs to `--out`.
//!
//!     cargo run --release -p lagrange-bench --example ur5_reach -- [--method rk4|euler] [--iterations N] [--repeats R] [--out u.csv]

use lagrange::Lagrangian;
use lagrange::linear::{OperatingPoint, StepMethod, Transition, Trim};
use lagrange::nalgebra::{DMatrix, DVector, SVector, Vector3};
use lagrange::plan::{Ddp, FramePosition, OptimalControl, Plan};
use lagrange::pose::Kinematics;
use std::time::Instant;

/// The UR5 with a torque input at each joint, its Jacobians and kinematics
/// emitted.
#[derive(Lagrangian)]
#[lagrange(
    urdf = "../robots/ur5.urdf",
    inputs(u1, u2, u3, u4, u5, u6),
    generalized_force(
        shoulder_pan_joint = u1,
        shoulder_lift_joint = u2,
        elbow_joint = u3,
        wrist_1_joint = u4,
        wrist_2_joint = u5,
        wrist_3_joint = u6
    ),
    gravity = [0, 0, -9.81],
    emit(jacobians, kinematics)
)]
struct Ur5 {}

/// `--name value` from the command line, or `default`.
fn option(name: &str, default: &str) -> String {
    let args: Vec<String> = std::env::args().collect();
    (args.iter().position(|a| a == name))
        .and_then(|i| args.get(i + 1).cloned())
        .unwrap_or_else(|| default.to_string())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let iterations: usize = option("--iterations", "200").parse()?;
    let repeats: usize = option("--repeats", "20").parse()?;
    let method = match option("--method", "rk4").as_str() {
        "rk4" => StepMethod::Rk4,
        "euler" => StepMethod::SemiImplicitEuler,
        other => return Err(format!("--method rk4 or euler, not {other}").into()),
    };
    let ur5 = Ur5 {};
    let tool = Ur5::body_index("tool0").ok_or("the UR5 has tool0")?;
    let home = SVector::<f64, 6>::from([0.0, -1.2, 1.5, -1.8, -1.57, 0.0]);
    let zero = SVector::<f64, 6>::zeros();
    let start = lagrange::Configuration::new(&ur5, home, 0.0)?;
    let target = start.poses().0[tool].origin + Vector3::new(0.1, 0.15, -0.05);
    let hold = Trim::new()
        .hold(&Ur5::COORDINATES)
        .solve(&ur5, &OperatingPoint::new(home, zero))?;
    let weight = |d: [f64; 12]| DMatrix::from_diagonal(&DVector::from_column_slice(&d));
    let speeds = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0];
    let problem = OptimalControl::new(
        Transition::new(&ur5, 0.02)?.method(method),
        30,
        (home, zero),
        weight(speeds) * 0.01,
        DMatrix::identity(6, 6) * 1e-4,
    )
    .input_target(hold.u)
    .final_weight(weight(speeds) * 100.0)
    .final_cost(FramePosition::new(&ur5, tool, target, 1e5))
    .input_bounds(SVector::repeat(-40.0), SVector::repeat(40.0));
    let solver = Ddp::new().max_iterations(iterations).tolerance(1e-9);
    let solve = || -> (Plan<6, 6>, f64) {
        let clock = Instant::now();
        let plan = match solver.solve(&problem, &[hold.u; 30]) {
            Ok(plan) => plan,
            // Out of iterations (a fixed count asked for) or stalled: the
            // best plan, as Crocoddyl returns its last iterate.
            Err(failure) => *failure.partial,
        };
        (plan, clock.elapsed().as_secs_f64())
    };
    let mut times = Vec::with_capacity(repeats);
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let (plan, seconds) = solve();
        times.push(seconds);
        last = Some(plan);
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let plan = last.ok_or("no solve")?;
    let done = plan.log.len();
    println!(
        "lagrange iterations {done} cost {:.12e} per_solve {median:.6e} per_iteration {:.6e}",
        plan.cost,
        median / done.max(1) as f64
    );
    let out = option("--out", "");
    if !out.is_empty() {
        let rows: Vec<String> = (plan.u.iter())
            .map(|u| {
                u.iter()
                    .map(|x| format!("{x:.17e}"))
                    .collect::<Vec<_>>()
                    .join(",")
            })
            .collect();
        std::fs::write(out, rows.join("\n") + "\n")?;
    }
    Ok(())
}
