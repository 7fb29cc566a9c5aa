//! `joint(q, motor = u, gear = n, rotor = Ir)`: a motor behind a gearbox.
//! Checked against the same system written out by hand (n u as a
//! generalized force, n² Ir as an armature) on both routes and every
//! output, against the closed form of a damped flywheel spun up from rest,
//! and a gear ratio computed as 0 from the parameters refused before a run.

use lagrange::prelude::*;
use lagrange::{Dop853, Driven, Dynamics, Error};

/// A flywheel turned by a geared motor (a kinematic tree: the recursive
/// route, the articulated q̈ and the inverse dynamics).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    inputs(u),
    body(wheel, mass = m, inertia = [j, j, j], at = [0, 0, 0], com = [0, -c, 0],
         rotation = rot_z(theta)),
    gravity = [0, -g, 0],
    joint(theta, damping = b, armature = ia, motor = u, gear = n, rotor = ir),
    emit(articulated, inverse_dynamics, jacobians),
)]
pub struct GearedMotor {
    pub m: f64,
    pub j: f64,
    pub c: f64,
    pub g: f64,
    pub b: f64,
    pub ia: f64,
    pub n: f64,
    pub ir: f64,
}

/// The same, written out: n u on the coordinate, n² Ir in its armature.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    inputs(u),
    body(wheel, mass = m, inertia = [j, j, j], at = [0, 0, 0], com = [0, -c, 0],
         rotation = rot_z(theta)),
    gravity = [0, -g, 0],
    generalized_force(theta = n * u),
    joint(theta, damping = b, armature = ia + pow(n, 2) * ir),
    emit(articulated, inverse_dynamics, jacobians),
)]
pub struct GearedByHand {
    pub m: f64,
    pub j: f64,
    pub c: f64,
    pub g: f64,
    pub b: f64,
    pub ia: f64,
    pub n: f64,
    pub ir: f64,
}

/// A geared motor at the pivot of a bob on a massless rod (the generic
/// route), with its rotor alone (no armature of the joint's own).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    inputs(u),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, motor = u, gear = n, rotor = ir),
)]
pub struct GearedBob {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub n: f64,
    pub ir: f64,
}

fn motor() -> (GearedMotor, GearedByHand) {
    let (m, j, c, g, b, ia, n, ir) = (1.3, 0.04, 0.2, 9.81, 0.3, 0.01, 50.0, 2.0e-5);
    (
        GearedMotor {
            m,
            j,
            c,
            g,
            b,
            ia,
            n,
            ir,
        },
        GearedByHand {
            m,
            j,
            c,
            g,
            b,
            ia,
            n,
            ir,
        },
    )
}

type V1 = SVector<f64, 1>;

/// Every output of the derive agrees with the hand-written system's at
/// several states: M, Q, the inputs' forces and Jacobians, the articulated
/// q̈ and the inverse dynamics.
#[test]
fn a_geared_motor_is_its_torque_times_n_and_its_rotor_times_n_squared() {
    let (geared, by_hand) = motor();
    for k in 0..5 {
        let x = k as f64;
        let (q, v, u) = (
            V1::new(0.9 * x - 1.7),
            V1::new(2.3 - 1.1 * x),
            V1::new(0.4 * x - 0.5),
        );
        let inertia = geared.j + geared.m * geared.c * geared.c + geared.ia;
        let reflected = geared.n * geared.n * geared.ir;
        let m = geared.mass_matrix(&q, 0.0)[(0, 0)];
        assert!((m - inertia - reflected).abs() < 1e-14, "M = {m}");
        assert_eq!(m, by_hand.mass_matrix(&q, 0.0)[(0, 0)]);
        let push = geared.input_forces(&q, &v, &u, 0.0);
        assert!(
            (push[0] - geared.n * u[0]).abs() < 1e-13,
            "n u = {}",
            push[0]
        );
        assert_eq!(push, by_hand.input_forces(&q, &v, &u, 0.0));
        let q_force = geared.generalized_forces(&q, &v, 0.0);
        assert_eq!(q_force, by_hand.generalized_forces(&q, &v, 0.0));
        assert_eq!(
            geared.input_jacobians(&q, &v, &u, 0.0),
            by_hand.input_jacobians(&q, &v, &u, 0.0)
        );
        let (ours, _) = geared.forward_dynamics(&q, &v, &push, 0.0).unwrap();
        let (theirs, _) = by_hand.forward_dynamics(&q, &v, &push, 0.0).unwrap();
        assert!((ours[0] - theirs[0]).abs() < 1e-12 * theirs[0].abs().max(1.0));
        let tau = geared.inverse_dynamics(&q, &v, &ours, 0.0);
        assert!(
            (tau[0] - push[0]).abs() < 1e-10,
            "τ = {}, n u = {}",
            tau[0],
            push[0]
        );
    }
}

/// A constant motor torque u from rest on the flywheel without gravity:
/// I ω̇ = n u − b ω, I = J + m c² + Ia + n² Ir, so
/// ω = (n u / b)(1 − e^(−t/τ)) and θ = (n u / b)(t − τ (1 − e^(−t/τ))),
/// τ = I / b.
#[test]
fn a_geared_motor_spins_a_damped_flywheel_up_as_the_closed_form() {
    let (mut geared, _) = motor();
    geared.g = 0.0;
    let u = 0.02;
    let inertia =
        geared.j + geared.m * geared.c * geared.c + geared.ia + geared.n * geared.n * geared.ir;
    let (speed, tau) = (geared.n * u / geared.b, inertia / geared.b);
    let run = Simulation::new(&geared)
        .integrator(Dop853::tol(1e-13))
        .open_loop(move |_| [u])
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap();
    let (q, v) = run.trajectory().final_state();
    let decay = (-1.0 / tau).exp();
    let omega = speed * (1.0 - decay);
    let theta = speed * (1.0 - tau * (1.0 - decay));
    eprintln!(
        "geared flywheel: θ off by {:.1e} rad, ω by {:.1e} rad/s",
        q[0] - theta,
        v[0] - omega
    );
    assert!((q[0] - theta).abs() < 1e-9 && (v[0] - omega).abs() < 1e-9);
}

/// On the generic route the rotor alone is the armature, n² Ir, and a
/// small swing's period is 2π √((m l² + n² Ir)/(m g l)).
#[test]
fn a_geared_rotor_slows_a_pendulum_by_n_squared() {
    let p = GearedBob {
        m: 0.5,
        l: 0.3,
        g: 9.81,
        n: 30.0,
        ir: 1.0e-4,
    };
    let q = V1::new(0.3);
    let inertia = p.m * p.l * p.l + p.n * p.n * p.ir;
    assert!((p.mass_matrix(&q, 0.0)[(0, 0)] - inertia).abs() < 1e-14);
    let push = p.input_forces(&q, &V1::zeros(), &V1::new(0.1), 0.0)[0];
    assert!((push - 3.0).abs() < 1e-13);
    let period = 2.0 * std::f64::consts::PI * (inertia / (p.m * p.g * p.l)).sqrt();
    let traj = Simulation::new(&p)
        .integrator(Dop853::tol(1e-13))
        .open_loop(|_| [0.0])
        .run([1e-4], [0.0], 0.0..2.2 * period)
        .unwrap();
    let zeros = traj.trajectory().crossings(|_, q, _| q[0]).unwrap();
    // Two half periods between the first and the third crossing.
    let measured = zeros[2] - zeros[0];
    // θ₀ = 10⁻⁴: the nonlinearity shifts the period by θ₀²/16.
    assert!(
        (measured / period - 1.0).abs() < 1e-8,
        "{measured} vs {period}"
    );
    // At rest the rotor's inertia slows the fall: θ̈ = −m g l sin θ / I.
    let accel = Dynamics::new(&p)
        .acceleration(0.0, &q, &V1::zeros())
        .unwrap()[0];
    assert!((accel + p.m * p.g * p.l * q[0].sin() / inertia).abs() < 1e-12);
}

/// A gear ratio computed from the parameters must be > 0: 0 would cut the
/// motor off, and is refused before the run, naming the joint.
#[test]
fn a_gear_ratio_of_zero_from_the_parameters_is_refused() {
    let (mut geared, _) = motor();
    geared.n = 0.0;
    let err = Simulation::new(&geared)
        .open_loop(|_| [0.0])
        .run([0.1], [0.0], 0.0..1.0)
        .unwrap_err();
    match err.error {
        Error::NonPhysicalParameter {
            body, entry, value, ..
        } => {
            assert_eq!((body, entry, value), ("theta", "gear", 0.0));
        }
        other => panic!("expected NonPhysicalParameter, got {other:?}"),
    }
}
