//! Inputs with a free orientation: a satellite turned by body-axis torques
//! (`catalog::free::Satellite`), against the closed form of a constant
//! torque about a principal axis from rest, under a feedback law that
//! despins and reorients it, and its tangent linearisation's B against the
//! closed form M⁻¹ and finite differences.

use crate::catalog;
use crate::common;

use catalog::free::Satellite;
use common::numeric::apart_from_linear;
use lagrange::control::{InputForces, OpenLoop, StateFeedback};
use lagrange::prelude::*;
use nalgebra::{DVector, SVector, Vector3, Vector4};

const SAT: Satellite = Satellite {
    m: 40.0,
    a: 2.0,
    b: 3.0,
    c: 4.5,
};

/// From rest, a constant torque τ about the body's y axis (principal, so it
/// stays the axis): ω = τ/B t, the angle ½ τ/B t², the quaternion
/// (cos φ/2, 0, sin φ/2, 0).
#[test]
fn a_constant_torque_about_a_principal_axis_turns_it_as_the_closed_form() {
    let tau = 0.6;
    let run = Simulation::new(&SAT)
        .integrator(Dopri5::tol(1e-12))
        .open_loop(|_| [0.0, tau, 0.0])
        .run([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0], 0.0..4.0)
        .unwrap();
    let traj = run.trajectory();
    let mut worst: f64 = 0.0;
    for ((&t, q), v) in traj
        .times()
        .iter()
        .zip(traj.positions())
        .zip(traj.velocities())
    {
        let angle = 0.5 * tau / SAT.b * t * t;
        let want_q = Vector4::new((angle / 2.0).cos(), 0.0, (angle / 2.0).sin(), 0.0);
        let want_v = Vector3::new(0.0, tau / SAT.b * t, 0.0);
        worst = worst.max((q - want_q).amax()).max((v - want_v).amax());
    }
    eprintln!("constant torque: largest gap to the closed form {worst:e}");
    assert!(worst < 1e-9, "{worst:e}");
    assert_eq!(run.input_names(), &["t1", "t2", "t3"]);
    assert_eq!(run.inputs()[0], SVector::from([0.0, tau, 0.0]));
}

/// The attitude error's vector part, on the short way round (w ≥ 0).
fn error(q: &SVector<f64, 4>) -> Vector3<f64> {
    let s = if q[0] < 0.0 { -1.0 } else { 1.0 };
    Vector3::new(q[1], q[2], q[3]) * s
}

/// u = −k_p I e − k_d I ω, e the quaternion's vector part: tumbling at a
/// few rad/s, the body comes to rest at the identity. Near it e ≈ θ/2, so
/// each axis obeys θ̈ + k_d θ̇ + k_p/2 θ = 0, poles −1 and −2 here: the
/// error decays as e^(−t) at the end.
#[test]
fn a_feedback_law_despins_and_reorients_the_body() {
    let (kp, kd) = (4.0, 3.0);
    let inertia = Vector3::new(SAT.a, SAT.b, SAT.c);
    let law = move |_: f64, q: &SVector<f64, 4>, v: &SVector<f64, 3>| {
        let u = -(error(q) * kp + v * kd).component_mul(&inertia);
        [u[0], u[1], u[2]]
    };
    let q0 = Vector4::new(0.2, -0.6, 0.7, 0.3).normalize();
    let run = Simulation::new(&SAT)
        .integrator(Dopri5::tol(1e-12))
        .feedback(law)
        .run(q0, [2.0, -3.0, 1.5], 0.0..25.0)
        .unwrap();
    let traj = run.trajectory();
    let (q, v) = traj.final_state();
    let (q15, _) = traj.state_at(15.0).unwrap();
    let (off, before) = (error(&q).norm(), error(&q15).norm());
    let rate = (before / off).ln() / 10.0;
    eprintln!(
        "feedback: after 25 s, attitude error {off:e}, rate {:e}; decay rate {rate}",
        v.amax()
    );
    assert!(off < 1e-9 && v.amax() < 1e-9, "{off:e} {:e}", v.amax());
    assert!((rate - 1.0).abs() < 1e-3, "decay rate {rate}");
    assert!(traj.max_unit_error() < 1e-15);
}

/// B of the tangent linearisation: zero in δθ, M⁻¹ ∂Q/∂u = diag(1/A, 1/B,
/// 1/C) in δω (the body fixed at its centre), and the same by central
/// differences of the driven dynamics in u, at a tumbling state with
/// torques on.
#[test]
fn the_tangent_input_matrix_is_the_inverse_inertia() {
    let q = SVector::from(Vector4::new(0.9, 0.1, -0.3, 0.2).normalize());
    let v = SVector::from([0.7, -1.1, 0.4]);
    let u = SVector::from([0.3, -0.2, 0.5]);
    let lin = Linearizer::new()
        .tangent_driven(&SAT, &q, &v, &u, 0.0)
        .unwrap();
    assert_eq!(lin.inputs(), ["t1", "t2", "t3"]);
    let b = lin.b();
    let accel = |u: SVector<f64, 3>| {
        let forcing = InputForces::new(&SAT, OpenLoop::new(move |_: f64| u));
        lagrange::Dynamics::new(&SAT)
            .with_forcing(forcing)
            .acceleration(0.0, &q, &v)
            .unwrap()
    };
    let moments = [SAT.a, SAT.b, SAT.c];
    let h = 1e-5;
    let mut worst: f64 = 0.0;
    for k in 0..3 {
        let mut e = SVector::<f64, 3>::zeros();
        e[k] = h;
        let fd = (accel(u + e) - accel(u - e)) / (2.0 * h);
        for i in 0..3 {
            assert_eq!(b[(i, k)], 0.0);
            let exact = if i == k { 1.0 / moments[k] } else { 0.0 };
            assert!((b[(3 + i, k)] - exact).abs() < 1e-14, "B[{}, {k}]", 3 + i);
            worst = worst.max((b[(3 + i, k)] - fd[i]).abs());
        }
    }
    eprintln!("tangent B against central differences: {worst:e}");
    assert!(worst < 1e-9, "{worst:e}");
}

/// Body-axis torques do not change as the body turns: ∂ΔQ/∂q along q ⊕ δ
/// is zero (the moving chart's −½[τ]× is accounted for), against central
/// differences of the input forces along q ⊕ δ; ∂ΔQ/∂u is the identity.
#[test]
fn the_input_jacobians_are_taken_along_the_tangent_space() {
    let q = SVector::from(Vector4::new(0.9, 0.1, -0.3, 0.2).normalize());
    let v = SVector::from([0.7, -1.1, 0.4]);
    let u = SVector::from([0.3, -0.2, 0.5]);
    let (du, dq, dv) = SAT.input_jacobians(&q, &v, &u, 0.0);
    assert!((du - nalgebra::Matrix3::identity()).amax() < 1e-15);
    assert!(dq.amax() < 1e-15 && dv.amax() < 1e-15, "{dq} {dv}");
    let h = 1e-6;
    for k in 0..3 {
        let turned = |s: f64| {
            let mut delta = [0.0; 3];
            delta[k] = s;
            let mut out = [0.0; 4];
            lagrange::numeric::orientation::integrate(SAT_LAYOUT, q.as_slice(), &delta, &mut out);
            SAT.input_forces(&SVector::from(out), &v, &u, 0.0)
        };
        let fd = (turned(h) - turned(-h)) / (2.0 * h);
        assert!(fd.amax() < 1e-9, "{fd}");
    }
}

const SAT_LAYOUT: &[lagrange::Orientation] = <Satellite as Lagrangian<f64, 3, 4>>::ORIENTATIONS;

/// LQR on the tangent linearisation about a tilted attitude at rest: the
/// gain acts on q ⊖ q* (the rotation vector from q* to q, in body axes), and
/// the nonlinear closed loop from a small error follows the linear one,
/// exp((A − BK) t) x₀, to second order in the error, then settles on q*.
#[test]
fn lqr_on_the_tangent_linearisation_holds_a_tilted_attitude() {
    let half = 0.35_f64;
    let axis = Vector3::new(1.0, 1.0, 0.0).normalize() * half.sin();
    let target = SVector::<f64, 4>::from([half.cos(), axis[0], axis[1], axis[2]]);
    let rest = SVector::<f64, 3>::zeros();
    let lin = Linearizer::new()
        .tangent_driven(&SAT, &target, &rest, &rest, 0.0)
        .unwrap();
    let weights = lagrange::nalgebra::DMatrix::<f64>::identity(6, 6);
    let effort = lagrange::nalgebra::DMatrix::<f64>::identity(3, 3);
    let lqr = lin.lqr(&weights, &effort).unwrap();
    assert!(
        lqr.closed_loop.iter().all(|l| l.re < -0.01),
        "{:?}",
        lqr.closed_loop
    );
    let law = StateFeedback::<f64, 3, 3, 4>::from_tangent_gain::<Satellite>(
        &lqr.gain,
        &lin,
        (target, rest, rest),
    )
    .unwrap();
    let closed = lin.a() - lin.b() * &lqr.gain;
    // The largest distance from the linear closed loop over 4 s, and the
    // final error after 30 s, from the error s·(δ₀, ω₀).
    let from = |s: f64| {
        let (d0, w0) = ([0.02 * s, -0.01 * s, 0.015 * s], [0.01 * s, 0.0, -0.02 * s]);
        let mut q0 = [0.0; 4];
        let layout = &Satellite::ORIENTATIONS;
        lagrange::numeric::orientation::integrate(layout, target.as_slice(), &d0, &mut q0);
        let run = Simulation::new(&SAT)
            .integrator(Dopri5::tol(1e-13))
            .control(law)
            .run(q0, w0, 0.0..30.0)
            .unwrap();
        let traj = run.trajectory();
        let x0 = DVector::from_column_slice(&[d0, w0].concat());
        let state = |q: &SVector<f64, 4>, v: &SVector<f64, 3>| {
            let mut delta = [0.0; 3];
            lagrange::numeric::orientation::difference(
                layout,
                target.as_slice(),
                q.as_slice(),
                &mut delta,
            );
            DVector::from_column_slice(&[delta, [v[0], v[1], v[2]]].concat())
        };
        let apart = apart_from_linear(traj, state, (&closed, &x0), &[0.5, 1.0, 2.0, 4.0]);
        let (q, v) = traj.final_state();
        (apart, state(&q, &v).norm())
    };
    let (apart, settled) = from(1.0);
    let (half_apart, _) = from(0.5);
    eprintln!(
        "from the linear loop: {apart:e}, at half the error {half_apart:e}; after 30 s {settled:e}"
    );
    // Second order: half the error, a quarter of the distance.
    assert!(
        (3.5..4.5).contains(&(apart / half_apart)),
        "{apart:e} {half_apart:e}"
    );
    assert!(apart < 1e-3 && settled < 1e-6);
}
