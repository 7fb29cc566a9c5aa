//! Constraints with free orientations (multiplier form): the rolling sphere
//! and the rolling disk with a quaternion against the same bodies in Euler
//! angles where those charts are regular, then the sphere through the state
//! where euler_zxz stops (its z axis vertical), with its conserved energy
//! and angular momentum about the contact point.

use crate::catalog;
use crate::common;
use crate::rolling;

use catalog::constrained::{RollingDisk, RollingSphere};
use catalog::rolling::{QuaternionDisk, QuaternionSphere};
use common::numeric::Lcg;
use lagrange::prelude::*;
use lagrange::{check_consistency, project_consistent};
use nalgebra::SVector;
use rolling::*;

const TOL: f64 = 1e-11;

/// Accelerations and multipliers of the quaternion sphere against a chart
/// sphere at `count` states where euler_zxz is regular.
fn compare_balls<S: Constrained<f64, 6, 3>>(ball: &QuaternionSphere, chart: &S, seed: u64) -> f64 {
    let mut rng = Lcg(seed);
    let mut worst: f64 = 0.0;
    for _ in 0..20 {
        let (q, v) = ball_start(chart, &mut rng, ball.a, (0.3, 2.8));
        let c = ConstrainedDynamics::new(chart).solve(0.0, &q, &v).unwrap();
        let (qq, vq, want) = ball_state(&q, &v, &c.accelerations);
        check_consistency(ball, &qq, &vq, 0.0, 1e-12).unwrap();
        let s = ConstrainedDynamics::new(ball).solve(0.0, &qq, &vq).unwrap();
        assert_close("sphere accelerations", &s.accelerations, &want, 1e-10);
        assert_close("sphere multipliers", &s.multipliers, &c.multipliers, 1e-10);
        let scale = 1.0 + want.amax();
        worst = worst.max((s.accelerations - want).amax() / scale);
        worst = worst.max((s.multipliers - c.multipliers).amax() / (1.0 + c.multipliers.amax()));
    }
    worst
}

#[test]
fn the_quaternion_sphere_rolls_as_the_euler_angle_sphere() {
    let worst = compare_balls(&BALL, &CHART_BALL, 3);
    let j = 0.4 * 1.3 * 0.7 * 0.7;
    let (iso, chart) = (
        QuaternionSphere {
            j1: j,
            j2: j,
            j3: j,
            ..BALL
        },
        RollingSphere {
            m: 1.3,
            j,
            a: 0.7,
            g: 9.81,
        },
    );
    let worst = worst.max(compare_balls(&iso, &chart, 5));
    eprintln!("sphere: largest relative gap in v̇ and ν {worst:e}");
}

/// At rest the contact carries the weight, and the reactions on the ball
/// are the multipliers (each row is one component of the contact point's
/// position or velocity).
#[test]
fn the_resting_quaternion_sphere_carries_its_weight() {
    let q = SVector::from([0.1, 0.2, BALL.a, 0.5, 0.5, 0.5, 0.5]);
    let v = SVector::zeros();
    let s = ConstrainedDynamics::new(&BALL).solve(0.0, &q, &v).unwrap();
    assert!(s.accelerations.amax() < 1e-14);
    let weight = BALL.m * BALL.g;
    assert_close(
        "multipliers",
        &s.multipliers,
        &SVector::from([weight, 0.0, 0.0]),
        1e-14,
    );
    let [r] = BALL.reactions(&q, &v, 0.0, &s.multipliers);
    assert_close("reaction", &r, &SVector::from([0.0, 0.0, weight]), 1e-14);
    assert_eq!(QuaternionSphere::REACTION_POINTS, ["ball"]);
}

#[test]
fn the_quaternion_disk_rolls_as_the_euler_angle_disk() {
    let chart = RollingDisk::thin(1.2, 0.4, 9.81);
    let disk = QuaternionDisk::thin(1.2, 0.4, 9.81);
    let pi = std::f64::consts::PI;
    let mut rng = Lcg(17);
    let mut worst: f64 = 0.0;
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
        check_consistency(&disk, &qq, &vq, 0.0, 1e-12).unwrap();
        let s = ConstrainedDynamics::new(&disk)
            .solve(0.0, &qq, &vq)
            .unwrap();
        assert_close("disk accelerations", &s.accelerations, &want, 1e-10);
        // The rolling rows' multipliers are the contact force's horizontal
        // components in both; the height row's is its normal one, m (z̈ + g).
        let nu = &s.multipliers;
        let rolling = SVector::from([nu[1], nu[2]]);
        assert_close("rolling multipliers", &rolling, &c.multipliers, 1e-10);
        let normal = chart.m * (want[2] + chart.g);
        assert!((nu[0] - normal).abs() < 1e-10 * (1.0 + normal.abs()));
        worst = worst.max((s.accelerations - want).amax() / (1.0 + want.amax()));
        worst = worst.max((rolling - c.multipliers).amax() / (1.0 + c.multipliers.amax()));
    }
    eprintln!("disk: largest relative gap in v̇ and ν {worst:e}");
}

/// Over three seconds the sphere in a quaternion follows the sphere in
/// Euler angles (started where that chart is regular) to the integrators'
/// tolerance, on its constraints to round-off.
#[test]
fn the_quaternion_sphere_follows_the_chart_sphere_over_seconds() {
    let mut rng = Lcg(23);
    let (q, v) = ball_start(&CHART_BALL, &mut rng, BALL.a, (0.8, 2.3));
    let (qq, vq, _) = ball_state(&q, &v, &SVector::zeros());
    let chart = Simulation::new(&CHART_BALL)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(q, v, 0.0..3.0)
        .unwrap();
    let quat = Simulation::new(&BALL)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(qq, vq, 0.0..3.0)
        .unwrap();
    let (qc, vc) = chart.final_state();
    let (qc, vc, _) = ball_state(&qc, &vc, &SVector::zeros());
    let (qf, vf) = quat.final_state();
    let (gap, speed_gap) = (quaternion_gap(&qf, &qc), (vf - vc).amax());
    let [phi, vel] = quat.max_residuals();
    eprintln!(
        "sphere over 3 s: state gap {gap:e}, velocity gap {speed_gap:e}, residuals {phi:e} {vel:e}, \
         energy drift {:e}, unit error {:e}",
        quat.integral_drift(),
        quat.max_unit_error()
    );
    assert!(gap < 1e-7 && speed_gap < 1e-7, "{gap:e} {speed_gap:e}");
    assert!(phi <= 1e-12 && vel <= 1e-12, "{phi:e} {vel:e}");
    assert!(quat.integral_drift() < 1e-8);
}

/// The same for the disk, rolling and wobbling (the tilt stays inside the
/// chart's regular set, which is where the disk has a contact point).
#[test]
fn the_quaternion_disk_follows_the_chart_disk_over_seconds() {
    let chart = RollingDisk::thin(1.2, 0.4, 9.81);
    let disk = QuaternionDisk::thin(1.2, 0.4, 9.81);
    let ((q, v), (qq, vq)) = wobbling_start(&chart);
    let c = Simulation::new(&chart)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(q, v, 0.0..3.0)
        .unwrap();
    let d = Simulation::new(&disk)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(qq, vq, 0.0..3.0)
        .unwrap();
    let (qc, vc) = c.final_state();
    let (qc, vc, _) = disk_state(&chart, &qc, &vc, &SVector::zeros());
    let (qf, vf) = d.final_state();
    let (gap, speed_gap) = (quaternion_gap(&qf, &qc), (vf - vc).amax());
    let [phi, vel] = d.max_residuals();
    eprintln!(
        "disk over 3 s: state gap {gap:e}, velocity gap {speed_gap:e}, residuals {phi:e} {vel:e}, \
         energy drift {:e}",
        d.integral_drift()
    );
    assert!(gap < 1e-7 && speed_gap < 1e-7, "{gap:e} {speed_gap:e}");
    assert!(phi <= 1e-12 && vel <= 1e-12, "{phi:e} {vel:e}");
    assert!(d.integral_drift() < 1e-8);
}

/// Started with its z axis vertical, where euler_zxz stops (θ = 0, which
/// the chart sphere refuses), the quaternion sphere rolls on: energy and the
/// angular momentum about the contact point stay, and so do the constraints.
#[test]
fn the_quaternion_sphere_rolls_through_the_chart_s_singular_state() {
    let w = [1.5, -0.7, 4.0];
    let q0 = SVector::from([0.0, 0.0, BALL.a, 1.0, 0.0, 0.0, 0.0]);
    // Body axes are world axes here: the centre moves as ω × (a e_z).
    let v0 = SVector::from([BALL.a * w[1], -BALL.a * w[0], 0.0, w[0], w[1], w[2]]);
    let traj = Simulation::new(&BALL)
        .integrator(Dopri5::tol(TOL))
        .drift(Drift::projection())
        .run(q0, v0, 0.0..5.0)
        .unwrap();
    let k0 = contact_momentum(&BALL, &q0, &v0);
    let drift = traj
        .positions()
        .iter()
        .zip(traj.velocities())
        .map(|(q, v)| (contact_momentum(&BALL, q, v) - k0).amax())
        .fold(0.0, f64::max);
    let [phi, vel] = traj.max_residuals();
    eprintln!(
        "sphere from θ = 0 over 5 s: momentum drift {drift:e} (of {:.3}), energy drift {:e}, \
         residuals {phi:e} {vel:e}",
        k0.amax(),
        traj.integral_drift()
    );
    assert!(drift < 1e-8 * k0.amax(), "{drift:e}");
    assert!(traj.integral_drift() < 1e-8);
    assert!(phi <= 1e-12 && vel <= 1e-12, "{phi:e} {vel:e}");
    let chart_q = SVector::from([0.0, 0.0, BALL.a, 0.0, 0.0, 0.0]);
    let chart_v = SVector::from([v0[0], v0[1], 0.0, 0.0, 0.0, w[2]]);
    assert!(
        Simulation::new(&CHART_BALL)
            .run(chart_q, chart_v, 0.0..1.0)
            .is_err()
    );
}
