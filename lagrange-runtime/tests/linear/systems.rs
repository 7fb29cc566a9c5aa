//! Hand-written systems with the symbolic derivatives linearisation needs (what
//! `emit(jacobians)` generates), and a wrapper that adds the inputs' forces so
//! the existing nonlinear solvers give the driven forward dynamics.

use lagrange_runtime::{Constrained, Driven, Lagrangian, Reduced};
use nalgebra::{Matrix1x2, Matrix2, Matrix2x3, SMatrix, SVector, Vector1, Vector2, Vector3};

/// A double pendulum in absolute angles θ1, θ2 from the downward vertical, with
/// joint damping d on both angles, driven by a shoulder torque `tau`, a
/// horizontal force `push` on the second bob and an extra elbow damping
/// coefficient `damp` (an input that multiplies a velocity):
///
/// ΔQ = (τ + F l1 c1 + c w, F l2 c2 − c w), w = θ̇2 − θ̇1.
pub struct DoublePendulum {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
    pub d: f64,
}

impl DoublePendulum {
    pub fn standard() -> Self {
        Self {
            m1: 1.3,
            m2: 0.7,
            l1: 1.1,
            l2: 0.8,
            g: 9.81,
            d: 0.1,
        }
    }
}

impl Lagrangian<f64, 2> for DoublePendulum {
    const COORDINATES: [&'static str; 2] = ["theta1", "theta2"];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, q: &Vector2<f64>, _t: f64) -> Matrix2<f64> {
        let k = self.m2 * self.l1 * self.l2 * (q[0] - q[1]).cos();
        Matrix2::new(
            (self.m1 + self.m2) * self.l1 * self.l1,
            k,
            k,
            self.m2 * self.l2 * self.l2,
        )
    }
    fn bias(&self, q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        let k = self.m2 * self.l1 * self.l2 * (q[0] - q[1]).sin();
        Vector2::new(k * v[1] * v[1], -k * v[0] * v[0])
    }
    fn generalized_forces(&self, q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::new(
            -(self.m1 + self.m2) * self.g * self.l1 * q[0].sin(),
            -self.m2 * self.g * self.l2 * q[1].sin(),
        ) - v * self.d
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
    fn potential_energy(&self, q: &Vector2<f64>, _t: f64) -> f64 {
        -(self.m1 + self.m2) * self.g * self.l1 * q[0].cos()
            - self.m2 * self.g * self.l2 * q[1].cos()
    }
    fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
    fn rhs_jacobians(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        a: &Vector2<f64>,
        _t: f64,
    ) -> Option<(Matrix2<f64>, Matrix2<f64>)> {
        let k = self.m2 * self.l1 * self.l2;
        let (s12, c12) = (q[0] - q[1]).sin_cos();
        let (m12, g) = (self.m1 + self.m2, self.g);
        let jq = Matrix2::new(
            -m12 * g * self.l1 * q[0].cos() - k * c12 * v[1] * v[1] + k * s12 * a[1],
            k * c12 * v[1] * v[1] - k * s12 * a[1],
            k * c12 * v[0] * v[0] + k * s12 * a[0],
            -self.m2 * g * self.l2 * q[1].cos() - k * c12 * v[0] * v[0] - k * s12 * a[0],
        );
        let jv = Matrix2::new(
            -self.d,
            -2.0 * k * s12 * v[1],
            2.0 * k * s12 * v[0],
            -self.d,
        );
        Some((jq, jv))
    }
}

impl Driven<f64, 2, 3> for DoublePendulum {
    const INPUTS: [&'static str; 3] = ["tau", "push", "damp"];

    fn input_forces(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        u: &Vector3<f64>,
        _t: f64,
    ) -> Vector2<f64> {
        let w = v[1] - v[0];
        Vector2::new(
            u[0] + u[1] * self.l1 * q[0].cos() + u[2] * w,
            u[1] * self.l2 * q[1].cos() - u[2] * w,
        )
    }
    fn input_jacobians(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        u: &Vector3<f64>,
        _t: f64,
    ) -> (Matrix2x3<f64>, Matrix2<f64>, Matrix2<f64>) {
        let w = v[1] - v[0];
        let (c1, c2) = (q[0].cos(), q[1].cos());
        (
            Matrix2x3::new(1.0, self.l1 * c1, w, 0.0, self.l2 * c2, -w),
            Matrix2::new(
                -u[1] * self.l1 * q[0].sin(),
                0.0,
                0.0,
                -u[1] * self.l2 * q[1].sin(),
            ),
            Matrix2::new(-u[2], u[2], u[2], -u[2]),
        )
    }
}

/// A point (x, y) of mass m on a rod x² + y² = l² under gravity, driven by a
/// torque `tau` about the pivot: ΔQ = τ/l² (−y, x).
pub struct Rod {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl Rod {
    pub fn standard() -> Self {
        Self {
            m: 1.2,
            l: 0.9,
            g: 9.81,
        }
    }

    /// The state at angle θ from the downward vertical with rate θ̇.
    pub fn state(&self, theta: f64, rate: f64) -> (Vector2<f64>, Vector2<f64>) {
        let (s, c) = theta.sin_cos();
        (
            Vector2::new(self.l * s, -self.l * c),
            Vector2::new(self.l * c * rate, self.l * s * rate),
        )
    }
}

impl Lagrangian<f64, 2> for Rod {
    const CONSTRAINED: bool = true;

    fn visit_form<F: lagrange_runtime::FormVisitor<f64, 2, Self>>(&self, form: F) -> F::Output {
        form.multipliers::<1>(self)
    }

    const COORDINATES: [&'static str; 2] = ["x", "y"];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, _q: &Vector2<f64>, _t: f64) -> Matrix2<f64> {
        Matrix2::identity() * self.m
    }
    fn bias(&self, _q: &Vector2<f64>, _v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::zeros()
    }
    fn generalized_forces(&self, _q: &Vector2<f64>, _v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::new(0.0, -self.m * self.g)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        t: f64,
    ) -> (Matrix2<f64>, Vector2<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, _q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> f64 {
        0.5 * self.m * v.norm_squared()
    }
    fn potential_energy(&self, q: &Vector2<f64>, _t: f64) -> f64 {
        self.m * self.g * q[1]
    }
    fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
    fn rhs_jacobians(
        &self,
        _q: &Vector2<f64>,
        _v: &Vector2<f64>,
        _a: &Vector2<f64>,
        _t: f64,
    ) -> Option<(Matrix2<f64>, Matrix2<f64>)> {
        Some((Matrix2::zeros(), Matrix2::zeros()))
    }
}

impl Constrained<f64, 2, 1> for Rod {
    const CONSTRAINTS: [&'static str; 1] = ["rod"];
    const HOLONOMIC: usize = 1;

    fn constraint_positions(&self, q: &Vector2<f64>, _t: f64) -> Vector1<f64> {
        Vector1::new(q.norm_squared() - self.l * self.l)
    }
    fn constraint_jacobian(&self, q: &Vector2<f64>, _t: f64) -> (Matrix1x2<f64>, Vector1<f64>) {
        (Matrix1x2::new(2.0 * q[0], 2.0 * q[1]), Vector1::zeros())
    }
    fn constraint_rhs(&self, _q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> Vector1<f64> {
        Vector1::new(-2.0 * v.norm_squared())
    }
    fn constrained_system(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        t: f64,
    ) -> (Matrix2<f64>, Vector2<f64>, Matrix1x2<f64>, Vector1<f64>) {
        let (m, f) = self.mass_matrix_and_rhs(q, v, t);
        (
            m,
            f,
            self.constraint_jacobian(q, t).0,
            self.constraint_rhs(q, v, t),
        )
    }
    fn constraint_derivatives(
        &self,
        _q: &Vector2<f64>,
        v: &Vector2<f64>,
        a: &Vector2<f64>,
        nu: &Vector1<f64>,
        _t: f64,
    ) -> Option<(Matrix2<f64>, Matrix1x2<f64>, Matrix1x2<f64>, Matrix1x2<f64>)> {
        Some((
            Matrix2::identity() * (2.0 * nu[0]),
            Matrix1x2::new(-2.0 * a[0], -2.0 * a[1]),
            Matrix1x2::new(-4.0 * v[0], -4.0 * v[1]),
            Matrix1x2::new(2.0 * v[0], 2.0 * v[1]),
        ))
    }
}

impl Driven<f64, 2, 1> for Rod {
    const INPUTS: [&'static str; 1] = ["tau"];

    fn input_forces(
        &self,
        q: &Vector2<f64>,
        _v: &Vector2<f64>,
        u: &Vector1<f64>,
        _t: f64,
    ) -> Vector2<f64> {
        Vector2::new(-q[1], q[0]) * (u[0] / (self.l * self.l))
    }
    fn input_jacobians(
        &self,
        q: &Vector2<f64>,
        _v: &Vector2<f64>,
        u: &Vector1<f64>,
        _t: f64,
    ) -> (Matrix2x1, Matrix2<f64>, Matrix2<f64>) {
        let l2 = self.l * self.l;
        (
            Matrix2x1::new(-q[1] / l2, q[0] / l2),
            Matrix2::new(0.0, -1.0, 1.0, 0.0) * (u[0] / l2),
            Matrix2::zeros(),
        )
    }
}

type Matrix2x1 = SMatrix<f64, 2, 1>;

/// A driven system with its inputs frozen at `u`: the inputs' forces ΔQ are added
/// to Q (and Wᵀ ΔQ to F*), so the runtime's own nonlinear solvers give the driven
/// forward dynamics.
pub struct Forced<'a, S, const P: usize> {
    pub sys: &'a S,
    pub u: SVector<f64, P>,
}

impl<S, const N: usize, const P: usize> Lagrangian<f64, N> for Forced<'_, S, P>
where
    S: Driven<f64, N, P>,
{
    const COORDINATES: [&'static str; N] = S::COORDINATES;
    const RHEONOMIC: bool = S::RHEONOMIC;

    fn mass_matrix(&self, q: &SVector<f64, N>, t: f64) -> SMatrix<f64, N, N> {
        self.sys.mass_matrix(q, t)
    }
    fn bias(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> SVector<f64, N> {
        self.sys.bias(q, v, t)
    }
    fn generalized_forces(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        t: f64,
    ) -> SVector<f64, N> {
        self.sys.generalized_forces(q, v, t) + self.sys.input_forces(q, v, &self.u, t)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        t: f64,
    ) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
        let (m, f) = self.sys.mass_matrix_and_rhs(q, v, t);
        (m, f + self.sys.input_forces(q, v, &self.u, t))
    }
    fn kinetic_energy(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> f64 {
        self.sys.kinetic_energy(q, v, t)
    }
    fn potential_energy(&self, q: &SVector<f64, N>, t: f64) -> f64 {
        self.sys.potential_energy(q, t)
    }
    fn integral(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> f64 {
        self.sys.integral(q, v, t)
    }
}

impl<S, const N: usize, const K: usize, const P: usize> Constrained<f64, N, K> for Forced<'_, S, P>
where
    S: Constrained<f64, N, K> + Driven<f64, N, P>,
{
    const CONSTRAINTS: [&'static str; K] = S::CONSTRAINTS;
    const HOLONOMIC: usize = S::HOLONOMIC;

    fn constraint_positions(&self, q: &SVector<f64, N>, t: f64) -> SVector<f64, K> {
        self.sys.constraint_positions(q, t)
    }
    fn constraint_jacobian(
        &self,
        q: &SVector<f64, N>,
        t: f64,
    ) -> (SMatrix<f64, K, N>, SVector<f64, K>) {
        self.sys.constraint_jacobian(q, t)
    }
    fn constraint_rhs(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> SVector<f64, K> {
        self.sys.constraint_rhs(q, v, t)
    }
    fn constrained_system(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        t: f64,
    ) -> (
        SMatrix<f64, N, N>,
        SVector<f64, N>,
        SMatrix<f64, K, N>,
        SVector<f64, K>,
    ) {
        let (m, f, g, gamma) = Constrained::<f64, N, K>::constrained_system(self.sys, q, v, t);
        (m, f + self.sys.input_forces(q, v, &self.u, t), g, gamma)
    }
}

impl<S, const N: usize, const K: usize, const P: usize> Reduced<f64, N, K> for Forced<'_, S, P>
where
    S: Reduced<f64, N, K> + Driven<f64, N, P>,
{
    const SPEEDS: [&'static str; K] = S::SPEEDS;
    const ROWS: [&'static str; N] = S::ROWS;

    fn velocity_rows(&self, q: &SVector<f64, N>, t: f64) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
        self.sys.velocity_rows(q, t)
    }
    fn row_rates(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> SVector<f64, N> {
        self.sys.row_rates(q, v, t)
    }
}
