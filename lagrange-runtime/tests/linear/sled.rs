//! The Chaplygin sleigh on an incline with every derivative linearisation
//! needs, in multiplier and reduced form, driven by thrust, torque and a brake.

use crate::common::constrained::{knife_edge_rates, knife_edge_rows};
use lagrange_runtime::{Constrained, Driven, Lagrangian, Reduced};
use nalgebra::{Matrix1x3, Matrix3, Vector1, Vector3};

/// The Chaplygin sleigh on an incline (slope gravity `gs` along +x): edge at
/// (x, y), heading θ, centre of mass a distance `a` ahead, no side slip
/// −s ẋ + c ẏ = 0. Both forms (multiplier and reduced in u = (σ, ω)), with all
/// derivatives. Driven by a `thrust` F along the heading at the edge, a `torque`
/// τ and a `brake` b that pulls back by b σ:
/// ΔQ = (F − b σ)(c, s, 0) + (0, 0, τ), σ = c ẋ + s ẏ.
pub struct Sled {
    pub m: f64,
    pub a: f64,
    pub ic: f64,
    pub gs: f64,
}

impl Sled {
    pub fn standard() -> Self {
        Self {
            m: 1.1,
            a: 0.4,
            ic: 0.25,
            gs: 0.6,
        }
    }
}

impl Lagrangian<f64, 3> for Sled {
    const CONSTRAINED: bool = true;

    fn visit_form<F: lagrange_runtime::FormVisitor<f64, 3, Self>>(&self, form: F) -> F::Output {
        form.multipliers::<1>(self)
    }

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
    fn rhs_jacobians(
        &self,
        q: &Vector3<f64>,
        v: &Vector3<f64>,
        acc: &Vector3<f64>,
        _t: f64,
    ) -> Option<(Matrix3<f64>, Matrix3<f64>)> {
        let (s, c) = q[2].sin_cos();
        let (m, a, w) = (self.m, self.a, v[2]);
        let mut jq = Matrix3::zeros();
        jq[(0, 2)] = -m * a * s * w * w + m * a * c * acc[2];
        jq[(1, 2)] = m * a * c * w * w + m * a * s * acc[2];
        jq[(2, 2)] = -m * self.gs * a * c + m * a * (c * acc[0] + s * acc[1]);
        let mut jv = Matrix3::zeros();
        jv[(0, 2)] = 2.0 * m * a * c * w;
        jv[(1, 2)] = 2.0 * m * a * s * w;
        Some((jq, jv))
    }
}

impl Constrained<f64, 3, 1> for Sled {
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
    fn constraint_derivatives(
        &self,
        q: &Vector3<f64>,
        v: &Vector3<f64>,
        acc: &Vector3<f64>,
        nu: &Vector1<f64>,
        _t: f64,
    ) -> Option<(Matrix3<f64>, Matrix1x3<f64>, Matrix1x3<f64>, Matrix1x3<f64>)> {
        let (s, c) = q[2].sin_cos();
        let mut dgn = Matrix3::zeros();
        dgn[(0, 2)] = -c * nu[0];
        dgn[(1, 2)] = -s * nu[0];
        let dga = Matrix1x3::new(
            0.0,
            0.0,
            v[2] * (-s * v[0] + c * v[1]) + c * acc[0] + s * acc[1],
        );
        let dgv = Matrix1x3::new(v[2] * c, v[2] * s, c * v[0] + s * v[1]);
        let dvel = Matrix1x3::new(0.0, 0.0, -c * v[0] - s * v[1]);
        Some((dgn, dga, dgv, dvel))
    }
}

impl Reduced<f64, 3, 2> for Sled {
    const SPEEDS: [&'static str; 2] = ["sigma", "omega"];
    const ROWS: [&'static str; 3] = ["sigma", "omega", "no_side_slip"];

    fn velocity_rows(&self, q: &Vector3<f64>, _t: f64) -> (Matrix3<f64>, Vector3<f64>) {
        (knife_edge_rows(q), Vector3::zeros())
    }
    fn row_rates(&self, q: &Vector3<f64>, v: &Vector3<f64>, _t: f64) -> Vector3<f64> {
        knife_edge_rates(q, v)
    }
    fn row_derivatives(
        &self,
        q: &Vector3<f64>,
        v: &Vector3<f64>,
        acc: &Vector3<f64>,
        nu: &Vector3<f64>,
        _t: f64,
    ) -> Option<(Matrix3<f64>, Matrix3<f64>, Matrix3<f64>, Matrix3<f64>)> {
        let (s, c) = q[2].sin_cos();
        let w = v[2];
        // Only θ moves A and c; each q-derivative is its θ column.
        let column = |x: Vector3<f64>| {
            let mut m = Matrix3::zeros();
            m.set_column(2, &x);
            m
        };
        let danu = column(Vector3::new(
            -s * nu[0] - c * nu[2],
            c * nu[0] - s * nu[2],
            0.0,
        ));
        let dres = column(Vector3::new(
            w * (c * v[0] + s * v[1]) + s * acc[0] - c * acc[1],
            0.0,
            w * (-s * v[0] + c * v[1]) + c * acc[0] + s * acc[1],
        ));
        let drate = Matrix3::new(
            w * s,
            -w * c,
            s * v[0] - c * v[1],
            0.0,
            0.0,
            0.0,
            w * c,
            w * s,
            c * v[0] + s * v[1],
        );
        let dvel = column(Vector3::new(
            -s * v[0] + c * v[1],
            0.0,
            -c * v[0] - s * v[1],
        ));
        Some((danu, dres, drate, dvel))
    }
}

impl Driven<f64, 3, 3> for Sled {
    const INPUTS: [&'static str; 3] = ["thrust", "torque", "brake"];

    fn input_forces(
        &self,
        q: &Vector3<f64>,
        v: &Vector3<f64>,
        u: &Vector3<f64>,
        _t: f64,
    ) -> Vector3<f64> {
        let (s, c) = q[2].sin_cos();
        let pull = u[0] - u[2] * (c * v[0] + s * v[1]);
        Vector3::new(pull * c, pull * s, u[1])
    }
    fn input_jacobians(
        &self,
        q: &Vector3<f64>,
        v: &Vector3<f64>,
        u: &Vector3<f64>,
        _t: f64,
    ) -> (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>) {
        let (s, c) = q[2].sin_cos();
        let sigma = c * v[0] + s * v[1];
        let lateral = -s * v[0] + c * v[1]; // ∂σ/∂θ
        let pull = u[0] - u[2] * sigma;
        let bu = Matrix3::new(c, 0.0, -sigma * c, s, 0.0, -sigma * s, 0.0, 1.0, 0.0);
        let mut dq = Matrix3::zeros();
        dq[(0, 2)] = -u[2] * lateral * c - pull * s;
        dq[(1, 2)] = -u[2] * lateral * s + pull * c;
        let dv = Matrix3::new(c * c, c * s, 0.0, c * s, s * s, 0.0, 0.0, 0.0, 0.0) * -u[2];
        (bu, dq, dv)
    }
}
