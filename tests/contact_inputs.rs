//! Contacts driven by inputs (`run_contacts` after `feedback`,
//! `open_loop`): a motor's ramped force breaking a joint's friction loose
//! at a t = fc, the same motion as the force written in the description; a
//! PD loop against dry friction ending inside its dead band |e| ≤ fc/kp;
//! a ball pressed onto the floor by an input, its normal force m g + u; a
//! sampled ramp breaking it loose at the first sample past fc, in all
//! three schemes.

use lagrange::prelude::*;
use lagrange::{ChangeKind, Compliant, ContactState, Dop853, MoreauJean, Radau5};

/// A cart on a rail with dry friction, pushed by a motor's force.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    inputs(force),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = force),
    joint(x, friction = 0.5),
)]
struct Motor {
    m: f64,
}

/// A ball on the floor pressed down by an input.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(z),
    inputs(press),
    point(ball, mass = m, at = [0, 0, z]),
    force(ball, [0, 0, -press]),
    gravity = [0, 0, -g],
    contact(floor, on = ball, normal = [0, 0, 1], restitution = 0.5),
)]
struct Pressed {
    m: f64,
    g: f64,
}

/// Open loop u = a t: held until a t = fc, then m ẍ = a (t − t_s).
#[test]
fn a_ramped_motor_breaks_friction_loose_at_fc() {
    let (motor, a) = (Motor { m: 1.5 }, 2.0);
    let run = Simulation::new(&motor)
        .integrator(Dop853::tol(1e-13))
        .open_loop(move |t| [a * t])
        .run_contacts([0.0], [0.0], 0.0..1.0)
        .unwrap();
    let ts = 0.5 / a;
    let slips: Vec<f64> = (run.changes.iter())
        .filter(|c| matches!(c.kind, ChangeKind::Slips))
        .map(|c| c.t)
        .collect();
    let (q, _) = run.trajectory.final_state();
    let want = a * (1.0 - ts).powi(3) / (6.0 * motor.m);
    eprintln!(
        "ramped motor: slips {:.1e} s from fc/a, x(1) {:.1e} m off",
        (slips[0] - ts).abs(),
        (q[0] - want).abs()
    );
    assert!((slips[0] - ts).abs() < 1e-9);
    assert!((q[0] - want).abs() < 1e-9);
}

/// u = −kp (x − 1) − kd ẋ against fc: the loop stops where the spring of
/// its gain no longer overcomes friction, |x − 1| ≤ fc/kp, and sticks.
#[test]
fn a_pd_loop_against_dry_friction_stops_inside_its_dead_band() {
    let motor = Motor { m: 1.0 };
    let (kp, kd) = (4.0, 0.8);
    let law =
        move |_: f64, q: &SVector<f64, 1>, v: &SVector<f64, 1>| [-kp * (q[0] - 1.0) - kd * v[0]];
    let exact = Simulation::new(&motor)
        .integrator(Dop853::tol(1e-12))
        .feedback(law)
        .run_contacts([0.0], [0.0], 0.0..15.0)
        .unwrap();
    let stepped = Simulation::new(&motor)
        .integrator(MoreauJean::step(1e-4))
        .feedback(law)
        .run_contacts([0.0], [0.0], 0.0..15.0)
        .unwrap();
    let rest = |x: f64| x - 1.0;
    let e = rest(exact.trajectory.final_state().0[0]);
    let e_stepped = rest(stepped.trajectory.final_state().0[0]);
    eprintln!(
        "PD against friction: rests at e = {e:.6} (band ±{}), stepped {e_stepped:.6}",
        0.5 / kp
    );
    assert!(e.abs() <= 0.5 / kp + 1e-12);
    assert_eq!(exact.states(15.0), [ContactState::Sticking]);
    assert!((e_stepped - e).abs() < 1e-3, "{e_stepped} vs {e}");
    // Friction holds the loop's pull there, inside its bound.
    let (q, v) = exact.trajectory.final_state();
    let u = SVector::from(law(15.0, &q, &v));
    let held = exact.forces_with(&motor, 15.0, (&q, &v), &u).unwrap()[0];
    assert!((held.tangential[0] + u[0]).abs() < 1e-9, "{held:?} vs {u}");
}

/// At rest on the floor the normal force carries the weight and the press.
#[test]
fn a_pressed_ball_s_normal_force_is_its_weight_and_the_press() {
    let ball = Pressed { m: 0.5, g: 9.81 };
    let run = Simulation::new(&ball)
        .integrator(Dop853::tol(1e-12))
        .feedback(|t: f64, _: &SVector<f64, 1>, _: &SVector<f64, 1>| [2.0 + t])
        .run_contacts([0.0], [0.0], 0.0..1.0)
        .unwrap();
    let (q, v) = run.trajectory.final_state();
    let u = SVector::from([3.0]);
    let force = run.forces_with(&ball, 1.0, (&q, &v), &u).unwrap()[0];
    assert!(
        (force.normal - (ball.m * ball.g + 3.0)).abs() < 1e-12,
        "{force:?}"
    );
    assert_eq!(q[0], 0.0);
}

/// A sampled ramp, u = a t_k held on [t_k, t_k + h): the cart holds while
/// u_k ≤ fc and breaks loose at the first sample past it, t = 0.3; then
/// m ẍ = u_k − fc, constant on each sample period, summed exactly. The
/// time stepper samples at its steps (h divides the period), exact for a
/// force constant over each step; the compliant model regularises the
/// friction, and comes within its creep.
#[test]
fn a_sampled_ramp_breaks_friction_loose_at_the_first_sample_past_fc() {
    let motor = Motor { m: 1.5 };
    let (a, period, end) = (2.0, 0.1, 1.0);
    let ramp = move |t: f64, _: &SVector<f64, 1>, _: &SVector<f64, 1>| [a * t];
    let exact = Simulation::new(&motor)
        .integrator(Dop853::tol(1e-13))
        .sampled(period, ramp)
        .run_contacts([0.0], [0.0], 0.0..end)
        .unwrap();
    // Piecewise-constant acceleration from the sample at 0.3 on.
    let (mut x, mut v) = (0.0, 0.0);
    for k in 3..10 {
        let accel = (a * period * k as f64 - 0.5) / motor.m;
        x += v * period + 0.5 * accel * period * period;
        v += accel * period;
    }
    let slips: Vec<f64> = (exact.changes.iter())
        .filter(|c| matches!(c.kind, ChangeKind::Slips))
        .map(|c| c.t)
        .collect();
    let (q, w) = exact.trajectory.final_state();
    let stepped = Simulation::new(&motor)
        .integrator(MoreauJean::step(1e-4))
        .sampled(period, ramp)
        .run_contacts([0.0], [0.0], 0.0..end)
        .unwrap();
    let compliant = Simulation::new(&motor)
        .integrator(Radau5::tol(1e-10))
        .compliant_contacts(Compliant::stiffness(1e6).slip_speed(1e-6))
        .sampled(period, ramp)
        .run_contacts([0.0], [0.0], 0.0..end)
        .unwrap();
    let off = |r: &lagrange::ContactRun<f64, 1>| (r.trajectory.final_state().0[0] - x).abs();
    eprintln!(
        "sampled ramp: slips at {:?}; x(1) off by {:.1e} (exact), {:.1e} (Moreau–Jean 1e-4), {:.1e} (compliant)",
        slips,
        (q[0] - x).abs(),
        off(&stepped),
        off(&compliant)
    );
    assert_eq!(slips.len(), 1);
    assert!((slips[0] - 0.3).abs() < 1e-12, "{slips:?}");
    assert!(
        (q[0] - x).abs() < 1e-9 && (w[0] - v).abs() < 1e-9,
        "{q:?} vs {x}"
    );
    assert!(off(&stepped) < 1e-9 && off(&compliant) < 1e-5);
}
