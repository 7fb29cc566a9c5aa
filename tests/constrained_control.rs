//! A gain designed on `Linearizer::constrained_tangent` applied through
//! `StateFeedback::from_tangent_gain`: a body with a free orientation, its
//! tip pinned by three holonomic rows (a ball joint made of constraints),
//! balanced upright by body torques. The model's states are the tangent
//! directions and velocities the law reads (q ⊖ q*, v − v*), so at a point at
//! rest the law is the model's to first order: the nonlinear closed loop
//! follows the linear one to second order in the error, then settles upright.

use crate::common;

use common::numeric::apart_from_linear;
use lagrange::control::StateFeedback;
use lagrange::linear::{Linearizer, OperatingPoint};
use lagrange::numeric::orientation;
use lagrange::prelude::*;
use nalgebra::{DMatrix, DVector, SVector, Vector3};

/// A rod (centre of mass at (x, y, z), half-length l) whose lower tip is held
/// at the origin by three rows, with body-axis torques τx, τy, τz from
/// couples of forces (no net force).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(turn),
    inputs(tx, ty, tz),
    body(rod, mass = m, inertia = [a, a, c], at = [x, y, z], rotation = turn),
    point(tip, on = rod, at = [0, 0, -l]),
    point(py, on = rod, at = [0, 1, 0]),
    point(ny, on = rod, at = [0, -1, 0]),
    point(pz, on = rod, at = [0, 0, 1]),
    point(nz, on = rod, at = [0, 0, -1]),
    point(px, on = rod, at = [1, 0, 0]),
    point(nx, on = rod, at = [-1, 0, 0]),
    // e_y × e_z = e_x: ½τx R e_z at +e_y and −½τx R e_z at −e_y turn about x.
    force(py, [tx * rod.axis_z.x / 2, tx * rod.axis_z.y / 2, tx * rod.axis_z.z / 2]),
    force(ny, [-tx * rod.axis_z.x / 2, -tx * rod.axis_z.y / 2, -tx * rod.axis_z.z / 2]),
    force(pz, [ty * rod.axis_x.x / 2, ty * rod.axis_x.y / 2, ty * rod.axis_x.z / 2]),
    force(nz, [-ty * rod.axis_x.x / 2, -ty * rod.axis_x.y / 2, -ty * rod.axis_x.z / 2]),
    force(px, [tz * rod.axis_y.x / 2, tz * rod.axis_y.y / 2, tz * rod.axis_y.z / 2]),
    force(nx, [-tz * rod.axis_y.x / 2, -tz * rod.axis_y.y / 2, -tz * rod.axis_y.z / 2]),
    gravity = [0, 0, -g],
    holonomic(pin_x = tip.x, pin_y = tip.y, pin_z = tip.z),
)]
pub(crate) struct Balanced {
    pub(crate) m: f64,
    pub(crate) a: f64,
    pub(crate) c: f64,
    pub(crate) l: f64,
    pub(crate) g: f64,
}

pub(crate) const ROD: Balanced = Balanced {
    m: 1.0,
    a: 0.1,
    c: 0.02,
    l: 0.5,
    g: 9.81,
};

/// Upright at rest: the centre of mass above the pin.
fn upright() -> (SVector<f64, 7>, SVector<f64, 6>) {
    (
        SVector::from([0.0, 0.0, ROD.l, 1.0, 0.0, 0.0, 0.0]),
        SVector::zeros(),
    )
}

/// A consistent state turned by δ from upright with body rate ω.
fn tilted(delta: [f64; 3], omega: [f64; 3]) -> (SVector<f64, 7>, SVector<f64, 6>) {
    let mut turn = [0.0; 4];
    orientation::integrate(
        &[lagrange::Orientation { q: 0, v: 0 }],
        &[1.0, 0.0, 0.0, 0.0],
        &delta,
        &mut turn,
    );
    let r = orientation::rotation_matrix(turn);
    let r = nalgebra::Matrix3::from_fn(|i, j| r[i][j]);
    let up = Vector3::new(0.0, 0.0, ROD.l);
    let (centre, w) = (r * up, Vector3::from(omega));
    let rate = r * w.cross(&up);
    let q = [
        centre.x, centre.y, centre.z, turn[0], turn[1], turn[2], turn[3],
    ];
    let v = [rate.x, rate.y, rate.z, omega[0], omega[1], omega[2]];
    (SVector::from(q), SVector::from(v))
}

#[test]
fn lqr_on_the_constrained_tangent_model_balances_the_pinned_rod() {
    let (q_star, v_star) = upright();
    let rest = SVector::<f64, 3>::zeros();
    let op = OperatingPoint::on_group(q_star, v_star).input(rest);
    let lin = Linearizer::new()
        .coordinates(&["turn.θx", "turn.θy", "turn.θz"])
        .speeds(&["turn.wx", "turn.wy", "turn.wz"])
        .constrained_tangent(&ROD, &op)
        .unwrap();
    assert_eq!(
        lin.states(),
        [
            "turn.θx", "turn.θy", "turn.θz", "turn.wx", "turn.wy", "turn.wz"
        ]
    );
    // Upright is unstable: ±√(m g l / A_pin) on each tilt.
    let growth = (ROD.m * ROD.g * ROD.l / (ROD.a + ROD.m * ROD.l * ROD.l)).sqrt();
    let open = lin.a().clone().complex_eigenvalues();
    let fastest = open.iter().map(|l| l.re).fold(f64::MIN, f64::max);
    assert!((fastest - growth).abs() < 1e-7, "{fastest} vs {growth}");
    let lqr = lin
        .lqr(&DMatrix::identity(6, 6), &DMatrix::identity(3, 3))
        .unwrap();
    assert!(lqr.closed_loop.iter().all(|l| l.re < -0.01));
    let law = StateFeedback::<f64, 6, 3, 7>::from_tangent_gain::<Balanced>(
        &lqr.gain,
        &lin,
        (q_star, v_star, rest),
    )
    .unwrap();
    let closed = lin.a() - lin.b() * &lqr.gain;
    let state = |q: &SVector<f64, 7>, v: &SVector<f64, 6>| {
        let mut delta = [0.0; 6];
        orientation::difference(
            Balanced::ORIENTATIONS,
            q_star.as_slice(),
            q.as_slice(),
            &mut delta,
        );
        DVector::from_column_slice(&[&delta[3..], &v.as_slice()[3..]].concat())
    };
    // The largest distance from the linear closed loop over 3 s, and the
    // error after 20 s, from the error s·(δ₀, ω₀).
    let from = |s: f64| {
        let (d0, w0) = ([0.03 * s, -0.02 * s, 0.01 * s], [0.0, 0.02 * s, -0.01 * s]);
        let (q0, v0) = tilted(d0, w0);
        let run = Simulation::new(&ROD)
            .integrator(Dopri5::tol(1e-12))
            .control(law)
            .run(q0, v0, 0.0..20.0)
            .unwrap();
        let traj = run.trajectory();
        let x0 = state(&q0, &v0);
        let apart = apart_from_linear(traj, state, (&closed, &x0), &[0.5, 1.0, 2.0, 3.0]);
        let (q, v) = traj.final_state();
        let residual = traj.max_residuals();
        (apart, state(&q, &v).norm(), residual)
    };
    let (apart, settled, residual) = from(1.0);
    let (half_apart, _, _) = from(0.5);
    eprintln!(
        "pinned rod: from the linear loop {apart:.2e}, at half the error {half_apart:.2e}; \
         after 20 s {settled:.1e}; residuals {residual:?}"
    );
    assert!(
        (3.5..4.5).contains(&(apart / half_apart)),
        "{apart:e} {half_apart:e}"
    );
    assert!(apart < 1e-3 && settled < 1e-6, "{apart:e} {settled:e}");
    assert!(residual[0] < 1e-9 && residual[1] < 1e-9, "{residual:?}");
}
