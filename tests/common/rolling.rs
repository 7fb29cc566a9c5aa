//! The rolling sphere and disk in Euler angles lifted to their quaternion
//! twins (`catalog::rolling`): the chart sphere, chart states as quaternion
//! states with their rates (by dual numbers), and the comparisons. Shared by
//! the tests of both constrained forms with orientations.
#![allow(dead_code)] // each test binary uses a different subset

use crate::catalog::constrained::RollingDisk;
use crate::catalog::rolling::QuaternionSphere;
use crate::common::numeric::Lcg;
use lagrange::prelude::*;
use lagrange::project_consistent;
use nalgebra::{Matrix3, SVector, Vector3};
use std::ops::{Add, Mul, Neg, Sub};

/// Chaplygin's ball in Euler angles z-x-z: `RollingSphere` with unequal
/// moments (singular at θ = 0).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(ball, mass = m, inertia = [j1, j2, j3], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
)]
pub struct ChartBall {
    m: f64,
    j1: f64,
    j2: f64,
    j3: f64,
    a: f64,
    g: f64,
}

pub const BALL: QuaternionSphere = QuaternionSphere {
    m: 1.3,
    j1: 0.2,
    j2: 0.35,
    j3: 0.5,
    a: 0.7,
    g: 9.81,
};
pub const CHART_BALL: ChartBall = ChartBall {
    m: 1.3,
    j1: 0.2,
    j2: 0.35,
    j3: 0.5,
    a: 0.7,
    g: 9.81,
};

/// A number with a first-order part: x + ε ẋ, ε² = 0. Evaluating the map
/// (q, q̇) ↦ v at (q + ε q̇, q̇ + ε q̈) gives v and v̇ exactly.
#[derive(Clone, Copy, Debug)]
pub struct D(pub f64, pub f64);

impl Add for D {
    type Output = D;
    fn add(self, o: D) -> D {
        D(self.0 + o.0, self.1 + o.1)
    }
}
impl Sub for D {
    type Output = D;
    fn sub(self, o: D) -> D {
        D(self.0 - o.0, self.1 - o.1)
    }
}
impl Mul for D {
    type Output = D;
    fn mul(self, o: D) -> D {
        D(self.0 * o.0, self.0 * o.1 + self.1 * o.0)
    }
}
impl Neg for D {
    type Output = D;
    fn neg(self) -> D {
        D(-self.0, -self.1)
    }
}
impl D {
    fn c(x: f64) -> D {
        D(x, 0.0)
    }
    fn sin(self) -> D {
        D(self.0.sin(), self.1 * self.0.cos())
    }
    fn cos(self) -> D {
        D(self.0.cos(), -self.1 * self.0.sin())
    }
}

/// rot_axis(α)ᵀ w.
pub fn turn_back(axis: usize, alpha: D, w: [D; 3]) -> [D; 3] {
    let (c, s) = (alpha.cos(), alpha.sin());
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut out = w;
    out[i] = c * w[i] + s * w[j];
    out[j] = c * w[j] - s * w[i];
    out
}

/// ω in body axes of R = rot_k1(a1) rot_k2(a2) rot_k3(a3) at angles `a`
/// and rates `r`: R3ᵀ(R2ᵀ e_k1 ȧ1 + e_k2 ȧ2) + e_k3 ȧ3.
pub fn body_rate(axes: [usize; 3], a: [D; 3], r: [D; 3]) -> [D; 3] {
    let unit = |k: usize, x: D| {
        let mut e = [D::c(0.0); 3];
        e[k] = x;
        e
    };
    let w = turn_back(axes[1], a[1], unit(axes[0], r[0]));
    let w = [0, 1, 2].map(|i| w[i] + unit(axes[1], r[1])[i]);
    let w = turn_back(axes[2], a[2], w);
    [0, 1, 2].map(|i| w[i] + unit(axes[2], r[2])[i])
}

/// The Hamilton product.
pub fn mul([a, b, c, d]: [f64; 4], [w, x, y, z]: [f64; 4]) -> [f64; 4] {
    [
        a * w - b * x - c * y - d * z,
        a * x + b * w + c * z - d * y,
        a * y - b * z + c * w + d * x,
        a * z + b * y - c * x + d * w,
    ]
}

/// The unit quaternion of rot_k1(a1) rot_k2(a2) rot_k3(a3).
pub fn quaternion_of(axes: [usize; 3], a: [f64; 3]) -> [f64; 4] {
    let about = |k: usize, x: f64| {
        let mut q = [(x / 2.0).cos(), 0.0, 0.0, 0.0];
        q[1 + k] = (x / 2.0).sin();
        q
    };
    mul(
        mul(about(axes[0], a[0]), about(axes[1], a[1])),
        about(axes[2], a[2]),
    )
}

/// Lifts a chart state (q, q̇, q̈) to duals: q + ε q̇ and q̇ + ε q̈.
pub fn lift<const M: usize>(
    q: &SVector<f64, M>,
    v: &SVector<f64, M>,
    a: &SVector<f64, M>,
) -> ([D; M], [D; M]) {
    (
        std::array::from_fn(|i| D(q[i], v[i])),
        std::array::from_fn(|i| D(v[i], a[i])),
    )
}

pub const ZXZ: [usize; 3] = [2, 0, 2];
/// rot_z(ψ) rot_x(θ) rot_y(φ), the disk's chart.
pub const ZXY: [usize; 3] = [2, 0, 1];

/// The sphere's chart state (x, y, z, ψ, θ, φ) with rates and accelerations
/// as the quaternion sphere's: q, v and v̇.
pub fn ball_state(
    q: &SVector<f64, 6>,
    v: &SVector<f64, 6>,
    a: &SVector<f64, 6>,
) -> (SVector<f64, 7>, SVector<f64, 6>, SVector<f64, 6>) {
    let (qd, vd) = lift(q, v, a);
    let w = body_rate(ZXZ, [qd[3], qd[4], qd[5]], [vd[3], vd[4], vd[5]]);
    let quat = quaternion_of(ZXZ, [q[3], q[4], q[5]]);
    let speeds = [vd[0], vd[1], vd[2], w[0], w[1], w[2]];
    let position = [q[0], q[1], q[2], quat[0], quat[1], quat[2], quat[3]];
    (
        SVector::from(position),
        SVector::from(speeds.map(|x| x.0)),
        SVector::from(speeds.map(|x| x.1)),
    )
}

/// The wobbling start of the disk comparisons (rolling at 6 rad/s, tilted
/// 0.3 and turning: it wobbles, it does not fall), made consistent in the
/// chart, and the same state of a quaternion disk.
#[allow(clippy::type_complexity)]
pub fn wobbling_start(
    chart: &RollingDisk,
) -> (
    (SVector<f64, 5>, SVector<f64, 5>),
    (SVector<f64, 7>, SVector<f64, 6>),
) {
    let q = SVector::from([0.0, 0.0, 0.2, 0.3, 0.0]);
    let v = SVector::from([0.0, 0.0, 1.0, 0.5, 6.0]);
    let (q, v) = project_consistent(chart, q, v, 0.0).unwrap();
    let (qq, vq, _) = disk_state(chart, &q, &v, &SVector::zeros());
    ((q, v), (qq, vq))
}

/// The disk's chart state (contact x, y, ψ, θ, φ) as the quaternion disk's
/// (centre, quaternion; centre velocity, ω in body axes) and its rate.
pub fn disk_state(
    disk: &RollingDisk,
    q: &SVector<f64, 5>,
    v: &SVector<f64, 5>,
    a: &SVector<f64, 5>,
) -> (SVector<f64, 7>, SVector<f64, 6>, SVector<f64, 6>) {
    let (qd, vd) = lift(q, v, a);
    let r = D::c(disk.a);
    let (psi, theta) = (qd[2], qd[3]);
    let (dpsi, dtheta) = (vd[2], vd[3]);
    let (st, ct, sp, cp) = (theta.sin(), theta.cos(), psi.sin(), psi.cos());
    let centre_rate = [
        vd[0] + r * (ct * sp * dtheta + st * cp * dpsi),
        vd[1] - r * (ct * cp * dtheta - st * sp * dpsi),
        -(r * st * dtheta),
    ];
    let w = body_rate(ZXY, [qd[2], qd[3], qd[4]], [vd[2], vd[3], vd[4]]);
    let quat = quaternion_of(ZXY, [q[2], q[3], q[4]]);
    let (s0, c0) = (q[3].sin(), q[3].cos());
    let centre = [
        q[0] + disk.a * s0 * q[2].sin(),
        q[1] - disk.a * s0 * q[2].cos(),
        disk.a * c0,
    ];
    let speeds = [
        centre_rate[0],
        centre_rate[1],
        centre_rate[2],
        w[0],
        w[1],
        w[2],
    ];
    let position = [
        centre[0], centre[1], centre[2], quat[0], quat[1], quat[2], quat[3],
    ];
    (
        SVector::from(position),
        SVector::from(speeds.map(|x| x.0)),
        SVector::from(speeds.map(|x| x.1)),
    )
}

pub fn assert_close<const M: usize>(
    what: &str,
    got: &SVector<f64, M>,
    want: &SVector<f64, M>,
    tol: f64,
) {
    let err = (got - want).amax();
    assert!(
        err < tol * (1.0 + want.amax()),
        "{what}: {got:?} vs {want:?} ({err:e})"
    );
}

/// Quaternions q and −q are the same rotation: the distance between them.
pub fn quaternion_gap(p: &SVector<f64, 7>, q: &SVector<f64, 7>) -> f64 {
    let same = (3..7).map(|i| (p[i] - q[i]).abs()).fold(0.0, f64::max);
    let opposite = (3..7).map(|i| (p[i] + q[i]).abs()).fold(0.0, f64::max);
    let position = (0..3).map(|i| (p[i] - q[i]).abs()).fold(0.0, f64::max);
    position.max(same.min(opposite))
}

pub fn rotation_of(q: &SVector<f64, 7>) -> Matrix3<f64> {
    let r = lagrange::numeric::orientation::rotation_matrix([q[3], q[4], q[5], q[6]]);
    Matrix3::from_fn(|i, j| r[i][j])
}

pub fn uniform(rng: &mut Lcg, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * 0.5 * (rng.next() + 1.0)
}

/// A chart state of the sphere on its constraints: Euler angles with θ in
/// `tilt`, random rates, projected onto the rolling rows.
pub fn ball_start<S: Constrained<f64, 6, 3>>(
    sys: &S,
    rng: &mut Lcg,
    a: f64,
    tilt: (f64, f64),
) -> (SVector<f64, 6>, SVector<f64, 6>) {
    let pi = std::f64::consts::PI;
    let q = SVector::from([
        rng.next(),
        rng.next(),
        a,
        uniform(rng, -pi, pi),
        uniform(rng, tilt.0, tilt.1),
        uniform(rng, -pi, pi),
    ]);
    project_consistent(sys, q, rng.vector::<6>(3.0), 0.0).unwrap()
}

/// The angular momentum about the contact point, I_world ω + a e_z × m v_c:
/// conserved for a ball with its centre of mass at its centre (the contact
/// force and the weight have no moment about it, and the contact point moves
/// with the centre).
pub fn contact_momentum(
    ball: &QuaternionSphere,
    q: &SVector<f64, 7>,
    v: &SVector<f64, 6>,
) -> Vector3<f64> {
    let r = rotation_of(q);
    let inertia = Matrix3::from_diagonal(&Vector3::new(ball.j1, ball.j2, ball.j3));
    let omega = Vector3::new(v[3], v[4], v[5]);
    let centre = Vector3::new(v[0], v[1], v[2]) * ball.m;
    r * (inertia * omega) + Vector3::new(0.0, 0.0, ball.a).cross(&centre)
}
