//! Hand-written driven systems with closed forms, for the tests of the
//! equilibria and the step derivatives (one with a free orientation).

use crate::numeric::orientation::{self, Orientation};
use crate::system::{Driven, Lagrangian};
use nalgebra::{Matrix2, SMatrix, Vector1, Vector2, Vector3};

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

/// States (q, v, u) of the spherical pendulum away from its poles, for the
/// tests of a step's derivatives and curvature: arbitrary, not chosen.
pub const SPHERICAL_STATES: [(Vector2<f64>, Vector2<f64>, Vector2<f64>); 3] = [
    (
        Vector2::new(0.7, 0.2),
        Vector2::new(0.3, 2.0),
        Vector2::new(0.5, -0.2),
    ),
    (
        Vector2::new(1.9, -1.0),
        Vector2::new(-1.2, 0.4),
        Vector2::new(0.0, 1.5),
    ),
    (
        Vector2::new(0.4, 3.0),
        Vector2::new(2.0, -3.0),
        Vector2::new(-2.0, 0.3),
    ),
];

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
    const INPUTS_AFFINE: bool = true;
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

/// A heavy body on a fixed pivot (unit mass, principal moments a, b, c
/// about the pivot, its centre of mass `lever` up its z axis) beside a sprung
/// cart x (unit mass, stiffness `K`) that its tilt pushes with `KAPPA`
/// times the world x of the body's z axis (a coupling no potential gives:
/// the cart's q̈ depends on the orientation too). Four inputs: the cart's
/// push and three torques in body axes.
pub struct PivotedBody {
    pub inertia: [f64; 3],
    pub lever: f64,
}
const K: f64 = 3.0;
const KAPPA: f64 = 2.0;

type V4 = SMatrix<f64, 4, 1>;
type Q5 = SMatrix<f64, 5, 1>;

impl PivotedBody {
    /// R(q) of the body.
    fn rotation(q: &Q5) -> [[f64; 3]; 3] {
        orientation::rotation_matrix([q[1], q[2], q[3], q[4]])
    }
}

impl Lagrangian<f64, 4, 5> for PivotedBody {
    const COORDINATES: [&'static str; 5] = ["x", "body.w", "body.x", "body.y", "body.z"];
    const VELOCITIES: [&'static str; 4] = ["x", "body.wx", "body.wy", "body.wz"];
    const ORIENTATIONS: &'static [Orientation] = &[Orientation { q: 1, v: 1 }];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Q5, _: f64) -> SMatrix<f64, 4, 4> {
        let [a, b, c] = self.inertia;
        SMatrix::from_diagonal(&V4::from([1.0, a, b, c]))
    }
    fn bias(&self, _: &Q5, v: &V4, _: f64) -> V4 {
        let [a, b, c] = self.inertia;
        let w = Vector3::new(v[1], v[2], v[3]);
        let gyro = w.cross(&Vector3::new(a * v[1], b * v[2], c * v[3]));
        V4::from([0.0, gyro[0], gyro[1], gyro[2]])
    }
    fn generalized_forces(&self, q: &Q5, _: &V4, _: f64) -> V4 {
        let r = Self::rotation(q);
        // Gravity's torque in body axes: (0, 0, l) × Rᵀ (0, 0, −g).
        let down = Vector3::new(r[2][0], r[2][1], r[2][2]) * -G;
        let torque = Vector3::new(0.0, 0.0, self.lever).cross(&down);
        V4::from([-K * q[0] + KAPPA * r[0][2], torque[0], torque[1], torque[2]])
    }
    fn mass_matrix_and_rhs(&self, q: &Q5, v: &V4, t: f64) -> (SMatrix<f64, 4, 4>, V4) {
        let rhs = self.generalized_forces(q, v, t) - self.bias(q, v, t);
        (self.mass_matrix(q, t), rhs)
    }
    fn kinetic_energy(&self, q: &Q5, v: &V4, t: f64) -> f64 {
        0.5 * v.dot(&(self.mass_matrix(q, t) * v))
    }
    fn potential_energy(&self, q: &Q5, _: f64) -> f64 {
        0.5 * K * q[0] * q[0] + G * self.lever * Self::rotation(q)[2][2]
    }
    fn integral(&self, q: &Q5, v: &V4, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Driven<f64, 4, 4, 5> for PivotedBody {
    const INPUTS: [&'static str; 4] = ["push", "tx", "ty", "tz"];
    fn input_forces(&self, _: &Q5, _: &V4, u: &V4, _: f64) -> V4 {
        *u
    }
    #[allow(clippy::type_complexity)]
    fn input_jacobians(
        &self,
        _: &Q5,
        _: &V4,
        _: &V4,
        _: f64,
    ) -> (SMatrix<f64, 4, 4>, SMatrix<f64, 4, 4>, SMatrix<f64, 4, 4>) {
        (SMatrix::identity(), SMatrix::zeros(), SMatrix::zeros())
    }
}
