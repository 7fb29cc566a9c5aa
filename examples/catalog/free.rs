//! Free rotations (`orientation(..)`): a unit quaternion in q and the
//! angular velocity in body axes in v, no chart anywhere.

use lagrange::prelude::*;

/// A brick tumbling in space: its centre of mass (x, y, z) and a free
/// orientation; principal moments a < b < c about the centre.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    orientation(turn),
    body(brick, mass = m, inertia = [a, b, c], at = [x, y, z], rotation = turn),
    gravity = [0, 0, -g],
    shape(brick, box(size = [lx, ly, lz])),
)]
pub struct Brick {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub g: f64,
    pub lx: f64,
    pub ly: f64,
    pub lz: f64,
}

impl Brick {
    /// A solid brick of mass `m` with sides (lx, ly, lz), in free space.
    pub fn solid(m: f64, [lx, ly, lz]: [f64; 3]) -> Self {
        let moment = |p: f64, q: f64| m * (p * p + q * q) / 12.0;
        Brick {
            m,
            a: moment(ly, lz),
            b: moment(lx, lz),
            c: moment(lx, ly),
            g: 0.0,
            lx,
            ly,
            lz,
        }
    }
}

/// A heavy symmetric top on a fixed pivot with a free orientation; its
/// moments (a, a, c) about the pivot, its centre of mass l up its axis.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    orientation(spin),
    body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
         at = [0, 0, 0], rotation = spin),
    gravity = [0, 0, -g],
    shape(top, cylinder(radius = 0.12, length = 0.04, axis = z), at = [0, 0, l]),
    shape(top, capsule(radius = 0.008, length = 2 * l, axis = z), at = [0, 0, l]),
)]
pub struct QuaternionTop {
    pub m: f64,
    pub a: f64,
    pub c: f64,
    pub l: f64,
    pub g: f64,
}

/// The same top in the user's Euler angles z-x-z (precession ψ, nutation θ,
/// spin φ) with an atlas: a run through θ = 0, where this chart is singular,
/// goes on in the second chart and comes back. Generic over the scalar (the
/// atlas runs in f32 as in f64).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
         at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -g],
    emit(atlas),
    shape(top, cylinder(radius = 0.12, length = 0.04, axis = z), at = [0, 0, l]),
    shape(top, capsule(radius = 0.008, length = 2 * l, axis = z), at = [0, 0, l]),
)]
pub struct EulerTop<T = f64> {
    pub m: T,
    pub a: T,
    pub c: T,
    pub l: T,
    pub g: T,
}

/// Two rigid bodies on spherical joints: the first on a fixed pivot, the
/// second at the first's tip, its orientation the first's followed by its own
/// (`rotation = upper * lower`). The lower joint's speeds are the relative
/// angular velocity in the lower body's axes.
#[derive(Lagrangian)]
#[lagrange(
    orientation(upper, lower),
    body(arm, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, -l],
         at = [0, 0, 0], rotation = upper),
    point(tip, on = arm, at = [0, 0, -2 * l]),
    body(hand, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, -l],
         at = [tip.x, tip.y, tip.z], rotation = upper * lower),
    gravity = [0, 0, -g],
)]
pub struct SphericalChain {
    pub m: f64,
    pub a: f64,
    pub c: f64,
    pub l: f64,
    pub g: f64,
}

/// The sleeping top's threshold spin: C² n² = 4 A m g l (A, C the
/// transverse and axial moments about the pivot).
pub fn sleeping_top_threshold(a: f64, c: f64, mgl: f64) -> f64 {
    (4.0 * a * mgl).sqrt() / c
}

/// The sleeping top's growth rate at spin n: the largest real part of the
/// roots of A ξ̈ − i C n ξ̇ − m g l ξ = 0, √(4 A m g l − C² n²) / (2A) below
/// the threshold and zero above it.
pub fn sleeping_top_growth(a: f64, c: f64, mgl: f64, n: f64) -> f64 {
    (4.0 * a * mgl - (c * n).powi(2)).max(0.0).sqrt() / (2.0 * a)
}

/// The time between flips of a body spun near its intermediate axis
/// (principal moments i1 < i2 < i3, angular velocity w with L² > 2 E i2):
/// half the period 4K(k)/s of Landau–Lifshitz §37, with
/// s² = (i3 − i2)(L² − 2E i1)/(i1 i2 i3), k² = (i2 − i1)(2E i3 − L²)/((i3 − i2)(L² − 2E i1))
/// and K(k) = π / (2 AGM(1, √(1 − k²))).
pub fn flip_half_period([i1, i2, i3]: [f64; 3], w: [f64; 3]) -> f64 {
    let two_e = i1 * w[0] * w[0] + i2 * w[1] * w[1] + i3 * w[2] * w[2];
    let l2 = (i1 * w[0]).powi(2) + (i2 * w[1]).powi(2) + (i3 * w[2]).powi(2);
    assert!(
        l2 > two_e * i2,
        "the other case of §37: spin nearer the smallest axis"
    );
    let s = ((i3 - i2) * (l2 - two_e * i1) / (i1 * i2 * i3)).sqrt();
    let k2 = (i2 - i1) * (two_e * i3 - l2) / ((i3 - i2) * (l2 - two_e * i1));
    let (mut a, mut b) = (1.0, (1.0 - k2).sqrt());
    // Quadratic convergence: 10 iterations reach round-off.
    for _ in 0..10 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / a / s
}

/// A rigid body turning freely about its fixed centre of mass (a satellite's
/// attitude), principal moments a, b, c, driven by three body-axis torques
/// (reaction wheels, thrusters): each a force at unit distance along one
/// body axis, in the direction of the next, `t1` about x, `t2` about y, `t3`
/// about z.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    orientation(attitude),
    inputs(t1, t2, t3),
    body(sat, mass = m, inertia = [a, b, c], at = [0, 0, 0], rotation = attitude),
    point(arm_y, on = sat, at = [0, 1, 0]),
    point(arm_z, on = sat, at = [0, 0, 1]),
    point(arm_x, on = sat, at = [1, 0, 0]),
    // r × F with r = R e_y, F = t1 R e_z: t1 R e_x; and so on round.
    force(arm_y, [t1 * sat.axis_z.x, t1 * sat.axis_z.y, t1 * sat.axis_z.z]),
    force(arm_z, [t2 * sat.axis_x.x, t2 * sat.axis_x.y, t2 * sat.axis_x.z]),
    force(arm_x, [t3 * sat.axis_y.x, t3 * sat.axis_y.y, t3 * sat.axis_y.z]),
    shape(sat, box(size = [0.6, 0.4, 0.3])),
)]
pub struct Satellite {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
}
