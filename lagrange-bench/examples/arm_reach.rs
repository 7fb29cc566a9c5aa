//! Our side of the Crocoddyl peer (`peer/crocoddyl/`): an arm's tool drawn
//! to a point within its torque limits, solved by `plan::Ddp` from gravity
//! compensation, timed as `arm_reach.py` times Crocoddyl's `SolverBoxFDDP`:
//! the median of `--repeats` solves, per solve and per iteration. Prints one
//! line in the Python script's format and writes the plan's inputs to
//! `--out`.
//!
//! The two problems (`--arm`), each written term for term in `arm_reach.py`:
//! - `ur5`: the problem of `tests/planning.rs`, the tool 20 cm away in 0.6 s
//!   (30 steps of 20 ms), torques within ±40 N·m;
//! - `xarm7`: the seven-joint xArm7's tool 25 cm away in 1 s (100 steps of
//!   10 ms), torques within the file's effort limits (50, 50, 30, 30, 30,
//!   20, 20 N·m).
//!
//! Running cost ½ Σ 0.01 v² + ½ 1e-4 |u − u_g|² per step (u_g gravity
//! compensation at home), final cost ½ Σ 100 v² + ½ 1e5 |p_tool − p*|².
//!
//!     cargo run --release -p lagrange-bench --example arm_reach -- [--arm ur5|xarm7] [--method euler|rk4] [--iterations N] [--repeats R] [--out u.csv] [--log yes]
//!
//! `--solver direct` (with `--features direct`) solves the same problem by
//! `plan::Direct` instead, which no peer here runs.

use lagrange::linear::{OperatingPoint, StepMethod, Transition, Trim};
use lagrange::nalgebra::{DMatrix, DVector, SVector, Vector3};
use lagrange::plan::{Ddp, FramePosition, OptimalControl, Plan};
use lagrange::pose::Kinematics;
use lagrange::{Driven, Lagrangian};
use std::time::Instant;

/// The UR5 with a torque input at each joint; its Jacobians, kinematics and
/// articulated-body q̈ emitted.
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
    emit(jacobians, kinematics, articulated)
)]
struct Ur5 {}

/// The xArm7 likewise.
#[derive(Lagrangian)]
#[lagrange(
    urdf("../robots/xarm7.urdf", dynamics = ignore),
    inputs(u1, u2, u3, u4, u5, u6, u7),
    generalized_force(
        joint1 = u1,
        joint2 = u2,
        joint3 = u3,
        joint4 = u4,
        joint5 = u5,
        joint6 = u6,
        joint7 = u7
    ),
    gravity = [0, 0, -9.81],
    emit(jacobians, kinematics, articulated)
)]
struct Xarm7 {}

/// One arm's reaching problem: where it starts, which body is the tool,
/// where the tool goes, in how many steps of what length, within which
/// torques.
struct Reach<const N: usize> {
    home: [f64; N],
    tool: &'static str,
    offset: [f64; 3],
    steps: usize,
    h: f64,
    limits: [f64; N],
}

/// `--name value` from the command line, or `default`.
fn option(name: &str, default: &str) -> String {
    let args: Vec<String> = std::env::args().collect();
    (args.iter().position(|a| a == name))
        .and_then(|i| args.get(i + 1).cloned())
        .unwrap_or_else(|| default.to_string())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    match option("--arm", "ur5").as_str() {
        "ur5" => solve(
            &Ur5 {},
            &Reach {
                home: [0.0, -1.2, 1.5, -1.8, -1.57, 0.0],
                tool: "tool0",
                offset: [0.1, 0.15, -0.05],
                steps: 30,
                h: 0.02,
                limits: [40.0; 6],
            },
        ),
        "xarm7" => solve(
            &Xarm7 {},
            &Reach {
                home: [0.0, -0.3, 0.0, 0.6, 0.0, 0.9, 0.0],
                tool: "link_eef",
                offset: [0.15, 0.15, -0.1],
                steps: 100,
                h: 0.01,
                limits: [50.0, 50.0, 30.0, 30.0, 30.0, 20.0, 20.0],
            },
        ),
        other => Err(format!("--arm ur5 or xarm7, not {other}").into()),
    }
}

/// Builds the arm's problem, solves it `--repeats` times, prints the line
/// and writes the plan.
fn solve<S, const N: usize>(arm: &S, reach: &Reach<N>) -> Result<(), Box<dyn std::error::Error>>
where
    S: Driven<f64, N, N> + Kinematics<f64, N>,
{
    let iterations: usize = option("--iterations", "200").parse()?;
    let repeats: usize = option("--repeats", "20").parse()?;
    let method = match option("--method", "euler").as_str() {
        "rk4" => StepMethod::Rk4,
        "euler" => StepMethod::SemiImplicitEuler,
        other => return Err(format!("--method rk4 or euler, not {other}").into()),
    };
    let tool = S::body_index(reach.tool).ok_or("the arm has its tool body")?;
    let home = SVector::<f64, N>::from(reach.home);
    let zero = SVector::<f64, N>::zeros();
    let start = lagrange::Configuration::new(arm, home, 0.0)?;
    let target = start.poses().0[tool].origin + Vector3::from(reach.offset);
    let hold = Trim::new()
        .hold(&S::COORDINATES)
        .solve(arm, &OperatingPoint::new(home, zero))?;
    let weight = |positions: f64, speeds: f64| {
        let d = DVector::from_fn(2 * N, |i, _| if i < N { positions } else { speeds });
        DMatrix::from_diagonal(&d)
    };
    let limit = SVector::<f64, N>::from(reach.limits);
    let problem = OptimalControl::new(
        Transition::new(arm, reach.h)?.method(method),
        reach.steps,
        (home, zero),
        weight(0.0, 0.01),
        DMatrix::identity(N, N) * 1e-4,
    )
    .input_target(hold.u)
    .final_weight(weight(0.0, 100.0))
    .final_cost(FramePosition::new(arm, tool, target, 1e5))
    .input_bounds(-limit, limit);
    let guess = vec![hold.u; reach.steps];
    match option("--solver", "ddp").as_str() {
        "ddp" => {}
        "direct" => return solve_direct(&problem, &guess, (iterations, repeats)),
        other => return Err(format!("--solver ddp or direct, not {other}").into()),
    }
    let solver = Ddp::new().max_iterations(iterations).tolerance(1e-9);
    let (plan, median) = time_solves(repeats, || match solver.solve(&problem, &guess) {
        Ok(plan) => plan,
        // Out of iterations (a fixed count asked for) or stalled: the best
        // plan, as Crocoddyl returns its last iterate.
        Err(failure) => *failure.partial,
    });
    report(&plan, median)
}

/// `--solver direct`: the same problem by `plan::Direct` (the feature
/// `direct`), for a look at the interior point on a seven-joint arm; no
/// peer runs it.
#[cfg(feature = "direct")]
fn solve_direct<S, const N: usize>(
    problem: &OptimalControl<S, N, N>,
    guess: &[SVector<f64, N>],
    (iterations, repeats): (usize, usize),
) -> Result<(), Box<dyn std::error::Error>>
where
    S: Driven<f64, N, N>,
{
    let solver = lagrange::plan::Direct::new()
        .max_iterations(iterations)
        .tolerance(1e-9)
        .verbose(option("--log", "no") == "yes");
    let (plan, median) = time_solves(repeats, || match solver.solve(problem, guess) {
        Ok(plan) => plan,
        Err(failure) => {
            eprintln!("direct: {}", failure.error);
            *failure.partial
        }
    });
    report(&plan, median)
}

#[cfg(not(feature = "direct"))]
fn solve_direct<S, const N: usize>(
    _: &OptimalControl<S, N, N>,
    _: &[SVector<f64, N>],
    _: (usize, usize),
) -> Result<(), Box<dyn std::error::Error>>
where
    S: Driven<f64, N, N>,
{
    Err("--solver direct needs the feature direct".into())
}

/// The last of `repeats` solves and the median time of one, in seconds.
fn time_solves<const N: usize>(
    repeats: usize,
    solve: impl Fn() -> Plan<N, N>,
) -> (Plan<N, N>, f64) {
    let mut times = Vec::with_capacity(repeats);
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let clock = Instant::now();
        let plan = solve();
        times.push(clock.elapsed().as_secs_f64());
        last = Some(plan);
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    (last.expect("at least one solve"), median)
}

/// Prints the log (`--log yes`) and the line `arm_reach.py` prints, and
/// writes the inputs to `--out`.
fn report<const N: usize>(
    plan: &Plan<N, N>,
    median: f64,
) -> Result<(), Box<dyn std::error::Error>> {
    if option("--log", "no") == "yes" {
        for (k, it) in plan.log.iter().enumerate() {
            eprintln!(
                "{k:3} cost {:.13e} stationarity {:.3e} step {} mu {:.0e}",
                it.cost, it.stationarity, it.step, it.regularization
            );
        }
    }
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
