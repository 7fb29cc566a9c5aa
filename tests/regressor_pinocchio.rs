//! The emitted regressor against Pinocchio's `computeJointTorqueRegressor`
//! on the same URDF files (`lagrange-bench/peer/pinocchio/urdf_regressor.py`,
//! which wrote `tests/data/urdf_regressor.txt`), column by column to 1e-12,
//! at two states (q, q̇, q̈) each: the UR5, Kinova (continuous joints),
//! Z1 and xArm7. Pinocchio has ten columns per joint, the inertia of the
//! link the joint moves (and of the links fixed to it, merged) about the
//! joint frame; the emitted Y has ten per body, about the body's frame, which
//! for a URDF link is its joint's: each moving link's ten columns are its
//! joint's, and a link fixed to another has its own (Pinocchio merges it).

use lagrange::Lagrangian;
use nalgebra::SVector;

use crate::regressor::{Kinova, Ur5, Xarm7, Z1};

const REFERENCE: &str = include_str!("data/urdf_regressor.txt");

fn line<'a>(robot: &str, key: &str) -> std::str::SplitWhitespace<'a> {
    let head = format!("{robot} {key} ");
    let line = REFERENCE.lines().find(|l| l.starts_with(&head));
    let line = line.unwrap_or_else(|| panic!("no {head:?} in the reference file"));
    line[head.len()..].split_whitespace()
}

fn numbers(robot: &str, key: &str) -> Vec<f64> {
    line(robot, key)
        .map(|x| x.parse().expect("a number"))
        .collect()
}

/// Max |Y − Y_Pinocchio| / (1 + |Y_Pinocchio|) over both states and every
/// moving link's columns.
fn against_pinocchio<S: Lagrangian<f64, N>, const N: usize>(robot: &str, sys: &S) -> f64 {
    let links: Vec<&str> = line(robot, "links").collect();
    let mut worst = 0.0f64;
    for k in 0..2 {
        let state = |key: &str| {
            SVector::<f64, N>::from_column_slice(&numbers(robot, &format!("{k} {key}")))
        };
        let y = sys
            .regressor(&state("q"), &state("v"), &state("a"), 0.0)
            .expect("Y is emitted");
        let want = numbers(robot, &format!("{k} y"));
        let joints = links.len();
        for (j, link) in links.iter().enumerate() {
            let first = S::REGRESSOR_PARAMETERS
                .iter()
                .position(|n| *n == format!("{link}.m"))
                .unwrap_or_else(|| panic!("{robot}: no body {link}"));
            for c in 0..10 {
                for i in 0..N {
                    let theirs = want[i * 10 * joints + 10 * j + c];
                    let ours = y[(i, first + c)];
                    worst = worst.max((ours - theirs).abs() / (1.0 + theirs.abs()));
                }
            }
        }
    }
    worst
}

#[test]
fn columns_agree_with_pinocchio() {
    for (robot, err) in [
        ("ur5", against_pinocchio("ur5", &Ur5 {})),
        ("kinova", against_pinocchio("kinova", &Kinova {})),
        ("z1", against_pinocchio("z1", &Z1 {})),
        ("xarm7", against_pinocchio("xarm7", &Xarm7 {})),
    ] {
        eprintln!("{robot}: max |Y − Y_Pinocchio| / (1 + |Y_Pinocchio|) = {err:.1e}");
        assert!(err < 1e-12, "{robot}: {err:e}");
    }
}

/// The number of base parameters [`BaseParameters::of`] finds against the
/// numerical rank of Pinocchio's regressor stacked at random states
/// (singular values below 1e-9 of the largest counted as zero; the genuine
/// ones end above 1, round-off lies below 1e-11): the emitted Y has ten
/// more columns per link fixed to another, which add no base parameter.
#[test]
fn base_parameter_counts_agree_with_pinocchios_rank() {
    use lagrange::identify::BaseParameters;
    let rank = |robot: &str| -> usize {
        let mut it = line(robot, "rank");
        it.next().expect("a rank").parse().expect("a count")
    };
    let counts = [
        ("ur5", BaseParameters::of(&Ur5 {}).expect("Y").len()),
        ("kinova", BaseParameters::of(&Kinova {}).expect("Y").len()),
        ("z1", BaseParameters::of(&Z1 {}).expect("Y").len()),
        ("xarm7", BaseParameters::of(&Xarm7 {}).expect("Y").len()),
    ];
    for (robot, count) in counts {
        eprintln!("{robot}: {count} base parameters");
        assert_eq!(count, rank(robot), "{robot}");
    }
}
