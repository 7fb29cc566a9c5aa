//! The program `emit(jacobians)` emits for a system without constraints
//! (`lagrange::acceleration_derivatives`: M factorised as Lᵀ D L in it, q̈ at
//! a given τ, its derivatives solved in it) against M's Cholesky
//! factorisation here and against central differences of its own q̈, at
//! τ ≠ 0; `Dynamics::acceleration_derivatives` with a forcing; and their
//! errors.

use lagrange::prelude::*;
use lagrange::{Differentiable, Dynamics, Forcing};
use nalgebra::{SMatrix, SVector};

use crate::floating_bases::Solo12;
use crate::urdf_derivatives::{Ur5, Xarm7};

fn state<const N: usize>(shift: f64) -> (SVector<f64, N>, SVector<f64, N>, SVector<f64, N>) {
    let q = SVector::from_fn(|k, _| 0.3 - 0.17 * k as f64 + shift);
    let v = SVector::from_fn(|k, _| 0.5 - 0.21 * k as f64);
    let tau = SVector::from_fn(|k, _| 2.0 * (0.1 * k as f64 - 0.2));
    (q, v, tau)
}

fn worst<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>, b: &SMatrix<f64, R, C>) -> f64 {
    a.iter()
        .zip(b.iter())
        .map(|(x, y)| (x - y).abs() / x.abs().max(y.abs()).max(1.0))
        .fold(0.0, f64::max)
}

/// q̈ against M⁻¹(Q − h + τ), ∂q̈/∂τ against M⁻¹, ∂q̈/∂q and ∂q̈/∂q̇ against
/// central differences of the emitted q̈ itself.
fn an_arm_at_a_torque<S: Differentiable<f64, N, N>, const N: usize>(name: &str, sys: &S) {
    let (q, v, tau) = state::<N>(0.0);
    let d = lagrange::acceleration_derivatives(sys, &q, &v, &tau, 0.0).expect("a regular state");
    let (m, rhs) = sys.mass_matrix_and_rhs(&q, &v, 0.0);
    let inverse = m.try_inverse().expect("M is invertible");
    let acc = inverse * (rhs + tau);
    assert!(worst(&d.acceleration, &acc) < 1e-12, "{name}: q''");
    assert!(worst(&d.dtau, &inverse) < 1e-11, "{name}: dq''/dtau");
    // One triangle of M⁻¹ is solved and mirrored: symmetric to the bit.
    assert_eq!(d.dtau, d.dtau.transpose(), "{name}: dq''/dtau symmetric");
    // Fourth-order central differences: truncation ~h⁴, round-off ~ε |q̈| / h,
    // 2e-8 on the xArm7 (at its ∂q̈₆/∂q₀, exactly 0 in the program). The
    // second-order stencil at h = 1e-5 left 1e-6 of round-off there: a
    // check of the stencil, not of the program, which agrees with
    // Pinocchio's `computeABADerivatives` to 1e-14.
    let h = 1e-3;
    let at = |q: SVector<f64, N>, v: SVector<f64, N>| {
        lagrange::acceleration_derivatives(sys, &q, &v, &tau, 0.0)
            .expect("a regular state")
            .acceleration
    };
    let stencil = |f: &dyn Fn(f64) -> SVector<f64, N>| {
        (f(-2.0 * h) - f(2.0 * h) + 8.0 * (f(h) - f(-h))) / (12.0 * h)
    };
    let mut dq = SMatrix::<f64, N, N>::zeros();
    let mut dv = SMatrix::<f64, N, N>::zeros();
    for k in 0..N {
        let e = SVector::<f64, N>::from_fn(|i, _| if i == k { 1.0 } else { 0.0 });
        dq.set_column(k, &stencil(&|s| at(q + e * s, v)));
        dv.set_column(k, &stencil(&|s| at(q, v + e * s)));
    }
    assert!(
        worst(&d.dq, &dq) < 1e-7,
        "{name}: dq''/dq off by {}",
        worst(&d.dq, &dq)
    );
    assert!(
        worst(&d.dv, &dv) < 1e-7,
        "{name}: dq''/dv off by {}",
        worst(&d.dv, &dv)
    );
}

/// The Panda with its mimic finger: eight coordinates, M with four zero
/// entries, factorised at run time as the seven-joint chains are.
#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/panda.urdf", dynamics = ignore),
    gravity = [0, 0, -9.81],
    emit(jacobians)
)]
struct Panda {}

#[test]
fn arms_at_a_torque_match_their_own_differences() {
    an_arm_at_a_torque("xArm7", &Xarm7 {});
    an_arm_at_a_torque("UR5", &Ur5 {});
    an_arm_at_a_torque("Panda", &Panda {});
}

/// A spring on every velocity's direction, ΔQ = −k (v + c), with its own
/// Jacobians: ∂ΔQ/∂δ = 0, ∂ΔQ/∂v = −k I.
struct Damper(f64);

impl Forcing<f64, 18, 19> for Damper {
    fn force(
        &self,
        _: f64,
        _: &SVector<f64, 19>,
        v: &SVector<f64, 18>,
    ) -> Result<SVector<f64, 18>, lagrange::Error> {
        Ok(-(v.add_scalar(0.3)) * self.0)
    }
}

/// `Dynamics::acceleration_derivatives` on a floating base (∂q̈/∂δ along
/// q ⊕ δ), with a forcing and its Jacobians: against M, Q − h and the
/// right-hand side's Jacobians solved here by nalgebra's Cholesky, an
/// independent route to the same numbers (the method takes the emitted
/// program, the forcing's Jacobians through its M⁻¹).
#[test]
fn a_floating_base_with_a_forcing_matches_a_factorisation_here() {
    let sys = Solo12 {};
    let mut q = SVector::<f64, 19>::from_fn(|k, _| 0.2 - 0.07 * k as f64);
    let quaternion = [0.9, 0.1, -0.3, 0.2];
    let norm = quaternion.iter().map(|x: &f64| x * x).sum::<f64>().sqrt();
    for (c, x) in quaternion.iter().enumerate() {
        q[15 + c] = x / norm;
    }
    let v = SVector::<f64, 18>::from_fn(|k, _| 0.4 - 0.05 * k as f64);
    let k = 0.7;
    let fv = SMatrix::<f64, 18, 18>::identity() * -k;
    let run = Dynamics::new(&sys)
        .with_forcing(Damper(k))
        .acceleration_derivatives(0.0, &q, &v, Some((SMatrix::zeros(), fv)))
        .expect("a regular state")
        .expect("emit(jacobians)");
    let (m, rhs) = sys.mass_matrix_and_rhs(&q, &v, 0.0);
    let chol = m.cholesky().expect("M is positive definite");
    let acceleration = chol.solve(&(rhs - v.add_scalar(0.3) * k));
    let (jq, jv) = sys
        .rhs_jacobians(&q, &v, &acceleration, 0.0)
        .expect("emit(jacobians)");
    assert!(worst(&run.acceleration, &acceleration) < 1e-12);
    for (what, a, b) in [
        ("dq", run.dq, chol.solve(&jq)),
        ("dv", run.dv, chol.solve(&(jv + fv))),
        ("dtau", run.dtau, chol.inverse()),
    ] {
        assert!(worst(&a, &b) < 1e-10, "{what}: off by {}", worst(&a, &b));
    }
}

/// A double pendulum whose masses are parameters: a massless one has a
/// singular M.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a, b),
    point(p, at = [l * sin(a), -l * cos(a)], mass = m1),
    point(r, at = [p.x + l * sin(b), p.y - l * cos(b)], mass = m2),
    gravity = [0, -g],
    emit(jacobians)
)]
struct Double {
    m1: f64,
    m2: f64,
    l: f64,
    g: f64,
}

#[test]
fn bad_input_is_a_typed_error() {
    let sys = Double {
        m1: 1.0,
        m2: 0.5,
        l: 1.0,
        g: 9.81,
    };
    let q = SVector::<f64, 2>::new(0.3, -0.2);
    let v = SVector::<f64, 2>::new(0.1, 0.4);
    let tau = SVector::<f64, 2>::new(0.0, f64::NAN);
    let e = lagrange::acceleration_derivatives(&sys, &q, &v, &tau, 0.0).unwrap_err();
    assert!(matches!(e, Error::NonFiniteInput { input: "b", .. }), "{e}");
    let nan = SVector::<f64, 2>::new(f64::NAN, 0.0);
    let e = lagrange::acceleration_derivatives(&sys, &nan, &v, &SVector::zeros(), 0.0).unwrap_err();
    assert!(matches!(e, Error::NonFiniteState { .. }), "{e}");
    let massless = Double {
        m1: 0.0,
        m2: 0.0,
        l: 1.0,
        g: 9.81,
    };
    let e =
        lagrange::acceleration_derivatives(&massless, &q, &v, &SVector::zeros(), 0.0).unwrap_err();
    assert!(matches!(e, Error::SingularMassMatrix { .. }), "{e}");
}
