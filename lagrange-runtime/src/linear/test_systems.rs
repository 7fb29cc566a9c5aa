//! Hand-written driven systems with closed forms, for the tests of the
//! equilibria and the step derivatives.

use crate::system::{Driven, Lagrangian};
use nalgebra::{Matrix2, SMatrix, Vector1, Vector2};

pub const G: f64 = 9.81;

/// θ̈ = −g sin θ + u: a unit pendulum with a torque.
pub struct Pendulum;

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
pub struct Thrusters;

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
pub struct Spherical {
    pub l: f64,
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

impl Driven<f64, 2, 2> for Spherical {
    const INPUTS: [&'static str; 2] = ["torque_theta", "torque_phi"];
    fn input_forces(
        &self,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        u: &Vector2<f64>,
        _: f64,
    ) -> Vector2<f64> {
        *u
    }
    fn input_jacobians(
        &self,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        _: f64,
    ) -> (Matrix2<f64>, Matrix2<f64>, Matrix2<f64>) {
        (Matrix2::identity(), Matrix2::zeros(), Matrix2::zeros())
    }
}

/// ẍ = −k x − c ẋ + u: a linear oscillator of unit mass, with its
/// right-hand side's Jacobians, so its linearisation is exact.
pub struct Oscillator {
    pub k: f64,
    pub c: f64,
}

impl Lagrangian<f64, 1> for Oscillator {
    const COORDINATES: [&'static str; 1] = ["x"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> SMatrix<f64, 1, 1> {
        SMatrix::identity()
    }
    fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, q: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::new(-self.k * q[0] - self.c * v[0])
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
        t: f64,
    ) -> (SMatrix<f64, 1, 1>, Vector1<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn rhs_jacobians(
        &self,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        _: f64,
    ) -> Option<(SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>)> {
        Some((
            SMatrix::from_element(-self.k),
            SMatrix::from_element(-self.c),
        ))
    }
    fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 {
        0.5 * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 {
        0.5 * self.k * q[0] * q[0]
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Driven<f64, 1, 1> for Oscillator {
    const INPUTS: [&'static str; 1] = ["force"];
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
