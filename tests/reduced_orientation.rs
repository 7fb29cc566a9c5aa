//! The reduced form (independent speeds) with free orientations: the
//! rolling sphere and the rolling disk with a quaternion on speeds of their
//! angular velocity (body axes) or of their centre, against the same
//! descriptions in the multiplier form and against the bodies in Euler
//! angles where those charts are regular; then the sphere through the state
//! where euler_zxz stops, with its energy and its angular momentum about the
//! contact point.

use crate::catalog;
use crate::common;
use crate::rolling;

use catalog::constrained::RollingDisk;
use common::numeric::Lcg;
use lagrange::linear::{Linearizer, OperatingPoint, sweep};
use lagrange::prelude::*;
use lagrange::project_consistent;
use nalgebra::SVector;
use rolling::*;

const TOL: f64 = 1e-11;

/// `QuaternionSphere` in both forms, the reduced one on the body-axis
/// angular velocities.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(ball_q),
    body(ball, mass = m, inertia = [j1, j2, j3], at = [x, y, z], rotation = ball_q),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
    speeds(w1 = ball.omega_1, w2 = ball.omega_2, w3 = ball.omega_3),
    formulation(multipliers, reduced),
)]
struct SpinningBall {
    m: f64,
    j1: f64,
    j2: f64,
    j3: f64,
    a: f64,
    g: f64,
}

/// The sphere in the reduced form alone, on the centre's velocity and the
/// spin about the vertical (world axes: regular at every orientation), so
/// that `Simulation::run` takes this form.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(ball_q),
    body(ball, mass = m, inertia = [j1, j2, j3], at = [x, y, z], rotation = ball_q),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
    speeds(u = dot(x), v = dot(y), spin = ball.omega_z),
)]
struct GlidingBall {
    m: f64,
    j1: f64,
    j2: f64,
    j3: f64,
    a: f64,
    g: f64,
}

/// The sphere with speeds the macro picks (`formulation(reduced)` alone).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(ball_q),
    body(ball, mass = m, inertia = [j1, j2, j3], at = [x, y, z], rotation = ball_q),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
    formulation(reduced),
)]
struct PickedBall {
    m: f64,
    j1: f64,
    j2: f64,
    j3: f64,
    a: f64,
    g: f64,
}

/// `QuaternionDisk` in both forms, the reduced one on the body-axis angular
/// velocities (the rows give the centre's velocity from them).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(disk_q),
    body(disk, mass = m, inertia = [b, c, b], at = [x, y, z], rotation = disk_q),
    gravity = [0, 0, -g],
    define(nz = disk.axis_y.z,
           s = sqrt(1 - pow(nz, 2)),
           ux = -nz * disk.axis_y.x / s,
           uy = -nz * disk.axis_y.y / s),
    holonomic(height = disk.z - a * s),
    nonholonomic(
        roll_x = dot(disk.x) - a * (disk.omega_y * s - disk.omega_z * uy),
        roll_y = dot(disk.y) - a * (disk.omega_z * ux - disk.omega_x * s)
    ),
    speeds(w1 = disk.omega_1, w2 = disk.omega_2, w3 = disk.omega_3),
    formulation(multipliers, reduced),
)]
struct SpinningDisk {
    m: f64,
    a: f64,
    b: f64,
    c: f64,
    g: f64,
}

const SPINNING: SpinningBall = SpinningBall {
    m: BALL.m,
    j1: BALL.j1,
    j2: BALL.j2,
    j3: BALL.j3,
    a: BALL.a,
    g: BALL.g,
};
const GLIDING: GlidingBall = GlidingBall {
    m: BALL.m,
    j1: BALL.j1,
    j2: BALL.j2,
    j3: BALL.j3,
    a: BALL.a,
    g: BALL.g,
};
const PICKED: PickedBall = PickedBall {
    m: BALL.m,
    j1: BALL.j1,
    j2: BALL.j2,
    j3: BALL.j3,
    a: BALL.a,
    g: BALL.g,
};

fn thin_disk(m: f64, a: f64, g: f64) -> SpinningDisk {
    SpinningDisk {
        m,
        a,
        b: m * a * a / 4.0,
        c: m * a * a / 2.0,
        g,
    }
}

/// Largest |a − b| relative to 1 + |b|.
fn gap<const M: usize>(a: &SVector<f64, M>, b: &SVector<f64, M>) -> f64 {
    (a - b).amax() / (1.0 + b.amax())
}

/// The velocity rows' residuals [max |Φ|, max |G v + g|] of a
/// multiplier-form twin along a trajectory.
fn residuals<S: Constrained<f64, 6, 3, 7>>(
    sys: &S,
    positions: &[SVector<f64, 7>],
    velocities: &[SVector<f64, 6>],
) -> [f64; 2] {
    let mut worst = [0.0f64; 2];
    for (q, v) in positions.iter().zip(velocities) {
        let (g, g0) = sys.constraint_jacobian(q, 0.0);
        let phi = sys.constraint_positions(q, 0.0);
        worst[0] = worst[0].max(phi.fixed_rows::<1>(0).amax());
        worst[1] = worst[1].max((g * v + g0).amax());
    }
    worst
}

#[test]
fn the_speeds_are_named_as_written_or_picked() {
    assert_eq!(SpinningBall::SPEEDS, ["w1", "w2", "w3"]);
    assert_eq!(GlidingBall::SPEEDS, ["u", "v", "spin"]);
    assert_eq!(
        SpinningBall::ROWS,
        ["w1", "w2", "w3", "height", "slip_x", "slip_y"]
    );
    // The rolling rows fix x and y; height fixes z: the angular velocities
    // are left, named as `VELOCITIES` names them.
    assert_eq!(PickedBall::SPEEDS, ["ball_q_wx", "ball_q_wy", "ball_q_wz"]);
    assert_eq!(PickedBall::HOLONOMIC, 1);
}

/// At states of the chart sphere, lifted to the quaternion: the reduced
/// form's v̇ on either set of speeds against the chart's and the multiplier
/// form's, and its speed rates against the speeds' own rates.
#[test]
fn the_reduced_quaternion_sphere_accelerates_as_the_other_forms() {
    let mut rng = Lcg(7);
    let (mut chart_gap, mut form_gap, mut rate_gap) = (0.0f64, 0.0f64, 0.0f64);
    for _ in 0..20 {
        let (q, v) = ball_start(&CHART_BALL, &mut rng, BALL.a, (0.3, 2.8));
        let c = ConstrainedDynamics::new(&CHART_BALL)
            .solve(0.0, &q, &v)
            .unwrap();
        let (qq, vq, want) = ball_state(&q, &v, &c.accelerations);
        let (du, a) = ReducedDynamics::new(&SPINNING)
            .solve(0.0, &qq, &vq)
            .unwrap();
        let (_, glide) = ReducedDynamics::new(&GLIDING).solve(0.0, &qq, &vq).unwrap();
        let (_, picked) = ReducedDynamics::new(&PICKED).solve(0.0, &qq, &vq).unwrap();
        let m = ConstrainedDynamics::new(&SPINNING)
            .solve(0.0, &qq, &vq)
            .unwrap();
        chart_gap = chart_gap.max(gap(&a, &want)).max(gap(&glide, &want));
        chart_gap = chart_gap.max(gap(&picked, &want));
        form_gap = form_gap.max(gap(&a, &m.accelerations));
        // The speeds are ω in body axes: their rates are v̇'s last three.
        let rates = SVector::from([want[3], want[4], want[5]]);
        rate_gap = rate_gap.max(gap(&du, &rates));
    }
    eprintln!(
        "sphere, reduced form: v̇ against the chart {chart_gap:e}, against the multipliers \
         {form_gap:e}, u̇ against ω̇ {rate_gap:e}"
    );
    assert!(chart_gap < 1e-10 && form_gap < 1e-12 && rate_gap < 1e-10);
}

#[test]
fn the_reduced_quaternion_disk_accelerates_as_the_other_forms() {
    let chart = RollingDisk::thin(1.2, 0.4, 9.81);
    let disk = thin_disk(1.2, 0.4, 9.81);
    let pi = std::f64::consts::PI;
    let mut rng = Lcg(19);
    let (mut chart_gap, mut form_gap) = (0.0f64, 0.0f64);
    for _ in 0..20 {
        let q = SVector::from([
            rng.next(),
            rng.next(),
            uniform(&mut rng, -pi, pi),
            uniform(&mut rng, -1.2, 1.2),
            uniform(&mut rng, -pi, pi),
        ]);
        let (q, v) = project_consistent(&chart, q, rng.vector::<5>(4.0), 0.0).unwrap();
        let c = ConstrainedDynamics::new(&chart).solve(0.0, &q, &v).unwrap();
        let (qq, vq, want) = disk_state(&chart, &q, &v, &c.accelerations);
        let (_, a) = ReducedDynamics::new(&disk).solve(0.0, &qq, &vq).unwrap();
        let m = ConstrainedDynamics::new(&disk)
            .solve(0.0, &qq, &vq)
            .unwrap();
        chart_gap = chart_gap.max(gap(&a, &want));
        form_gap = form_gap.max(gap(&a, &m.accelerations));
    }
    eprintln!(
        "disk, reduced form: v̇ against the chart {chart_gap:e}, against the multipliers \
         {form_gap:e}"
    );
    assert!(chart_gap < 1e-10 && form_gap < 1e-12);
}

/// Over three seconds the reduced sphere follows the chart sphere and the
/// multiplier form to the integrator's tolerance, its velocity rows at
/// round-off, its energy kept.
#[test]
fn the_reduced_quaternion_sphere_follows_the_other_forms_over_seconds() {
    let mut rng = Lcg(23);
    let (q, v) = ball_start(&CHART_BALL, &mut rng, BALL.a, (0.8, 2.3));
    let (qq, vq, _) = ball_state(&q, &v, &SVector::zeros());
    let chart = Simulation::new(&CHART_BALL)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(q, v, 0.0..3.0)
        .unwrap();
    let sim = Simulation::new(&SPINNING).integrator(Dopri5::tol(TOL));
    let multipliers = sim
        .drift(Drift::projection())
        .run(qq, vq, 0.0..3.0)
        .unwrap();
    let reduced = Simulation::new(&SPINNING)
        .integrator(Dopri5::tol(TOL))
        .run_reduced(qq, vq, 0.0..3.0)
        .unwrap();
    // The reduced form alone: `run` takes it.
    let gliding = Simulation::new(&GLIDING)
        .integrator(Dopri5::tol(TOL))
        .run(qq, vq, 0.0..3.0)
        .unwrap();
    let (qc, vc) = chart.final_state();
    let (qc, vc, _) = ball_state(&qc, &vc, &SVector::zeros());
    let (qm, vm) = multipliers.final_state();
    let (qr, vr) = reduced.final_state();
    let (qg, vg) = gliding.final_state();
    let to_chart = quaternion_gap(&qr, &qc).max((vr - vc).amax());
    let to_multipliers = quaternion_gap(&qr, &qm).max((vr - vm).amax());
    let between_speeds = quaternion_gap(&qr, &qg).max((vr - vg).amax());
    let [phi, vel] = residuals(&SPINNING, reduced.positions(), reduced.velocities());
    let [phi_g, vel_g] = residuals(&SPINNING, gliding.positions(), gliding.velocities());
    eprintln!(
        "reduced sphere over 3 s: gap to the chart {to_chart:e}, to the multipliers \
         {to_multipliers:e}, between the speeds {between_speeds:e}; residuals {phi:e} {vel:e} \
         ({phi_g:e} {vel_g:e} on u, v, spin); energy drift {:e} ({:e}); unit error {:e}",
        reduced.integral_drift(),
        gliding.integral_drift(),
        reduced.max_unit_error()
    );
    assert!(to_chart < 1e-7 && to_multipliers < 1e-7 && between_speeds < 1e-7);
    assert!(phi <= 1e-12 && vel <= 1e-12 && phi_g <= 1e-12 && vel_g <= 1e-12);
    assert!(reduced.integral_drift() < 1e-8 && gliding.integral_drift() < 1e-8);
}

/// The disk rolling and wobbling, in the reduced form, against the chart
/// disk and the multiplier form.
#[test]
fn the_reduced_quaternion_disk_follows_the_other_forms_over_seconds() {
    let chart = RollingDisk::thin(1.2, 0.4, 9.81);
    let disk = thin_disk(1.2, 0.4, 9.81);
    let ((q, v), (qq, vq)) = wobbling_start(&chart);
    let c = Simulation::new(&chart)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(q, v, 0.0..3.0)
        .unwrap();
    let m = Simulation::new(&disk)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(qq, vq, 0.0..3.0)
        .unwrap();
    let r = Simulation::new(&disk)
        .integrator(Dopri5::tol(TOL))
        .run_reduced(qq, vq, 0.0..3.0)
        .unwrap();
    let (qc, vc) = c.final_state();
    let (qc, vc, _) = disk_state(&chart, &qc, &vc, &SVector::zeros());
    let (qm, vm) = m.final_state();
    let (qr, vr) = r.final_state();
    let to_chart = quaternion_gap(&qr, &qc).max((vr - vc).amax());
    let to_multipliers = quaternion_gap(&qr, &qm).max((vr - vm).amax());
    let [phi, vel] = residuals(&disk, r.positions(), r.velocities());
    eprintln!(
        "reduced disk over 3 s: gap to the chart {to_chart:e}, to the multipliers \
         {to_multipliers:e}; residuals {phi:e} {vel:e}; energy drift {:e}",
        r.integral_drift()
    );
    assert!(to_chart < 1e-7 && to_multipliers < 1e-7);
    // The height row is kept at the velocity level only (the reduced form
    // projects no positions): Φ drifts at the integrator's tolerance.
    assert!(phi <= 1e-9 && vel <= 1e-12, "{phi:e} {vel:e}");
    assert!(r.integral_drift() < 1e-8);
}

/// Started with its z axis vertical, where euler_zxz stops, the reduced
/// sphere rolls on as the multiplier form does: energy and the angular
/// momentum about the contact point stay, and so do the velocity rows.
#[test]
fn the_reduced_quaternion_sphere_rolls_through_the_chart_s_singular_state() {
    let w = [1.5, -0.7, 4.0];
    let q0 = SVector::from([0.0, 0.0, BALL.a, 1.0, 0.0, 0.0, 0.0]);
    let v0 = SVector::from([BALL.a * w[1], -BALL.a * w[0], 0.0, w[0], w[1], w[2]]);
    let r = Simulation::new(&SPINNING)
        .integrator(Dopri5::tol(TOL))
        .run_reduced(q0, v0, 0.0..5.0)
        .unwrap();
    let m = Simulation::new(&SPINNING)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(q0, v0, 0.0..5.0)
        .unwrap();
    let k0 = contact_momentum(&BALL, &q0, &v0);
    let drift = r
        .positions()
        .iter()
        .zip(r.velocities())
        .map(|(q, v)| (contact_momentum(&BALL, q, v) - k0).amax())
        .fold(0.0, f64::max);
    let (qr, vr) = r.final_state();
    let (qm, vm) = m.final_state();
    let to_multipliers = quaternion_gap(&qr, &qm).max((vr - vm).amax());
    let [phi, vel] = residuals(&SPINNING, r.positions(), r.velocities());
    eprintln!(
        "reduced sphere from θ = 0 over 5 s: momentum drift {drift:e} (of {:.3}), energy drift \
         {:e}, gap to the multipliers {to_multipliers:e}, residuals {phi:e} {vel:e}, unit error {:e}",
        k0.amax(),
        r.integral_drift(),
        r.max_unit_error()
    );
    assert!(drift < 1e-8 * k0.amax(), "{drift:e}");
    assert!(r.integral_drift() < 1e-8);
    assert!(to_multipliers < 1e-7, "{to_multipliers:e}");
    assert!(phi <= 1e-12 && vel <= 1e-12, "{phi:e} {vel:e}");
}

/// A bad state is a typed error, not a panic or NaN.
#[test]
fn a_non_finite_state_is_refused() {
    let q = SVector::from([0.0, 0.0, BALL.a, f64::NAN, 0.0, 0.0, 0.0]);
    let v = SVector::<f64, 6>::zeros();
    let e = ReducedDynamics::new(&SPINNING).solve(0.0, &q, &v);
    assert!(matches!(e, Err(Error::NonFiniteState { .. })), "{e:?}");
    let run = Simulation::new(&SPINNING).run_reduced(q, v, 0.0..1.0);
    assert!(run.is_err());
}

/// Events watch a reduced run with orientations as they watch the
/// multiplier form's: the ball's body z axis crossing 26° from the vertical
/// (cos = 0.9; it tips to 41°) is located at the same times.
#[test]
fn events_watch_the_reduced_form_with_orientations() {
    let w = [1.5, -0.7, 4.0];
    let q0 = SVector::from([0.0, 0.0, BALL.a, 1.0, 0.0, 0.0, 0.0]);
    let v0 = SVector::from([BALL.a * w[1], -BALL.a * w[0], 0.0, w[0], w[1], w[2]]);
    const LEVEL: f64 = 0.9;
    let tilt = |_: f64, q: &SVector<f64, 7>, _: &SVector<f64, 6>| rotation_of(q)[(2, 2)] - LEVEL;
    let reduced = Simulation::new(&SPINNING)
        .integrator(Dopri5::tol(TOL))
        .event(Event::new(tilt))
        .run_reduced(q0, v0, 0.0..5.0)
        .unwrap();
    let multipliers = Simulation::new(&SPINNING)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .event(Event::new(tilt))
        .run(q0, v0, 0.0..5.0)
        .unwrap();
    let times = |r: &EventRun<f64, 6, 7>| r.occurrences.iter().map(|o| o.t).collect::<Vec<_>>();
    let (a, b) = (times(&reduced), times(&multipliers));
    assert!(!a.is_empty() && a.len() == b.len(), "{a:?} {b:?}");
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "events on the reduced sphere: {} crossings, largest time gap to the multipliers {worst:e}",
        a.len()
    );
    assert!(worst < 1e-8, "{worst:e}");
}

/// The sphere pushed at its centre by an input force along x, in both forms.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(ball_q),
    inputs(push),
    body(ball, mass = m, inertia = [j1, j2, j3], at = [x, y, z], rotation = ball_q),
    point(centre, on = ball, at = [0, 0, 0]),
    force(centre, [push, 0, 0]),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
    speeds(w1 = ball.omega_1, w2 = ball.omega_2, w3 = ball.omega_3),
    formulation(multipliers, reduced),
)]
struct PushedBall {
    m: f64,
    j1: f64,
    j2: f64,
    j3: f64,
    a: f64,
    g: f64,
}

/// `BALL` with its push.
fn pushed_ball() -> PushedBall {
    PushedBall {
        m: BALL.m,
        j1: BALL.j1,
        j2: BALL.j2,
        j3: BALL.j3,
        a: BALL.a,
        g: BALL.g,
    }
}

/// A controlled run takes the reduced form with orientations: the pushed
/// sphere follows its multiplier form under the same open-loop force.
#[test]
fn a_controlled_run_takes_the_reduced_form_with_orientations() {
    let ball = pushed_ball();
    let q0 = SVector::from([0.0, 0.0, BALL.a, 0.5, 0.5, 0.5, 0.5]);
    let v0 = SVector::from([0.0, 0.0, 0.0, 0.3, -0.2, 2.0]);
    let v0 = ReducedDynamics::new(&ball)
        .consistent_velocities(0.0, &q0, &v0)
        .unwrap();
    let push = |t: f64| [(2.0 * t).sin()];
    let reduced = Simulation::new(&ball)
        .integrator(Dopri5::tol(TOL))
        .open_loop(push)
        .run_reduced(q0, v0, 0.0..3.0)
        .unwrap();
    let multipliers = Simulation::new(&ball)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .open_loop(push)
        .run(q0, v0, 0.0..3.0)
        .unwrap();
    let (qr, vr) = reduced.trajectory().final_state();
    let (qm, vm) = multipliers.trajectory().final_state();
    let gap = quaternion_gap(&qr, &qm).max((vr - vm).amax());
    eprintln!("pushed sphere over 3 s: gap between the forms {gap:e}");
    assert!(gap < 1e-7, "{gap:e}");
    assert!(vr[0].abs() > 1e-3, "the push moved it: {vr:?}");
}

/// The disk rolling upright along x at spin ω about its axle (body y, here
/// world y): centre (0, 0, a), identity orientation.
fn upright(disk: &SpinningDisk, spin: f64) -> OperatingPoint<f64, 6, 0, 7> {
    OperatingPoint::on_group(
        SVector::from([0.0, 0.0, disk.a, 1.0, 0.0, 0.0, 0.0]),
        SVector::from([disk.a * spin, 0.0, 0.0, 0.0, spin, 0.0]),
    )
}

/// The disk's states: its position on the floor, its turn, its spin rates.
fn disk_linearizer() -> Linearizer {
    Linearizer::new()
        .coordinates(&["x", "y", "disk_q.θx", "disk_q.θy", "disk_q.θz"])
        .speeds(&["disk_q.wx", "disk_q.wy", "disk_q.wz"])
}

/// `Linearizer::reduced_tangent` reads the model of the multiplier form's
/// `constrained_tangent` from the reduced form's dynamics: the upright
/// rolling disk's A at four spins, the critical spin √(g/3a) from a sweep
/// of the reduced form, and the pushed sphere's B.
#[test]
fn the_reduced_form_linearises_on_the_group_as_the_multiplier_form() {
    let disk = thin_disk(1.0, 0.3, 9.81);
    for spin in [0.5, 2.0, 3.0, 6.0] {
        let op = upright(&disk, spin);
        let reduced = disk_linearizer().reduced_tangent(&disk, &op).unwrap();
        let multipliers = disk_linearizer().constrained_tangent(&disk, &op).unwrap();
        assert_eq!(reduced.states(), multipliers.states());
        let gap = (reduced.a() - multipliers.a()).amax();
        eprintln!("upright disk at spin {spin}: A of the two forms within {gap:.1e}");
        assert!(gap < 1e-12 * multipliers.a().amax(), "{gap:e}");
    }
    let exact = (disk.g / (3.0 * disk.a)).sqrt();
    let spins: Vec<f64> = (1..=20).map(|i| 0.5 * i as f64).collect();
    let linear = |w: f64| disk_linearizer().reduced_tangent(&disk, &upright(&disk, w));
    let found = sweep(&spins, linear)
        .unwrap()
        .boundaries(1e-4, 1e-14)
        .unwrap();
    assert_eq!(found.len(), 1, "{found:?}");
    let rel = (found[0].parameter - exact).abs() / exact;
    eprintln!(
        "reduced disk: critical spin {:.10}, √(g/3a) {exact:.10}",
        found[0].parameter
    );
    assert!(rel < 1e-7, "{rel:e}");

    let ball = pushed_ball();
    let q0 = SVector::from([0.2, -0.1, BALL.a, 0.5, 0.5, 0.5, 0.5]);
    let v0 = SVector::from([0.0, 0.0, 0.0, 0.3, -0.2, 2.0]);
    let v0 = ReducedDynamics::new(&ball)
        .consistent_velocities(0.0, &q0, &v0)
        .unwrap();
    let op = OperatingPoint::on_group(q0, v0).input(SVector::from([0.0]));
    let lz = Linearizer::new();
    let reduced = lz.reduced_tangent(&ball, &op).unwrap();
    let multipliers = lz.constrained_tangent(&ball, &op).unwrap();
    assert_eq!(reduced.states(), multipliers.states());
    let gaps = [
        (reduced.a() - multipliers.a()).amax(),
        (reduced.b() - multipliers.b()).amax(),
    ];
    eprintln!("pushed sphere: A and B of the two forms within {gaps:?}");
    // Two computations that round differently: B agreed to the bit while the
    // Cholesky solves divided by L_ii (and A to 2e-12); multiplying by 1/L_ii,
    // 9e-12 and 1.1e-12, with B's entries of order one.
    assert!(gaps[0] < 1e-10 && gaps[1] < 1e-11, "{gaps:?}");
    assert!(reduced.b().amax() > 0.1, "the push acts: {}", reduced.b());
}

/// An operating point off the constraints or off the unit sphere is a typed
/// error naming what is wrong.
#[test]
fn the_reduced_linearisation_refuses_a_bad_operating_point() {
    let disk = thin_disk(1.0, 0.3, 9.81);
    let mut op = upright(&disk, 2.0);
    op.v[0] += 0.1;
    match Linearizer::new().reduced_tangent(&disk, &op) {
        Err(Error::Linear(lagrange::LinearError::InconsistentOperatingPoint {
            worst,
            velocity_residual,
            ..
        })) => {
            assert!(worst.contains("roll_x"), "{worst}");
            assert!((velocity_residual - 0.1).abs() < 1e-12);
        }
        other => panic!("{other:?}"),
    }
    let off = OperatingPoint::on_group(
        SVector::from([0.0, 0.0, disk.a, 2.0, 0.0, 0.0, 0.0]),
        SVector::from([0.6, 0.0, 0.0, 0.0, 2.0, 0.0]),
    );
    let result = Linearizer::new().reduced_tangent(&disk, &off);
    assert!(
        matches!(result, Err(Error::NonUnitQuaternion { .. })),
        "{result:?}"
    );
}
