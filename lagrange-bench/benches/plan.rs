//! Time per DDP iteration on the UR5's tool problem (the tool drawn 20 cm
//! in 0.6 s, 30 RK4 steps of 20 ms, torques within ±40 N·m, the test in
//! `tests/planning.rs`) with each stage's derivatives on the stack
//! (`Dynamics::input_derivatives`: q̈ and its emitted Jacobians from one
//! factorisation) and, in the same run, through the stages' linearisations
//! (`Linearizer::tangent_driven`, the path before it). Each solve runs
//! three iterations from gravity compensation; the time is per solve. The
//! group `transition_ur5` times one step's derivatives alone both ways.
//!
//!     cargo bench -p lagrange-bench --bench plan

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::Lagrangian;
use lagrange::linear::{OperatingPoint, Transition, Trim};
use lagrange::nalgebra::{DMatrix, DVector, SVector, Vector3};
use lagrange::plan::{Ddp, FramePosition, OptimalControl};
use lagrange::pose::Kinematics;
use std::hint::black_box;

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

const ITERATIONS: usize = 3;

fn plan(c: &mut Criterion) {
    let ur5 = Ur5 {};
    let tool = Ur5::body_index("tool0").expect("the UR5 has tool0");
    let home = SVector::<f64, 6>::from([0.0, -1.2, 1.5, -1.8, -1.57, 0.0]);
    let zero = SVector::<f64, 6>::zeros();
    let start = lagrange::Configuration::new(&ur5, home, 0.0).unwrap();
    let target = start.poses().0[tool].origin + Vector3::new(0.1, 0.15, -0.05);
    let hold = Trim::new()
        .hold(&Ur5::COORDINATES)
        .solve(&ur5, &OperatingPoint::new(home, zero))
        .unwrap();
    let weight = |d: [f64; 12]| DMatrix::from_diagonal(&DVector::from_column_slice(&d));
    let still = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
    let problem = |through_linearizer: bool| {
        let transition = Transition::new(&ur5, 0.02)
            .unwrap()
            .through_linearizer(through_linearizer);
        OptimalControl::new(
            transition,
            30,
            (home, zero),
            weight([0.0; 12]),
            DMatrix::identity(6, 6) * 1e-4,
        )
        .input_target(hold.u)
        .final_weight(weight(still) * 100.0)
        .final_cost(FramePosition::new(&ur5, tool, target, 1e4))
        .input_bounds(SVector::repeat(-40.0), SVector::repeat(40.0))
    };
    let solver = Ddp::new().max_iterations(ITERATIONS).tolerance(1e-12);
    interleaved(&solver, &problem(false), &problem(true), &[hold.u; 30]);
    let mut group = c.benchmark_group(format!("ddp_ur5_{ITERATIONS}_iterations"));
    group.sample_size(20);
    for (name, through_linearizer) in [("stack", false), ("linearizer", true)] {
        let problem = problem(through_linearizer);
        let log = solver
            .solve(&problem, &[hold.u; 30])
            .unwrap_err()
            .partial
            .log;
        eprintln!(
            "{name}: costs {:?}",
            log.iter().map(|i| i.cost).collect::<Vec<_>>()
        );
        group.bench_function(name, |b| {
            b.iter(|| solver.solve(black_box(&problem), &[hold.u; 30]).is_err())
        });
    }
    group.finish();
    let q = home;
    let v = SVector::<f64, 6>::from([0.5, -0.3, 0.8, 1.1, -0.6, 0.9]);
    let mut group = c.benchmark_group("transition_ur5");
    for (name, through_linearizer) in [("stack", false), ("linearizer", true)] {
        let transition = Transition::new(&ur5, 0.02)
            .unwrap()
            .through_linearizer(through_linearizer);
        group.bench_function(name, |b| {
            b.iter(|| transition.derivatives(black_box(&q), black_box(&v), &hold.u, 0.0))
        });
    }
    group.finish();
}

/// Seconds per iteration of each problem's solve, timed in alternation
/// (15 rounds of 20 solves each way), so that a machine shared with other
/// work slows both alike; printed with the ratio's median and range.
fn interleaved<S: lagrange::Driven<f64, 6, 6>>(
    solver: &Ddp,
    stack: &OptimalControl<S, 6, 6>,
    linearizer: &OptimalControl<S, 6, 6>,
    guess: &[SVector<f64, 6>],
) {
    let per_iteration = |problem: &OptimalControl<S, 6, 6>| {
        let start = std::time::Instant::now();
        for _ in 0..20 {
            black_box(solver.solve(black_box(problem), guess).is_err());
        }
        start.elapsed().as_secs_f64() / (20 * ITERATIONS) as f64
    };
    let mut rounds: Vec<(f64, f64)> = (0..15)
        .map(|_| (per_iteration(stack), per_iteration(linearizer)))
        .collect();
    rounds.sort_by(|a, b| (a.1 / a.0).total_cmp(&(b.1 / b.0)));
    let (fast, slow) = rounds[rounds.len() / 2];
    let (low, high) = (rounds[0].1 / rounds[0].0, rounds[14].1 / rounds[14].0);
    eprintln!(
        "per DDP iteration (UR5, 30 steps): stack {:.3} ms, linearizer {:.3} ms, \
         ratio {:.2} (median of 15 rounds; {low:.2}–{high:.2})",
        fast * 1e3,
        slow * 1e3,
        slow / fast
    );
}

criterion_group!(benches, plan);
criterion_main!(benches);
