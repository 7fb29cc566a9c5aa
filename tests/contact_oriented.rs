//! Contacts on descriptions with a free orientation (a unit quaternion in
//! q, ω in v): a ball on a quaternion thrown without spin rolls at 5/7 of
//! its speed from t = 2v₀/(7μg), in the direction it was thrown, as on
//! Euler angles; the time stepper on the group gives the same to its
//! order; a box on eight corners tossed onto the floor settles flat.

use lagrange::prelude::*;
use lagrange::{ChangeKind, ContactRun, ContactState, Dop853, MoreauJean};

const G: f64 = 9.81;

/// A solid ball turning freely, on the floor.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(attitude),
    body(ball, mass = m, inertia = [0.4 * m * r * r, 0.4 * m * r * r, 0.4 * m * r * r],
         at = [x, y, z], rotation = attitude),
    gravity = [0, 0, -g],
    contact(ground, on = ball, radius = r, normal = [0, 0, 1], restitution = 0.5, friction = 0.3),
)]
struct Ball {
    m: f64,
    r: f64,
    g: f64,
}

/// A box a × b × c turning freely, each of its corners against the floor.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(attitude),
    body(block, mass = m, inertia = [m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                                     m * (a * a + b * b) / 12],
         at = [x, y, z], rotation = attitude),
    gravity = [0, 0, -g],
    point(c1, on = block, at = [a / 2, b / 2, c / 2]),
    point(c2, on = block, at = [-a / 2, b / 2, c / 2]),
    point(c3, on = block, at = [a / 2, -b / 2, c / 2]),
    point(c4, on = block, at = [-a / 2, -b / 2, c / 2]),
    point(c5, on = block, at = [a / 2, b / 2, -c / 2]),
    point(c6, on = block, at = [-a / 2, b / 2, -c / 2]),
    point(c7, on = block, at = [a / 2, -b / 2, -c / 2]),
    point(c8, on = block, at = [-a / 2, -b / 2, -c / 2]),
    contact(k1, on = c1, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(k2, on = c2, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(k3, on = c3, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(k4, on = c4, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(k5, on = c5, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(k6, on = c6, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(k7, on = c7, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(k8, on = c8, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
)]
struct Brick {
    m: f64,
    a: f64,
    b: f64,
    c: f64,
    g: f64,
}

/// A satellite on a quaternion with a wheel on its z axis, the wheel's
/// bearing holding up to 0.2 N·m.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(yaw),
    orientation(attitude),
    body(sat, mass = 1, inertia = [1, 2, 3], at = [0, 0, 0], rotation = attitude),
    body(wheel, mass = 1, inertia = [1, 1, 1], at = [0, 0, 1],
         rotation = attitude * rot_z(yaw)),
    joint(yaw, friction = 0.2),
)]
struct Satellite;

const BALL: Ball = Ball {
    m: 0.3,
    r: 0.1,
    g: G,
};

#[test]
fn a_ball_on_a_quaternion_rolls_at_five_sevenths_where_it_was_thrown() {
    let v0 = [1.2, 1.6, 0.0, 0.0, 0.0, 0.0];
    let q0 = [0.0, 0.0, BALL.r, 1.0, 0.0, 0.0, 0.0];
    let speed = 2.0;
    let run: ContactRun<f64, 6, 7> = Simulation::new(&BALL)
        .integrator(Dop853::tol(1e-13))
        .run_contacts(q0, v0, 0.0..1.0)
        .unwrap();
    let rolls: Vec<f64> = (run.changes.iter())
        .filter(|c| matches!(c.kind, ChangeKind::Sticks))
        .map(|c| c.t)
        .collect();
    let t_roll = 2.0 * speed / (7.0 * 0.3 * G);
    let (q, v) = run.trajectory.final_state();
    let want = [1.2 * 5.0 / 7.0, 1.6 * 5.0 / 7.0];
    eprintln!(
        "ball on a quaternion: rolls {:.1e} s from 2v0/(7μg), at {:.1e} m/s from 5/7 v0",
        (rolls[0] - t_roll).abs(),
        (v[0] - want[0]).abs().max((v[1] - want[1]).abs())
    );
    assert!((rolls[0] - t_roll).abs() < 1e-9);
    assert!((v[0] - want[0]).abs() < 1e-9 && (v[1] - want[1]).abs() < 1e-9);
    // Rolling: |ω| = |v| / r (ω in body axes, which turn with the ball).
    let spin = v.fixed_rows::<3>(3).norm();
    assert!((spin - 5.0 / 7.0 * speed / BALL.r).abs() < 1e-8, "{spin}");
    assert!((q.fixed_rows::<4>(3).norm() - 1.0).abs() < 1e-12);
    assert!((q[2] - BALL.r).abs() < 1e-12);
    assert_eq!(run.states(1.0), [ContactState::Sticking]);
}

#[test]
fn the_time_stepper_on_the_group_rolls_the_ball_too() {
    let v0 = [1.2, 1.6, 0.0, 0.0, 0.0, 0.0];
    let q0 = [0.0, 0.0, BALL.r, 1.0, 0.0, 0.0, 0.0];
    let run = Simulation::new(&BALL)
        .integrator(MoreauJean::step(1e-4))
        .run_contacts(q0, v0, 0.0..1.0)
        .unwrap();
    let (q, v) = run.trajectory.final_state();
    let off = (v[0] - 1.2 * 5.0 / 7.0)
        .abs()
        .max((v[1] - 1.6 * 5.0 / 7.0).abs());
    eprintln!("ball on a quaternion, time-stepped (h = 1e-4): {off:.1e} m/s from 5/7 v0");
    assert!(off < 1e-6, "{off}");
    assert!((q.fixed_rows::<4>(3).norm() - 1.0).abs() < 1e-12);
    assert_eq!(run.states(1.0), [ContactState::Sticking]);
}

/// Dropped tilted and spinning from 0.3 m: the box bounces on its corners
/// and comes to rest flat on a face, four corners down, its centre half
/// that face's height above the floor.
#[test]
fn a_box_on_eight_corners_settles_flat() {
    let brick = Brick {
        m: 1.0,
        a: 0.3,
        b: 0.2,
        c: 0.1,
        g: G,
    };
    let half = 0.25f64;
    let (w, i) = (half.cos(), half.sin());
    let q0 = [0.0, 0.0, 0.3, w, i * 0.6, i * 0.8, 0.0];
    let v0 = [0.5, 0.0, 0.0, 0.0, 0.0, 2.0];
    let run = Simulation::new(&brick)
        .integrator(MoreauJean::step(2e-4))
        .run_contacts(q0, v0, 0.0..2.0)
        .unwrap();
    let (q, v) = run.trajectory.final_state();
    let face = [brick.a, brick.b, brick.c]
        .map(|side| q[2] - side / 2.0)
        .into_iter()
        .fold(f64::INFINITY, |m, d| if d.abs() < m.abs() { d } else { m });
    eprintln!(
        "box on eight corners: at rest {face:.1e} m off a face's half height, speed {:.1e}",
        v.norm()
    );
    assert!(face.abs() < 1e-3, "{q}");
    assert!(v.norm() < 1e-6, "{v}");
    let resting = run.states(2.0);
    let touching = resting
        .iter()
        .filter(|s| **s != ContactState::Apart)
        .count();
    assert_eq!(touching, 4, "{resting:?}");
}

/// At a turned attitude the slip rows give the contact point's velocity
/// ẋ + R ω × (−r n), ω in body axes as v holds it.
#[test]
fn the_derived_slip_is_the_contact_point_s_velocity() {
    use lagrange::Contacts;
    use nalgebra::{Quaternion, UnitQuaternion, Vector3};
    let (w, i) = (0.7f64.cos(), 0.7f64.sin());
    let axis = Vector3::new(0.3, 0.5, 0.8).normalize() * i;
    let q = SVector::<f64, 7>::from([0.1, 0.2, 0.1, w, axis.x, axis.y, axis.z]);
    let v = SVector::<f64, 6>::from([1.0, 2.0, 0.0, 0.3, -0.7, 1.1]);
    let rows = BALL.contact_rows(0, &q, &v, 0.0).unwrap();
    let turn = UnitQuaternion::from_quaternion(Quaternion::new(q[3], q[4], q[5], q[6]));
    let omega = turn * Vector3::new(v[3], v[4], v[5]);
    let point = Vector3::new(v[0], v[1], v[2]) + omega.cross(&Vector3::new(0.0, 0.0, -BALL.r));
    assert!((rows.tangents[0].dot(&v) - point.x).abs() < 1e-15);
    assert!((rows.tangents[1].dot(&v) - point.y).abs() < 1e-15);
    assert_eq!(
        rows.normal,
        SVector::<f64, 6>::from([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    );
    // The slip's rate at q̈ = 0 is zero: R [ω]× ω = 0.
    assert!(rows.tangent_bias.iter().all(|b| b.abs() < 1e-15));
}

/// The wheel spun at ψ̇₀ = 2 in a satellite at rest: the bearing's friction
/// turns the one against the other, ψ̈ = −fc (1/I_w + 1/I_s) with I_w = 1
/// and I_s = 3 about z, until the relative spin stops at t = 7.5 s; the
/// angular momentum about z is kept throughout.
#[test]
fn a_wheel_s_bearing_friction_brings_it_to_the_satellite_s_spin() {
    let run = Simulation::new(&Satellite)
        .integrator(Dop853::tol(1e-13))
        .run_contacts([0.0, 1.0, 0.0, 0.0, 0.0], [2.0, 0.0, 0.0, 0.0], 0.0..10.0)
        .unwrap();
    let sticks: Vec<f64> = (run.changes.iter())
        .filter(|c| matches!(c.kind, ChangeKind::Sticks))
        .map(|c| c.t)
        .collect();
    let (_, v) = run.trajectory.final_state();
    eprintln!(
        "wheel in a satellite: stops {:.1e} s from 7.5 s",
        (sticks[0] - 7.5).abs()
    );
    assert!((sticks[0] - 7.5).abs() < 1e-9);
    // L_z = I_s ω + I_w (ω + ψ̇) = 2 at the start; after, ω = 2/4 and ψ̇ = 0.
    assert!(v[0].abs() < 1e-9 && (v[3] - 0.5).abs() < 1e-9, "{v}");
}
