//! Systems for the stability studies at the extremes (issue "Stability at the
//! extremes"): a stiff spring pendulum, the heavy symmetric top, and a wrapper that
//! gives a constant-mass-matrix system the ∂T/∂q the symplectic Gauss method needs.

use lagrange::Lagrangian;

/// A pendulum whose rod is a stiff spring: polar coordinates (r, θ) of the bob,
/// θ from the downward vertical, spring stiffness `k` and rest length `l0`. With
/// k/m = 10⁸ the radial mode is 10⁴ times faster than the swing: a stiff system.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(r, theta),
    point(bob, mass = m, at = [r * sin(theta), -r * cos(theta)]),
    gravity = [0, -g],
    potential = k * ((r - l0)^2) / 2,
)]
pub struct SpringPendulum {
    pub m: f64,
    pub k: f64,
    pub l0: f64,
    pub g: f64,
}

/// The heavy symmetric top (Lagrange's top) on a fixed pivot: centre of mass at
/// distance `l` up the symmetry axis, moments `a` (transverse, about the centre of
/// mass) and `c` (axial); z-x-z Euler angles ψ (precession), θ (nutation), φ (spin).
/// ψ and φ are cyclic, so p_ψ and p_φ are conserved along with the energy.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = m, inertia = [a, a, c],
         at = [l * sin(theta) * sin(psi), -l * sin(theta) * cos(psi), l * cos(theta)],
         rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -g],
)]
pub struct HeavyTop {
    pub m: f64,
    pub a: f64,
    pub c: f64,
    pub l: f64,
    pub g: f64,
}
