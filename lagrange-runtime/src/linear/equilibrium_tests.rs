//! Against closed forms on hand-written systems: a pendulum held out by a
//! torque and left to hang under a constant one, a body on two thrusters
//! (least-norm inputs), a conical pendulum's steady precession, and a torque
//! no angle can balance.

use super::*;
use crate::linear::test_systems::{G, Pendulum, Spherical, Thrusters};
use nalgebra::{Vector1, Vector2};

fn at_rest(theta: f64) -> OperatingPoint<f64, 1> {
    OperatingPoint::new(Vector1::new(theta), Vector1::zeros())
}

#[test]
fn the_torque_that_holds_a_pendulum_out() {
    for theta in [0.3, 1.2, 2.5, -0.7] {
        let found = Trim::new()
            .hold(&["theta"])
            .solve(&Pendulum, &at_rest(theta))
            .unwrap();
        assert!(
            (found.u[0] - G * theta.sin()).abs() < 1e-12,
            "θ = {theta}: u = {}",
            found.u[0]
        );
        assert_eq!(found.q[0], theta);
        assert_eq!(found.iterations, 1, "q̈ is affine in u: one step");
    }
}

/// A constant torque u tilts the pendulum to sin θ = u / g.
#[test]
fn where_a_constant_torque_leaves_a_pendulum() {
    let u = 4.0;
    let guess = at_rest(0.1).input(Vector1::new(u));
    let found = Trim::new()
        .hold_inputs(&["torque"])
        .solve(&Pendulum, &guess)
        .unwrap();
    assert!(
        (found.q[0] - (u / G).asin()).abs() < 1e-10,
        "θ = {}",
        found.q[0]
    );
    assert!(found.residual <= 1e-10 && found.u[0] == u);
    assert!(found.iterations <= 6, "{} iterations", found.iterations);
}

/// Two inputs for one equation: the least-norm pair shares the weight.
#[test]
fn least_norm_inputs_share_the_weight() {
    let guess = OperatingPoint::new(Vector1::new(2.0), Vector1::zeros());
    let found = Trim::new().hold(&["y"]).solve(&Thrusters, &guess).unwrap();
    assert!(
        (found.u - Vector2::new(G / 2.0, G / 2.0)).amax() < 1e-12,
        "u = {}",
        found.u
    );
    // From a guess with inputs, the smallest change from it.
    let found = Trim::new()
        .hold(&["y"])
        .solve(&Thrusters, &guess.input(Vector2::new(G, 2.0)))
        .unwrap();
    assert!(
        (found.u - Vector2::new(G - 1.0, 1.0)).amax() < 1e-12,
        "u = {}",
        found.u
    );
}

/// A conical pendulum turning at Ω: cos θ = g / (l Ω²).
#[test]
fn a_conical_pendulum_precesses_steadily() {
    let (l, omega) = (0.8, 5.0);
    let guess = OperatingPoint::new(Vector2::new(0.9, 0.0), Vector2::new(0.0, omega));
    let found = Trim::new()
        .hold(&["phi"])
        .hold_inputs(&["torque_theta", "torque_phi"])
        .solve(&Spherical { l }, &guess)
        .unwrap();
    let expected = (G / (l * omega * omega)).acos();
    assert!(
        (found.q[0] - expected).abs() < 1e-10,
        "θ = {} vs {expected}",
        found.q[0]
    );
    assert_eq!(found.v, guess.v);
}

/// A torque above g: no angle balances it. The error says how close the
/// best point came (|θ̈| = u − g at θ = π/2) and holds it.
#[test]
fn no_angle_balances_too_large_a_torque() {
    let guess = at_rest(0.2).input(Vector1::new(2.0 * G));
    let e = Trim::new()
        .hold_inputs(&["torque"])
        .solve(&Pendulum, &guess)
        .unwrap_err();
    let Error::Linear(LinearError::NoEquilibrium {
        residual,
        worst,
        best,
        ..
    }) = &e
    else {
        panic!("expected NoEquilibrium, got {e}");
    };
    let (q, u) = (&best.q, &best.u);
    assert!((residual - G).abs() < 1e-3 * G, "residual {residual}");
    assert!(
        (q[0] - std::f64::consts::FRAC_PI_2).abs() < 0.05,
        "θ = {}",
        q[0]
    );
    assert_eq!((worst.as_str(), u[0]), ("theta", 2.0 * G));
    assert!(e.to_string().contains("no equilibrium found"), "{e}");
}

#[test]
fn bad_settings_and_names() {
    let e = Trim::new()
        .hold(&["psi"])
        .solve(&Pendulum, &at_rest(0.1))
        .unwrap_err();
    assert!(
        e.to_string()
            .contains("no coordinate or orientation named `psi`"),
        "{e}"
    );
    let e = Trim::new()
        .hold_inputs(&["force"])
        .solve(&Pendulum, &at_rest(0.1))
        .unwrap_err();
    assert!(e.to_string().contains("[\"torque\"]"), "{e}");
    let e = Trim::new()
        .tolerance(f64::NAN)
        .solve(&Pendulum, &at_rest(0.1))
        .unwrap_err();
    assert!(
        matches!(e, Error::Settings(SettingsError::Value { .. })),
        "{e}"
    );
    let e = Trim::new()
        .max_iterations(0)
        .solve(&Pendulum, &at_rest(0.1))
        .unwrap_err();
    assert!(
        matches!(e, Error::Settings(SettingsError::ZeroCount { .. })),
        "{e}"
    );
    let e = Trim::new()
        .solve(&Pendulum, &at_rest(f64::NAN))
        .unwrap_err();
    assert!(matches!(e, Error::NonFiniteState { .. }), "{e}");
    let e = Trim::new()
        .hold(&["theta"])
        .hold_inputs(&["torque"])
        .solve(&Pendulum, &at_rest(0.4))
        .unwrap_err();
    assert!(e.to_string().contains("everything is held"), "{e}");
}
