//! The system catalog as `#[derive(Lagrangian)]` descriptions: the systems
//! the project keeps running, each checked against its closed form, a
//! published benchmark or a second formulation in `tests/closed_forms.rs` and
//! the other behaviour tests, and shown by the gallery.
//!
//! Shared by the gallery example, the other examples and the behaviour tests
//! (`tests/` includes this file by path), so every system is written once.

#![allow(dead_code)]

use lagrange::Lagrangian;

/// Complete elliptic integral of the first kind, K(k) = π / (2 AGM(1, √(1−k²))):
/// the pendulum's closed-form period is 4 √(l/g) K(sin(θ0/2)).
pub fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..60 {
        let (an, bn) = ((a + b) / 2.0, (a * b).sqrt());
        a = an;
        b = bn;
        if (a - b).abs() < 1e-17 {
            break;
        }
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Simple pendulum, θ from the downward vertical. Generic over the scalar, so the
/// same description runs in `f64` and `f32`.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    // Hamilton's form (p and ∂T/∂q), for the symplectic Gauss method.
    emit(hamiltonian),
)]
pub struct Pendulum<T> {
    pub m: T,
    pub l: T,
    pub g: T,
}

/// C1: spherical pendulum in the chart (θ, φ), θ from the downward vertical
/// (seed 001, 12.16–12.18). det M = m² l⁴ sin²θ: singular at the poles.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(theta, phi),
    point(bob, mass = m, at = [l * sin(theta) * cos(phi),
                               l * sin(theta) * sin(phi),
                               -l * cos(theta)]),
    gravity = [0, 0, -g],
    emit(hamiltonian),
)]
pub struct SphericalPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// C2, Suslov ex. 95: a heavy particle on the ellipsoid x²/(at)² + y²/(bt)² + z²/(ct)² = 1
/// whose semi-axes grow with time. The map is rheonomic: T has T1 and T0 terms and
/// the energy is not conserved (nor, since V depends on t through z, the Jacobi integral).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(q1, q2),
    point(p, mass = m, at = [a * t * sin(q1) * cos(q2),
                             b * t * sin(q1) * sin(q2),
                             c * t * cos(q1)]),
    gravity = [0, 0, -g],
)]
pub struct GrowingEllipsoid {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub g: f64,
}

/// C3, Suslov ex. 96/100: two particles joined by a rigid rod of length `l`, free in
/// uniform gravity. Coordinates: the centre of mass (xc, yc, zc), the rod's angle φ
/// from Oz and the azimuth ψ of its projection on Oxy.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(xc, yc, zc, phi, psi),
    // The centre of mass divides the rod in the ratio a : b = m2 : m1.
    define(a = m2 * l / (m1 + m2), b = m1 * l / (m1 + m2)),
    point(p1, mass = m1, at = [xc + a * sin(phi) * cos(psi),
                               yc + a * sin(phi) * sin(psi),
                               zc + a * cos(phi)]),
    point(p2, mass = m2, at = [xc - b * sin(phi) * cos(psi),
                               yc - b * sin(phi) * sin(psi),
                               zc - b * cos(phi)]),
    gravity = [gx, gy, gz],
)]
pub struct Dumbbell {
    pub m1: f64,
    pub m2: f64,
    pub l: f64,
    pub gx: f64,
    pub gy: f64,
    pub gz: f64,
}

/// C7, Suslov ex. 101: a heavy particle in the vertical plane Oyz, Oz up.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(y, z),
    point(p, mass = m, at = [y, z]),
    gravity = [0, -g],
)]
pub struct HeavyParticle {
    pub m: f64,
    pub g: f64,
}

/// Planar double pendulum, absolute angles from the downward vertical.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(th1, th2),
    define(x1 = l1 * sin(th1), y1 = -l1 * cos(th1)),
    point(b1, mass = m1, at = [x1, y1]),
    point(b2, mass = m2, at = [x1 + l2 * sin(th2), y1 - l2 * cos(th2)]),
    gravity = [0, -g],
    emit(hamiltonian),
)]
pub struct DoublePendulum {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
}

/// Planar 5-link pendulum in relative angles: link k turns by θk relative to link
/// k−1, so the positions hold sin/cos of sums of angles, which the engine expands
/// into products of sin/cos of the angles themselves.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(a1, a2, a3, a4, a5),
    define(
        p1 = a1, p2 = a1 + a2, p3 = a1 + a2 + a3, p4 = a1 + a2 + a3 + a4,
        p5 = a1 + a2 + a3 + a4 + a5,
        x1 = l * sin(p1), y1 = -l * cos(p1),
        x2 = x1 + l * sin(p2), y2 = y1 - l * cos(p2),
        x3 = x2 + l * sin(p3), y3 = y2 - l * cos(p3),
        x4 = x3 + l * sin(p4), y4 = y3 - l * cos(p4),
        x5 = x4 + l * sin(p5), y5 = y4 - l * cos(p5),
    ),
    point(b1, mass = m, at = [x1, y1]),
    point(b2, mass = m, at = [x2, y2]),
    point(b3, mass = m, at = [x3, y3]),
    point(b4, mass = m, at = [x4, y4]),
    point(b5, mass = m, at = [x5, y5]),
    gravity = [0, -g],
)]
pub struct Chain5 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// A damped, driven pendulum: Rayleigh dissipation, a time-dependent generalized
/// torque and a horizontal Cartesian wind force on the bob, to exercise every kind
/// of applied force.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    dissipation = c * (dot(theta)^2) / 2,
    generalized_force(theta = a * cos(w * t)),
    force(bob, [f, 0]),
)]
pub struct DrivenPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
    pub a: f64,
    pub w: f64,
    pub f: f64,
}
pub mod bicycle;
pub mod cavity;
pub mod constrained;
pub mod contact;
pub mod control;
pub mod extremes;
pub mod free;
pub mod rolling;
pub mod study;
