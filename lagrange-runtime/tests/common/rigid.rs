//! Rigid bodies with a quaternion orientation, written by hand: what the
//! derive's free bodies must agree with, and what the runtime's handling of
//! nq ≠ nv is tested on.

use lagrange_runtime::numeric::orientation::{quaternion, rotation_matrix};
use lagrange_runtime::{Lagrangian, Orientation};
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

/// ω × (I ω) for principal moments `inertia`.
fn gyroscopic(inertia: [f64; 3], w: Vector3<f64>) -> Vector3<f64> {
    let iw = Vector3::from(inertia).component_mul(&w);
    w.cross(&iw)
}

/// R(q) of the quaternion at `at`.
pub fn rotation<const Q: usize>(q: &SVector<f64, Q>, at: usize) -> Matrix3<f64> {
    let r = rotation_matrix(quaternion(q.as_slice(), at));
    Matrix3::from_fn(|i, j| r[i][j])
}

/// A free body under gravity g along −z: q = (x, y, z, w, qx, qy, qz), the
/// centre of mass in the world and the orientation; v = (ẋ, ẏ, ż, ω) with ω in
/// body axes along the principal axes.
pub struct FreeBody {
    pub m: f64,
    pub inertia: [f64; 3],
    pub g: f64,
}

impl Lagrangian<f64, 6, 7> for FreeBody {
    const COORDINATES: [&'static str; 7] = ["x", "y", "z", "body.w", "body.x", "body.y", "body.z"];
    const VELOCITIES: [&'static str; 6] = ["x", "y", "z", "body.wx", "body.wy", "body.wz"];
    const ORIENTATIONS: &'static [Orientation] = &[Orientation { q: 3, v: 3 }];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, _: &SVector<f64, 7>, _: f64) -> SMatrix<f64, 6, 6> {
        let [a, b, c] = self.inertia;
        SMatrix::from_diagonal(&SVector::<f64, 6>::from([self.m, self.m, self.m, a, b, c]))
    }

    fn bias(&self, _: &SVector<f64, 7>, v: &SVector<f64, 6>, _: f64) -> SVector<f64, 6> {
        let h = gyroscopic(self.inertia, v.fixed_rows::<3>(3).into_owned());
        SVector::from([0.0, 0.0, 0.0, h[0], h[1], h[2]])
    }

    fn generalized_forces(
        &self,
        _: &SVector<f64, 7>,
        _: &SVector<f64, 6>,
        _: f64,
    ) -> SVector<f64, 6> {
        SVector::from([0.0, 0.0, -self.m * self.g, 0.0, 0.0, 0.0])
    }

    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<f64, 7>,
        v: &SVector<f64, 6>,
        t: f64,
    ) -> (SMatrix<f64, 6, 6>, SVector<f64, 6>) {
        let rhs = self.generalized_forces(q, v, t) - self.bias(q, v, t);
        (self.mass_matrix(q, t), rhs)
    }

    fn kinetic_energy(&self, _: &SVector<f64, 7>, v: &SVector<f64, 6>, _: f64) -> f64 {
        let w = v.fixed_rows::<3>(3);
        let spin: f64 = (0..3).map(|k| self.inertia[k] * w[k] * w[k]).sum();
        0.5 * (self.m * v.fixed_rows::<3>(0).norm_squared() + spin)
    }

    fn potential_energy(&self, q: &SVector<f64, 7>, _: f64) -> f64 {
        self.m * self.g * q[2]
    }

    fn integral(&self, q: &SVector<f64, 7>, v: &SVector<f64, 6>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }

    /// T depends on neither the position nor, at fixed ω, the rotation.
    fn kinetic_gradient(
        &self,
        _: &SVector<f64, 7>,
        _: &SVector<f64, 6>,
        _: f64,
    ) -> Option<SVector<f64, 6>> {
        Some(SVector::zeros())
    }
}

impl FreeBody {
    /// The angular momentum about the centre of mass, in world axes.
    pub fn world_momentum(&self, q: &SVector<f64, 7>, v: &SVector<f64, 6>) -> Vector3<f64> {
        let w = v.fixed_rows::<3>(3).into_owned();
        rotation(q, 3) * Vector3::from(self.inertia).component_mul(&w)
    }
}

/// A heavy symmetric top on a fixed pivot: q = (w, x, y, z) turns body axes
/// into the world's, the symmetry axis is the body's z with the centre of mass
/// at distance `l` along it; `a` is the transverse moment about the pivot, `c`
/// the axial one; v = ω in body axes.
pub struct HeavyTop {
    pub a: f64,
    pub c: f64,
    pub mgl: f64,
}

impl Lagrangian<f64, 3, 4> for HeavyTop {
    const COORDINATES: [&'static str; 4] = ["top.w", "top.x", "top.y", "top.z"];
    const VELOCITIES: [&'static str; 3] = ["top.wx", "top.wy", "top.wz"];
    const ORIENTATIONS: &'static [Orientation] = &[Orientation { q: 0, v: 0 }];
    const RHEONOMIC: bool = false;

    fn mass_matrix(&self, _: &SVector<f64, 4>, _: f64) -> SMatrix<f64, 3, 3> {
        Matrix3::from_diagonal(&Vector3::new(self.a, self.a, self.c))
    }

    fn bias(&self, _: &SVector<f64, 4>, v: &SVector<f64, 3>, _: f64) -> SVector<f64, 3> {
        gyroscopic([self.a, self.a, self.c], *v)
    }

    /// The torque of gravity about the pivot in body axes: l e₃ × Rᵀ(−m g e_z).
    fn generalized_forces(
        &self,
        q: &SVector<f64, 4>,
        _: &SVector<f64, 3>,
        _: f64,
    ) -> SVector<f64, 3> {
        let r = rotation(q, 0);
        Vector3::new(self.mgl * r[(2, 1)], -self.mgl * r[(2, 0)], 0.0)
    }

    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<f64, 4>,
        v: &SVector<f64, 3>,
        t: f64,
    ) -> (SMatrix<f64, 3, 3>, SVector<f64, 3>) {
        let rhs = self.generalized_forces(q, v, t) - self.bias(q, v, t);
        (self.mass_matrix(q, t), rhs)
    }

    fn kinetic_energy(&self, _: &SVector<f64, 4>, v: &SVector<f64, 3>, _: f64) -> f64 {
        0.5 * (self.a * (v[0] * v[0] + v[1] * v[1]) + self.c * v[2] * v[2])
    }

    fn potential_energy(&self, q: &SVector<f64, 4>, _: f64) -> f64 {
        self.mgl * rotation(q, 0)[(2, 2)]
    }

    fn integral(&self, q: &SVector<f64, 4>, v: &SVector<f64, 3>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}
