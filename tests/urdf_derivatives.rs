//! ∂q̈/∂q and ∂q̈/∂q̇ of a robot read from its URDF (`emit(jacobians)` and
//! [`lagrange::acceleration_derivatives`]) against Pinocchio's
//! `computeABADerivatives` on the same file
//! (`lagrange-bench/peer/pinocchio/urdf_derivatives.py`, which wrote
//! `tests/data/urdf_derivatives.txt`), to 1e-10, at two states; and the
//! linearisation reads the same numbers.

use lagrange::prelude::*;
use nalgebra::SVector;

#[derive(Lagrangian)]
#[lagrange(urdf = "robots/ur5.urdf", gravity = [0, 0, -9.81], emit(jacobians))]
struct Ur5 {}

const REFERENCE: &str = include_str!("data/urdf_derivatives.txt");

fn reference(k: usize, key: &str) -> Vec<f64> {
    let head = format!("ur5 {k} {key} ");
    let line = REFERENCE.lines().find(|l| l.starts_with(&head));
    let line = line.unwrap_or_else(|| panic!("no {head:?} in the reference file"));
    line[head.len()..]
        .split(' ')
        .map(|x| x.parse().expect("a number"))
        .collect()
}

#[test]
fn the_ur5_s_acceleration_derivatives_are_pinocchio_s() {
    for k in 0..2 {
        let q = SVector::<f64, 6>::from_column_slice(&reference(k, "q"));
        let v = SVector::<f64, 6>::from_column_slice(&reference(k, "v"));
        let (dq, dv) = lagrange::acceleration_derivatives(&Ur5 {}, &q, &v, 0.0)
            .expect("a regular state")
            .expect("emit(jacobians)");
        let a = Linearizer::new()
            .tangent(&Ur5 {}, &q, &v, 0.0)
            .expect("linearises");
        for (what, got, want) in [
            ("dq''/dq", dq, reference(k, "dadq")),
            ("dq''/dv", dv, reference(k, "dadv")),
        ] {
            for i in 0..6 {
                for j in 0..6 {
                    let (g, w) = (got[(i, j)], want[6 * i + j]);
                    assert!(
                        (g - w).abs() <= 1e-10 * w.abs().max(1.0),
                        "state {k} {what}[{i}][{j}]: {g} against Pinocchio's {w}"
                    );
                    let col = if what == "dq''/dq" { j } else { 6 + j };
                    assert_eq!(a.a()[(6 + i, col)], g, "the linearisation reads them");
                }
            }
        }
    }
}
