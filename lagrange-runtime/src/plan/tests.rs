//! DDP against the discrete LQR (a linear system with the Riccati solution
//! as terminal weight is solved exactly, and its gains are the LQR gain),
//! against its own optimality conditions under input bounds, on a
//! pendulum's swing-up with a torque below its weight, and in closed loop as
//! MPC; state bounds as a penalty, active.

use super::ddp::Ddp;
use super::problem::OptimalControl;
use super::*;
use crate::error::{Error, PlanError, SettingsError};
use crate::linear::test_systems::{G, Oscillator, Pendulum};
use crate::linear::{StepMethod, Transition, dlqr};
use nalgebra::{DMatrix, SVector, Vector1};

fn diagonal(d: &[f64]) -> DMatrix<f64> {
    DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(d))
}

const OSCILLATOR: Oscillator = Oscillator { k: 4.0, c: 0.3 };

fn oscillator_problem(steps: usize) -> OptimalControl<'static, Oscillator, 1, 1> {
    let tr = Transition::new(&OSCILLATOR, 0.05).unwrap();
    let start = (Vector1::new(2.0), Vector1::new(-1.0));
    OptimalControl::new(tr, steps, start, diagonal(&[1.0, 0.5]), diagonal(&[0.1]))
}

/// With the DARE's P as terminal weight, the finite horizon's optimal law is
/// the stationary LQR one, u_k = −K x_k, at every step.
#[test]
fn a_linear_problem_is_the_discrete_lqr() {
    let tr = Transition::new(&OSCILLATOR, 0.05).unwrap();
    let d = tr
        .derivatives(&Vector1::zeros(), &Vector1::zeros(), &Vector1::zeros(), 0.0)
        .unwrap();
    let lqr = dlqr(&d.dx, &d.du, &diagonal(&[1.0, 0.5]), &diagonal(&[0.1])).unwrap();
    let problem = oscillator_problem(40).final_weight(lqr.riccati.clone());
    let plan = Ddp::new().tolerance(1e-10).solve(&problem, &[]).unwrap();
    assert!(
        plan.log.len() <= 3,
        "{} iterations for a quadratic problem",
        plan.log.len()
    );
    for k in [0, 17, 39] {
        let x = nalgebra::DVector::from_column_slice(&[plan.q[k][0], plan.v[k][0]]);
        let lqr_u = -(&lqr.gain * &x)[0];
        assert!(
            (plan.u[k][0] - lqr_u).abs() < 1e-9,
            "step {k}: {} vs {lqr_u}",
            plan.u[k][0]
        );
        assert!(
            (&plan.gains[k] + &lqr.gain).amax() < 1e-9,
            "step {k}: gain {}",
            plan.gains[k]
        );
    }
}

/// Under |u| ≤ 0.3 the plan stays inside the bounds, saturates early, and no
/// feasible perturbation of its inputs lowers its cost.
#[test]
fn bounded_inputs_are_locally_optimal() {
    let problem = oscillator_problem(60).input_bounds(Vector1::new(-0.3), Vector1::new(0.3));
    let plan = Ddp::new().tolerance(1e-9).solve(&problem, &[]).unwrap();
    assert!(plan.u.iter().all(|u| u[0].abs() <= 0.3 + 1e-15));
    assert!(
        plan.u.iter().any(|u| u[0].abs() >= 0.3 - 1e-12),
        "never saturates"
    );
    let start = (Vector1::new(2.0), Vector1::new(-1.0));
    let cost_of = |us: &[SVector<f64, 1>]| rollout_cost(&problem, start, us);
    let base = cost_of(&plan.u);
    assert!((base - plan.cost).abs() < 1e-12 * plan.cost);
    for (k, delta) in [(0, 0.01), (5, -0.02), (30, 0.01), (59, -0.01)] {
        let mut us = plan.u.clone();
        us[k][0] = (us[k][0] + delta).clamp(-0.3, 0.3);
        assert!(
            cost_of(&us) >= plan.cost - 1e-12,
            "step {k} by {delta} lowers the cost"
        );
    }
}

/// The cost of applying `us` open loop from (q, v): step by step with the
/// problem's transition.
fn rollout_cost(
    problem: &OptimalControl<Oscillator, 1, 1>,
    (mut q, mut v): (Vector1<f64>, Vector1<f64>),
    us: &[SVector<f64, 1>],
) -> f64 {
    let x = |q: Vector1<f64>, v: Vector1<f64>| nalgebra::DVector::from_column_slice(&[q[0], v[0]]);
    let mut cost = 0.0;
    for (k, u) in us.iter().enumerate() {
        cost += problem.running(
            k,
            &x(q, v),
            &nalgebra::DVector::from_column_slice(u.as_slice()),
        );
        (q, v) = problem.transition.step(&q, &v, u, problem.time(k)).unwrap();
    }
    cost + problem.terminal(&x(q, v))
}

fn swing_up() -> OptimalControl<'static, Pendulum, 1, 1> {
    let tr = Transition::new(&Pendulum, 0.02).unwrap();
    let start = (Vector1::new(0.0), Vector1::new(0.0));
    OptimalControl::new(tr, 200, start, diagonal(&[0.0, 0.0]), diagonal(&[0.01]))
        .goal(Vector1::new(std::f64::consts::PI), Vector1::new(0.0))
        .final_weight(diagonal(&[1000.0, 100.0]))
        .input_bounds(Vector1::new(-3.0), Vector1::new(3.0))
}

/// A torque of at most 3 against a weight of g = 9.81: the pendulum must be
/// pumped up. The plan ends upright and at rest, within the bounds, with a
/// cost that never rose along the log.
#[test]
fn a_pendulum_swings_up_under_a_torque_below_its_weight() {
    let plan = Ddp::new().tolerance(1e-5).solve(&swing_up(), &[]).unwrap();
    let (theta, omega) = (plan.q[200][0], plan.v[200][0]);
    assert!((theta - std::f64::consts::PI).abs() < 0.02, "θ_K = {theta}");
    assert!(omega.abs() < 0.05, "ω_K = {omega}");
    assert!(plan.u.iter().all(|u| u[0].abs() <= 3.0));
    assert!(
        plan.u.iter().filter(|u| u[0].abs() > 3.0 - 1e-9).count() > 20,
        "hardly saturates"
    );
    let costs: Vec<f64> = plan.log.iter().map(|i| i.cost).collect();
    assert!(
        costs.windows(2).all(|w| w[1] <= w[0]),
        "cost rose: {costs:?}"
    );
    const { assert!(G > 3.0) };
}

/// A tolerance tighter than the cost can resolve: the solve ends where a
/// full step was predicted to change the cost by round-off only, that step
/// taken without a line search, converged, at the regularisation it started
/// from (not raised tenfold an iteration until the input changes vanish),
/// with the optimum a reachable tolerance gives.
#[test]
fn a_tolerance_below_the_cost_s_round_off_ends_at_the_optimum() {
    let reachable = Ddp::new().tolerance(1e-7).solve(&swing_up(), &[]).unwrap();
    let plan = Ddp::new().tolerance(1e-15).solve(&swing_up(), &[]).unwrap();
    let last = plan.log.last().unwrap();
    assert!(last.stationarity > 1e-15, "the tolerance was met: {last:?}");
    assert_eq!(last.step, 1.0, "the last iteration's full step: {last:?}");
    assert!(
        last.regularization <= 1e-6,
        "regularisation raised: {last:?}"
    );
    let apart = (plan.cost - reachable.cost).abs() / reachable.cost;
    assert!(apart < 1e-12, "costs {} and {}", plan.cost, reachable.cost);
}

/// Out of budget: the error says so and the failure holds the best plan so
/// far, whole.
#[test]
fn a_budget_hit_keeps_the_best_plan() {
    let failure = Ddp::new()
        .max_iterations(2)
        .solve(&swing_up(), &[])
        .unwrap_err();
    assert!(
        matches!(
            failure.error,
            Error::Plan(PlanError::NotConverged { iterations: 2, .. })
        ),
        "{}",
        failure.error
    );
    assert_eq!(
        (failure.partial.q.len(), failure.partial.u.len()),
        (201, 200)
    );
    assert_eq!(failure.partial.log.len(), 2);
    let message = failure.to_string();
    assert!(
        message.contains("did not converge in 2 iteration(s)"),
        "{message}"
    );
    assert!(
        message.contains("the plan stopped short after 2 iteration(s)"),
        "{message}"
    );
}

#[test]
fn bad_problems_and_settings() {
    let e = Ddp::new()
        .solve(&oscillator_problem(0), &[])
        .unwrap_err()
        .error;
    assert!(
        matches!(e, Error::Settings(SettingsError::ZeroCount { .. })),
        "{e}"
    );
    let e = Ddp::new()
        .solve(&oscillator_problem(5), &[Vector1::new(1.0)])
        .unwrap_err()
        .error;
    assert!(
        e.to_string().contains("1 guessed inputs for 5 steps"),
        "{e}"
    );
    let e = Ddp::new()
        .tolerance(0.0)
        .solve(&oscillator_problem(5), &[])
        .unwrap_err()
        .error;
    assert!(
        matches!(e, Error::Settings(SettingsError::Value { .. })),
        "{e}"
    );
    let bad = oscillator_problem(5).input_bounds(Vector1::new(1.0), Vector1::new(-1.0));
    let e = Ddp::new().solve(&bad, &[]).unwrap_err().error;
    assert!(e.to_string().contains("lower bound must be at most"), "{e}");
    let tr = Transition::new(&OSCILLATOR, 0.05)
        .unwrap()
        .method(StepMethod::SemiImplicitEuler);
    let start = (Vector1::new(1.0), Vector1::new(0.0));
    let bad = OptimalControl::new(tr, 5, start, diagonal(&[1.0, -1.0]), diagonal(&[0.1]));
    let e = Ddp::new().solve(&bad, &[]).unwrap_err().error;
    assert!(
        e.to_string().contains("W_x must be positive semidefinite"),
        "{e}"
    );
}

/// MPC on the oscillator, the plant stepped by the model's own transition
/// (a sampled run's zero-order hold, without the builder, which sits above
/// this layer): every sample re-plans from the state reached; the loop
/// brings it to rest within the bounds.
#[test]
fn mpc_brings_the_oscillator_to_rest() {
    let problem = oscillator_problem(30).input_bounds(Vector1::new(-1.0), Vector1::new(1.0));
    let plant = Transition::new(&OSCILLATOR, 0.05).unwrap();
    let mut mpc = Mpc::new(problem, Ddp::new().max_iterations(5).tolerance(1e-8));
    let (mut q, mut v) = (Vector1::new(2.0), Vector1::new(-1.0));
    let mut saturated = false;
    for k in 0..160 {
        let t = k as f64 * 0.05;
        let u = mpc.control(t, &q, &v);
        assert!(u[0].abs() <= 1.0 + 1e-15, "u = {} at t = {t}", u[0]);
        saturated |= u[0].abs() >= 1.0 - 1e-12;
        (q, v) = plant.step(&q, &v, &u, t).unwrap();
    }
    assert!(
        q[0].abs() < 5e-3 && v[0].abs() < 5e-3,
        "ends at ({}, {})",
        q[0],
        v[0]
    );
    assert!(saturated, "never saturates");
    assert_eq!(mpc.samples().len(), 160);
    assert!(mpc.samples().iter().all(|s| s.iterations <= 5));
    let stopped = mpc.samples().iter().filter(|s| s.stopped.is_some()).count();
    assert_eq!(mpc.budget_hits(), stopped);
}

/// A user's term written as closures gives the plan the built-in goal gives:
/// ½ (x − 1)² on the position by `CostFn` against the quadratic cost about
/// the goal x* = 1.
#[test]
fn a_closure_term_is_a_goal_written_by_hand() {
    let tr = Transition::new(&OSCILLATOR, 0.05).unwrap();
    let start = (Vector1::new(0.0), Vector1::new(0.0));
    let r = diagonal(&[0.1]);
    let built_in = OptimalControl::new(tr.clone(), 30, start, diagonal(&[1.0, 0.0]), r.clone())
        .goal(Vector1::new(1.0), Vector1::new(0.0))
        .final_weight(diagonal(&[0.0, 0.0]));
    let pull = |_: f64, q: &Vector1<f64>, _: &Vector1<f64>, _: Option<&Vector1<f64>>| {
        0.5 * (q[0] - 1.0).powi(2)
    };
    let model = |t: f64, q: &Vector1<f64>, v: &Vector1<f64>, u: Option<&Vector1<f64>>| {
        let mut m = CostModel::zero(2, usize::from(u.is_some()));
        m.value = pull(t, q, v, u);
        m.lx[0] = q[0] - 1.0;
        m.lxx[(0, 0)] = 1.0;
        m
    };
    let by_hand = OptimalControl::new(tr, 30, start, diagonal(&[0.0, 0.0]), r)
        .final_weight(diagonal(&[0.0, 0.0]))
        .running_cost(CostFn::new(pull, model));
    let a = Ddp::new().tolerance(1e-10).solve(&built_in, &[]).unwrap();
    let b = Ddp::new().tolerance(1e-10).solve(&by_hand, &[]).unwrap();
    assert!((a.cost - b.cost).abs() < 1e-12, "{} vs {}", a.cost, b.cost);
    let gap = (a.u.iter().zip(&b.u))
        .map(|(x, y)| (x - y).amax())
        .fold(0.0, f64::max);
    assert!(gap < 1e-10, "inputs differ by {gap:e}");
    // A model of the wrong size is refused, not used.
    let wrong = |_: f64, _: &Vector1<f64>, _: &Vector1<f64>, _: Option<&Vector1<f64>>| {
        CostModel::zero(3, 1)
    };
    let bad = oscillator_problem(5).running_cost(CostFn::new(pull, wrong));
    let e = Ddp::new().solve(&bad, &[]).unwrap_err().error;
    assert!(
        e.to_string().contains("lx of shape (3, 1), not (2, 1)"),
        "{e}"
    );
}

/// The oscillator brought to rest from (2, −1) with its speed held to 80 %
/// of the peak the free plan reaches, as a penalty of weight 10⁴: the bound
/// is active (the plan rides it) and overshot by less than 1 %.
#[test]
fn a_speed_bound_is_active_as_a_penalty() {
    let osc = Oscillator { k: 4.0, c: 0.3 };
    let problem = || {
        let tr = Transition::new(&osc, 0.05).unwrap();
        let start = (Vector1::new(2.0), Vector1::new(-1.0));
        OptimalControl::new(tr, 60, start, diagonal(&[1.0, 0.1]), diagonal(&[0.1]))
    };
    let solver = Ddp::new().tolerance(1e-8);
    let free = solver.solve(&problem(), &[]).unwrap();
    let peak = |p: &super::Plan<1, 1>| p.v.iter().map(|v| v[0].abs()).fold(0.0, f64::max);
    let limit = 0.8 * peak(&free);
    let inf = Vector1::new(f64::INFINITY);
    let bounds = StateBounds::new(
        (-inf, Vector1::new(-limit)),
        (inf, Vector1::new(limit)),
        1e4,
    );
    let bounded = solver.solve(&problem().running_cost(bounds), &[]).unwrap();
    let reached = peak(&bounded);
    assert!(reached <= 1.01 * limit, "peak {reached} against {limit}");
    assert!(
        reached >= 0.99 * limit,
        "not active: peak {reached}, bound {limit}"
    );
    let riding = bounded
        .v
        .iter()
        .filter(|v| v[0].abs() > 0.99 * limit)
        .count();
    assert!(riding >= 3, "{riding} steps at the bound");
    assert!(bounded.cost > free.cost);
}

/// Raising the regularisation must make the backward pass more cautious,
/// never undefined: the value function's Hessian V_xx is built from the true
/// Q, so at μ = 10⁹ it is as large as at μ = 10³, not 10⁶ times larger, and
/// every Q̃_uu stays positive definite. (Built from the regularised Q, it
/// lost μ f_xᵀ P f_x per step, and a planar quadrotor's flip stalled with
/// "Q_uu is not positive definite at the largest regularisation".)
#[test]
fn the_value_function_stays_bounded_as_the_regularisation_grows() {
    use super::passes::{backward_pass, jacobians, rollout};
    let problem = swing_up();
    let us = vec![nalgebra::DVector::from_element(1, 1.0); problem.steps()];
    let nominal = rollout(&problem, &us).unwrap();
    let mut derivatives = Vec::new();
    jacobians(&problem, &nominal, &mut derivatives).unwrap();
    let size = |mu: f64| {
        let pass = backward_pass(&problem, &nominal, &derivatives, mu, None).unwrap();
        let pass = pass.unwrap_or_else(|| panic!("Q̃_uu indefinite at μ = {mu:e}"));
        pass.hessians.iter().map(|h| h.amax()).fold(0.0, f64::max)
    };
    let (small, large) = (size(1e3), size(1e9));
    assert!(
        large.is_finite() && large < 10.0 * small,
        "{small:e} → {large:e}"
    );
}

/// Constraints on states are the direct method's: DDP refuses a final
/// equality and hard state limits, naming what to use instead.
#[test]
fn ddp_refuses_constraints_on_states() {
    let inf = f64::INFINITY;
    let limited = oscillator_problem(10).state_limits(
        (Vector1::new(-1.0), Vector1::new(-inf)),
        (Vector1::new(1.0), Vector1::new(inf)),
    );
    for problem in [oscillator_problem(10).final_equality(), limited] {
        let failure = Ddp::new().solve(&problem, &[]).unwrap_err();
        let Error::Settings(SettingsError::Data { owner, problem }) = &failure.error else {
            panic!("{}", failure.error)
        };
        assert_eq!(*owner, "Ddp");
        assert!(problem.contains("plan::Direct") && problem.contains("StateBounds"));
    }
}

/// The oscillator brought to rest over 3 s with |u| ≤ 0.3, its running cost
/// written as the integral it approximates (weights times h): as the step
/// is refined from 60 to 480 steps the optimal cost converges, each
/// difference about half the last (the running cost's sum is a first-order
/// quadrature), towards the continuous problem's optimum.
#[test]
fn refining_the_step_converges_to_the_continuous_optimum() {
    let optimum = |steps: usize| {
        let h = 3.0 / steps as f64;
        let tr = Transition::new(&OSCILLATOR, h).unwrap();
        let start = (Vector1::new(2.0), Vector1::new(-1.0));
        let problem = OptimalControl::new(
            tr,
            steps,
            start,
            diagonal(&[1.0, 0.5]) * h,
            diagonal(&[0.1]) * h,
        )
        .final_weight(diagonal(&[10.0, 10.0]))
        .input_bounds(Vector1::new(-0.3), Vector1::new(0.3));
        Ddp::new()
            .tolerance(1e-9)
            .solve(&problem, &[])
            .unwrap()
            .cost
    };
    let costs: Vec<f64> = [60, 120, 240, 480].into_iter().map(optimum).collect();
    let differences: Vec<f64> = costs.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    for pair in differences.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((1.7..2.3).contains(&ratio), "{costs:?}: ratio {ratio}");
    }
    // From one side: each refinement moves the cost the same way.
    let signs: Vec<bool> = costs.windows(2).map(|w| w[1] > w[0]).collect();
    assert!(signs.iter().all(|&s| s == signs[0]), "{costs:?}");
}
