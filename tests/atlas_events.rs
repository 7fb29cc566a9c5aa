//! Events with the atlas (`Simulation::event` then `run_atlas`): a brick tumbling
//! under gravity, its turn in yaw–pitch–roll, with events on a corner's
//! height, on the pitch angle and on the centre's height, read on the
//! user's coordinates in every chart; located against the same brick with
//! a free orientation (`catalog::free::Brick`).

use crate::catalog;

use catalog::free::Brick;
use lagrange::numeric::euler::EulerChart;
use lagrange::numeric::orientation::rotation_matrix;
use lagrange::prelude::*;
use nalgebra::{Matrix3, SVector, Vector3};

/// The brick of `catalog::free::Brick` in z-y-x angles.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z, yaw, pitch, roll),
    body(brick, mass = m, inertia = [a, b, c], at = [x, y, z],
         rotation = euler_zyx(yaw, pitch, roll)),
    gravity = [0, 0, -g],
    emit(atlas),
)]
struct EulerBrick {
    m: f64,
    a: f64,
    b: f64,
    c: f64,
    g: f64,
}

fn zyx() -> EulerChart {
    EulerChart::new([2, 1, 0]).unwrap()
}

fn quaternion_matrix(q: &SVector<f64, 7>) -> Matrix3<f64> {
    let r = rotation_matrix([q[3], q[4], q[5], q[6]]);
    Matrix3::from_fn(|i, j| r[i][j])
}

fn euler_matrix(q: &SVector<f64, 6>) -> Matrix3<f64> {
    zyx().matrix([q[3], q[4], q[5]])
}

/// A corner of the brick, in body axes.
const CORNER: Vector3<f64> = Vector3::new(0.15, 0.1, 0.05);

/// The two bricks and the start: spun about the intermediate axis lying
/// level, so that the body's x axis passes the vertical twice a turn.
fn bricks() -> (EulerBrick, Brick, [f64; 6], [f64; 6], [f64; 7], [f64; 6]) {
    let brick = Brick {
        g: 9.81,
        ..Brick::solid(2.0, [0.3, 0.2, 0.1])
    };
    let euler = EulerBrick {
        m: brick.m,
        a: brick.a,
        b: brick.b,
        c: brick.c,
        g: brick.g,
    };
    let angles = [-std::f64::consts::FRAC_PI_2, 0.1, 0.05];
    let w = Vector3::new(0.05, 6.0, 0.08);
    let rates = zyx().rates(angles).try_inverse().unwrap() * w;
    let q = nalgebra::UnitQuaternion::from_matrix(&zyx().matrix(angles));
    (
        euler,
        brick,
        [0.0, 0.0, 0.0, angles[0], angles[1], angles[2]],
        [1.0, -0.5, 6.0, rates[0], rates[1], rates[2]],
        [0.0, 0.0, 0.0, q.w, q.i, q.j, q.k],
        [1.0, -0.5, 6.0, w[0], w[1], w[2]],
    )
}

/// The largest gap between the times of each event's occurrences in two
/// runs (which must have as many of each).
fn time_gap(
    events: usize,
    atlas: &[Occurrence<f64, 6>],
    reference: &[Occurrence<f64, 6, 7>],
) -> f64 {
    let mut worst: f64 = 0.0;
    for k in 0..events {
        let a: Vec<f64> = atlas.iter().filter(|o| o.event == k).map(|o| o.t).collect();
        let b: Vec<f64> = (reference.iter())
            .filter(|o| o.event == k)
            .map(|o| o.t)
            .collect();
        assert_eq!(a.len(), b.len(), "event {k}: {a:?} {b:?}");
        assert!(!a.is_empty(), "event {k} never occurs");
        for (x, y) in a.iter().zip(&b) {
            worst = worst.max((x - y).abs());
        }
    }
    worst
}

/// A corner's height over the centre, the pitch crossing 1 rad or π − 1
/// (its sine crossing sin 1: past the switch at |cos pitch| = 0.6, so
/// located in the second chart, close to a switch; the sine, because the
/// user's pitch runs on continuously past π/2 where the quaternion's
/// principal one turns back) and the centre's height falling through
/// −2 m (terminal), and |cos pitch| falling through 0.601, a hair before
/// the switch at 0.6 and in the same step: each located where the quaternion brick's run locates
/// the same function of its state.
#[test]
fn events_on_the_users_angles_are_located_as_on_the_quaternion() {
    let (euler, brick, q0, v0, qq0, vq0) = bricks();
    let run = Simulation::new(&euler)
        .integrator(Dopri5::tol(1e-11))
        .event(Event::new(|_, q, _| (euler_matrix(q) * CORNER)[2]))
        .event(Event::new(|_: f64, q, _| q[4].sin() - 1.0f64.sin()).rising())
        .event(Event::new(|_, q, _| q[2] + 2.0).falling().terminal())
        .event(Event::new(|_: f64, q, _| q[4].cos().abs() - 0.601).falling())
        .run_atlas(q0, v0, 0.0..3.0)
        .unwrap();
    // sin(pitch) = −R₂₀ on either branch (pitch or π − pitch).
    let sin_pitch = |q: &SVector<f64, 7>| -quaternion_matrix(q)[(2, 0)];
    let reference = Simulation::new(&brick)
        .integrator(Dopri5::tol(1e-11))
        .event(Event::new(|_, q, _| (quaternion_matrix(q) * CORNER)[2]))
        .event(Event::new(move |_, q, _| sin_pitch(q) - 1.0f64.sin()).rising())
        .event(
            Event::new(|_, q: &SVector<f64, 7>, _| q[2] + 2.0)
                .falling()
                .terminal(),
        )
        .event(Event::new(move |_, q, _| (1.0 - sin_pitch(q).powi(2)).sqrt() - 0.601).falling())
        .run(qq0, vq0, 0.0..3.0)
        .unwrap();
    let worst = time_gap(4, run.occurrences(), &reference.occurrences);
    let switches = run.switches();
    // How close the crossings come to a switch: those of |cos pitch|
    // through 0.601 fall in the step that ends at a switch (at 0.6).
    let nearest_switch = |k: usize| {
        (run.times(k).iter())
            .map(|t| {
                (switches.iter())
                    .map(|s| (s.t - t).abs())
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    eprintln!(
        "{} switches; {} / {} / {} / {} occurrences; largest time gap {worst:e}; \
         pitch crossings within {:e} s of a switch, |cos pitch| = 0.601 within {:e} s",
        switches.len(),
        run.times(0).len(),
        run.times(1).len(),
        run.times(2).len(),
        run.times(3).len(),
        nearest_switch(1),
        nearest_switch(3),
    );
    assert!(nearest_switch(3) < 1e-3);
    assert!(switches.len() >= 4);
    assert!(worst < 1e-9, "{worst:e}");
    assert_eq!(run.terminated_by(), Some(2));
    assert_eq!(reference.terminated_by, Some(2));
    // The occurrences hold the user's coordinates: the pitch at its
    // crossings is 1 or π − 1 (up to 2π).
    for o in run.occurrences().iter().filter(|o| o.event == 1) {
        assert!((o.q[4].sin() - 1.0f64.sin()).abs() < 1e-9, "{}", o.q[4]);
    }
}

/// An action in the user's coordinates: at each rising crossing of
/// sin(pitch) through 0.9 (in the second chart: |cos pitch| = 0.44) every
/// velocity is reversed, the rates of the angles included. The motion then
/// retraces its path, as the quaternion brick's does when its v (with ω)
/// is reversed.
#[test]
fn an_action_on_the_users_rates_goes_back_into_the_charts() {
    let (euler, brick, q0, v0, qq0, vq0) = bricks();
    let run = Simulation::new(&euler)
        .integrator(Dopri5::tol(1e-11))
        .event(
            Event::new(|_: f64, q, _| q[4].sin() - 0.9)
                .rising()
                .action(|_, _, v| *v = -*v),
        )
        .run_atlas(q0, v0, 0.0..2.0)
        .unwrap();
    let reference = Simulation::new(&brick)
        .integrator(Dopri5::tol(1e-11))
        .event(
            Event::new(|_, q, _| -quaternion_matrix(q)[(2, 0)] - 0.9)
                .rising()
                .action(|_, _, v| *v = -*v),
        )
        .run(qq0, vq0, 0.0..2.0)
        .unwrap();
    let worst_time = time_gap(1, run.occurrences(), &reference.occurrences);
    let traj = run.charted();
    let mut worst: f64 = 0.0;
    for (i, &t) in traj.times().iter().enumerate() {
        let (q, _) = reference.trajectory.state_at(t).unwrap();
        worst = worst.max((run.rotation(i, 0) - quaternion_matrix(&q)).abs().max());
    }
    let in_second = (run.occurrences().iter())
        .filter(|o| run.charted().state_at(o.t).is_some() && run.charts_at(o.t) & 1 == 1)
        .count();
    eprintln!(
        "{} reversals ({in_second} in the second chart), {} switches; time gap {worst_time:e}, rotation gap {worst:e}",
        run.occurrences().len(),
        run.switches().len()
    );
    assert!(in_second >= 1, "no reversal in the second chart");
    assert!(
        worst_time < 1e-9 && worst < 1e-8,
        "{worst_time:e} {worst:e}"
    );
}
