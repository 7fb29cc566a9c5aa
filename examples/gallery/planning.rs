//! Gallery rows that plan: a motion optimised by DDP over a horizon
//! (`plan::Ddp`, on the model's one-step map and its derivatives), then flown
//! on the continuous model with the plan's own feedback, u = u_k + K_k (x ⊖
//! x_k) sampled at the plan's step (x − x_k without orientations), and
//! caught at the end by LQR; and one closed by MPC against a model that is
//! wrong.

use crate::catalog::control::{Acrobot, CartPole, PlanarQuadrotor, Quadrotor};
use crate::free::{angular_velocity, csv, free_row};
use crate::operational::Ur5;
use crate::row::{Row, TOL, row};
use lagrange::linear::{OperatingPoint, Transition, Trim, linearize};
use lagrange::nalgebra::{DMatrix, DVector, SVector, Vector3};
use lagrange::orientation::{configuration_minus, state_minus};
use lagrange::plan::{Ddp, FramePosition, Mpc, OptimalControl, Plan};
use lagrange::pose::Kinematics;
use lagrange::prelude::*;
use std::f64::consts::PI;
use std::time::Instant;

/// The step every plan here takes (50 Hz), which is also the rate its
/// feedback is sampled at on the continuous model.
const STEP: f64 = 0.02;

fn diagonal(d: &[f64]) -> DMatrix<f64> {
    DMatrix::from_diagonal(&DVector::from_column_slice(d))
}

/// The plan's input at sample t with its feedback on the state's distance
/// from the plan, u_k + K_k (x ⊖ x_k), clamped into the bounds; `None` past
/// the horizon (or at a state that is not finite).
fn follow<S, const N: usize, const P: usize, const Q: usize>(
    (system, plan): (&S, &Plan<N, P, Q>),
    bounds: (f64, f64),
    t: f64,
    q: &SVector<f64, Q>,
    v: &SVector<f64, N>,
) -> Option<SVector<f64, P>>
where
    S: Lagrangian<f64, N, Q>,
{
    let k = (t / STEP).round() as usize;
    let u = plan.u.get(k)?;
    let (dq, dv) = state_minus(system, (q, v), (&plan.q[k], &plan.v[k])).ok()?;
    let dx = DVector::from_iterator(2 * N, dq.iter().chain(dv.iter()).copied());
    let du = &plan.gains[k] * dx;
    Some(u.zip_map(
        &SVector::<f64, P>::from_column_slice(du.as_slice()),
        |u, d| (u + d).clamp(bounds.0, bounds.1),
    ))
}

/// The LQR law that holds the system at rest at `q` with inputs `u`, on
/// the weights `state` (one per state) and `input`: u = u* − K (x − x*).
fn holding<S, const N: usize, const P: usize>(
    system: &S,
    q: SVector<f64, N>,
    u: SVector<f64, P>,
    state: &[f64],
    input: f64,
) -> Result<StateFeedback<f64, N, P>, Error>
where
    S: Lagrangian<f64, N> + lagrange::Driven<f64, N, P>,
{
    let op = OperatingPoint::new(q, SVector::zeros()).input(u);
    let lin = linearize(system, &op)?;
    let gain = lin
        .lqr(&diagonal(state), &(DMatrix::identity(P, P) * input))?
        .gain;
    Ok(StateFeedback::from_gain(&gain, &lin, &S::COORDINATES)?.about(&op))
}

/// How a plan went, for a row's note.
fn solved<const N: usize, const P: usize, const Q: usize>(plan: &Plan<N, P, Q>) -> String {
    let last = plan.log.last().map_or(f64::NAN, |i| i.stationarity);
    format!(
        "DDP: {} iterations, cost {:.4}, stationarity {last:.0e}",
        plan.log.len(),
        plan.cost
    )
}

/// The cart-pole from hanging to upright with at most 5 N on the cart (a
/// fifth of what lifts the pole straight up in the time), in 2.5 s.
pub(crate) fn cart_pole_swing_up(system: &'static str) -> Result<Row, Error> {
    let cp = CartPole::standard();
    let (steps, limit) = (125, 5.0);
    let problem = OptimalControl::new(
        Transition::new(&cp, STEP)?,
        steps,
        (SVector::from([0.0, PI]), SVector::zeros()),
        diagonal(&[0.0; 4]),
        diagonal(&[0.01]),
    )
    .goal(SVector::zeros(), SVector::zeros())
    .final_weight(diagonal(&[100.0, 1000.0, 10.0, 100.0]))
    .input_bounds(SVector::from([-limit]), SVector::from([limit]));
    let plan = Ddp::new().tolerance(1e-6).solve(&problem, &[])?;
    let catch = cp.lqr_feedback()?;
    let span = 0.0..5.0;
    row(
        system,
        &cp,
        span.clone(),
        false,
        || {
            Simulation::new(&cp)
                .integrator(Dopri5::tol(TOL))
                .sampled(STEP, |t, q, v| {
                    follow((&cp, &plan), (-limit, limit), t, q, v)
                        .unwrap_or_else(|| catch.input(q, v))
                })
                .run([0.0, PI], [0.0; 2], span.clone())
                .map(|run| run.into_trajectory())
        },
        |tr| {
            let off = plan_error(&plan, tr);
            let (q, _) = tr.final_state();
            format!(
                "{}; flown on the continuous model within {off:.1e} of the plan, caught by LQR: θ(5) = {:.1e}",
                solved(&plan),
                q[1]
            )
        },
    )
}

/// The largest distance of the run's configuration from the plan's at the
/// plan's steps (the run records its accepted steps; the samples are among
/// them).
fn plan_error<const N: usize, const P: usize>(plan: &Plan<N, P>, tr: &Trajectory<f64, N>) -> f64 {
    tr.times()
        .iter()
        .zip(tr.positions())
        .filter_map(|(t, q)| {
            let k = (t / STEP).round() as usize;
            let on_sample = (t - k as f64 * STEP).abs() < 1e-9;
            (on_sample && k < plan.q.len()).then(|| (q - plan.q[k]).amax())
        })
        .fold(0.0, f64::max)
}

/// The acrobot from hanging to upright, driven only at the elbow with at
/// most 10 N·m, in 5 s, then held there by LQR.
pub(crate) fn acrobot_swing_up(system: &'static str) -> Result<Row, Error> {
    let acrobot = Acrobot::standard();
    let (steps, limit) = (250, 10.0);
    let upright = SVector::from([PI, 0.0]);
    let problem = OptimalControl::new(
        Transition::new(&acrobot, STEP)?,
        steps,
        (SVector::zeros(), SVector::zeros()),
        diagonal(&[0.0; 4]),
        diagonal(&[0.01]),
    )
    .goal(upright, SVector::zeros())
    .final_weight(diagonal(&[1e4, 1e4, 1e3, 1e3]))
    .input_bounds(SVector::from([-limit]), SVector::from([limit]));
    // A pumping guess at about the hanging swing's frequency: from u = 0 at
    // rest the first backward pass sees no way up.
    let guess: Vec<_> = (0..steps)
        .map(|k| SVector::from([(4.0 * k as f64 * STEP).sin()]))
        .collect();
    let plan = Ddp::new()
        .tolerance(1e-6)
        .max_iterations(500)
        .solve(&problem, &guess)?;
    let catch = holding(
        &acrobot,
        upright,
        SVector::zeros(),
        &[100.0, 100.0, 10.0, 10.0],
        1.0,
    )?;
    let span = 0.0..8.0;
    row(
        system,
        &acrobot,
        span.clone(),
        false,
        || {
            Simulation::new(&acrobot)
                .integrator(Dopri5::tol(TOL))
                .sampled(STEP, |t, q, v| {
                    follow((&acrobot, &plan), (-limit, limit), t, q, v)
                        .unwrap_or_else(|| catch.input(q, v))
                })
                .run([0.0; 2], [0.0; 2], span.clone())
                .map(|run| run.into_trajectory())
        },
        |tr| {
            let (q, _) = tr.final_state();
            format!(
                "{}; flown within {:.1e} rad of the plan, held upright: |q(8) − (π, 0)| = {:.1e}",
                solved(&plan),
                plan_error(&plan, tr),
                (q - upright).amax()
            )
        },
    )
}

/// A planar quadrotor's flip: from a hover back to the same hover turned
/// once round, in 2 s, each rotor's thrust between 0 and the weight.
pub(crate) fn quadrotor_flip(system: &'static str) -> Result<Row, Error> {
    let quad = PlanarQuadrotor::standard();
    let (steps, hover) = (100, quad.hover_thrust());
    let bounds = (0.0, 2.0 * hover);
    let flipped = SVector::from([0.0, 0.0, 2.0 * PI]);
    let problem = OptimalControl::new(
        Transition::new(&quad, STEP)?,
        steps,
        (SVector::zeros(), SVector::zeros()),
        diagonal(&[0.0; 6]),
        diagonal(&[0.01, 0.01]),
    )
    .goal(flipped, SVector::zeros())
    .input_target(SVector::repeat(hover))
    .final_weight(diagonal(&[1e3, 1e3, 1e3, 100.0, 100.0, 100.0]))
    .input_bounds(SVector::repeat(bounds.0), SVector::repeat(bounds.1));
    let plan = Ddp::new()
        .tolerance(1e-6)
        .max_iterations(500)
        .solve(&problem, &vec![SVector::repeat(hover); steps])?;
    let catch = holding(
        &quad,
        flipped,
        SVector::repeat(hover),
        &[10.0, 10.0, 10.0, 1.0, 1.0, 1.0],
        1.0,
    )?;
    let span = 0.0..4.0;
    row(
        system,
        &quad,
        span.clone(),
        false,
        || {
            Simulation::new(&quad)
                .integrator(Dopri5::tol(TOL))
                .sampled(STEP, |t, q, v| {
                    follow((&quad, &plan), bounds, t, q, v).unwrap_or_else(|| catch.input(q, v))
                })
                .run([0.0; 3], [0.0; 3], span.clone())
                .map(|run| run.into_trajectory())
        },
        |tr| {
            let heights = plan.q.iter().map(|q| q[1]);
            let (low, high) = heights.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), z| {
                (l.min(z), h.max(z))
            });
            let (q, _) = tr.final_state();
            format!(
                "{}; the plan's height between {low:.2} and {high:.2} m; flown within {:.1e} of it, hovering at the end {:.1e} from the start turned by 2π",
                solved(&plan),
                plan_error(&plan, tr),
                (q - flipped).amax()
            )
        },
    )
}

/// A quadrotor's flip in space, on the rotation group: from a hover back
/// to it rolled once round its x axis in 2 s (the catalog's
/// `Quadrotor::flip`: two attitude waypoints on the way; FDDP from a guess
/// rolling at a constant rate), each thrust between zero and twice the
/// hover's; flown on the continuous model with
/// the plan's gains on the tangent error x ⊖ x_k, then held by LQR on the
/// hover's tangent linearisation.
pub(crate) fn quadrotor_flip_3d(system: &'static str) -> Result<Row, Error> {
    let quad = Quadrotor::standard();
    let (steps, hover) = (100, quad.hover_thrust());
    let bounds = (0.0, 2.0 * hover);
    // From a guess that rolls the right way (see `Quadrotor::flip_guess`).
    let (q, v, u) = quad.flip_guess(STEP, steps)?;
    let plan = Ddp::new().tolerance(1e-6).max_iterations(500).solve_from(
        &quad.flip(STEP, steps)?,
        &q,
        &v,
        &u,
    )?;
    let level = Quadrotor::rolled([0.0; 3], 0.0)?;
    let still = SVector::<f64, 6>::zeros();
    let op = OperatingPoint::on_group(level, still).input(SVector::<f64, 4>::repeat(hover));
    let lin = linearize(&quad, &op)?;
    let gain = lin
        .lqr(&diagonal(&[10.0; 12]), &DMatrix::identity(4, 4))?
        .gain;
    let catch = StateFeedback::from_tangent_gain::<Quadrotor>(&gain, &lin, (op.q, op.v, op.u))?;
    // How far a configuration is from the start: (metres, radians).
    let off = |q: &SVector<f64, 7>| -> Result<(f64, f64), Error> {
        let d = configuration_minus(&quad, q, &level)?;
        Ok((d.fixed_rows::<3>(0).norm(), d.fixed_rows::<3>(3).norm()))
    };
    let planned_turn = quad.accumulated_turn(&plan.q)?;
    let (_, planned_miss) = off(&plan.q[steps])?;
    let span = 0.0..4.0;
    let clock = Instant::now();
    let traj = Simulation::new(&quad)
        .integrator(Dopri5::tol(TOL))
        .sampled(STEP, |t, q, v| {
            follow((&quad, &plan), bounds, t, q, v).unwrap_or_else(|| catch.input(q, v))
        })
        .run(level, still, span.clone())?
        .into_trajectory();
    let wall_ms = clock.elapsed().as_secs_f64() * 1e3;
    let flown_turn = quad.accumulated_turn(traj.positions())?;
    let (metres, radians) = off(&traj.final_state().0)?;
    let note = format!(
        "{}; the plan rolls {:.4} rad about x (2π = {:.4}) and ends {planned_miss:.1e} rad \
         from level; flown with its gains it rolls {:.4} rad, and hovers at the end {metres:.1e} m \
         and {radians:.1e} rad from the start",
        solved(&plan),
        planned_turn.x,
        2.0 * PI,
        flown_turn.x
    );
    let figure = angular_velocity(&traj, Quadrotor::VELOCITIES, 3, csv(&quad, &traj)?);
    let mut row = free_row(system, &quad, &traj, span, (note, wall_ms), figure)?;
    // Driven by its rotors, it keeps no energy integral: no drift to show.
    row.drift = None;
    Ok(row)
}

/// The UR5's tool drawn 20 cm to a point in 0.6 s with its torques held
/// within ±40 N·m (its file allows 150), through its emitted kinematics,
/// from gravity compensation at home; flown with the plan's feedback.
pub(crate) fn ur5_reach(system: &'static str) -> Result<Row, Error> {
    let ur5 = Ur5 {};
    let tool =
        Ur5::body_index("tool0").ok_or_else(|| crate::gallery_error("the UR5 has no tool0"))?;
    let home = SVector::<f64, 6>::from([0.0, -1.2, 1.5, -1.8, -1.57, 0.0]);
    let zero = SVector::<f64, 6>::zeros();
    let tool_at = |q: SVector<f64, 6>| -> Result<Vector3<f64>, Error> {
        let (bodies, _) = lagrange::Configuration::new(&ur5, q, 0.0)?.poses();
        Ok(bodies[tool].origin)
    };
    let target = tool_at(home)? + Vector3::new(0.1, 0.15, -0.05);
    let hold = Trim::new()
        .hold(&Ur5::COORDINATES)
        .solve(&ur5, &OperatingPoint::new(home, zero))?;
    let (steps, limit) = (30, 40.0);
    let still = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
    let problem = OptimalControl::new(
        Transition::new(&ur5, STEP)?,
        steps,
        (home, zero),
        // Speed costs a little all the way: without it the tool's target
        // leaves the last wrist free, and the plan spins it through its
        // ±2π limits.
        diagonal(&still) * 0.1,
        DMatrix::identity(6, 6) * 1e-4,
    )
    .input_target(hold.u)
    .final_weight(diagonal(&still) * 1000.0)
    .final_cost(FramePosition::new(&ur5, tool, target, 1e5))
    .input_bounds(SVector::repeat(-limit), SVector::repeat(limit));
    let plan = Ddp::new()
        .tolerance(1e-4)
        .solve(&problem, &vec![hold.u; steps])?;
    let end = plan.q[steps];
    // Past the horizon, computed torque through the robot's inverse
    // dynamics holds the plan's last pose.
    let stay = |q: &SVector<f64, 6>, v: &SVector<f64, 6>| {
        ur5.inverse_dynamics(q, v, &((end - q) * 100.0 - v * 20.0), 0.0)
    };
    let miss = (tool_at(end)? - target).norm();
    let span = 0.0..1.5;
    row(
        system,
        &ur5,
        span.clone(),
        false,
        || {
            Simulation::new(&ur5)
                .integrator(Dopri5::tol(TOL))
                .sampled(STEP, |t, q, v| {
                    follow((&ur5, &plan), (-limit, limit), t, q, v).unwrap_or_else(|| stay(q, v))
                })
                .run(home, zero, span.clone())
                .map(|run| run.into_trajectory())
        },
        |tr| {
            let (q, _) = tr.final_state();
            let flown = tool_at(q).map_or(f64::NAN, |p| (p - target).norm());
            format!(
                "{}; the plan's tool ends {miss:.1e} m from the target; flown: {:.1e} m at {} s",
                solved(&plan),
                flown,
                span.end
            )
        },
    )
}

/// The cart-pole swung up and held by MPC (a 2.5 s horizon re-planned at
/// 20 Hz, at most 10 iterations a sample) designed on the catalog's model,
/// flying a cart-pole whose pole is 50 % heavier.
pub(crate) fn cart_pole_mpc(system: &'static str) -> Result<Row, Error> {
    let model = CartPole::standard();
    let real = CartPole {
        m_p: 1.5 * model.m_p,
        ..model
    };
    let (h, limit) = (0.05, 5.0);
    let problem = OptimalControl::new(
        Transition::new(&model, h)?,
        50,
        (SVector::from([0.0, PI]), SVector::zeros()),
        diagonal(&[1.0, 0.0, 0.1, 0.1]),
        diagonal(&[0.01]),
    )
    .goal(SVector::zeros(), SVector::zeros())
    .final_weight(diagonal(&[100.0, 1000.0, 10.0, 100.0]))
    .input_bounds(SVector::from([-limit]), SVector::from([limit]));
    let mut mpc = Mpc::new(problem, Ddp::new().max_iterations(10));
    let span = 0.0..8.0;
    let mut summary = String::new();
    let mut row = row(
        system,
        &real,
        span.clone(),
        false,
        || {
            let run = Simulation::new(&real)
                .integrator(Dopri5::tol(TOL))
                .sampled(h, |t, q, v| mpc.control(t, q, v))
                .run([0.0, PI], [0.0; 2], span.clone())
                .map(|run| run.into_trajectory());
            let iterations: usize = mpc.samples().iter().map(|s| s.iterations).sum();
            summary = format!(
                "{} samples, {:.1} iterations each on average, {} hit the budget",
                mpc.samples().len(),
                iterations as f64 / mpc.samples().len().max(1) as f64,
                mpc.budget_hits()
            );
            run
        },
        |tr| {
            let (q, v) = tr.final_state();
            format!(
                "pole 1.5× the model's; |θ(8)| = {:.1e}, |θ̇(8)| = {:.1e}",
                q[1].abs(),
                v[1].abs()
            )
        },
    )?;
    row.note = format!("{}; {summary}", row.note);
    Ok(row)
}
