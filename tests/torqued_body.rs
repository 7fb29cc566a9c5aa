//! Inputs with a free orientation: a satellite turned by body-axis torques
//! (`catalog::free::Satellite`), against the closed form of a constant
//! torque about a principal axis from rest, under a feedback law that
//! despins and reorients it, and its tangent linearisation's B against the
//! closed form M⁻¹ and finite differences.

#[path = "../examples/catalog/mod.rs"]
mod catalog;

use catalog::free::Satellite;
use lagrange::control::{InputForces, OpenLoop};
use lagrange::prelude::*;
use nalgebra::{SVector, Vector3, Vector4};

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
