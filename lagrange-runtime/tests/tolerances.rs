//! Every tolerance of the public API refuses a sign slip, a NaN and an
//! infinity with a typed error naming the setting, rather than answering with
//! it; and a linearisation names a non-finite input and a model without inputs.

mod common;
#[allow(dead_code)] // this binary uses two of its systems
#[path = "linear/systems.rs"]
mod systems;

use common::Pendulum;
use common::constrained::CartesianPendulum;
use lagrange_runtime::linear::{Linearizer, OperatingPoint, lqr};
use lagrange_runtime::{
    ConstrainedDynamics, Dynamics, Error, ReducedDynamics, SecondOrder, Simulation, linearize,
};
use nalgebra::{DMatrix, Vector1, Vector2, Vector3};
use systems::{DoublePendulum, Rod};

const BAD: [f64; 4] = [-1e-9, -1.0, f64::NAN, f64::INFINITY];

/// The error is an `Error::Settings` whose message names `setting`.
fn names_setting(result: Result<impl std::fmt::Debug, Error>, setting: &str, bad: f64) {
    match result {
        Err(Error::Settings(m)) if m.to_string().contains(setting) => {}
        other => panic!("{setting} = {bad}: expected a settings error naming it, got {other:?}"),
    }
}

#[test]
fn the_linearizer_refuses_bad_tolerances_at_a_consistent_point() {
    let bob = Rod::standard();
    // Exactly consistent: hanging straight down, at rest.
    let op = OperatingPoint::new(Vector2::new(0.0, -bob.l), Vector2::zeros());
    assert!(Linearizer::new().constrained(&bob, &op).is_ok());
    for bad in BAD {
        let settings = [
            (
                "consistency tolerance",
                Linearizer::new().consistency_tolerance(bad),
            ),
            (
                "singular tolerance",
                Linearizer::new().singular_tolerance(bad),
            ),
            (
                "redundant tolerance",
                Linearizer::new().redundant_tolerance(bad),
            ),
            ("Newton tolerance", Linearizer::new().newton(bad, 20)),
        ];
        for (setting, linearizer) in settings {
            names_setting(linearizer.constrained(&bob, &op), setting, bad);
            let (q, v) = (op.q, op.v);
            names_setting(linearizer.complete_state(&bob, q, v, 0.0), setting, bad);
        }
    }
    let no_newton = Linearizer::new().newton(1e-12, 0);
    names_setting(
        no_newton.constrained(&bob, &op),
        "Newton iteration limit",
        0.0,
    );
}

#[test]
fn stability_and_selection_refuse_bad_tolerances() {
    let p = DoublePendulum::standard();
    let lin = linearize(&p, &OperatingPoint::new(Vector2::zeros(), Vector2::zeros())).unwrap();
    assert!(lin.stability(1e-9).is_ok());
    for bad in BAD {
        names_setting(lin.stability(bad), "stability tolerance", bad);
        names_setting(
            lin.select_with_tolerance(&["theta1"], bad),
            "coupling tolerance",
            bad,
        );
    }
}

#[test]
fn the_dynamics_refuse_bad_tolerances_at_the_first_evaluation() {
    let (q, v) = (Vector1::new(0.3), Vector1::new(0.0));
    let p = Pendulum::standard();
    let bob = CartesianPendulum::<1>::standard();
    let (qc, vc) = bob.state(0.3, 0.0);
    for bad in BAD {
        let free = Dynamics::new(&p).with_singular_tolerance(bad);
        names_setting(free.acceleration(0.0, &q, &v), "singular tolerance", bad);
        let held = ConstrainedDynamics::<_, f64, 1>::new(&bob);
        let singular = held.with_singular_tolerance(bad);
        names_setting(
            SecondOrder::acceleration(&singular, 0.0, &qc, &vc),
            "singular",
            bad,
        );
        let redundant = ConstrainedDynamics::<_, f64, 1>::new(&bob).with_redundant_tolerance(bad);
        names_setting(
            SecondOrder::acceleration(&redundant, 0.0, &qc, &vc),
            "redundant",
            bad,
        );
        names_setting(
            Simulation::new(&p)
                .singular_tolerance(bad)
                .run([0.3], [0.0], 0.0..1.0)
                .map_err(|f| f.error),
            "singular tolerance",
            bad,
        );
    }
    let skate = common::driven::Skate { m: 2.0, j: 0.5 };
    let (sq, sv) = (Vector3::new(0.0, 0.0, 0.3), Vector3::new(0.0, 0.0, 1.0));
    let reduced = ReducedDynamics::<_, f64, 2>::new(&skate).with_singular_tolerance(-1.0);
    names_setting(reduced.solve(0.0, &sq, &sv), "singular tolerance", -1.0);
}

#[test]
fn a_linearisation_names_a_non_finite_input() {
    let sys = DoublePendulum::standard();
    let op = OperatingPoint::new(Vector2::new(0.1, 0.2), Vector2::zeros()).input(Vector3::new(
        0.0,
        f64::NAN,
        0.0,
    ));
    match linearize(&sys, &op) {
        Err(Error::NonFiniteInput { input, value, .. }) => {
            assert_eq!(input, "push");
            assert!(value.is_nan());
        }
        other => panic!("expected NonFiniteInput naming `push`, got {other:?}"),
    }
}

#[test]
fn lqr_on_a_model_without_inputs_says_so() {
    // A model without inputs has a B with no columns.
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, 0.0]);
    let b = DMatrix::zeros(2, 0);
    let e = lqr(&a, &b, &DMatrix::identity(2, 2), &DMatrix::zeros(0, 0)).unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains("has no inputs") && message.contains("inputs(...)"),
        "{message}"
    );
}
