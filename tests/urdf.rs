//! Robots straight from their URDF files (`robots/`, from the PyPI package
//! `example-robot-data`): the derived M and Q − h against Pinocchio's
//! `crba`, `nonLinearEffects`, `rnea` and `computeGeneralizedGravity` on the
//! same files
//! (`lagrange-bench/peer/pinocchio/urdf_reference.py`), to 1e-12, and the
//! published joint limits.

use lagrange::Route;
use lagrange::prelude::*;
use nalgebra::SVector;

/// The file's numbers as written (`snap = 0`), as Pinocchio reads them: the
/// references below were computed by Pinocchio on this file.
#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/ur5.urdf", snap = 0),
    gravity = [0, 0, -9.81],
    emit(inverse_dynamics, kinematics)
)]
struct Ur5 {}

#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/panda.urdf", dynamics = ignore),
    gravity = [0, 0, -9.81],
    emit(inverse_dynamics, kinematics)
)]
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
#[lagrange(urdf("robots/ur5.urdf", snap = 0), gravity = [0, 0, -9.81])]
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

/// The file's `1.57079632679` (π/2 to twelve digits, 5e-12 off) is read as
/// the exact quarter turn by default and listed; `snap = 0` (`Ur5`) keeps
/// the file's numbers. The motion changes by the 5e-12 the angles moved.
#[derive(Lagrangian)]
#[lagrange(urdf = "robots/ur5.urdf", gravity = [0, 0, -9.81])]
struct Ur5Default {}

/// The xArm7's `1.5708` is 3.7e-6 from π/2, beyond even the largest
/// tolerance: kept.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/xarm7.urdf", dynamics = ignore, snap = 1e-6), gravity = [0, 0, -9.81])]
struct Xarm7Snapped {}

#[test]
fn quarter_turns_written_to_nine_decimals_or_more_are_made_exact() {
    assert!(Ur5::URDF_SNAPPED.is_empty());
    // Three quarter turns, a half turn and a negative quarter turn.
    let snapped = Ur5Default::URDF_SNAPPED;
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
    let (ms, fs) = Ur5Default {}.mass_matrix_and_rhs(&q, &v, 0.0);
    assert!((m - ms).amax() < 1e-9 && (f - fs).amax() < 1e-9);
    assert!(
        (m - ms).amax() > 0.0,
        "the snapped angles change the motion"
    );

    assert!(Xarm7Snapped::URDF_SNAPPED.is_empty());
}

/// What Pinocchio gives for one frame and the centre of mass.
struct FrameReference<'a> {
    frame: &'a str,
    row0: &'a [f64],
    row5: &'a [f64],
    /// Rows 0 and 5 of the Jacobian in the frame's own axes (`LOCAL`).
    local: [&'a [f64]; 2],
    bias: [f64; 6],
    com: [f64; 3],
    com_row0: &'a [f64],
}

fn close_all(name: &str, ours: impl Iterator<Item = f64>, theirs: &[f64]) {
    for (k, (a, b)) in ours.zip(theirs).enumerate() {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs().max(1.0),
            "{name}[{k}]: {a} vs {b}"
        );
    }
}

/// The frame Jacobian (LOCAL_WORLD_ALIGNED), J̇ q̇, the centre of mass and
/// its Jacobian against `computeFrameJacobian`, `getFrameClassicalAcceleration`,
/// `centerOfMass` and `jacobianCenterOfMass`.
fn kinematics_agree<S: lagrange::Kinematics<f64, N>, const N: usize>(
    sys: &S,
    arm: usize,
    r: FrameReference,
) {
    let (q, v) = state::<N>(arm);
    let body = S::body_index(r.frame).expect("the frame is a body");
    let j = sys.frame_jacobian(body, &q, 0.0).expect("a body");
    close_all("J row 0", (0..arm).map(|k| j[(0, k)]), r.row0);
    close_all("J row 5", (0..arm).map(|k| j[(5, k)]), r.row5);
    let local = sys.frame_jacobian_local(body, &q, 0.0).expect("a body");
    close_all("J local row 0", (0..arm).map(|k| local[(0, k)]), r.local[0]);
    close_all("J local row 5", (0..arm).map(|k| local[(5, k)]), r.local[1]);
    let bias = sys.frame_bias(body, &q, &v, 0.0).expect("a body");
    close_all("Jdot v", bias.iter().copied(), &r.bias);
    close_all("com", sys.center_of_mass(&q, 0.0).iter().copied(), &r.com);
    let jc = sys.center_of_mass_jacobian(&q, 0.0);
    close_all("Jcom row 0", (0..arm).map(|k| jc[(0, k)]), r.com_row0);
    assert!(sys.frame_jacobian(S::BODIES.len(), &q, 0.0).is_none());
}

#[test]
fn ur5_frames_and_centre_of_mass_match_pinocchio() {
    kinematics_agree(
        &Ur5 {},
        6,
        FrameReference {
            frame: "tool0",
            local: [
                &[
                    -0.11653700301507783,
                    0.6227178549425902,
                    0.324236027321386,
                    0.05897934751853523,
                    -0.07016276816549731,
                    0.0,
                ],
                &[
                    -0.044403708129536645,
                    0.9286646355774596,
                    0.9286646355774596,
                    0.9286646355774596,
                    4.174504524882494e-12,
                    1.0,
                ],
            ],
            row0: &[
                -0.4116675019269206,
                -0.1795775939757901,
                -0.1269437976382908,
                -0.09326354258140457,
                0.06346915364971446,
                2.6020852139652106e-18,
            ],
            row5: &[1.0, 0.0, 0.0, 0.0, -0.992808635852694, -0.04440370812567669],
            bias: [
                -0.22204384860097487,
                -0.20840704245392314,
                0.027888948584321945,
                0.33263042670397713,
                0.2602011492845997,
                -0.018051629597868046,
            ],
            com: [
                0.3132534424371484,
                0.18006597942719585,
                0.045848805741710276,
            ],
            com_row0: &[
                -0.18006597942719585,
                -0.04137580892606247,
                -0.009070578288644392,
                -0.0009926045284632584,
                0.0,
                0.0,
            ],
        },
    );
}

#[test]
fn panda_frames_and_centre_of_mass_match_pinocchio() {
    kinematics_agree(
        &Panda {},
        7,
        FrameReference {
            frame: "panda_hand",
            local: [
                &[
                    0.13191106368729374,
                    0.2604964726147533,
                    0.06683627078156168,
                    -0.10189741530891945,
                    0.019053805908450475,
                    0.0069926165186352494,
                    0.0,
                ],
                &[
                    -0.6429191563196264,
                    0.21981153381080126,
                    -0.7326086640678745,
                    -0.1938753923111311,
                    -0.8525245220595057,
                    2.220446049250313e-16,
                    1.0,
                ],
            ],
            row0: &[
                -0.032999588220948506,
                0.5320632934542463,
                -0.011385109072863487,
                -0.24571816181376027,
                0.001891131633072354,
                0.13537465330231213,
                -1.2468324983583301e-18,
            ],
            row5: &[
                1.0,
                2.220446049250313e-16,
                0.9915618937147881,
                0.005183983051216994,
                0.942776281462301,
                0.1284737534299602,
                -0.6429191563196266,
            ],
            bias: [
                -0.09302309802784717,
                0.1496098522593604,
                0.02460812488863324,
                -0.022442575539986298,
                0.03912917951738135,
                -0.6294666445240152,
            ],
            com: [
                0.07648172785261936,
                0.026244227702494058,
                0.6166196289472685,
            ],
            com_row0: &[
                -0.02624422770249405,
                0.2843947062602523,
                -0.01360877197873552,
                -0.10273767230503518,
                -0.0032506426596487325,
                0.01726874834800034,
                -1.2964046748144731e-05,
            ],
        },
    );
}
