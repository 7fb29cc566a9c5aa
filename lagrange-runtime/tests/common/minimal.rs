//! Hand-written unconstrained systems in minimal coordinates: the simple and
//! spherical pendulums, the harmonic oscillator and a ball in free fall.

use lagrange_runtime::{Lagrangian, Real, func};
use nalgebra::{Matrix1, Matrix2, SMatrix, Vector1, Vector2};

/// Simple pendulum, θ from the downward vertical: M = m l², h = 0, Q = −m g l sin θ.
/// Generic over the scalar, as generated code is.
pub struct Pendulum<T> {
    pub m: T,
    pub l: T,
    pub g: T,
}

impl Pendulum<f64> {
    pub fn standard() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        }
    }
}

impl<T: Real> Lagrangian<T, 1> for Pendulum<T> {
    const COORDINATES: [&'static str; 1] = ["theta"];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, _q: &Vector1<T>, _t: T) -> SMatrix<T, 1, 1> {
        SMatrix::<T, 1, 1>::new(self.m * self.l * self.l)
    }
    fn bias(&self, _q: &Vector1<T>, _v: &Vector1<T>, _t: T) -> Vector1<T> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, q: &Vector1<T>, _v: &Vector1<T>, _t: T) -> Vector1<T> {
        Vector1::new(-self.m * self.g * self.l * func::sin(q[0]))
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<T>,
        v: &Vector1<T>,
        t: T,
    ) -> (SMatrix<T, 1, 1>, Vector1<T>) {
        (
            self.mass_matrix(q, t),
            self.generalized_forces(q, v, t) - self.bias(q, v, t),
        )
    }
    fn kinetic_energy(&self, _q: &Vector1<T>, v: &Vector1<T>, _t: T) -> T {
        func::lit::<T>(0.5) * self.m * self.l * self.l * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<T>, _t: T) -> T {
        -self.m * self.g * self.l * func::cos(q[0])
    }
    fn integral(&self, q: &Vector1<T>, v: &Vector1<T>, t: T) -> T {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

/// Spherical pendulum in (θ, φ), θ from the downward vertical:
/// M = diag(m l², m l² sin²θ), h = (−m l² sinθ cosθ φ̇², 2 m l² sinθ cosθ θ̇ φ̇),
/// Q = (−m g l sin θ, 0). Singular at the poles θ = 0, π.
pub struct SphericalPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl SphericalPendulum {
    pub fn standard() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        }
    }

    /// The conserved angular momentum about the vertical, p_φ = m l² sin²θ φ̇.
    pub fn p_phi(&self, q: &Vector2<f64>, v: &Vector2<f64>) -> f64 {
        let s = q[0].sin();
        self.m * self.l * self.l * s * s * v[1]
    }
}

impl Lagrangian<f64, 2> for SphericalPendulum {
    const COORDINATES: [&'static str; 2] = ["theta", "phi"];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, q: &Vector2<f64>, _t: f64) -> Matrix2<f64> {
        let ml2 = self.m * self.l * self.l;
        let s = q[0].sin();
        Matrix2::new(ml2, 0.0, 0.0, ml2 * s * s)
    }
    fn bias(&self, q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        let ml2 = self.m * self.l * self.l;
        let sc = q[0].sin() * q[0].cos();
        Vector2::new(-ml2 * sc * v[1] * v[1], 2.0 * ml2 * sc * v[0] * v[1])
    }
    fn generalized_forces(&self, q: &Vector2<f64>, _v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::new(-self.m * self.g * self.l * q[0].sin(), 0.0)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        t: f64,
    ) -> (Matrix2<f64>, Vector2<f64>) {
        // One sin/cos for everything, as generated code does.
        let ml2 = self.m * self.l * self.l;
        let (s, c) = q[0].sin_cos();
        let m = Matrix2::new(ml2, 0.0, 0.0, ml2 * s * s);
        let rhs = Vector2::new(
            -self.m * self.g * self.l * s + ml2 * s * c * v[1] * v[1],
            -2.0 * ml2 * s * c * v[0] * v[1],
        );
        let _ = t;
        (m, rhs)
    }
    fn kinetic_energy(&self, q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> f64 {
        let s = q[0].sin();
        0.5 * self.m * self.l * self.l * (v[0] * v[0] + s * s * v[1] * v[1])
    }
    fn potential_energy(&self, q: &Vector2<f64>, _t: f64) -> f64 {
        -self.m * self.g * self.l * q[0].cos()
    }
    fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

/// Harmonic oscillator m q̈ = −k q as a Lagrangian system.
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
}

impl Lagrangian<f64, 1> for Oscillator {
    const COORDINATES: [&'static str; 1] = ["x"];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, _q: &Vector1<f64>, _t: f64) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(self.m)
    }
    fn bias(&self, _q: &Vector1<f64>, _v: &Vector1<f64>, _t: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, q: &Vector1<f64>, _v: &Vector1<f64>, _t: f64) -> Vector1<f64> {
        q * -self.k
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
        t: f64,
    ) -> (SMatrix<f64, 1, 1>, Vector1<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, _q: &Vector1<f64>, v: &Vector1<f64>, _t: f64) -> f64 {
        0.5 * self.m * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<f64>, _t: f64) -> f64 {
        0.5 * self.k * q[0] * q[0]
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

/// A ball of unit mass falling along z under gravity g: z̈ = −g.
pub struct Ball {
    pub g: f64,
}

impl Lagrangian<f64, 1> for Ball {
    const COORDINATES: [&'static str; 1] = ["z"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> {
        Matrix1::new(1.0)
    }
    fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::new(-self.g)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
        t: f64,
    ) -> (Matrix1<f64>, Vector1<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 {
        0.5 * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 {
        self.g * q[0]
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
    // For the symplectic Gauss method: T does not depend on z.
    fn kinetic_gradient(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Option<Vector1<f64>> {
        Some(Vector1::zeros())
    }
}
