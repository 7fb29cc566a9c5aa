//! Our side of the CasADi peer (`peer/casadi/`): the quantities that
//! `casadi_codegen.py` traces from Pinocchio into C, computed by the code
//! `#[derive(Lagrangian)]` emits for the same URDF files, at the same state,
//! timed with the same loop as the C harness (`peer/casadi/harness.c`): the
//! median over batches of the mean time of one call in a batch
//! ([`timing`]).
//!
//! It prints, per arm and quantity, one `value` line (the outputs, each
//! matrix row-major) and one `time` line (ns per call), which
//! `peer/casadi/compare.py` reads:
//!
//!     cargo run --release -p lagrange-bench --example casadi_peer [--wide] [--interleave LIB] [ARM ...]
//!
//! With `--interleave` (`run.sh` passes the `libharness.so` that
//! `casadi_codegen.py` builds), each quantity's batches alternate with
//! those of the C's function in this process, and a `pair` line gives both
//! times and the median of the batches' ratios ([`timing`]).
//!
//! The quantities, each beside its CasADi function:
//! - `crba_nle`: M and Q − h in one call (`mass_matrix_and_rhs`), beside
//!   CRBA's M and NLE's h (Q − h = −nle, gravity being in nle);
//! - `rnea`: τ(q, q̇, q̈) (`inverse_dynamics`, `emit(inverse_dynamics)`);
//! - `aba`: q̈(q, q̇, τ) by the articulated-body algorithm (`emit(articulated)`),
//!   through [`Dynamics`] with τ as its forcing, as `lagrange::accelerations`;
//! - `chol`: q̈(q, q̇, τ) from M and its Cholesky factorisation, the same way;
//! - `aba_derivatives`: ∂q̈/∂q, ∂q̈/∂q̇ and M⁻¹ from the program
//!   `emit(jacobians)` emits (`lagrange::acceleration_derivatives`), beside
//!   `computeABADerivatives`; `aba_derivatives_runtime` the same from M's
//!   Cholesky factorisation at run time (`Dynamics::acceleration_derivatives`
//!   with τ as a forcing);
//! - `rnea_derivatives`: ∂τ/∂q and ∂τ/∂q̇ at q̈, which are −J_q and −J_v of
//!   `rhs_jacobians` at a = q̈, beside `computeRNEADerivatives`.
//!
//! `crba_nle`, `aba` and `chol` are timed twice: as
//! called (the parameter-only terms computed in each call) and with the
//! terms computed once (`parameter_terms`, `_with`; suffix `_terms`), as a
//! loop of its own would call them. The values are the same.
//!
//! The state: q_k = 0.3 − 0.17 k (every angle within 0.55 rad, where the C
//! library's sin and cos take their short path), or with `--wide`
//! q_k = 2.8 − 0.93 k (spread over a turn, as a moving arm's are);
//! q̇_k = 0.5 − 0.21 k, q̈_k = τ_k = 0.1 k − 0.2. Solo 12 (`base = floating`)
//! is at the same physical state as the C's Pinocchio free flyer, whose
//! pattern (`casadi_codegen.state`) is mapped to this crate's coordinates
//! ([`solo_state`]); its values are checked in this crate's convention
//! (`floating_reference.py`).

use lagrange::nalgebra::{Quaternion, SMatrix, SVector, UnitQuaternion, Vector3};
use lagrange::{Differentiable, Dynamics, Error, Forcing, Lagrangian};
use std::hint::black_box;

mod timing;
use timing::{Peer, Timer};

/// An arm with M + Cholesky q̈, the inverse dynamics and the Jacobians, and
/// its twin with `emit(articulated)`, whose q̈ is the articulated one.
macro_rules! arm {
    ($name:ident, $articulated:ident, $file:tt) => {
        #[derive(Lagrangian, Default)]
        #[lagrange(urdf($file, dynamics = ignore), gravity = [0, 0, -9.81], emit(jacobians, inverse_dynamics))]
        struct $name {}

        #[derive(Lagrangian, Default)]
        #[lagrange(urdf($file, dynamics = ignore), gravity = [0, 0, -9.81], emit(articulated))]
        struct $articulated {}
    };
}

arm!(Ur5, Ur5Articulated, "../robots/ur5.urdf");
arm!(Ur10, Ur10Articulated, "../robots/ur10.urdf");
arm!(Kinova, KinovaArticulated, "../robots/kinova.urdf");
arm!(Z1, Z1Articulated, "../robots/z1.urdf");
arm!(Xarm7, Xarm7Articulated, "../robots/xarm7.urdf");

/// Solo 12 on a free root, with the same outputs.
#[derive(Lagrangian, Default)]
#[lagrange(urdf("../robots/solo12.urdf", base = floating), gravity = [0, 0, -9.81], emit(jacobians, inverse_dynamics))]
struct Solo12 {}

#[derive(Lagrangian, Default)]
#[lagrange(urdf("../robots/solo12.urdf", base = floating), gravity = [0, 0, -9.81], emit(articulated))]
struct Solo12Articulated {}

/// Constant joint torques τ, added to Q as a forcing.
struct Torques<const N: usize>(SVector<f64, N>);

impl<const N: usize, const Q: usize> Forcing<f64, N, Q> for Torques<N> {
    fn force(
        &self,
        _: f64,
        _: &SVector<f64, Q>,
        _: &SVector<f64, N>,
    ) -> Result<SVector<f64, N>, Error> {
        Ok(self.0)
    }
}

/// Prints one `value` line: the outputs, comma-separated, matrices row-major.
fn value(robot: &str, quantity: &str, outputs: &[(&str, &[f64], usize)]) {
    for (name, data, rows) in outputs {
        // nalgebra stores columns; print rows.
        let cols = data.len() / rows;
        let text: Vec<String> = (0..*rows)
            .flat_map(|i| (0..cols).map(move |j| format!("{:e}", data[j * rows + i])))
            .collect();
        println!("value {robot} {quantity} {name} {}", text.join(","));
    }
}

/// Joint angle k of the wide state (spread over a turn) or the small one
/// (within 0.55 rad).
fn angle(k: usize, wide: bool) -> f64 {
    match wide {
        true => 2.8 - 0.93 * k as f64,
        false => 0.3 - 0.17 * k as f64,
    }
}

/// Where the quantities are taken: q̈ = `a` for the inverse dynamics and its
/// derivatives, the joint forces `tau` for q̈ and its derivatives.
struct State<const N: usize, const Q: usize> {
    q: SVector<f64, Q>,
    v: SVector<f64, N>,
    a: SVector<f64, N>,
    tau: SVector<f64, N>,
}

/// An arm's state: the same pattern as the C's.
fn arm_state<const N: usize>(wide: bool) -> State<N, N> {
    let a = SVector::from_fn(|k, _| 0.1 * k as f64 - 0.2);
    State {
        q: SVector::from_fn(|k, _| angle(k, wide)),
        v: SVector::from_fn(|k, _| 0.5 - 0.21 * k as f64),
        a,
        tau: a,
    }
}

/// Solo 12's state: the C's (Pinocchio's free flyer: q = (x, y, z, qx, qy,
/// qz, qw, joints leg by leg), v = (root velocity and ω in root axes, joint
/// rates), a = τ zero on the root) in this crate's coordinates (joints
/// breadth-first, the quaternion last, scalar first; ẋ in world axes). With
/// v_pin = P v: τ = Pᵀ τ_pin, and q̈ = Pᵀ (a_pin − Ṗ v), Ṗ v = (−ω × v_lin, 0).
fn solo_state(wide: bool) -> State<18, 19> {
    const LEGS: [&str; 4] = ["FL", "FR", "HL", "HR"];
    const JOINTS: [&str; 3] = ["HAA", "HFE", "KFE"];
    // Pinocchio's index (leg by leg) of our joint k, by its name.
    let pinocchio = |k: usize| {
        let name = <Solo12 as Lagrangian<f64, 18, 19>>::COORDINATES[3 + k];
        let (leg, joint) = name.split_once('_').expect("LEG_JOINT");
        let at = |list: &[&str], x: &str| list.iter().position(|y| *y == x).expect("a Solo joint");
        3 * at(&LEGS, leg) + at(&JOINTS, joint)
    };
    // casadi_codegen.py's ROOT_POSITION and ROOT_QUATERNION (x, y, z, w).
    let (x, y, z, w) = (0.1, -0.15, 0.25, 0.95);
    let rotation = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
    let v_pin = |k: usize| 0.5 - 0.21 * k as f64;
    let v_lin = Vector3::new(v_pin(0), v_pin(1), v_pin(2));
    let omega = Vector3::new(v_pin(3), v_pin(4), v_pin(5));
    let (mut q, mut v) = (SVector::<f64, 19>::zeros(), SVector::<f64, 18>::zeros());
    let (mut a, mut tau) = (SVector::<f64, 18>::zeros(), SVector::<f64, 18>::zeros());
    q.fixed_rows_mut::<3>(0).copy_from_slice(&[0.1, -0.2, 0.3]);
    q.fixed_rows_mut::<4>(15)
        .copy_from_slice(&[rotation.w, rotation.i, rotation.j, rotation.k]);
    v.fixed_rows_mut::<3>(0).copy_from(&(rotation * v_lin));
    v.fixed_rows_mut::<3>(15).copy_from(&omega);
    a.fixed_rows_mut::<3>(0)
        .copy_from(&(rotation * omega.cross(&v_lin)));
    for k in 0..12 {
        let p = pinocchio(k);
        q[3 + k] = angle(p, wide);
        v[3 + k] = v_pin(6 + p);
        (a[3 + k], tau[3 + k]) = (0.1 * p as f64 - 0.2, 0.1 * p as f64 - 0.2);
    }
    State { q, v, a, tau }
}

/// Values and times of one robot at a state.
fn robot<S, A, const N: usize, const Q: usize>(timer: &Timer, at: &State<N, Q>)
where
    S: Differentiable<f64, N, Q> + Default,
    A: Lagrangian<f64, N, Q> + Default,
{
    let robot = timer.robot;
    let (sys, articulated) = (S::default(), A::default());
    let State { q, v, a, tau } = at;
    let (q, v, a, tau) = (*q, *v, *a, *tau);
    let forced = Dynamics::new(&sys).with_forcing(Torques(tau));
    let forced_articulated = Dynamics::new(&articulated).with_forcing(Torques(tau));
    // The parameter-only terms computed once, as a loop of its own would.
    let (terms, articulated_terms) = (sys.parameter_terms(), articulated.parameter_terms());
    let kept = Dynamics::new(&sys)
        .with_parameter_terms(&terms)
        .with_forcing(Torques(tau));
    let kept_articulated = Dynamics::new(&articulated)
        .with_parameter_terms(&articulated_terms)
        .with_forcing(Torques(tau));

    let (m, rhs) = sys.mass_matrix_and_rhs(&q, &v, 0.0);
    value(
        robot,
        "crba_nle",
        &[("M", m.as_slice(), N), ("rhs", rhs.as_slice(), N)],
    );
    timer.time("crba_nle", || {
        sys.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0)
    });
    timer.time("crba_nle_terms", || {
        sys.mass_matrix_and_rhs_with(&terms, black_box(&q), black_box(&v), 0.0)
    });

    let id = sys.inverse_dynamics(&q, &v, &a, 0.0);
    value(robot, "rnea", &[("tau", id.as_slice(), N)]);
    timer.time("rnea", || {
        sys.inverse_dynamics(black_box(&q), black_box(&v), black_box(&a), 0.0)
    });

    let ddq = forced_articulated.acceleration(0.0, &q, &v).expect("q̈");
    value(robot, "aba", &[("ddq", ddq.as_slice(), N)]);
    timer.time("aba", || {
        forced_articulated.acceleration(0.0, black_box(&q), black_box(&v))
    });
    timer.time("aba_terms", || {
        kept_articulated.acceleration(0.0, black_box(&q), black_box(&v))
    });

    let ddq = forced.acceleration(0.0, &q, &v).expect("q̈");
    value(robot, "chol", &[("ddq", ddq.as_slice(), N)]);
    timer.time("chol", || {
        forced.acceleration(0.0, black_box(&q), black_box(&v))
    });
    timer.time("chol_terms", || {
        kept.acceleration(0.0, black_box(&q), black_box(&v))
    });
    derivatives(&sys, timer, at);
}

/// Values and times of the derivatives of q̈ and of τ.
fn derivatives<S, const N: usize, const Q: usize>(sys: &S, timer: &Timer, at: &State<N, Q>)
where
    S: Differentiable<f64, N, Q>,
{
    let robot = timer.robot;
    let State { q, v, a, tau } = at;
    let forced = Dynamics::new(sys).with_forcing(Torques(*tau));
    let d = lagrange::acceleration_derivatives(sys, q, v, tau, 0.0).expect("derivatives");
    value(
        robot,
        "aba_derivatives",
        &[
            ("ddq_dq", d.dq.as_slice(), N),
            ("ddq_dv", d.dv.as_slice(), N),
            ("Minv", d.dtau.as_slice(), N),
        ],
    );
    timer.time("aba_derivatives", || {
        lagrange::acceleration_derivatives(sys, black_box(q), black_box(v), black_box(tau), 0.0)
    });
    timer.time("aba_derivatives_runtime", || {
        forced.acceleration_derivatives(0.0, black_box(q), black_box(v), None)
    });

    let (jq, jv): (SMatrix<f64, N, N>, SMatrix<f64, N, N>) =
        sys.rhs_jacobians(q, v, a, 0.0).expect("emit(jacobians)");
    let (dq, dv) = (-jq, -jv);
    value(
        robot,
        "rnea_derivatives",
        &[("dtau_dq", dq.as_slice(), N), ("dtau_dv", dv.as_slice(), N)],
    );
    timer.time("rnea_derivatives", || {
        sys.rhs_jacobians(black_box(q), black_box(v), black_box(a), 0.0)
    });
}

/// Every arm, or those named on the command line (`casadi_peer xarm7`, for a
/// profile of one), at the small state or, with `--wide`, the wide one;
/// with `--interleave path/to/libharness.so`, each measurement alternates
/// its batches with the C's function's in this process and prints `pair`
/// lines too.
fn main() {
    const ROBOTS: [&str; 6] = ["ur5", "ur10", "kinova", "z1", "xarm7", "solo12"];
    let (mut wide, mut library, mut named) = (false, None, Vec::new());
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--wide" => wide = true,
            "--interleave" => library = args.next(),
            _ if ROBOTS.contains(&arg.as_str()) => named.push(arg),
            _ => {
                eprintln!(
                    "casadi_peer: unknown argument {arg} (--wide, --interleave LIBRARY, or one of {})",
                    ROBOTS.join(", ")
                );
                std::process::exit(2);
            }
        }
    }
    let peer = library.map(|path| {
        Peer::load(&path).unwrap_or_else(|e| {
            eprintln!("casadi_peer: {e}");
            std::process::exit(2);
        })
    });
    let timer = |robot| Timer {
        robot,
        wide,
        peer: peer.as_ref(),
    };
    let run = |robot: &str| named.is_empty() || named.iter().any(|n| n == robot);
    if run("ur5") {
        robot::<Ur5, Ur5Articulated, 6, 6>(&timer("ur5"), &arm_state(wide));
    }
    if run("ur10") {
        robot::<Ur10, Ur10Articulated, 6, 6>(&timer("ur10"), &arm_state(wide));
    }
    if run("kinova") {
        robot::<Kinova, KinovaArticulated, 6, 6>(&timer("kinova"), &arm_state(wide));
    }
    if run("z1") {
        robot::<Z1, Z1Articulated, 7, 7>(&timer("z1"), &arm_state(wide));
    }
    if run("xarm7") {
        robot::<Xarm7, Xarm7Articulated, 7, 7>(&timer("xarm7"), &arm_state(wide));
    }
    if run("solo12") {
        robot::<Solo12, Solo12Articulated, 18, 19>(&timer("solo12"), &solo_state(wide));
    }
}
