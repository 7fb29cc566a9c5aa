//! The momentum regressor (`emit(regressor)`): Y_p π = p = ∂T/∂q̇ = M q̇ at
//! random states on the UR5, on Solo 12 on its floating base and on a
//! slider-crank (no tree: the generic route); and on Solo 12 the base's rows
//! are the robot's total linear momentum in world axes and its angular
//! momentum about the base's reference point in the base's axes, against
//! the same summed over the bodies from their poses, differenced along the
//! motion.

use lagrange::Lagrangian;
use lagrange::numeric::orientation::integrate;
use lagrange::pose::{BodyInertia, BodyPose, Posed};
use nalgebra::{Matrix3, SVector, Vector3};

use crate::regressor::{CRANK, Lcg, Solo12, Ur5, state};

/// Max over 20 random states of |Y_p π − M q̇| and |Y_p π − ∂T/∂q̇| (the
/// emitted momentum), each relative to 1 + |p|.
fn momentum_misfit<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(sys: &S) -> f64 {
    let pi = sys.inertial_parameters().expect("π is emitted");
    let mut rng = Lcg(51);
    let mut worst = 0.0f64;
    for _ in 0..20 {
        let (q, v, _) = state::<S, N, Q>(&mut rng);
        let y_p = sys.momentum_regressor(&q, &v, 0.0).expect("Y_p is emitted");
        assert_eq!(y_p.shape(), (N, pi.len()));
        let p = &y_p * &pi;
        let m_v = sys.mass_matrix(&q, 0.0) * v;
        let emitted = sys.momentum(&q, &v, 0.0);
        for i in 0..N {
            assert!(p[i].is_finite());
            worst = worst.max((p[i] - m_v[i]).abs() / (1.0 + m_v[i].abs()));
            worst = worst.max((p[i] - emitted[i]).abs() / (1.0 + emitted[i].abs()));
        }
    }
    worst
}

#[test]
fn y_p_pi_is_the_momentum() {
    for (system, err) in [
        ("UR5", momentum_misfit(&Ur5 {})),
        ("Solo 12", momentum_misfit(&Solo12 {})),
        ("slider-crank", momentum_misfit(&CRANK)),
    ] {
        eprintln!("{system}: max |Y_p π − M q̇| / (1 + |M q̇|) = {err:.1e}");
        assert!(err < 1e-12, "{system}: {err:e}");
    }
}

/// The bodies' poses at q.
fn poses(sys: &Solo12, q: &SVector<f64, 19>) -> Vec<BodyPose<f64>> {
    let bodies = <Solo12 as Posed<f64, 18, 19>>::BODIES.len();
    let points = <Solo12 as Posed<f64, 18, 19>>::POINTS.len();
    let mut out = vec![BodyPose::default(); bodies];
    let mut at = vec![Vector3::zeros(); points];
    sys.poses(q, 0.0, &mut out, &mut at);
    out
}

/// Solo 12's total linear momentum (world axes) and angular momentum about
/// the base's reference point (the base's axes), summed over the bodies:
/// each centre's velocity and each body's ω by central differences of the
/// poses along q ⊕ ±h q̇.
fn momenta_from_poses(
    sys: &Solo12,
    q: &SVector<f64, 19>,
    v: &SVector<f64, 18>,
) -> [Vector3<f64>; 2] {
    let layout = <Solo12 as Lagrangian<f64, 18, 19>>::ORIENTATIONS;
    let h = 1e-5;
    let moved = |s: f64| {
        let mut out = SVector::<f64, 19>::zeros();
        integrate(layout, q.as_slice(), (v * s).as_slice(), out.as_mut_slice());
        poses(sys, &out)
    };
    let (now, ahead, behind) = (poses(sys, q), moved(h), moved(-h));
    let mut inertias = vec![BodyInertia::default(); now.len()];
    sys.inertias(&mut inertias);
    let base = <Solo12 as Posed<f64, 18, 19>>::BODIES
        .iter()
        .position(|b| *b == "base_link")
        .expect("the base");
    let origin = now[base].origin;
    let (mut linear, mut angular) = (Vector3::zeros(), Vector3::zeros());
    for (k, body) in now.iter().enumerate() {
        let m = inertias[k].mass;
        let velocity = (ahead[k].centre - behind[k].centre) / (2.0 * h);
        let rate: Matrix3<f64> = (ahead[k].rotation - behind[k].rotation) / (2.0 * h);
        // Rᵀ Ṙ = [ω]× in the body's axes.
        let w = body.rotation.transpose() * rate;
        let omega = Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]);
        linear += m * velocity;
        angular += (body.centre - origin).cross(&(m * velocity))
            + body.rotation * (inertias[k].inertia * omega);
    }
    [linear, now[base].rotation.transpose() * angular]
}

#[test]
fn solo_12s_base_rows_are_its_total_momentum() {
    let names = <Solo12 as Lagrangian<f64, 18, 19>>::VELOCITIES;
    let turn = <Solo12 as Lagrangian<f64, 18, 19>>::ORIENTATIONS[0].v;
    assert_eq!(&names[..3], ["base_link_x", "base_link_y", "base_link_z"]);
    let sys = Solo12 {};
    let pi = sys.inertial_parameters().expect("π");
    let mut rng = Lcg(52);
    let mut worst = 0.0f64;
    for _ in 0..10 {
        let (q, v, _) = state::<Solo12, 18, 19>(&mut rng);
        let p = sys.momentum_regressor(&q, &v, 0.0).expect("Y_p") * &pi;
        let [linear, angular] = momenta_from_poses(&sys, &q, &v);
        for c in 0..3 {
            worst = worst.max((p[c] - linear[c]).abs() / (1.0 + linear.norm()));
            worst = worst.max((p[turn + c] - angular[c]).abs() / (1.0 + angular.norm()));
        }
    }
    eprintln!(
        "Solo 12: velocities {names:?}, ω at {turn}; max |base rows − momenta from the poses| = {worst:.1e}"
    );
    // Central differences of step 1e-5: truncation ~1e-10, round-off ~1e-11.
    assert!(worst < 1e-7, "{worst:e}");
}
