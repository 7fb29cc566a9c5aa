//! Holonomic constraints with the atlas: a top written as a free body (its
//! centre and its z-x-z angles) whose tip is held at the origin by three
//! holonomic rows that read the rotation, swung through the upright; the
//! twin carries the same rows on its quaternion. Against the quaternion top
//! on a fixed pivot (`catalog::free::QuaternionTop`).

use crate::catalog;

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

/// The pinned top driven by a couple `tau` about a body axis across its
/// own (two opposite forces at the rim, through points of the body).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    inputs(tau),
    body(top, mass = m, inertia = [a - m * l * l, a - m * l * l, c], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    point(tip, on = top, at = [0, 0, -l]),
    point(rim_a, on = top, at = [0, 1, 0]),
    point(rim_b, on = top, at = [0, -1, 0]),
    force(rim_a, [tau * top.axis_z.x / 2, tau * top.axis_z.y / 2, tau * top.axis_z.z / 2]),
    force(rim_b, [-tau * top.axis_z.x / 2, -tau * top.axis_z.y / 2, -tau * top.axis_z.z / 2]),
    holonomic(pin_x = tip.x, pin_y = tip.y, pin_z = tip.z),
    gravity = [0, 0, -g],
    emit(atlas),
)]
struct DrivenPinnedTop {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// The top on a pivot with a free orientation, driven by the same couple.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    orientation(turn),
    inputs(tau),
    body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
         at = [0, 0, 0], rotation = turn),
    point(rim_a, on = top, at = [0, 1, l]),
    point(rim_b, on = top, at = [0, -1, l]),
    force(rim_a, [tau * top.axis_z.x / 2, tau * top.axis_z.y / 2, tau * top.axis_z.z / 2]),
    force(rim_b, [-tau * top.axis_z.x / 2, -tau * top.axis_z.y / 2, -tau * top.axis_z.z / 2]),
    gravity = [0, 0, -g],
)]
struct DrivenTop {
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
    let traj = run.charted();
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

/// The pinned top driven by a couple about its body x axis that varies in
/// time and damps the body rate about that axis (a feedback read on the
/// user's angles and rates): constraints,
/// inputs and switches together, against the driven top on a pivot under
/// the same law read on its quaternion and ω.
#[test]
fn a_driven_pinned_top_matches_the_driven_top_on_a_pivot() {
    let (m, a, c, l, g) = (1.5, 0.8, 0.5, 0.4, 9.81);
    let pinned = DrivenPinnedTop { m, a, c, l, g };
    let top = DrivenTop { m, a, c, l, g };
    let angles = [0.2, 0.6, -0.4];
    let rates = Vector3::new(0.0, -6.0, 2.0);
    let r0 = zxz().matrix(angles);
    let w0 = zxz().rates(angles) * rates;
    let arm = Vector3::new(0.0, 0.0, l);
    let (centre, speed) = (r0 * arm, r0 * w0.cross(&arm));
    let q0 = [
        centre[0], centre[1], centre[2], angles[0], angles[1], angles[2],
    ];
    let v0 = [speed[0], speed[1], speed[2], rates[0], rates[1], rates[2]];
    // Damping of the body-axis rate ω_x, read from the user's angles and
    // rates (ω = E q̇) in the one run and from ω in the other.
    let law = |t: f64, w: Vector3<f64>| [0.3 * t.sin() - 0.2 * w[0]];
    let run = Simulation::new(&pinned)
        .integrator(Dopri5::tol(1e-11))
        .feedback(move |t, q, v| {
            let x = [q[3], q[4], q[5]];
            law(t, zxz().rates(x) * Vector3::new(v[3], v[4], v[5]))
        })
        .run_atlas(q0, v0, 0.0..4.0)
        .unwrap();
    let q = nalgebra::UnitQuaternion::from_matrix(&r0);
    let reference = Simulation::new(&top)
        .integrator(Dopri5::tol(1e-11))
        .feedback(
            move |t, _: &nalgebra::SVector<f64, 4>, v: &nalgebra::SVector<f64, 3>| {
                law(t, Vector3::from(*v))
            },
        )
        .run([q.w, q.i, q.j, q.k], [w0[0], w0[1], w0[2]], 0.0..4.0)
        .unwrap();
    let traj = run.charted();
    let (mut worst, mut pin): (f64, f64) = (0.0, 0.0);
    for (i, &t) in traj.times().iter().enumerate() {
        let (qr, _) = reference.trajectory().state_at(t).unwrap();
        let r = run.rotation(i, 0);
        worst = worst.max((r - matrix(qr.as_slice())).abs().max());
        let c = traj.positions()[i].fixed_rows::<3>(0).into_owned();
        pin = pin.max((c - r * arm).norm());
    }
    let switches = run.switches().len();
    eprintln!(
        "driven pinned top: {switches} switches, rotation gap {worst:e}, tip off the origin {pin:e}"
    );
    assert!(switches >= 2, "{switches}");
    assert!(worst < 1e-7 && pin < 1e-8, "{worst:e} {pin:e}");
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
    assert_eq!(failure.partial.charted().len(), 1);
    let projected = Simulation::new(&PINNED)
        .drift(Drift::projection())
        .run_atlas([0.0, 0.0, 0.4, 0.0, 0.0, 0.0], [0.0; 6], 0.0..1.0)
        .unwrap_err();
    assert!(
        matches!(projected.error, Error::Settings(_)),
        "{}",
        projected.error
    );
    // The linearisation checks its point against the rows too.
    let lin = Linearizer::new().atlas(
        &PINNED,
        &nalgebra::SVector::zeros(),
        &nalgebra::SVector::zeros(),
        0.0,
    );
    assert!(
        matches!(&lin, Err(Error::Linear(lagrange::LinearError::InconsistentOperatingPoint { worst, .. })) if worst.contains("pin_z")),
        "{lin:?}"
    );
}

/// The sleeping pinned top linearised where its own chart is singular: in
/// the second chart, on the angles and their rates as independent states,
/// A is the pivoted top's (`catalog::free::EulerTop`, unconstrained), and
/// its largest real part is √(4 A m g l − C² n²) / (2A) below the threshold
/// spin and zero above it. Tilted, in the user's own chart, it is
/// `constrained_tangent`'s model of the same description.
#[test]
fn the_pinned_top_linearises_in_a_regular_chart() {
    use catalog::free::{EulerTop, sleeping_top_growth, sleeping_top_threshold};
    use lagrange::linear::OperatingPoint;
    use nalgebra::SVector;
    let pivoted = EulerTop {
        m: PINNED.m,
        a: PINNED.a,
        c: PINNED.c,
        l: PINNED.l,
        g: PINNED.g,
    };
    let mgl = PINNED.m * PINNED.g * PINNED.l;
    let threshold = sleeping_top_threshold(PINNED.a, PINNED.c, mgl);
    let angles = ["psi@2", "theta@2", "phi@2"];
    let lz = Linearizer::new().coordinates(&angles).speeds(&angles);
    for ratio in [0.9, 0.99, 1.01, 1.5] {
        let n = ratio * threshold;
        let q = SVector::from([0.0, 0.0, PINNED.l, 0.0, 0.0, 0.0]);
        let v = SVector::from([0.0, 0.0, 0.0, 0.0, 0.0, n]);
        let lin = lz.atlas(&PINNED, &q, &v, 0.0).unwrap();
        assert_eq!(lin.states()[..3], angles);
        let free = Linearizer::new()
            .atlas(
                &pivoted,
                &SVector::zeros(),
                &SVector::from([0.0, 0.0, n]),
                0.0,
            )
            .unwrap();
        let gap = (lin.a() - free.a()).amax();
        let growth = lin.eigenvalues()[0].re;
        let expected = sleeping_top_growth(PINNED.a, PINNED.c, mgl, n);
        eprintln!(
            "n/n_c = {ratio}: A within {gap:.1e} of the pivoted top's; growth {growth:e} vs {expected:e}"
        );
        // Two linearisations by central differences (about 1e-10 relative
        // each), and the tilt's stiffness against its closed form m g l / A.
        assert!(gap < 1e-9 * free.a().amax(), "{gap:e}");
        for (i, j) in [(3, 0), (4, 1)] {
            let stiffness = lin.a()[(i, j)];
            assert!(
                (stiffness / (mgl / PINNED.a) - 1.0).abs() < 1e-9,
                "{stiffness}"
            );
        }
        assert!((growth - expected).abs() < 1e-6 * (1.0 + expected));
    }
    let arm = Vector3::new(0.0, 0.0, PINNED.l);
    let x = [0.3, 0.7, -0.2];
    let r = zxz().matrix(x);
    let w = zxz().rates(x) * Vector3::new(0.5, -1.0, 4.0);
    let (c, dc) = (r * arm, r * w.cross(&arm));
    let q = SVector::from([c.x, c.y, c.z, x[0], x[1], x[2]]);
    let v = SVector::from([dc.x, dc.y, dc.z, 0.5, -1.0, 4.0]);
    let names = ["psi", "theta", "phi"];
    let lz = Linearizer::new().coordinates(&names).speeds(&names);
    let atlas = lz.atlas(&PINNED, &q, &v, 0.0).unwrap();
    let tangent = lz
        .constrained_tangent(&PINNED, &OperatingPoint::on_group(q, v))
        .unwrap();
    assert_eq!(atlas.states(), tangent.states());
    let gap = (atlas.a() - tangent.a()).amax();
    eprintln!("tilted pinned top: A of the atlas and constrained_tangent within {gap:.1e}");
    assert!(gap < 1e-9 * tangent.a().amax(), "{gap:e}");
}
