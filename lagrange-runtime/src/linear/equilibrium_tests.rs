//! Against closed forms on hand-written systems: a pendulum held out by a
//! torque and left to hang under a constant one, a body on two thrusters
//! (least-norm inputs), a conical pendulum's steady precession, and a torque
//! no angle can balance.

use super::*;
use crate::system::Lagrangian;
use nalgebra::{Matrix2, SMatrix, Vector1, Vector2};

const G: f64 = 9.81;

/// θ̈ = −g sin θ + u: a unit pendulum with a torque.
struct Pendulum;

impl Lagrangian<f64, 1> for Pendulum {
    const COORDINATES: [&'static str; 1] = ["theta"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> SMatrix<f64, 1, 1> {
        SMatrix::identity()
    }
    fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::new(-G * q[0].sin())
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
        t: f64,
    ) -> (SMatrix<f64, 1, 1>, Vector1<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 {
        0.5 * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 {
        -G * q[0].cos()
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Driven<f64, 1, 1> for Pendulum {
    const INPUTS: [&'static str; 1] = ["torque"];
    fn input_forces(
        &self,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        u: &Vector1<f64>,
        _: f64,
    ) -> Vector1<f64> {
        *u
    }
    fn input_jacobians(
        &self,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        _: f64,
    ) -> (SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>) {
        (SMatrix::identity(), SMatrix::zeros(), SMatrix::zeros())
    }
}

/// ÿ = u₁ + u₂ − g: a unit mass on two thrusters.
struct Thrusters;

impl Lagrangian<f64, 1> for Thrusters {
    const COORDINATES: [&'static str; 1] = ["y"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> SMatrix<f64, 1, 1> {
        SMatrix::identity()
    }
    fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::new(-G)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
        t: f64,
    ) -> (SMatrix<f64, 1, 1>, Vector1<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 {
        0.5 * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 {
        G * q[0]
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Driven<f64, 1, 2> for Thrusters {
    const INPUTS: [&'static str; 2] = ["left", "right"];
    fn input_forces(
        &self,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        u: &Vector2<f64>,
        _: f64,
    ) -> Vector1<f64> {
        Vector1::new(u[0] + u[1])
    }
    fn input_jacobians(
        &self,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        _: &Vector2<f64>,
        _: f64,
    ) -> (SMatrix<f64, 1, 2>, SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>) {
        (
            SMatrix::from_element(1.0),
            SMatrix::zeros(),
            SMatrix::zeros(),
        )
    }
}

/// A spherical pendulum of unit mass and length l (θ from the downward
/// vertical, φ the azimuth): M = diag(l², l² sin²θ).
struct Spherical {
    l: f64,
}

impl Lagrangian<f64, 2> for Spherical {
    const COORDINATES: [&'static str; 2] = ["theta", "phi"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, q: &Vector2<f64>, _: f64) -> Matrix2<f64> {
        let l2 = self.l * self.l;
        Matrix2::new(l2, 0.0, 0.0, l2 * q[0].sin().powi(2))
    }
    fn bias(&self, q: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> Vector2<f64> {
        let (l2, (s, c)) = (self.l * self.l, q[0].sin_cos());
        Vector2::new(-l2 * s * c * v[1] * v[1], 2.0 * l2 * s * c * v[0] * v[1])
    }
    fn generalized_forces(&self, q: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> {
        Vector2::new(-G * self.l * q[0].sin(), 0.0)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        t: f64,
    ) -> (Matrix2<f64>, Vector2<f64>) {
        (
            self.mass_matrix(q, t),
            self.generalized_forces(q, v, t) - self.bias(q, v, t),
        )
    }
    fn kinetic_energy(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        0.5 * v.dot(&(self.mass_matrix(q, t) * v))
    }
    fn potential_energy(&self, q: &Vector2<f64>, _: f64) -> f64 {
        -G * self.l * q[0].cos()
    }
    fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Driven<f64, 2, 0> for Spherical {}

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
