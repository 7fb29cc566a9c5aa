//! ∂q̈/∂q, ∂q̈/∂q̇ and ∂q̈/∂τ = M⁻¹ of robots read from their URDF (`emit(jacobians)` and
//! [`lagrange::acceleration_derivatives`]) against Pinocchio's
//! `computeABADerivatives` on the same files
//! (`lagrange-bench/peer/pinocchio/urdf_derivatives.py`, which wrote
//! `tests/data/urdf_derivatives.txt`), to 1e-10, at two states each: the UR5,
//! UR10, Kinova (continuous joints: (cos, sin) in Pinocchio's q), Z1 and
//! xArm7; and the linearisation reads the same numbers.

use lagrange::Differentiable;
use lagrange::prelude::*;
use nalgebra::SVector;

// The files' numbers as written (`snap = 0`), as Pinocchio reads them.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", snap = 0), gravity = [0, 0, -9.81], emit(jacobians))]
pub(crate) struct Ur5 {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur10.urdf", snap = 0), gravity = [0, 0, -9.81], emit(jacobians))]
struct Ur10 {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/kinova.urdf", snap = 0), gravity = [0, 0, -9.81], emit(jacobians))]
struct Kinova {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/z1.urdf", dynamics = ignore), gravity = [0, 0, -9.81], emit(jacobians))]
struct Z1 {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/xarm7.urdf", dynamics = ignore), gravity = [0, 0, -9.81], emit(jacobians))]
pub(crate) struct Xarm7 {}

const REFERENCE: &str = include_str!("data/urdf_derivatives.txt");

fn reference(robot: &str, k: usize, key: &str) -> Vec<f64> {
    let head = format!("{robot} {k} {key} ");
    let line = REFERENCE.lines().find(|l| l.starts_with(&head));
    let line = line.unwrap_or_else(|| panic!("no {head:?} in the reference file"));
    line[head.len()..]
        .split(' ')
        .map(|x| x.parse().expect("a number"))
        .collect()
}

/// The emitted derivatives at both states against Pinocchio's, and the
/// tangent linearisation's A (which solves with M at run time) agreeing with
/// them to round-off.
fn matches_pinocchio<S: Differentiable<f64, N, N>, const N: usize>(robot: &str, sys: &S) {
    for k in 0..2 {
        let q = SVector::<f64, N>::from_column_slice(&reference(robot, k, "q"));
        let v = SVector::<f64, N>::from_column_slice(&reference(robot, k, "v"));
        let d = lagrange::acceleration_derivatives(sys, &q, &v, &SVector::zeros(), 0.0)
            .expect("a regular state");
        let a = Linearizer::new()
            .tangent(sys, &q, &v, 0.0)
            .expect("linearises");
        for (what, got, want) in [
            ("dq''/dq", d.dq, reference(robot, k, "dadq")),
            ("dq''/dv", d.dv, reference(robot, k, "dadv")),
            ("dq''/dtau", d.dtau, reference(robot, k, "dadtau")),
        ] {
            for i in 0..N {
                for j in 0..N {
                    let (g, w) = (got[(i, j)], want[N * i + j]);
                    assert!(
                        (g - w).abs() <= 1e-10 * w.abs().max(1.0),
                        "{robot}, state {k}: {what}[{i}][{j}]: {g} against Pinocchio's {w}"
                    );
                    let col = match what {
                        "dq''/dq" => j,
                        "dq''/dv" => N + j,
                        _ => continue,
                    };
                    let lin = a.a()[(N + i, col)];
                    assert!(
                        (lin - g).abs() <= 1e-12 * g.abs().max(1.0),
                        "{robot}, state {k}: {what}[{i}][{j}]: linearisation {lin}, emitted {g}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_ur5_s_acceleration_derivatives_are_pinocchio_s() {
    matches_pinocchio("ur5", &Ur5 {});
}

#[test]
fn four_more_arms_acceleration_derivatives_are_pinocchio_s() {
    matches_pinocchio("ur10", &Ur10 {});
    matches_pinocchio("kinova", &Kinova {});
    matches_pinocchio("z1", &Z1 {});
    matches_pinocchio("xarm7", &Xarm7 {});
}
