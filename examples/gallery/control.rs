//! Gallery rows of driven systems: controllers through closures, models from the
//! linearisation.

use crate::catalog::bicycle::{Bicycle, published};
use crate::catalog::constrained::RollingDisk;
use crate::catalog::control::{CartPole, TwoLinkArm};
use crate::operational::{Ur5, start_off_the_circle, tool_circle};
use crate::row::{Row, TOL, row};
use lagrange::Posed;
use lagrange::linear::sweep;
use lagrange::pose::BodyPose;
use lagrange::prelude::*;
use lagrange::task_space::{OperationalSpace, critically_damped};
use nalgebra::SVector;

/// The cart-pole caught from a 0.3 rad tilt by continuous LQR feedback.
pub(crate) fn cart_pole_continuous(system: &'static str) -> Result<Row, Error> {
    cart_pole(system, None)
}

/// The same gain sampled at 100 Hz with zero-order hold.
pub(crate) fn cart_pole_sampled(system: &'static str) -> Result<Row, Error> {
    cart_pole(system, Some(0.01))
}

/// The cart-pole caught from a 0.3 rad tilt by u = −K x, continuously or
/// sampled with zero-order hold.
fn cart_pole(system: &'static str, period: Option<f64>) -> Result<Row, Error> {
    let cp = CartPole::standard();
    let law = cp.lqr_feedback()?;
    row(
        system,
        &cp,
        0.0..10.0,
        false,
        || {
            let sim = Simulation::new(&cp).integrator(Dopri5::tol(TOL));
            let run = match period {
                None => sim.control(law).run([0.0, 0.3], [0.0; 2], 0.0..10.0),
                Some(h) => {
                    sim.sampled(h, |_, q, v| law.input(q, v))
                        .run([0.0, 0.3], [0.0; 2], 0.0..10.0)
                }
            };
            run.map(|r| r.into_trajectory())
        },
        |tr| {
            let (q, _) = tr.final_state();
            format!("from θ = 0.3: x(10) = {:.1e}, θ(10) = {:.1e}", q[0], q[1])
        },
    )
}

/// The critical spin of upright rolling from the eigenvalues, then the
/// nonlinear disk at 1.2 Ω_c kicked by a tilt rate: it wobbles and stays up.
pub(crate) fn disk(system: &'static str) -> Result<Row, Error> {
    let d = RollingDisk::thin(1.0, 0.5, 9.81);
    let spins: Vec<f64> = (1..=20).map(|i| 0.25 * i as f64).collect();
    let critical = sweep(&spins, |w| d.upright_tilt(w))?
        .boundaries(1e-6, 1e-14)?
        .first()
        .map_or(f64::NAN, |b| b.parameter);
    let exact = (d.g / (3.0 * d.a)).sqrt();
    let spin = 1.2 * critical;
    row(
        system,
        &d,
        0.0..10.0,
        true,
        || {
            Simulation::new(&d)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .project_initial(true)
                .run_constrained([0.0; 5], [d.a * spin, 0.0, 0.0, 0.05, spin], 0.0..10.0)
        },
        |tr| {
            let tilt = tr
                .positions()
                .iter()
                .map(|q| q[3].abs())
                .fold(0.0, f64::max);
            format!(
                "Ω_c = {critical:.10} (√(g/3a): {:.0e}); at 1.2 Ω_c max tilt {tilt:.3}",
                (critical - exact).abs() / exact
            )
        },
    )
}

/// The benchmark bicycle: self-stable speeds from the eigenvalues, and the
/// nonlinear machine at 5 m/s recovering from a roll-rate kick.
pub(crate) fn bicycle(system: &'static str) -> Result<Row, Error> {
    let b = Bicycle::benchmark();
    let speeds: Vec<f64> = (1..=20).map(|i| 0.5 * i as f64).collect();
    let found = sweep(&speeds, |v| b.lateral(v))?.boundaries(1e-12, 1e-13)?;
    let speed_of = |oscillatory: bool| {
        found
            .iter()
            .find(|x| x.oscillatory == oscillatory)
            .map_or(f64::NAN, |x| x.parameter)
    };
    let (weave, capsize) = (speed_of(true), speed_of(false));
    // The same roll-rate kick at a forward speed v.
    let kicked = |v: f64| {
        let (q0, mut v0) = b.upright(v);
        v0[3] = 0.5;
        Simulation::new(&b)
            .integrator(Dopri5::tol(TOL))
            .drift(Drift::projection())
            .project_initial(true)
            .run_constrained(q0, v0, 0.0..8.0)
    };
    let mut row = row(
        system,
        &b,
        0.0..8.0,
        true,
        || kicked(5.0),
        |tr| {
            let (q, _) = tr.final_state();
            format!(
                "weave {weave:.6} m/s ({:.0e}), capsize {capsize:.6} ({:.0e}); roll(8) = {:.1e}",
                (weave - published::WEAVE_SPEED).abs() / published::WEAVE_SPEED,
                (capsize - published::CAPSIZE_SPEED).abs() / published::CAPSIZE_SPEED,
                q[3]
            )
        },
    )?;
    row.scene = Some(bicycle_scene(&b, &kicked(5.0)?, kicked(3.0))?);
    Ok(row)
}

/// The bicycle at 5 m/s (self-stable: between the weave and capsize speeds)
/// beside the same kick at 3 m/s, below the weave speed, where it falls; a
/// run that fails (the bicycle on the ground) is shown up to its failure.
fn bicycle_scene(
    b: &Bicycle,
    stable: &Trajectory<f64, 8>,
    slow: Result<Trajectory<f64, 8>, Failure<Trajectory<f64, 8>>>,
) -> Result<String, Error> {
    let slow = slow.unwrap_or_else(|f| *f.partial);
    Scene::new(b)
        .title("Whipple bicycle: the same roll-rate kick at 5 m/s (self-stable) and 3 m/s (falls)")
        .run(stable, "5 m/s")
        .run(&slow, "3 m/s")
        .plot(&["phi", "delta"])
        .side_by_side(true)
        .to_html()
}

/// Computed-torque tracking from a 0.1 rad error: τ = M (q̈_d + K_d ė + K_p e)
/// − (Q − h) at zero torque.
pub(crate) fn arm(system: &'static str) -> Result<Row, Error> {
    let arm = TwoLinkArm::standard();
    let [q0, v0, _] = TwoLinkArm::reference(0.0);
    row(
        system,
        &arm,
        0.0..5.0,
        false,
        || {
            Simulation::new(&arm)
                .integrator(Dopri5::tol(TOL))
                .feedback(|t, q, v| arm.computed_torque((100.0, 20.0), t, q, v))
                .run(q0 + Vector2::new(0.1, -0.1), v0, 0.0..5.0)
                .map(|run| run.into_trajectory())
        },
        |tr| {
            let after = |from: f64| {
                tr.times()
                    .iter()
                    .zip(tr.positions())
                    .filter(|(t, _)| **t >= from)
                    .map(|(t, q)| (TwoLinkArm::reference(*t)[0] - q).abs().max())
                    .fold(0.0f64, f64::max)
            };
            format!(
                "tracking error {:.1e} rad after 1 s, {:.1e} after 3 s",
                after(1.0),
                after(3.0)
            )
        },
    )
}

/// The UR5 driven from its home pose to a target by computed torque through
/// its own inverse dynamics (recursive Newton–Euler): τ = ID(q, q̇, K_p e −
/// K_d q̇), so every joint's error follows e'' + 12 e' + 36 e = 0, e(t) =
/// e0 (1 + 6t) e^(−6t).
pub(crate) fn ur5(system: &'static str) -> Result<Row, Error> {
    let ur5 = Ur5 {};
    let home = SVector::<f64, 6>::from([0.0, -1.57, 1.57, -1.57, -1.57, 0.0]);
    let target = SVector::<f64, 6>::from([0.8, -1.2, 1.4, -1.8, -1.5, 0.6]);
    let (kp, kd, span) = (36.0, 12.0, 0.0..3.0);
    row(
        system,
        &ur5,
        span.clone(),
        false,
        || {
            Simulation::new(&ur5)
                .integrator(Dopri5::tol(TOL))
                .feedback(|t, q: &SVector<f64, 6>, v: &SVector<f64, 6>| {
                    let a = (target - q) * kp - v * kd;
                    ur5.inverse_dynamics(q, v, &a, t)
                })
                .run(home, SVector::zeros(), span.clone())
                .map(|run| run.into_trajectory())
        },
        |tr| {
            let (q, _) = tr.final_state();
            let exact =
                (home - target).abs().max() * (1.0 + 6.0 * span.end) * (-6.0 * span.end).exp();
            format!(
                "joint error {:.1e} rad at {} s (closed form {exact:.1e}); tool0 {:.1e} m from its target",
                (target - q).abs().max(),
                span.end,
                tool_distance(&ur5, &q, &target)
            )
        },
    )
}

/// How far the UR5's tool frame at q is from where it is at the target.
fn tool_distance(ur5: &Ur5, q: &SVector<f64, 6>, target: &SVector<f64, 6>) -> f64 {
    let tool = Ur5::BODIES
        .iter()
        .position(|&b| b == "tool0")
        .expect("the UR5 has a tool0 link");
    let at = |q: &SVector<f64, 6>| {
        let mut bodies = vec![BodyPose::default(); Ur5::BODIES.len()];
        let mut points = vec![nalgebra::Vector3::zeros(); Ur5::POINTS.len()];
        ur5.poses(q, 0.0, &mut bodies, &mut points);
        bodies[tool].origin
    };
    (at(q) - at(target)).norm()
}

/// The UR5's tool driven round a circle, position and orientation, by
/// operational-space control through its frame Jacobian, J̇ q̇ and inverse
/// dynamics, from rest 5 cm off the goal and 0.3 rad behind it: the task
/// error e = (p_d − p, log(R_d Rᵀ)) follows e'' + 20 e' + 100 e = 0, e(t) =
/// (e0 + (ė0 + 10 e0) t) e^(−10t).
pub(crate) fn ur5_circle(system: &'static str) -> Result<Row, Error> {
    let ur5 = Ur5 {};
    let omega = 10.0;
    let osc = OperationalSpace::new(&ur5, "tool0", omega)?;
    let circle = tool_circle();
    let q0 = start_off_the_circle(&osc, &circle)?;
    let span = 0.0..4.0;
    row(
        system,
        &ur5,
        span.clone(),
        false,
        || {
            Simulation::new(&ur5)
                .integrator(Dopri5::tol(TOL))
                .feedback(osc.feedback(move |t| circle.at(t)))
                .run(q0, SVector::zeros(), span.clone())
                .map(|run| run.into_trajectory())
        },
        |tr| {
            let (e0, de0) = osc.error(&circle.at(0.0), &q0, &SVector::zeros());
            let (mut off, mut after, mut smallest) = (0.0f64, 0.0f64, f64::INFINITY);
            for ((t, q), v) in tr.times().iter().zip(tr.positions()).zip(tr.velocities()) {
                let (e, _) = osc.error(&circle.at(*t), q, v);
                off = off.max((e - critically_damped(&e0, &de0, omega, *t)).amax());
                if *t >= 1.0 {
                    after = after.max(e.amax());
                }
                smallest = smallest.min(osc.accelerations(&circle.at(*t), q, v).1);
            }
            let (q, v) = tr.final_state();
            let (end, _) = osc.error(&circle.at(span.end), &q, &v);
            format!(
                "tool error {after:.1e} (m, rad) after 1 s, {:.1e} at {} s; off the closed form (e0 + (ė0 + 10 e0) t) e^(−10t) by {off:.1e}; σ_min(J) ≥ {smallest:.2}",
                end.amax(),
                span.end
            )
        },
    )
}
