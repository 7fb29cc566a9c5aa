//! Nonholonomic constraints with the atlas: the rolling sphere in z-x-z
//! angles (`catalog::constrained::RollingSphere`, homogeneous, emitted in
//! both constrained forms) and Chaplygin's ball (unequal moments, the
//! sphere's rows) rolled through θ = 0, where z-x-z stops, by
//! `run_atlas`, against the same bodies with a free orientation
//! (`catalog::rolling::QuaternionSphere`); and rolled at regular states,
//! where the user's chart can run them itself, against `run`; and with
//! events on the user's θ, located in the second chart. The twin
//! keeps the height and the two rolling rows (written on the ball's
//! velocity and ω), so both charts run the multiplier form with all three.

use crate::catalog;
use crate::rolling;

use catalog::constrained::RollingSphere;
use catalog::rolling::QuaternionSphere;
use lagrange::numeric::euler::EulerChart;
use lagrange::prelude::*;
use nalgebra::{SVector, Vector3};
use rolling::{BALL, ZXZ, contact_momentum, quaternion_of, rotation_of};
use std::f64::consts::TAU;

/// Chaplygin's ball in z-x-z angles with an atlas: `rolling::ChartBall`
/// with `emit(atlas)`.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(ball, mass = m, inertia = [j1, j2, j3], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
    emit(atlas),
)]
struct AtlasBall {
    m: f64,
    j1: f64,
    j2: f64,
    j3: f64,
    a: f64,
    g: f64,
}

const ATLAS_BALL: AtlasBall = AtlasBall {
    m: BALL.m,
    j1: BALL.j1,
    j2: BALL.j2,
    j3: BALL.j3,
    a: BALL.a,
    g: BALL.g,
};

/// The homogeneous sphere of the catalog and its quaternion twin.
const SPHERE: RollingSphere = RollingSphere {
    m: 2.0,
    j: 0.4 * 2.0 * 0.3 * 0.3,
    a: 0.3,
    g: 9.81,
};
const QUATERNION_SPHERE: QuaternionSphere = QuaternionSphere {
    m: 2.0,
    j1: 0.4 * 2.0 * 0.3 * 0.3,
    j2: 0.4 * 2.0 * 0.3 * 0.3,
    j3: 0.4 * 2.0 * 0.3 * 0.3,
    a: 0.3,
    g: 9.81,
};

const TOL: f64 = 1e-11;

fn zxz() -> EulerChart {
    EulerChart::new(ZXZ).unwrap()
}

/// A rolling state in the user's coordinates from the centre (x, y) on
/// the plane z = a, the angles and their rates (any, θ = 0 included: ω =
/// E q̇ is defined there), and the same state with a free orientation:
/// centre, unit quaternion; centre velocity, ω in body axes.
#[allow(clippy::type_complexity)]
fn rolling_start(
    a: f64,
    angles: [f64; 3],
    rates: [f64; 3],
) -> (
    (SVector<f64, 6>, SVector<f64, 6>),
    (SVector<f64, 7>, SVector<f64, 6>),
) {
    let w = zxz().rates(angles) * Vector3::from(rates);
    let world = zxz().matrix(angles) * w;
    // No slip at the contact: v + ω × (−a e_z) = 0.
    let (vx, vy) = (a * world[1], -a * world[0]);
    let (x, y) = (0.3, -0.2);
    let [psi, theta, phi] = angles;
    let chart = (
        SVector::from([x, y, a, psi, theta, phi]),
        SVector::from([vx, vy, 0.0, rates[0], rates[1], rates[2]]),
    );
    let [qw, qx, qy, qz] = quaternion_of(ZXZ, angles);
    let free = (
        SVector::from([x, y, a, qw, qx, qy, qz]),
        SVector::from([vx, vy, 0.0, w[0], w[1], w[2]]),
    );
    (chart, free)
}

/// What a run through the atlas gives against the quaternion run: the
/// largest gaps in the rotation matrix and the centre, the largest
/// residual, the energy drift and the largest change of the angular
/// momentum about the contact point.
struct Agreement {
    switches: usize,
    rotation: f64,
    centre: f64,
    residual: f64,
    drift: f64,
    momentum: f64,
}

fn compare<const N: usize>(
    run: &AtlasRun<f64, N>,
    reference: &Trajectory<f64, 6, 7>,
    ball: &QuaternionSphere,
) -> Agreement {
    let traj = run.charted();
    let (mut rotation, mut centre, mut momentum) = (0.0f64, 0.0f64, 0.0f64);
    let mut first = None;
    for (i, &t) in traj.times().iter().enumerate() {
        let (qr, _) = reference.state_at(t).unwrap();
        rotation = rotation.max((run.rotation(i, 0) - rotation_of(&qr)).amax());
        let (q, v) = (&traj.positions()[i], &traj.velocities()[i]);
        let c = q.fixed_rows::<3>(0).into_owned();
        centre = centre.max((c - qr.fixed_rows::<3>(0)).amax());
        // The angular momentum about the contact, read off the atlas run.
        let [qw, qx, qy, qz] = run.quaternion(i, 0);
        let w = run.angular_velocity(i, 0);
        let free_q = SVector::from([c[0], c[1], c[2], qw, qx, qy, qz]);
        let free_v = SVector::from([v[0], v[1], v[2], w[0], w[1], w[2]]);
        let k = contact_momentum(ball, &free_q, &free_v);
        let k0 = *first.get_or_insert(k);
        momentum = momentum.max((k - k0).amax());
    }
    let residual = (traj.residuals().iter()).fold(0.0f64, |m, r| m.max(r[0]).max(r[1]));
    Agreement {
        switches: run.switches().len(),
        rotation,
        centre,
        residual,
        drift: traj.integral_drift(),
        momentum,
    }
}

/// Chaplygin's ball started on z-x-z's singular set (θ = 0: the body's z
/// axis vertical) and tumbling for 6 s: it leaves the user's chart at once
/// and switches back and forth as its axis swings, its rotation and centre
/// those of the quaternion ball, the rolling rows and the height kept, its
/// energy and its angular momentum about the contact conserved.
#[test]
fn chaplygins_ball_from_the_singular_set_matches_the_quaternion_ball() {
    let ((q0, v0), (qf, vf)) = rolling_start(BALL.a, [0.4, 0.0, -0.7], [1.5, 2.5, -0.8]);
    let run = Simulation::new(&ATLAS_BALL)
        .integrator(Dopri5::tol(TOL))
        .run_atlas(q0, v0, 0.0..6.0)
        .unwrap();
    let reference = Simulation::new(&BALL)
        .integrator(Dopri5::tol(TOL))
        .run(qf, vf, 0.0..6.0)
        .unwrap();
    assert_eq!(run.charts()[0], 1, "started in the second chart");
    let got = compare(&run, &reference, &BALL);
    eprintln!(
        "Chaplygin's ball through θ = 0: {} switches, rotation gap {:e}, centre gap {:e}, \
         largest residual {:e}, energy drift {:e}, contact momentum change {:e}",
        got.switches, got.rotation, got.centre, got.residual, got.drift, got.momentum
    );
    assert!(got.switches >= 2, "{}", got.switches);
    assert!(
        got.rotation < 1e-8 && got.centre < 1e-8,
        "{:e} {:e}",
        got.rotation,
        got.centre
    );
    assert!(got.residual < 1e-9, "{:e}", got.residual);
    assert!(
        got.drift < 1e-9 && got.momentum < 1e-8,
        "{:e} {:e}",
        got.drift,
        got.momentum
    );
    // `run` stays in the user's chart, singular at this start.
    let plain = Simulation::new(&ATLAS_BALL)
        .integrator(Dopri5::tol(TOL))
        .run(q0, v0, 0.0..6.0)
        .unwrap_err();
    assert!(
        matches!(plain.error, Error::SingularMassMatrix { .. }),
        "{}",
        plain.error
    );
}

/// The catalog's homogeneous sphere (emitted with multipliers and the
/// reduced form: the atlas runs the multiplier form) rolled through the
/// upright with a spin: its ω is constant in space, 0.7 off the vertical,
/// and its z axis, on a cone of the same opening about ω, passes the
/// vertical at t = 1/3 and once a turn after (ψ and φ race there: the
/// user's chart alone cannot follow).
#[test]
fn the_catalog_sphere_rolls_through_the_upright_as_the_quaternion_sphere() {
    let (speed, opening, lead): (f64, f64, f64) = (3.0, 0.7, 1.0);
    let axis = Vector3::new(opening.sin(), 0.0, opening.cos());
    // The body's z axis `lead` radians of turn before the vertical.
    let z0 = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), -lead)
        * Vector3::z();
    let (theta, psi) = (z0[2].acos(), z0[0].atan2(-z0[1]));
    let angles = [psi, theta, 0.4];
    let body = zxz().matrix(angles).transpose() * axis * speed;
    let rates = zxz().rates(angles).try_inverse().unwrap() * body;
    let ((q0, v0), (qf, vf)) = rolling_start(SPHERE.a, angles, rates.into());
    let run = Simulation::new(&SPHERE)
        .integrator(Dopri5::tol(TOL))
        .run_atlas(q0, v0, 0.0..5.0)
        .unwrap();
    let reference = Simulation::new(&QUATERNION_SPHERE)
        .integrator(Dopri5::tol(TOL))
        .run(qf, vf, 0.0..5.0)
        .unwrap();
    let got = compare(&run, &reference, &QUATERNION_SPHERE);
    let upright = (0..run.charted().len())
        .map(|i| 1.0 - run.rotation(i, 0)[(2, 2)])
        .fold(f64::INFINITY, f64::min);
    eprintln!(
        "catalog sphere through θ = 0: {} switches, closest to the upright 1 − cos θ = {upright:e}, \
         rotation gap {:e}, centre gap {:e}, largest residual {:e}, energy drift {:e}",
        got.switches, got.rotation, got.centre, got.residual, got.drift
    );
    // A turn takes 2π/3 ≈ 2.1 s: at least two passes, each in and out of
    // the second chart.
    assert!(got.switches >= 4, "{}", got.switches);
    assert!(upright < 1e-3, "{upright:e}");
    assert!(
        got.rotation < 1e-8 && got.centre < 1e-8,
        "{:e} {:e}",
        got.rotation,
        got.centre
    );
    assert!(
        got.residual < 1e-9 && got.drift < 1e-9,
        "{:e} {:e}",
        got.residual,
        got.drift
    );
}

/// At regular states the atlas and `run` in the user's chart solve the
/// same motion: Chaplygin's ball tilted so that θ swings between 0.47
/// and 1.09 (the user's chart regular throughout, `run` gets through)
/// leaves the user's chart below |sin θ| = 0.6 and comes back above 0.8;
/// read back in the user's coordinates the atlas run is `run`'s.
#[test]
fn at_regular_states_the_atlas_matches_the_users_chart() {
    let ((q0, v0), _) = rolling_start(BALL.a, [0.2, 0.7, 0.5], [0.0, 1.0, 3.0]);
    let run = Simulation::new(&ATLAS_BALL)
        .integrator(Dopri5::tol(TOL))
        .run_atlas(q0, v0, 0.0..4.0)
        .unwrap();
    let plain = Simulation::new(&ATLAS_BALL)
        .integrator(Dopri5::tol(TOL))
        .run(q0, v0, 0.0..4.0)
        .unwrap();
    let traj = run.charted();
    let (mut gap, mut lowest) = (0.0f64, f64::INFINITY);
    for (i, &t) in traj.times().iter().enumerate() {
        let (q, v) = run.user_state(i).unwrap();
        let (qp, vp) = plain.state_at(t).unwrap();
        // ψ and φ read back nearest where they left, up to whole turns.
        let turns = |d: f64| d - (d / TAU).round() * TAU;
        let dq = (q - qp).map_with_location(|i, _, d| if i == 3 || i == 5 { turns(d) } else { d });
        gap = gap.max(dq.amax()).max((v - vp).amax());
        lowest = lowest.min(q[4].sin().abs());
    }
    let switches = run.switches().len();
    let residual = (traj.residuals().iter()).fold(0.0f64, |m, r| m.max(r[0]).max(r[1]));
    eprintln!(
        "Chaplygin's ball at regular states: {switches} switches, lowest |sin θ| {lowest:.3}, \
         gap to `run` {gap:e}, largest residual {residual:e}, energy drift {:e} (run's {:e})",
        traj.integral_drift(),
        plain.integral_drift()
    );
    assert!(switches >= 2, "{switches}");
    assert!(gap < 1e-8, "{gap:e}");
    assert!(
        residual < 1e-9 && traj.integral_drift() < 1e-9,
        "{residual:e}"
    );
}

/// A start off the rolling rows is refused before any step, naming the
/// row, as `run` refuses it.
#[test]
fn a_slipping_start_is_refused() {
    let ((q0, mut v0), _) = rolling_start(BALL.a, [0.4, 0.0, -0.7], [1.5, 2.5, -0.8]);
    v0[0] += 0.1;
    let failure = Simulation::new(&ATLAS_BALL)
        .run_atlas(q0, v0, 0.0..1.0)
        .unwrap_err();
    match failure.error {
        Error::InconsistentInitialConditions { constraint, .. } => {
            assert_eq!(constraint, "slip_x")
        }
        e => panic!("{e}"),
    }
}

/// Events with rolling: Chaplygin's ball from θ = 0 with an event on the
/// user's θ crossing 0.5 or π − 0.5 (|cos θ| against cos 0.5, the same on
/// either branch: located in the second chart, where the user's angles
/// are read back from the rotation) and one on the centre's x crossing 0.5;
/// located where the quaternion ball's run locates the same functions.
#[test]
fn events_on_the_rolling_balls_angles_are_located_as_on_the_quaternion_ball() {
    let ((q0, v0), (qf, vf)) = rolling_start(BALL.a, [0.4, 0.0, -0.7], [1.5, 2.5, -0.8]);
    let tilt = 0.5f64.cos();
    let run = Simulation::new(&ATLAS_BALL)
        .integrator(Dopri5::tol(TOL))
        .event(Event::new(move |_, q: &SVector<f64, 6>, _| {
            q[4].cos().abs() - tilt
        }))
        .event(Event::new(|_, q: &SVector<f64, 6>, _| q[0] - 0.5))
        .run_atlas(q0, v0, 0.0..6.0)
        .unwrap();
    let reference = Simulation::new(&BALL)
        .integrator(Dopri5::tol(TOL))
        .event(Event::new(move |_, q, _| {
            rotation_of(q)[(2, 2)].abs() - tilt
        }))
        .event(Event::new(|_, q: &SVector<f64, 7>, _| q[0] - 0.5))
        .run(qf, vf, 0.0..6.0)
        .unwrap();
    let mut worst = 0.0f64;
    for k in 0..2 {
        let got = run.times(k);
        let want: Vec<f64> = (reference.occurrences.iter())
            .filter(|o| o.event == k)
            .map(|o| o.t)
            .collect();
        assert_eq!(got.len(), want.len(), "event {k}: {got:?} {want:?}");
        assert!(!got.is_empty(), "event {k} never occurs");
        for (a, b) in got.iter().zip(&want) {
            worst = worst.max((a - b).abs());
        }
    }
    // The tilt crossings are located in the second chart.
    let in_second = (run.times(0).iter()).all(|&t| run.charts_at(t) == 1);
    eprintln!(
        "rolling events: {} tilt crossings, {} x crossings, largest time gap {worst:e}, \
         all tilt crossings in the second chart: {in_second}",
        run.times(0).len(),
        run.times(1).len()
    );
    assert!(in_second);
    assert!(worst < 1e-9, "{worst:e}");
}

/// `Linearizer::atlas` with rolling rows: at a regular state it is
/// `constrained_tangent`'s model of the user's chart; at θ = 0 it reads the
/// second chart (states named `@2`), where the ball at rest on the plane
/// has no restoring force: on its 5 independent coordinates and 3
/// independent speeds, no column of A reads a coordinate and no speed
/// changes.
#[test]
fn the_rolling_ball_linearises_in_a_regular_chart() {
    use lagrange::linear::{Linearizer, OperatingPoint};
    let ((q, v), _) = rolling_start(BALL.a, [0.2, 0.9, 0.5], [0.3, 1.0, 3.0]);
    let lz = Linearizer::new();
    let atlas = lz.atlas(&ATLAS_BALL, &q, &v, 0.0).unwrap();
    let tangent = lz
        .constrained_tangent(&ATLAS_BALL, &OperatingPoint::on_group(q, v))
        .unwrap();
    assert_eq!(atlas.states(), tangent.states());
    let gap = (atlas.a() - tangent.a()).amax();
    eprintln!("rolling ball at θ = 0.9: A of the atlas and constrained_tangent within {gap:.1e}");
    assert!(gap < 1e-9 * tangent.a().amax(), "{gap:e}");
    let ((q, v), _) = rolling_start(BALL.a, [0.0; 3], [0.0; 3]);
    let rest = lz.atlas(&ATLAS_BALL, &q, &v, 0.0).unwrap();
    assert!(
        rest.states().iter().any(|s| s == "theta@2"),
        "{:?}",
        rest.states()
    );
    let (states, coordinates) = (rest.states().len(), rest.n_coordinates());
    assert_eq!((states, coordinates), (8, 5), "{:?}", rest.states());
    let accelerations = rest.a().rows(coordinates, states - coordinates);
    assert!(accelerations.amax() < 1e-12, "{}", rest.a());
    assert!(
        rest.a().columns(0, coordinates).amax() < 1e-12,
        "{}",
        rest.a()
    );
}
