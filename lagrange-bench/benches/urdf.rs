//! Six arms read from their URDF files (`robots/`, from `example-robot-data`):
//! per call, M + (Q − h), q̈ (from M and its Cholesky factorisation, and by
//! the articulated-body algorithm), the inverse dynamics, the tool frame's
//! Jacobian and the centre of mass Jacobian — the figures to set beside
//! Pinocchio's CRBA + NLE, ABA, RNEA, `computeFrameJacobian` and
//! `jacobianCenterOfMass` on the same files from `peer/pinocchio/urdf.sh`,
//! run on the same machine in one session.
//!
//!     cargo bench -p lagrange-bench --bench urdf

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::{Kinematics, Lagrangian};
use nalgebra::SVector;
use std::hint::black_box;

/// An arm with everything the bench times but the articulated q̈, and the
/// same arm with `emit(articulated)` alone, so that the first's q̈ is the
/// M + Cholesky one. The Panda has no articulated twin: its fingers are one
/// coordinate driving two joints (a mimic), which the articulated-body
/// algorithm refuses.
macro_rules! arm {
    ($name:ident, $file:tt) => {
        #[derive(Lagrangian, Default)]
        #[lagrange(urdf = $file, gravity = [0, 0, -9.81], emit(inverse_dynamics, kinematics))]
        struct $name {}
    };
    ($name:ident, $articulated:ident, $file:tt) => {
        arm!($name, $file);

        #[derive(Lagrangian, Default)]
        #[lagrange(urdf = $file, gravity = [0, 0, -9.81], emit(articulated))]
        struct $articulated {}
    };
}

arm!(Ur5, Ur5Articulated, "../robots/ur5.urdf");
arm!(Panda, "../robots/panda.urdf");
arm!(Ur10, Ur10Articulated, "../robots/ur10.urdf");
arm!(Kinova, KinovaArticulated, "../robots/kinova.urdf");
arm!(Z1, Z1Articulated, "../robots/z1.urdf");
arm!(Xarm7, Xarm7Articulated, "../robots/xarm7.urdf");

/// The state the peer uses: q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k on the
/// arm's `arm` coordinates, the rest (the Panda's fingers) at 0.02 and at
/// rest; and q̈_k = 0.1 + 0.05 k on the arm for the inverse dynamics.
type State<const N: usize> = (SVector<f64, N>, SVector<f64, N>, SVector<f64, N>);
fn state<const N: usize>(arm: usize) -> State<N> {
    let on = |k: usize, x: f64, rest: f64| if k < arm { x } else { rest };
    (
        SVector::from_fn(|k, _| on(k, 0.3 - 0.17 * k as f64, 0.02)),
        SVector::from_fn(|k, _| on(k, 0.5 - 0.21 * k as f64, 0.0)),
        SVector::from_fn(|k, _| on(k, 0.1 + 0.05 * k as f64, 0.0)),
    )
}

/// One criterion group per arm: `urdf_<name>`.
fn time<S, const N: usize>(c: &mut Criterion, name: &str, arm: usize, tool: &str)
where
    S: Lagrangian<f64, N> + Kinematics<f64, N> + Default,
{
    let sys = S::default();
    let mut group = c.benchmark_group(format!("urdf_{name}"));
    let (q, v, a) = state::<N>(arm);
    group.bench_function("M + (Q - h)", |b| {
        b.iter(|| sys.mass_matrix_and_rhs(black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("accelerations", |b| {
        b.iter(|| lagrange::accelerations(&sys, black_box(&q), black_box(&v), 0.0))
    });
    group.bench_function("inverse dynamics", |b| {
        b.iter(|| sys.inverse_dynamics(black_box(&q), black_box(&v), black_box(&a), 0.0))
    });
    let body = S::body_index(tool).expect("the tool frame is a body");
    group.bench_function("frame jacobian", |b| {
        b.iter(|| sys.frame_jacobian(black_box(body), black_box(&q), 0.0))
    });
    group.bench_function("com jacobian", |b| {
        b.iter(|| sys.center_of_mass_jacobian(black_box(&q), 0.0))
    });
    group.finish();
}

/// q̈ by the articulated-body algorithm (`emit(articulated)`), in the arm's
/// group.
fn time_articulated<A: Lagrangian<f64, N> + Default, const N: usize>(
    c: &mut Criterion,
    name: &str,
    arm: usize,
) {
    let articulated = A::default();
    let mut group = c.benchmark_group(format!("urdf_{name}"));
    let (q, v, _) = state::<N>(arm);
    group.bench_function("accelerations (articulated)", |b| {
        b.iter(|| lagrange::accelerations(&articulated, black_box(&q), black_box(&v), 0.0))
    });
    group.finish();
}

fn arms(c: &mut Criterion) {
    time::<Ur5, 6>(c, "ur5", 6, "tool0");
    time_articulated::<Ur5Articulated, 6>(c, "ur5", 6);
    time::<Panda, 8>(c, "panda", 7, "panda_hand");
    time::<Ur10, 6>(c, "ur10", 6, "tool0");
    time_articulated::<Ur10Articulated, 6>(c, "ur10", 6);
    time::<Kinova, 6>(c, "kinova", 6, "j2s6s200_end_effector");
    time_articulated::<KinovaArticulated, 6>(c, "kinova", 6);
    time::<Z1, 7>(c, "z1", 7, "gripperStator");
    time_articulated::<Z1Articulated, 7>(c, "z1", 7);
    time::<Xarm7, 7>(c, "xarm7", 7, "link_eef");
    time_articulated::<Xarm7Articulated, 7>(c, "xarm7", 7);
}

criterion_group!(benches, arms);
criterion_main!(benches);
