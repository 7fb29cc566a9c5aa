//! The atlas (`emit(atlas)`, `Simulation::run_atlas`): a system written in
//! Euler angles runs through its chart's singular set by switching to the
//! second chart, against the same system with a quaternion.

#[allow(dead_code)]
#[path = "../examples/catalog/mod.rs"]
mod catalog;

use catalog::free::{EulerTop, QuaternionTop};
use lagrange::numeric::euler::EulerChart;
use lagrange::numeric::orientation::rotation_matrix;
use lagrange::prelude::*;
use nalgebra::{Matrix3, Vector3};

const EULER_TOP: EulerTop = EulerTop {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};
const TOP: QuaternionTop = QuaternionTop {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};

fn matrix(q: &[f64]) -> Matrix3<f64> {
    let r = rotation_matrix([q[0], q[1], q[2], q[3]]);
    Matrix3::from_fn(|i, j| r[i][j])
}

/// Started exactly upright (θ = 0, where z-x-z is singular) with a nudge
/// across, the atlas top and the quaternion top move alike.
#[test]
fn the_upright_top_in_euler_angles_matches_the_quaternion_top() {
    let (spin, nudge) = (30.0, 0.3);
    let sim = Simulation::new(&EULER_TOP).integrator(Dopri5::tol(1e-11));
    let run = sim
        .run_atlas([0.0, 0.0, 0.0], [0.0, nudge, spin], 0.0..3.0)
        .unwrap();
    let reference = Simulation::new(&TOP)
        .integrator(Dopri5::tol(1e-11))
        .run([1.0, 0.0, 0.0, 0.0], [nudge, 0.0, spin], 0.0..3.0)
        .unwrap();
    // It starts in the second chart and, sleeping, stays there.
    assert_eq!(run.charts()[0], 1);
    let traj = run.trajectory();
    let mut worst: f64 = 0.0;
    for (i, &t) in traj.times().iter().enumerate() {
        let (q, _) = reference.state_at(t).unwrap();
        worst = worst.max((run.rotation(i, 0) - matrix(q.as_slice())).abs().max());
    }
    assert!(worst < 1e-7, "{worst:e}");
    assert!(traj.integral_drift() < 1e-8, "{:e}", traj.integral_drift());
    // The user's own run refuses that start.
    assert!(
        sim.run([0.0, 0.0, 0.0], [0.0, nudge, spin], 0.0..3.0)
            .is_err()
    );
}

/// The quaternion of the z-x-z angles (ψ, θ, φ).
fn zxz_quaternion([psi, theta, phi]: [f64; 3]) -> [f64; 4] {
    let r = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), psi)
        * nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), theta)
        * nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), phi);
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&r);
    [q.w, q.i, q.j, q.k]
}

/// A slow top swung over the top through the upright, again and again:
/// each pass leaves the user's chart and comes back, and the motion matches
/// the quaternion top's.
#[test]
fn a_top_swung_through_the_upright_switches_charts_and_back() {
    let q0 = [0.2, 0.6, -0.4];
    let v0 = [0.0, -6.0, 2.0];
    let sim = Simulation::new(&EULER_TOP).integrator(Dopri5::tol(1e-11));
    let run = sim.run_atlas(q0, v0, 0.0..4.0).unwrap();
    let omega0 = EulerChart::new([2, 0, 2]).unwrap().rates(q0) * Vector3::from(v0);
    let reference = Simulation::new(&TOP)
        .integrator(Dopri5::tol(1e-11))
        .run(
            zxz_quaternion(q0),
            [omega0[0], omega0[1], omega0[2]],
            0.0..4.0,
        )
        .unwrap();
    let traj = run.trajectory();
    let mut worst: f64 = 0.0;
    for (i, &t) in traj.times().iter().enumerate() {
        let (q, _) = reference.state_at(t).unwrap();
        worst = worst.max((run.rotation(i, 0) - matrix(q.as_slice())).abs().max());
    }
    let switches = run.switches();
    eprintln!(
        "{} switches, worst {worst:e}, drift {:e}",
        switches.len(),
        traj.integral_drift()
    );
    assert!(switches.len() >= 4, "{switches:?}");
    assert!(
        switches
            .iter()
            .zip(switches.iter().skip(1))
            .all(|(a, b)| a.to_second != b.to_second)
    );
    assert!(worst < 1e-7, "{worst:e}");
    assert!(traj.integral_drift() < 1e-8, "{:e}", traj.integral_drift());
    // Back in the user's chart the user's angles read as the chart holds them.
    let charts = run.charts();
    let last = traj.len() - 1;
    if charts[last] == 0 {
        let (q, _) = run.user_state(last).unwrap();
        assert!((q - traj.positions()[last]).abs().max() < 1e-12);
    }
}
