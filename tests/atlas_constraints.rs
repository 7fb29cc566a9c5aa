//! Holonomic constraints with the atlas: a top written as a free body (its
//! centre and its z-x-z angles) whose tip is held at the origin by three
//! holonomic rows that read the rotation, swung through the upright; the
//! twin carries the same rows on its quaternion. Against the quaternion top
//! on a fixed pivot (`catalog::free::QuaternionTop`).

#[path = "../examples/catalog/mod.rs"]
mod catalog;

use catalog::free::QuaternionTop;
use lagrange::numeric::euler::EulerChart;
use lagrange::numeric::orientation::rotation_matrix;
use lagrange::prelude::*;
use nalgebra::{Matrix3, Vector3};

/// The heavy top as a free body on a pivot: the centre of mass (x, y, z),
/// z-x-z angles, the tip a distance l down the axis held at the origin.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(top, mass = m, inertia = [a - m * l * l, a - m * l * l, c], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    point(tip, on = top, at = [0, 0, -l]),
    holonomic(pin_x = tip.x, pin_y = tip.y, pin_z = tip.z),
    gravity = [0, 0, -g],
    emit(atlas),
)]
struct PinnedTop {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

const PINNED: PinnedTop = PinnedTop {
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

fn zxz() -> EulerChart {
    EulerChart::new([2, 0, 2]).unwrap()
}

fn matrix(q: &[f64]) -> Matrix3<f64> {
    let r = rotation_matrix([q[0], q[1], q[2], q[3]]);
    Matrix3::from_fn(|i, j| r[i][j])
}

/// Swung over the top through the upright (θ = 0, where z-x-z is
/// singular) again and again: the pinned free body switches charts with the
/// constraint rows in force in both, and turns as the quaternion top does,
/// its tip at the origin to the integrator's tolerance.
#[test]
fn a_pinned_top_swung_through_the_upright_matches_the_top_on_a_pivot() {
    let angles = [0.2, 0.6, -0.4];
    let rates = Vector3::new(0.0, -6.0, 2.0);
    let r0 = zxz().matrix(angles);
    let w0 = zxz().rates(angles) * rates;
    // The centre a distance l up the axis, moving with the turn about the tip.
    let arm = Vector3::new(0.0, 0.0, PINNED.l);
    let (centre, speed) = (r0 * arm, r0 * w0.cross(&arm));
    let q0 = [
        centre[0], centre[1], centre[2], angles[0], angles[1], angles[2],
    ];
    let v0 = [speed[0], speed[1], speed[2], rates[0], rates[1], rates[2]];
    let run = Simulation::new(&PINNED)
        .integrator(Dopri5::tol(1e-11))
        .run_atlas(q0, v0, 0.0..4.0)
        .unwrap();
    let q = nalgebra::UnitQuaternion::from_matrix(&r0);
    let reference = Simulation::new(&TOP)
        .integrator(Dopri5::tol(1e-11))
        .run([q.w, q.i, q.j, q.k], [w0[0], w0[1], w0[2]], 0.0..4.0)
        .unwrap();
    let traj = run.trajectory();
    let (mut worst, mut pin): (f64, f64) = (0.0, 0.0);
    for (i, &t) in traj.times().iter().enumerate() {
        let (qr, _) = reference.state_at(t).unwrap();
        let r = run.rotation(i, 0);
        worst = worst.max((r - matrix(qr.as_slice())).abs().max());
        let c = traj.positions()[i].fixed_rows::<3>(0).into_owned();
        pin = pin.max((c - r * arm).norm());
    }
    let residual = (traj.residuals().iter()).fold(0.0f64, |m, r| m.max(r[0]).max(r[1]));
    let switches = run.switches().len();
    eprintln!(
        "pinned top: {switches} switches, rotation gap {worst:e}, tip off the origin {pin:e}, \
         largest residual {residual:e}, energy drift {:e}",
        traj.integral_drift()
    );
    assert!(switches >= 4, "{switches}");
    assert!(worst < 1e-7, "{worst:e}");
    assert!(pin < 1e-8 && residual < 1e-8, "{pin:e} {residual:e}");
    assert!(traj.integral_drift() < 1e-8, "{:e}", traj.integral_drift());
}

/// A start off the constraints is refused before any step, in the user's
/// coordinates, as `run` refuses it; so is drift control, which the atlas
/// does not apply.
#[test]
fn an_inconsistent_start_is_refused() {
    let q0 = [0.0, 0.0, 0.5, 0.2, 0.6, -0.4];
    let failure = Simulation::new(&PINNED)
        .run_atlas(q0, [0.0; 6], 0.0..1.0)
        .unwrap_err();
    assert!(
        matches!(failure.error, Error::InconsistentInitialConditions { .. }),
        "{}",
        failure.error
    );
    assert_eq!(failure.partial.trajectory().len(), 1);
    let projected = Simulation::new(&PINNED)
        .drift(Drift::projection())
        .run_atlas([0.0, 0.0, 0.4, 0.0, 0.0, 0.0], [0.0; 6], 0.0..1.0)
        .unwrap_err();
    assert!(
        matches!(projected.error, Error::InvalidSettings(_)),
        "{}",
        projected.error
    );
    let lin = Linearizer::new().atlas(
        &PINNED,
        &nalgebra::SVector::zeros(),
        &nalgebra::SVector::zeros(),
        0.0,
    );
    assert!(matches!(lin, Err(Error::InvalidSettings(_))));
}
