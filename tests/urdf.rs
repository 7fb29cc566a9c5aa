//! Robots straight from their URDF files (`robots/`, from the PyPI package
//! `example-robot-data`): the derived M and Q − h against Pinocchio's
//! `crba`, `nonLinearEffects`, `rnea` and `computeGeneralizedGravity` on the
//! same files
//! (`lagrange-bench/peer/pinocchio/urdf_reference.py`), to 1e-12, and the
//! published joint limits.

use lagrange::Route;
use lagrange::prelude::*;
use nalgebra::SVector;

#[derive(Lagrangian)]
#[lagrange(urdf = "robots/ur5.urdf", gravity = [0, 0, -9.81], emit(inverse_dynamics))]
struct Ur5 {}

#[derive(Lagrangian)]
#[lagrange(urdf = "robots/panda.urdf", gravity = [0, 0, -9.81], emit(inverse_dynamics))]
struct Panda {}

/// τ by recursive Newton–Euler at q̈_k = 0.1 + 0.05 k (the fingers at rest)
/// and the gravity torques, against Pinocchio's `rnea` and
/// `computeGeneralizedGravity`; and τ at the accelerations the dynamics give
/// is zero.
fn inverse_agrees<S: Lagrangian<f64, N>, const N: usize>(
    name: &str,
    sys: &S,
    arm: usize,
    rnea: &[f64],
    gravity: &[f64],
) {
    let (q, v) = state::<N>(arm);
    let a = SVector::<f64, N>::from_fn(|k, _| if k < arm { 0.1 + 0.05 * k as f64 } else { 0.0 });
    let tau = sys.inverse_dynamics(&q, &v, &a, 0.0);
    let g = sys.gravity_torques(&q, 0.0).expect("emitted");
    for k in 0..arm {
        assert!(
            (tau[k] - rnea[k]).abs() <= 1e-12 * rnea[k].abs().max(1.0),
            "{name}: tau[{k}] {} vs {}",
            tau[k],
            rnea[k]
        );
        assert!(
            (g[k] - gravity[k]).abs() <= 1e-12 * gravity[k].abs().max(1.0),
            "{name}: g[{k}] {} vs {}",
            g[k],
            gravity[k]
        );
    }
    let qdd = lagrange::accelerations(sys, &q, &v, 0.0).unwrap();
    let rest = sys.inverse_dynamics(&q, &v, &qdd, 0.0);
    assert!(
        rest.amax() < 1e-10,
        "{name}: tau at the free accelerations {rest}"
    );
}

/// The state the reference script uses: q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k
/// on the arm's joints, the fingers at 0.02 and at rest.
fn state<const N: usize>(arm: usize) -> (SVector<f64, N>, SVector<f64, N>) {
    let q = SVector::from_fn(|k, _| if k < arm { 0.3 - 0.17 * k as f64 } else { 0.02 });
    let v = SVector::from_fn(|k, _| if k < arm { 0.5 - 0.21 * k as f64 } else { 0.0 });
    (q, v)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

/// Row 0 of M, its diagonal and Q − h on the first `reference.len()` joints.
fn agrees<const N: usize>(
    name: &str,
    (m, f): (nalgebra::SMatrix<f64, N, N>, SVector<f64, N>),
    row0: &[f64],
    diag: &[f64],
    rhs: &[f64],
) {
    for k in 0..row0.len() {
        assert!(
            close(m[(0, k)], row0[k]),
            "{name}: M[0][{k}] {} vs {}",
            m[(0, k)],
            row0[k]
        );
        assert!(
            close(m[(k, k)], diag[k]),
            "{name}: M[{k}][{k}] {} vs {}",
            m[(k, k)],
            diag[k]
        );
        assert!(
            close(f[k], rhs[k]),
            "{name}: (Q - h)[{k}] {} vs {}",
            f[k],
            rhs[k]
        );
    }
}

#[test]
fn ur5_from_its_urdf_matches_pinocchio() {
    let (q, v) = state::<6>(6);
    agrees(
        "UR5",
        Ur5 {}.mass_matrix_and_rhs(&q, &v, 0.0),
        &[
            4.319483539164107,
            0.059266121006629396,
            0.006310676305278529,
            -0.0006227903818485613,
            -0.24606852604913182,
            -0.0007609229518518384,
        ],
        &[
            4.319483539164107,
            3.9720782121626415,
            0.8403528895878274,
            0.2417924794146909,
            0.24868348170529445,
            0.0171364731454,
        ],
        &[
            0.08942250497005594,
            58.662849091233696,
            15.624483593317478,
            0.02984933118715202,
            -0.0038020908595054813,
            0.00604661544350677,
        ],
    );
    inverse_agrees(
        "UR5",
        &Ur5 {},
        6,
        &[
            0.2784353239150551,
            -57.689203886716314,
            -15.1604001927325,
            0.12235062416422743,
            0.0554549883948916,
            0.009423479815381774,
        ],
        &[
            -1.1102230246251565e-16,
            -58.761259878292094,
            -15.641237825825822,
            -0.020885979352930614,
            0.0,
            0.0,
        ],
    );
    assert_eq!(Ur5::ROBOT, "ur5");
    // The file's ±6.28318530718, kept as written (not 2π).
    let (lower, upper) = Ur5::JOINT_LIMITS[0];
    assert!(
        lower == -upper
            && (upper - std::f64::consts::TAU).abs() < 1e-10
            && upper != std::f64::consts::TAU
    );
    assert_eq!(
        <Ur5 as Lagrangian<f64, 6>>::COORDINATES,
        [
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint"
        ]
    );
}

#[test]
fn panda_from_its_urdf_matches_pinocchio_on_the_arm() {
    let (q, v) = state::<8>(7);
    agrees(
        "Panda",
        Panda {}.mass_matrix_and_rhs(&q, &v, 0.0),
        &[
            0.29058702621609,
            -0.0160279716253119,
            0.16110291081885933,
            0.012989869102031398,
            0.04458813383534247,
            -0.010246788870440159,
            -0.003888289574017855,
        ],
        &[
            0.29058702621609,
            2.817909233952939,
            0.11297098422206134,
            0.5773093058923416,
            0.026863069785381517,
            0.0538414143058625,
            0.006696151967360947,
        ],
        &[
            -0.23082727593350477,
            13.371949925909558,
            -0.15498816047242353,
            -1.7559629687647642,
            -0.1045651244930427,
            -0.15486091567440036,
            -0.005750803349196086,
        ],
    );
    inverse_agrees(
        "Panda",
        &Panda {},
        7,
        &[
            0.3011845804669382,
            -13.195590220923204,
            0.20122723165348927,
            1.7151092470564209,
            0.12250288257153022,
            0.17841779500209404,
            0.005317400205041516,
        ],
        &[
            -2.914335439641036e-16,
            -13.148620505166942,
            0.036814207115614256,
            1.6319038361635216,
            0.08569502542388215,
            0.1955012471817792,
            0.00288857296301313,
        ],
    );
    assert_eq!(Panda::JOINT_LIMITS[7], (0.0, 0.04));
    // The fingers slide: a prismatic joint on the recursive route.
    assert_eq!(<Panda as Lagrangian<f64, 8>>::ROUTE, Route::Recursive);
}

/// The UR5 with a payload: a field named `<link>_mass` replaces that link's
/// mass from the file.
#[derive(Lagrangian)]
#[lagrange(urdf = "robots/ur5.urdf", gravity = [0, 0, -9.81])]
struct Ur5Payload {
    wrist_3_link_mass: f64,
}

#[test]
fn a_field_named_for_a_link_overrides_its_mass() {
    let (q, v) = state::<6>(6);
    let (m, f) = Ur5 {}.mass_matrix_and_rhs(&q, &v, 0.0);
    let same = Ur5Payload {
        wrist_3_link_mass: 0.1879,
    }
    .mass_matrix_and_rhs(&q, &v, 0.0);
    assert!((same.0 - m).amax() < 1e-14 && (same.1 - f).amax() < 1e-12);
    let heavy = Ur5Payload {
        wrist_3_link_mass: 2.0,
    }
    .mass_matrix_and_rhs(&q, &v, 0.0);
    assert!((heavy.0 - m).amax() > 1e-3 && (heavy.1 - f).amax() > 1e-2);
}

/// `snap` makes the file's `1.57079632679` an exact quarter turn and says so;
/// the motion changes by the 1e-12 it moved.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", snap = 1e-6), gravity = [0, 0, -9.81])]
struct Ur5Snapped {}

#[test]
fn snapping_reports_the_angles_it_made_exact() {
    assert!(Ur5::URDF_SNAPPED.is_empty());
    // Three quarter turns, a half turn and a negative quarter turn.
    let snapped = Ur5Snapped::URDF_SNAPPED;
    assert_eq!(snapped.len(), 5, "{snapped:?}");
    for &(at, written, exact) in snapped {
        let k = exact / std::f64::consts::FRAC_PI_2;
        assert!(at.starts_with("joint `") && k == k.round(), "{at}: {exact}");
        assert!(
            written != exact && (written - exact).abs() < 1e-10,
            "{at}: {written}"
        );
    }
    let (q, v) = state::<6>(6);
    let (m, f) = Ur5 {}.mass_matrix_and_rhs(&q, &v, 0.0);
    let (ms, fs) = Ur5Snapped {}.mass_matrix_and_rhs(&q, &v, 0.0);
    assert!((m - ms).amax() < 1e-9 && (f - fs).amax() < 1e-9);
}
