//! `emit(articulated)` builds q̈ by the articulated-body algorithm and by M
//! factorised in the program, and emits the one with fewer operations. On
//! the shipped arms (and Solo 12, floating) the route taken is the cheaper
//! of the two counts it publishes, both routes are taken somewhere, and the
//! emitted q̈ agrees with M⁻¹(Q − h + τ) through the runtime's Cholesky
//! factorisation at τ ≠ 0, as does its pivot check. The Panda, whose finger
//! mimics the other, has only the factored route.

use lagrange::prelude::*;
use lagrange::{Dynamics, ForwardRoute};
use nalgebra::SVector;

use crate::floating_bases::Solo12;

macro_rules! arm {
    ($name:ident, $file:literal) => {
        #[derive(Lagrangian)]
        #[lagrange(urdf($file, dynamics = ignore), gravity = [0, 0, -9.81], emit(articulated))]
        struct $name {}
    };
}

arm!(Ur5, "robots/ur5.urdf");
arm!(Ur10, "robots/ur10.urdf");
arm!(Kinova, "robots/kinova.urdf");
arm!(Z1, "robots/z1.urdf");
arm!(Xarm7, "robots/xarm7.urdf");
// The second finger mimics the first: one coordinate drives two joints, so
// only the factored route applies.
arm!(Panda, "robots/panda.urdf");

/// The route's counts, with the taken one the smaller.
fn counts<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(name: &str) -> ForwardRoute {
    let route = S::FORWARD_ROUTE;
    match route {
        ForwardRoute::ArticulatedBody {
            articulated_body,
            factored_mass,
        } => assert!(articulated_body <= factored_mass, "{name}: {route:?}"),
        ForwardRoute::FactoredMass {
            articulated_body,
            factored_mass,
        } => assert!(
            articulated_body.is_none_or(|a| factored_mass < a),
            "{name}: {route:?}"
        ),
        ForwardRoute::MassMatrix => panic!("{name}: emit(articulated) gave no route"),
    }
    route
}

/// The emitted q̈ against the runtime's M and Cholesky at two states, τ ≠ 0.
fn agrees<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(
    name: &str,
    sys: &S,
    q: SVector<f64, Q>,
) {
    let v = SVector::<f64, N>::from_fn(|k, _| 0.5 - 0.21 * k as f64);
    let tau = SVector::<f64, N>::from_fn(|k, _| 2.0 * (0.1 * k as f64 - 0.2));
    let (emitted, ratio) = sys.forward_dynamics(&q, &v, &tau, 0.0).expect("emitted");
    let (m, rhs) = sys.mass_matrix_and_rhs(&q, &v, 0.0);
    let solved = m
        .cholesky()
        .expect("M positive definite")
        .solve(&(rhs + tau));
    let worst = (emitted - solved).amax() / solved.amax().max(1.0);
    assert!(worst < 1e-12, "{name}: q'' off by {worst:.1e}");
    assert!(ratio > 0.0 && ratio <= 1.0, "{name}: pivot ratio {ratio}");
    // The runtime's two routes, unforced.
    let dynamics = Dynamics::new(sys);
    let a = dynamics.acceleration(0.0, &q, &v).expect("regular");
    let b = dynamics
        .acceleration_from_mass_matrix(0.0, &q, &v)
        .expect("regular");
    let worst = (a - b).amax() / b.amax().max(1.0);
    assert!(
        worst < 1e-12,
        "{name}: the runtime's routes differ by {worst:.1e}"
    );
}

fn arm_state<const N: usize>(shift: f64) -> SVector<f64, N> {
    SVector::from_fn(|k, _| 0.3 - 0.17 * k as f64 + shift)
}

#[test]
fn the_cheaper_route_is_emitted_and_agrees_with_the_mass_matrix() {
    let routes = [
        counts::<Ur5, 6, 6>("UR5"),
        counts::<Ur10, 6, 6>("UR10"),
        counts::<Kinova, 6, 6>("Kinova"),
        counts::<Z1, 7, 7>("Z1"),
        counts::<Xarm7, 7, 7>("xArm7"),
        counts::<Solo12, 18, 19>("Solo 12"),
        counts::<Panda, 8, 8>("Panda"),
    ];
    assert!(matches!(
        routes[6],
        ForwardRoute::FactoredMass {
            articulated_body: None,
            ..
        }
    ));
    for shift in [0.0, 0.7] {
        agrees("UR5", &Ur5 {}, arm_state(shift));
        agrees("UR10", &Ur10 {}, arm_state(shift));
        agrees("Kinova", &Kinova {}, arm_state(shift));
        agrees("Z1", &Z1 {}, arm_state(shift));
        agrees("xArm7", &Xarm7 {}, arm_state(shift));
        agrees("Panda", &Panda {}, arm_state(shift));
        // Solo 12: 15 coordinates, then the trunk's unit quaternion.
        let mut q = arm_state::<19>(shift);
        let norm = q.rows(15, 4).norm();
        q.rows_mut(15, 4).unscale_mut(norm);
        agrees("Solo 12", &Solo12 {}, q);
    }
    let articulated = |r: &ForwardRoute| matches!(r, ForwardRoute::ArticulatedBody { .. });
    assert!(
        routes.iter().any(articulated),
        "no robot takes the articulated-body route"
    );
    assert!(
        !routes.iter().all(articulated),
        "no robot takes the factored route"
    );
    eprintln!("{routes:#?}");
}
