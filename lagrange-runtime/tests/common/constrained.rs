//! Hand-written constrained systems (the macro does not emit constraints yet).

use lagrange_runtime::{Constrained, Lagrangian, Reduced};
use nalgebra::{Matrix1x2, Matrix1x3, Matrix2, Matrix3, Matrix3x2, Vector1, Vector2, Vector3};

/// A planar pendulum as a point (x, y) of mass m under gravity −g ŷ, held at
/// distance l from the origin by the holonomic constraint x² + y² − l² = 0,
/// written K times (K = 2 is the redundant "same rod twice").
pub struct CartesianPendulum<const K: usize> {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl<const K: usize> CartesianPendulum<K> {
    pub fn standard() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        }
    }

    /// The state at angle θ from the downward vertical with angular rate θ̇.
    pub fn state(&self, theta: f64, theta_dot: f64) -> (Vector2<f64>, Vector2<f64>) {
        let (s, c) = theta.sin_cos();
        (
            Vector2::new(self.l * s, -self.l * c),
            Vector2::new(self.l * c * theta_dot, self.l * s * theta_dot),
        )
    }

    /// The rod tension from the state alone: the centripetal force m |v|²/l plus
    /// the pull of gravity along the outward radius r/l, m (0, −g)·r/l = −m g y/l.
    pub fn tension(&self, q: &Vector2<f64>, v: &Vector2<f64>) -> f64 {
        self.m * (v.norm_squared() / self.l - self.g * q[1] / self.l)
    }
}

impl<const K: usize> Lagrangian<f64, 2> for CartesianPendulum<K> {
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
}

fn rod(l: f64, q: &Vector2<f64>) -> f64 {
    q.norm_squared() - l * l
}

impl Constrained<f64, 2, 1> for CartesianPendulum<1> {
    const CONSTRAINTS: [&'static str; 1] = ["rod"];
    const HOLONOMIC: usize = 1;

    fn constraint_positions(&self, q: &Vector2<f64>, _t: f64) -> Vector1<f64> {
        Vector1::new(rod(self.l, q))
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
}

impl Constrained<f64, 2, 2> for CartesianPendulum<2> {
    const CONSTRAINTS: [&'static str; 2] = ["rod", "rod_again"];
    const HOLONOMIC: usize = 2;

    fn constraint_positions(&self, q: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::repeat(rod(self.l, q))
    }
    fn constraint_jacobian(&self, q: &Vector2<f64>, _t: f64) -> (Matrix2<f64>, Vector2<f64>) {
        let row = [2.0 * q[0], 2.0 * q[1]];
        (
            Matrix2::new(row[0], row[1], row[0], row[1]),
            Vector2::zeros(),
        )
    }
    fn constraint_rhs(&self, _q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::repeat(-2.0 * v.norm_squared())
    }
    fn constrained_system(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        t: f64,
    ) -> (Matrix2<f64>, Vector2<f64>, Matrix2<f64>, Vector2<f64>) {
        let (m, f) = self.mass_matrix_and_rhs(q, v, t);
        (
            m,
            f,
            self.constraint_jacobian(q, t).0,
            self.constraint_rhs(q, v, t),
        )
    }
}

/// The Chaplygin sleigh on an inclined plane: a body whose knife edge touches the
/// plane at (x, y), heading θ, with its centre of mass a distance `a` ahead of the
/// edge along the heading; mass m, central moment of inertia `ic`, and the slope's
/// gravity component `gs` along +x. The edge cannot slide sideways:
/// −sin θ ẋ + cos θ ẏ = 0.
///
/// With c = (x + a cos θ, y + a sin θ):
/// T = ½ m |ċ|² + ½ ic θ̇², V = −m gs cₓ,
/// M = [[m, 0, −m a s], [0, m, m a c], [−m a s, m a c, ic + m a²]],
/// h = (−m a c θ̇², −m a s θ̇², 0), Q = (m gs, 0, −m gs a s).
///
/// Reduced form with speeds u = (σ, ω), σ = c ẋ + s ẏ the forward speed of the
/// edge and ω = θ̇: q̇ = W u, W = [[c, 0], [s, 0], [0, 1]], M* = diag(m, ic + m a²),
/// F* = (m gs c + m a ω², −m a (σ ω + gs s)), κ = Ẇ u = (−s ω σ, c ω σ, 0).
pub struct Sleigh {
    pub m: f64,
    pub a: f64,
    pub ic: f64,
    pub gs: f64,
}

impl Sleigh {
    pub fn standard() -> Self {
        Self {
            m: 1.0,
            a: 0.5,
            ic: 0.2,
            gs: 0.5,
        }
    }

    /// The lateral velocity of the edge, −sin θ ẋ + cos θ ẏ (zero when admissible).
    pub fn slip(q: &Vector3<f64>, v: &Vector3<f64>) -> f64 {
        let (s, c) = q[2].sin_cos();
        -s * v[0] + c * v[1]
    }
}

impl Lagrangian<f64, 3> for Sleigh {
    const COORDINATES: [&'static str; 3] = ["x", "y", "theta"];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, q: &Vector3<f64>, _t: f64) -> Matrix3<f64> {
        let (s, c) = q[2].sin_cos();
        let (m, a) = (self.m, self.a);
        Matrix3::new(
            m,
            0.0,
            -m * a * s,
            0.0,
            m,
            m * a * c,
            -m * a * s,
            m * a * c,
            self.ic + m * a * a,
        )
    }
    fn bias(&self, q: &Vector3<f64>, v: &Vector3<f64>, _t: f64) -> Vector3<f64> {
        let (s, c) = q[2].sin_cos();
        let w2 = v[2] * v[2];
        Vector3::new(-self.m * self.a * c * w2, -self.m * self.a * s * w2, 0.0)
    }
    fn generalized_forces(&self, q: &Vector3<f64>, _v: &Vector3<f64>, _t: f64) -> Vector3<f64> {
        let mg = self.m * self.gs;
        Vector3::new(mg, 0.0, -mg * self.a * q[2].sin())
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector3<f64>,
        v: &Vector3<f64>,
        t: f64,
    ) -> (Matrix3<f64>, Vector3<f64>) {
        (
            self.mass_matrix(q, t),
            self.generalized_forces(q, v, t) - self.bias(q, v, t),
        )
    }
    fn kinetic_energy(&self, q: &Vector3<f64>, v: &Vector3<f64>, t: f64) -> f64 {
        0.5 * v.dot(&(self.mass_matrix(q, t) * v))
    }
    fn potential_energy(&self, q: &Vector3<f64>, _t: f64) -> f64 {
        -self.m * self.gs * (q[0] + self.a * q[2].cos())
    }
    fn integral(&self, q: &Vector3<f64>, v: &Vector3<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Constrained<f64, 3, 1> for Sleigh {
    const CONSTRAINTS: [&'static str; 1] = ["no_side_slip"];
    const HOLONOMIC: usize = 0;

    fn constraint_positions(&self, _q: &Vector3<f64>, _t: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn constraint_jacobian(&self, q: &Vector3<f64>, _t: f64) -> (Matrix1x3<f64>, Vector1<f64>) {
        let (s, c) = q[2].sin_cos();
        (Matrix1x3::new(-s, c, 0.0), Vector1::zeros())
    }
    fn constraint_rhs(&self, q: &Vector3<f64>, v: &Vector3<f64>, _t: f64) -> Vector1<f64> {
        // γ = −Ġ q̇ with Ġ = θ̇ (−c, −s, 0).
        let (s, c) = q[2].sin_cos();
        Vector1::new(v[2] * (c * v[0] + s * v[1]))
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

impl Reduced<f64, 3, 2> for Sleigh {
    const SPEEDS: [&'static str; 2] = ["sigma", "omega"];
    const ROWS: [&'static str; 3] = ["sigma", "omega", "no_side_slip"];

    fn velocity_rows(&self, q: &Vector3<f64>, _t: f64) -> (Matrix3<f64>, Vector3<f64>) {
        (knife_edge_rows(q), Vector3::zeros())
    }
    fn row_rates(&self, q: &Vector3<f64>, v: &Vector3<f64>, _t: f64) -> Vector3<f64> {
        knife_edge_rates(q, v)
    }
}

/// The stacked rows of a knife edge at (x, y) heading θ = q[2], on the speeds
/// (forward = cos θ ẋ + sin θ ẏ, turn = θ̇), then the no-side-slip row.
pub fn knife_edge_rows(q: &Vector3<f64>) -> Matrix3<f64> {
    let (s, c) = q[2].sin_cos();
    Matrix3::new(c, s, 0.0, 0.0, 0.0, 1.0, -s, c, 0.0)
}

/// Their rates c = −Ȧ q̇, with Ȧ = θ̇ ∂A/∂θ.
pub fn knife_edge_rates(q: &Vector3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
    let (s, c) = q[2].sin_cos();
    Vector3::new(
        v[2] * (s * v[0] - c * v[1]),
        0.0,
        v[2] * (c * v[0] + s * v[1]),
    )
}

impl Sleigh {
    /// The reduced form on (σ, ω) in closed form, by hand: M*, F*, W, κ.
    pub fn closed_form(
        &self,
        q: &Vector3<f64>,
        u: &Vector2<f64>,
    ) -> (Matrix2<f64>, Vector2<f64>, Matrix3x2<f64>, Vector3<f64>) {
        let (s, c) = q[2].sin_cos();
        let (m, a, gs) = (self.m, self.a, self.gs);
        let (sigma, omega) = (u[0], u[1]);
        let mstar = Matrix2::new(m, 0.0, 0.0, self.ic + m * a * a);
        let fstar = Vector2::new(
            m * gs * c + m * a * omega * omega,
            -m * a * (sigma * omega + gs * s),
        );
        let w = Matrix3x2::new(c, 0.0, s, 0.0, 0.0, 1.0);
        let kappa = Vector3::new(-s * omega * sigma, c * omega * sigma, 0.0);
        (mstar, fstar, w, kappa)
    }
}

/// A pendulum whose rod length is driven, l(t) = l0 + e sin(w t): the rheonomic
/// constraint x² + y² − l(t)² = 0 with g = Φ_t = −2 l l̇ ≠ 0 and
/// γ = −2 |v|² + 2 (l̇² + l l̈).
pub struct DrivenPendulum {
    pub g: f64,
    pub l0: f64,
    pub e: f64,
    pub w: f64,
}

impl DrivenPendulum {
    pub fn standard() -> Self {
        Self {
            g: 9.81,
            l0: 1.0,
            e: 0.2,
            w: 3.0,
        }
    }

    /// l, l̇, l̈ at time t.
    pub fn length(&self, t: f64) -> [f64; 3] {
        let (s, c) = (self.w * t).sin_cos();
        [
            self.l0 + self.e * s,
            self.e * self.w * c,
            -self.e * self.w * self.w * s,
        ]
    }

    /// The Cartesian state at angle θ (from the downward vertical), rate θ̇, time t.
    pub fn state(&self, theta: f64, theta_dot: f64, t: f64) -> (Vector2<f64>, Vector2<f64>) {
        let [l, ld, _] = self.length(t);
        let (s, c) = theta.sin_cos();
        (
            Vector2::new(l * s, -l * c),
            Vector2::new(ld * s + l * c * theta_dot, -ld * c + l * s * theta_dot),
        )
    }
}

impl Lagrangian<f64, 2> for DrivenPendulum {
    const COORDINATES: [&'static str; 2] = ["x", "y"];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, _q: &Vector2<f64>, _t: f64) -> Matrix2<f64> {
        Matrix2::identity()
    }
    fn bias(&self, _q: &Vector2<f64>, _v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::zeros()
    }
    fn generalized_forces(&self, _q: &Vector2<f64>, _v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::new(0.0, -self.g)
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
        0.5 * v.norm_squared()
    }
    fn potential_energy(&self, q: &Vector2<f64>, _t: f64) -> f64 {
        self.g * q[1]
    }
    fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Constrained<f64, 2, 1> for DrivenPendulum {
    const CONSTRAINTS: [&'static str; 1] = ["driven_rod"];
    const HOLONOMIC: usize = 1;

    fn constraint_positions(&self, q: &Vector2<f64>, t: f64) -> Vector1<f64> {
        let l = self.length(t)[0];
        Vector1::new(q.norm_squared() - l * l)
    }
    fn constraint_jacobian(&self, q: &Vector2<f64>, t: f64) -> (Matrix1x2<f64>, Vector1<f64>) {
        let [l, ld, _] = self.length(t);
        (
            Matrix1x2::new(2.0 * q[0], 2.0 * q[1]),
            Vector1::new(-2.0 * l * ld),
        )
    }
    fn constraint_rhs(&self, _q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> Vector1<f64> {
        let [l, ld, ldd] = self.length(t);
        Vector1::new(-2.0 * v.norm_squared() + 2.0 * (ld * ld + l * ldd))
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
}
