//! Feasibility-driven DDP (`Ddp::solve_from`): from a rollout it is the
//! solve from inputs; from states that do not satisfy the dynamics it
//! closes the gaps and reaches the same plan (from a straight line to the
//! goal and from wild guesses); on a linear-quadratic problem
//! one full step closes them and lands on the optimum.

use super::ddp::{Ddp, Plan};
use super::problem::OptimalControl;
use crate::error::{Error, PlanError};
use crate::linear::test_systems::{Oscillator, Pendulum};
use crate::linear::{Transition, dlqr};
use nalgebra::{DMatrix, DVector, SVector, Vector1};
use std::f64::consts::PI;

fn diagonal(d: &[f64]) -> DMatrix<f64> {
    DMatrix::from_diagonal(&DVector::from_column_slice(d))
}

const STEPS: usize = 200;

fn swing_up() -> OptimalControl<'static, Pendulum, 1, 1> {
    let tr = Transition::new(&Pendulum, 0.02).unwrap();
    let start = (Vector1::new(0.0), Vector1::new(0.0));
    OptimalControl::new(tr, STEPS, start, diagonal(&[0.0, 0.0]), diagonal(&[0.01]))
        .goal(Vector1::new(PI), Vector1::new(0.0))
        .final_weight(diagonal(&[1000.0, 100.0]))
        .input_bounds(Vector1::new(-3.0), Vector1::new(3.0))
}

/// The largest difference of two plans' inputs.
fn input_gap<const N: usize, const P: usize>(a: &Plan<N, P>, b: &Plan<N, P>) -> f64 {
    (a.u.iter().zip(&b.u))
        .map(|(x, y)| (x - y).amax())
        .fold(0.0, f64::max)
}

/// The rollout of `us` from the problem's start.
fn rollout(
    problem: &OptimalControl<Pendulum, 1, 1>,
    us: &[Vector1<f64>],
) -> (Vec<Vector1<f64>>, Vec<Vector1<f64>>) {
    let (mut q, mut v) = (vec![Vector1::new(0.0)], vec![Vector1::new(0.0)]);
    for (k, u) in us.iter().enumerate() {
        let (q1, v1) = problem
            .transition
            .step(&q[k], &v[k], u, problem.time(k))
            .unwrap();
        q.push(q1);
        v.push(v1);
    }
    (q, v)
}

#[test]
fn from_a_rollout_it_is_the_solve_from_inputs() {
    let problem = swing_up();
    let guess = vec![Vector1::new(0.5); STEPS];
    let (q, v) = rollout(&problem, &guess);
    let solver = Ddp::new().tolerance(1e-5);
    let a = solver.solve(&problem, &guess).unwrap();
    let b = solver.solve_from(&problem, &q, &v, &guess).unwrap();
    assert_eq!(a.log.len(), b.log.len());
    assert!(
        (a.cost - b.cost).abs() <= 1e-9 * a.cost,
        "{} vs {}",
        a.cost,
        b.cost
    );
    let du = input_gap(&a, &b);
    assert!(du <= 1e-9, "inputs differ by {du:e}");
    assert!(b.log.iter().all(|i| i.gap == 0.0));
}

/// A straight line from hanging to upright at constant speed, with no
/// torque: nothing like a motion of the pendulum (whose torque is below its
/// weight). The gaps close, the log's feasibility falls to zero and stays
/// there, and the plan is the one the solve from inputs finds.
#[test]
fn from_a_straight_line_it_reaches_the_swing_up() {
    let problem = swing_up();
    let rate = PI / (STEPS as f64 * 0.02);
    let q: Vec<_> = (0..=STEPS)
        .map(|k| Vector1::new(PI * k as f64 / STEPS as f64))
        .collect();
    let v = vec![Vector1::new(rate); STEPS + 1];
    let u = vec![Vector1::zeros(); STEPS];
    let solver = Ddp::new().tolerance(1e-5);
    let fddp = solver.solve_from(&problem, &q, &v, &u).unwrap();
    let ddp = solver.solve(&problem, &[]).unwrap();
    let first = (0..STEPS)
        .map(|k| {
            let (q1, v1) = problem.transition.step(&q[k], &v[k], &u[k], 0.0).unwrap();
            (q1 - q[k + 1]).amax().max((v1 - v[k + 1]).amax())
        })
        .fold(0.0, f64::max);
    assert!(first > 0.1, "the guess's largest gap is {first}");
    let gaps: Vec<f64> = fddp.log.iter().map(|i| i.gap).collect();
    let closed = gaps.iter().position(|&g| g == 0.0).expect("the gaps close");
    assert!(gaps[closed..].iter().all(|&g| g == 0.0), "{gaps:?}");
    assert!(gaps.windows(2).all(|w| w[1] <= w[0]), "{gaps:?}");
    assert_eq!(fddp.gap, 0.0);
    let (theta, omega) = (fddp.q[STEPS][0], fddp.v[STEPS][0]);
    assert!(
        (theta - PI).abs() < 0.02 && omega.abs() < 0.05,
        "ends at ({theta}, {omega})"
    );
    assert!(
        (fddp.cost - ddp.cost).abs() <= 1e-6 * ddp.cost,
        "FDDP {} vs DDP {} ({} and {} iterations)",
        fddp.cost,
        ddp.cost,
        fddp.log.len(),
        ddp.log.len()
    );
    let du = input_gap(&fddp, &ddp);
    assert!(du < 1e-4, "inputs differ by {du:e}");
    // The plan is a rollout of its inputs.
    let (q1, v1) = rollout(&problem, &fddp.u);
    let off = (q1.iter().zip(&fddp.q)).chain(v1.iter().zip(&fddp.v));
    assert!(off.map(|(a, b)| (a - b).amax()).fold(0.0, f64::max) < 1e-12);
}

/// A linear system with the DARE's P as terminal weight, from states drawn
/// at random: the first step is full (α = 1), closes every gap, and lands on
/// the LQR's plan, which the next backward pass finds stationary.
#[test]
fn a_linear_quadratic_problem_closes_its_gaps_in_one_step() {
    let osc = Oscillator { k: 4.0, c: 0.3 };
    let tr = Transition::new(&osc, 0.05).unwrap();
    let (z, one) = (Vector1::zeros(), Vector1::zeros());
    let d = tr.derivatives(&z, &z, &one, 0.0).unwrap();
    let (wx, wu) = (diagonal(&[1.0, 0.5]), diagonal(&[0.1]));
    let lqr = dlqr(&d.dx, &d.du, &wx, &wu).unwrap();
    let start = (Vector1::new(2.0), Vector1::new(-1.0));
    let problem = OptimalControl::new(tr, 40, start, wx, wu).final_weight(lqr.riccati.clone());
    let wobble = |k: usize, s: f64| Vector1::new((k as f64 * s).sin() * 3.0);
    let q: Vec<_> = (0..=40).map(|k| wobble(k, 1.3)).collect();
    let v: Vec<_> = (0..=40).map(|k| wobble(k, 0.7)).collect();
    let u: Vec<_> = (0..40).map(|k| wobble(k, 2.1)).collect();
    let plan = Ddp::new()
        .tolerance(1e-10)
        .regularization(0.0)
        .solve_from(&problem, &q, &v, &u)
        .unwrap();
    assert_eq!(plan.log[0].step, 1.0);
    assert_eq!(plan.log[0].gap, 0.0);
    assert_eq!(plan.log.len(), 2, "{:?}", plan.log);
    for k in [0, 17, 39] {
        let x = DVector::from_column_slice(&[plan.q[k][0], plan.v[k][0]]);
        let lqr_u = -(&lqr.gain * &x)[0];
        assert!(
            (plan.u[k][0] - lqr_u).abs() < 1e-9,
            "step {k}: {} vs {lqr_u}",
            plan.u[k][0]
        );
    }
    assert_eq!((plan.q[0][0], plan.v[0][0]), (2.0, -1.0));
}

/// Stopped short from an infeasible guess: the failure keeps the iterate,
/// gaps and all, and says how large they are.
#[test]
fn a_budget_hit_reports_the_gaps() {
    let problem = swing_up();
    let q = vec![Vector1::new(1.0); STEPS + 1];
    let v = vec![Vector1::new(0.0); STEPS + 1];
    let u = vec![SVector::<f64, 1>::zeros(); STEPS];
    let failure = Ddp::new()
        .max_iterations(1)
        .solve_from(&problem, &q, &v, &u)
        .unwrap_err();
    let Error::Plan(PlanError::NotConverged { gap, .. }) = failure.error else {
        panic!("{}", failure.error)
    };
    assert_eq!(gap, failure.partial.gap);
    assert!(failure.to_string().contains("largest gap"), "{failure}");
    let e = Ddp::new()
        .solve_from(&problem, &q[..3], &v, &u)
        .unwrap_err()
        .error;
    assert!(e.to_string().contains("3 configurations"), "{e}");
}

/// Wild guesses, oscillating up to 10 rad and 50 rad/s with no relation
/// between q and v: the first step closes every gap, and the plans found
/// are the swing-up the solve from inputs finds (cost to 1e-9).
#[test]
fn from_wild_guesses_it_reaches_the_swing_up() {
    let problem = swing_up();
    let solver = Ddp::new().tolerance(1e-5);
    let ddp = solver.solve(&problem, &[]).unwrap();
    for amplitude in [3.0, 10.0] {
        let wave = |k: usize, a: f64, period: f64| Vector1::new(a * (k as f64 / period).sin());
        let q: Vec<_> = (0..=STEPS).map(|k| wave(k, amplitude, 7.0)).collect();
        let v: Vec<_> = (0..=STEPS).map(|k| wave(k, 5.0 * amplitude, 3.0)).collect();
        let u = vec![SVector::<f64, 1>::zeros(); STEPS];
        let plan = solver.solve_from(&problem, &q, &v, &u).unwrap();
        assert_eq!((plan.log[0].step, plan.log[0].gap), (1.0, 0.0));
        assert_eq!(plan.gap, 0.0);
        assert!(
            (plan.cost - ddp.cost).abs() <= 1e-9 * ddp.cost,
            "amplitude {amplitude}: {} vs {}",
            plan.cost,
            ddp.cost
        );
    }
}
