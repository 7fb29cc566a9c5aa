//! Linearisation of constrained systems with orientations
//! (`Linearizer::constrained_tangent`): the rolling disk with a quaternion
//! against the Euler-angle disk's symbolic linearisation (`constrained`) and
//! the closed form of its critical spin, the rolling sphere's neutral
//! stability and its input matrix against the closed form, and A against
//! central differences of the nonlinear dynamics on the constraints.

#[path = "../examples/catalog/mod.rs"]
mod catalog;

use catalog::constrained::RollingDisk;
use catalog::rolling::{QuaternionDisk, QuaternionSphere};
use lagrange::linear::{Linear, Linearizer, OperatingPoint, Verdict, sweep};
use lagrange::nalgebra::{DMatrix, SVector};
use lagrange::prelude::*;

const M: f64 = 1.0;
const A: f64 = 0.5;
const G: f64 = 9.81;

const DISK_COORDINATES: [&str; 5] = ["x", "y", "disk_q.θx", "disk_q.θy", "disk_q.θz"];
const DISK_SPEEDS: [&str; 3] = ["disk_q.wx", "disk_q.wy", "disk_q.wz"];

/// The quaternion disk rolling upright along x at spin ω about its axle
/// (body y, here world y): centre (0, 0, a), identity orientation.
fn upright(spin: f64) -> OperatingPoint<f64, 6, 0, 7> {
    OperatingPoint::on_group(
        SVector::from([0.0, 0.0, A, 1.0, 0.0, 0.0, 0.0]),
        SVector::from([A * spin, 0.0, 0.0, 0.0, spin, 0.0]),
    )
}

fn disk_linear(spin: f64) -> Result<Linear, lagrange::Error> {
    Linearizer::new()
        .coordinates(&DISK_COORDINATES)
        .speeds(&DISK_SPEEDS)
        .constrained_tangent(&QuaternionDisk::thin(M, A, G), &upright(spin))
}

/// The chart disk's states (x, y, ψ, θ, φ, ψ', θ', φ') to the quaternion
/// disk's (x, y, θx, θy, θz, wx', wy', wz') about upright rolling at spin ω:
/// the centre is the contact point less a θ in y; the rotation
/// rot_z(ψ) rot_x(θ) rot_y(ωt + φ) is the fixed-axes turn (θ, φ, ψ) of the
/// reference; its angular velocity in space axes changes by
/// (θ' − ω ψ, φ', ψ' + ω θ).
fn chart_to_group(spin: f64) -> DMatrix<f64> {
    let mut t = DMatrix::zeros(8, 8);
    for (row, entries) in [
        (0, vec![(0, 1.0)]),
        (1, vec![(1, 1.0), (3, -A)]),
        (2, vec![(3, 1.0)]),
        (3, vec![(4, 1.0)]),
        (4, vec![(2, 1.0)]),
        (5, vec![(6, 1.0), (2, -spin)]),
        (6, vec![(7, 1.0)]),
        (7, vec![(5, 1.0), (3, spin)]),
    ] {
        for (col, x) in entries {
            t[(row, col)] = x;
        }
    }
    t
}

fn chart_linear(spin: f64) -> Linear {
    let v = SVector::from([A * spin, 0.0, 0.0, 0.0, spin]);
    Linearizer::new()
        .coordinates(&["x", "y", "psi", "theta", "phi"])
        .speeds(&["psi", "theta", "phi"])
        .constrained(
            &RollingDisk::thin(M, A, G),
            &OperatingPoint::new(SVector::zeros(), v),
        )
        .unwrap()
}

/// Eigenvalues with a non-zero imaginary part or a real part above `floor`,
/// sorted: what the two models must share (their zero eigenvalues sit in
/// Jordan chains, which a numerical eigen-solver spreads by √ε).
fn moving(lin: &Linear, floor: f64) -> Vec<(f64, f64)> {
    let mut ev: Vec<(f64, f64)> = lin
        .eigenvalues()
        .iter()
        .filter(|z| z.norm() > floor)
        .map(|z| (z.re, z.im))
        .collect();
    ev.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0)));
    ev
}

/// Upright rolling at spins below, near and above the critical one: the
/// quaternion disk's A is the chart disk's in the quaternion's states,
/// T A_chart T⁻¹, entry by entry, and the eigenvalues agree.
#[test]
fn the_quaternion_disk_linearises_as_the_chart_disk() {
    for spin in [1.0, 2.0, 2.6, 5.0] {
        let lin = disk_linear(spin).unwrap();
        assert_eq!(
            lin.states(),
            [
                "x",
                "y",
                "disk_q.θx",
                "disk_q.θy",
                "disk_q.θz",
                "disk_q.wx'",
                "disk_q.wy'",
                "disk_q.wz'"
            ]
        );
        let chart = chart_linear(spin);
        let t = chart_to_group(spin);
        let want = &t * chart.a() * t.clone().try_inverse().unwrap();
        let gap = (lin.a() - &want).amax() / want.amax();
        let (ours, theirs) = (moving(&lin, 1e-6), moving(&chart, 1e-6));
        assert_eq!(ours.len(), theirs.len(), "{ours:?} vs {theirs:?}");
        let eig_gap = ours
            .iter()
            .zip(&theirs)
            .map(|(a, b)| (a.0 - b.0).abs().max((a.1 - b.1).abs()))
            .fold(0.0, f64::max);
        eprintln!(
            "disk upright at ω = {spin}: A gap {gap:.1e} (relative), eigenvalue gap {eig_gap:.1e}, \
             eigenvalues {ours:?}"
        );
        assert!(gap < 1e-8, "{}\nvs\n{want}", lin.a());
        assert!(eig_gap < 1e-8);
    }
}
