//! Hand-written driven systems (`Lagrangian` + `Driven`): the oscillator with a
//! force input, the Cartesian pendulum pushed sideways (multiplier form) and
//! the same pendulum in its angle (`Arm`), and a knife edge with thrust and torque.

use super::Oscillator;
use super::constrained::{CartesianPendulum, knife_edge_rates, knife_edge_rows};
use lagrange_runtime::{Constrained, Driven, Lagrangian, Reduced};
use nalgebra::{
    Matrix1, Matrix1x3, Matrix2, Matrix3, Matrix3x2, SMatrix, Vector1, Vector2, Vector3,
};

/// m ẍ + k x = u (k = 0: a double integrator).
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
    ) -> (Matrix1<f64>, Matrix1<f64>, Matrix1<f64>) {
        (Matrix1::identity(), Matrix1::zeros(), Matrix1::zeros())
    }
}

/// The pendulum bob at (x, y) on its rod x² + y² = l², pushed horizontally by u.
impl Driven<f64, 2, 1> for CartesianPendulum<1> {
    const INPUTS: [&'static str; 1] = ["push"];
    fn input_forces(
        &self,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        u: &Vector1<f64>,
        _: f64,
    ) -> Vector2<f64> {
        Vector2::new(u[0], 0.0)
    }
    fn input_jacobians(
        &self,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        _: &Vector1<f64>,
        _: f64,
    ) -> (SMatrix<f64, 2, 1>, Matrix2<f64>, Matrix2<f64>) {
        (
            SMatrix::<f64, 2, 1>::new(1.0, 0.0),
            Matrix2::zeros(),
            Matrix2::zeros(),
        )
    }
}

/// The same pendulum in its angle θ from the downward vertical; the horizontal
/// push u at the bob is the generalized force u ∂x/∂θ = u l cos θ.
pub struct Arm {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl Lagrangian<f64, 1> for Arm {
    const COORDINATES: [&'static str; 1] = ["theta"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> {
        Matrix1::new(self.m * self.l * self.l)
    }
    fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::new(-self.m * self.g * self.l * q[0].sin())
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
        0.5 * self.m * self.l * self.l * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 {
        -self.m * self.g * self.l * q[0].cos()
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Driven<f64, 1, 1> for Arm {
    const INPUTS: [&'static str; 1] = ["push"];
    fn input_forces(
        &self,
        q: &Vector1<f64>,
        _: &Vector1<f64>,
        u: &Vector1<f64>,
        _: f64,
    ) -> Vector1<f64> {
        Vector1::new(u[0] * self.l * q[0].cos())
    }
    fn input_jacobians(
        &self,
        q: &Vector1<f64>,
        _: &Vector1<f64>,
        u: &Vector1<f64>,
        _: f64,
    ) -> (Matrix1<f64>, Matrix1<f64>, Matrix1<f64>) {
        (
            Matrix1::new(self.l * q[0].cos()),
            Matrix1::new(-u[0] * self.l * q[0].sin()),
            Matrix1::zeros(),
        )
    }
}

/// A knife edge (skate) in the plane: position (x, y), heading φ, no sideways
/// velocity (−ẋ sin φ + ẏ cos φ = 0). Inputs: thrust along the heading and a
/// torque. Speeds u = (forward speed, φ̇).
pub struct Skate {
    pub m: f64,
    pub j: f64,
}

impl Lagrangian<f64, 3> for Skate {
    const COORDINATES: [&'static str; 3] = ["x", "y", "phi"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Vector3<f64>, _: f64) -> Matrix3<f64> {
        Matrix3::from_diagonal(&Vector3::new(self.m, self.m, self.j))
    }
    fn bias(&self, _: &Vector3<f64>, _: &Vector3<f64>, _: f64) -> Vector3<f64> {
        Vector3::zeros()
    }
    fn generalized_forces(&self, _: &Vector3<f64>, _: &Vector3<f64>, _: f64) -> Vector3<f64> {
        Vector3::zeros()
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector3<f64>,
        _: &Vector3<f64>,
        t: f64,
    ) -> (Matrix3<f64>, Vector3<f64>) {
        (self.mass_matrix(q, t), Vector3::zeros())
    }
    fn kinetic_energy(&self, _: &Vector3<f64>, v: &Vector3<f64>, _: f64) -> f64 {
        0.5 * (self.m * (v[0] * v[0] + v[1] * v[1]) + self.j * v[2] * v[2])
    }
    fn potential_energy(&self, _: &Vector3<f64>, _: f64) -> f64 {
        0.0
    }
    fn integral(&self, q: &Vector3<f64>, v: &Vector3<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t)
    }
}

impl Driven<f64, 3, 2> for Skate {
    const INPUTS: [&'static str; 2] = ["thrust", "torque"];
    fn input_forces(
        &self,
        q: &Vector3<f64>,
        _: &Vector3<f64>,
        u: &Vector2<f64>,
        _: f64,
    ) -> Vector3<f64> {
        Vector3::new(u[0] * q[2].cos(), u[0] * q[2].sin(), u[1])
    }
    fn input_jacobians(
        &self,
        q: &Vector3<f64>,
        _: &Vector3<f64>,
        u: &Vector2<f64>,
        _: f64,
    ) -> (Matrix3x2<f64>, Matrix3<f64>, Matrix3<f64>) {
        let (s, c) = q[2].sin_cos();
        let mut dq = Matrix3::zeros();
        dq[(0, 2)] = -u[0] * s;
        dq[(1, 2)] = u[0] * c;
        (
            Matrix3x2::new(c, 0.0, s, 0.0, 0.0, 1.0),
            dq,
            Matrix3::zeros(),
        )
    }
}

impl Constrained<f64, 3, 1> for Skate {
    const CONSTRAINTS: [&'static str; 1] = ["no_slip"];
    const HOLONOMIC: usize = 0;
    fn constraint_positions(&self, _: &Vector3<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn constraint_jacobian(&self, q: &Vector3<f64>, _: f64) -> (Matrix1x3<f64>, Vector1<f64>) {
        let (s, c) = q[2].sin_cos();
        (Matrix1x3::new(-s, c, 0.0), Vector1::zeros())
    }
    /// γ = −Ġ q̇ = φ̇ (ẋ cos φ + ẏ sin φ).
    fn constraint_rhs(&self, q: &Vector3<f64>, v: &Vector3<f64>, _: f64) -> Vector1<f64> {
        let (s, c) = q[2].sin_cos();
        Vector1::new(v[2] * (v[0] * c + v[1] * s))
    }
    fn constrained_system(
        &self,
        q: &Vector3<f64>,
        v: &Vector3<f64>,
        t: f64,
    ) -> (Matrix3<f64>, Vector3<f64>, Matrix1x3<f64>, Vector1<f64>) {
        let (m, f) = self.mass_matrix_and_rhs(q, v, t);
        (
            m,
            f,
            self.constraint_jacobian(q, t).0,
            self.constraint_rhs(q, v, t),
        )
    }
}

impl Reduced<f64, 3, 2> for Skate {
    const SPEEDS: [&'static str; 2] = ["forward", "turn"];
    const ROWS: [&'static str; 3] = ["forward", "turn", "no_side_slip"];
    fn velocity_rows(&self, q: &Vector3<f64>, _: f64) -> (Matrix3<f64>, Vector3<f64>) {
        (knife_edge_rows(q), Vector3::zeros())
    }
    fn row_rates(&self, q: &Vector3<f64>, v: &Vector3<f64>, _: f64) -> Vector3<f64> {
        knife_edge_rates(q, v)
    }
}
