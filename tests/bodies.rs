//! Body conveniences checked against the descriptions they replace: inertia
//! given about a point other than the centre of mass (`about`, the
//! parallel-axis theorem applied by the macro) and a body's axes in
//! expressions (`B.axis_z.x`, entries of its rotation matrix).

use crate::common;

use common::numeric::Lcg;
use lagrange::prelude::*;

/// A heavy symmetric top on a fixed pivot, its inertia about the pivot
/// (A, A, C), its centre of mass l up the symmetry axis.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(phi, theta, psi),
    body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
         at = [0, 0, 0], rotation = euler_zxz(phi, theta, psi)),
    gravity = [0, 0, -g],
)]
struct TopAboutPivot {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// The same top written by hand: inertia about the centre of mass A − m l²,
/// the centre at R·(0, 0, l).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(phi, theta, psi),
    body(top, mass = m, inertia = [a - m * (l^2), a - m * (l^2), c],
         at = [l * sin(theta) * sin(phi), -l * sin(theta) * cos(phi), l * cos(theta)],
         rotation = euler_zxz(phi, theta, psi)),
    gravity = [0, 0, -g],
)]
struct TopByHand {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// A rigid rod swinging in 3-D on a pivot, with a second rod hung at its tip:
/// the tip found from the first rod's axis, `rod.axis_z` times its length.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(a1, b1, a2, b2),
    body(rod, mass = m, inertia = [j, j, 0], at = [0, 0, 0], com = [0, 0, -l / 2],
         rotation = rot_x(a1) * rot_y(b1)),
    body(bob, mass = m, inertia = [j, j, 0], com = [0, 0, -l / 2],
         at = [-l * rod.axis_z.x, -l * rod.axis_z.y, -l * rod.axis_z.z],
         rotation = rot_x(a2) * rot_y(b2)),
    gravity = [0, 0, -g],
)]
struct ChainByAxes {
    m: f64,
    j: f64,
    l: f64,
    g: f64,
}

/// The same chain with the tip as a point on the first rod.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(a1, b1, a2, b2),
    body(rod, mass = m, inertia = [j, j, 0], at = [0, 0, 0], com = [0, 0, -l / 2],
         rotation = rot_x(a1) * rot_y(b1)),
    point(tip, on = rod, at = [0, 0, -l]),
    body(bob, mass = m, inertia = [j, j, 0], com = [0, 0, -l / 2],
         at = [tip.x, tip.y, tip.z], rotation = rot_x(a2) * rot_y(b2)),
    gravity = [0, 0, -g],
)]
struct ChainByPoint {
    m: f64,
    j: f64,
    l: f64,
    g: f64,
}

/// Largest difference of M and Q − h between two descriptions at random states.
fn gap<A, B, const N: usize>(a: &A, b: &B, seed: u64) -> f64
where
    A: Lagrangian<f64, N>,
    B: Lagrangian<f64, N>,
{
    let mut rng = Lcg(seed);
    let mut worst: f64 = 0.0;
    for _ in 0..20 {
        let q = SVector::<f64, N>::from_fn(|_, _| 1.5 * rng.next());
        let v = SVector::<f64, N>::from_fn(|_, _| 2.0 * rng.next());
        let (ma, fa) = a.mass_matrix_and_rhs(&q, &v, 0.0);
        let (mb, fb) = b.mass_matrix_and_rhs(&q, &v, 0.0);
        worst = worst.max((ma - mb).amax()).max((fa - fb).amax());
    }
    worst
}

#[test]
fn inertia_about_the_pivot_is_moved_to_the_centre_of_mass() {
    let (m, a, c, l, g) = (1.3, 0.9, 0.4, 0.5, 9.81);
    let about = TopAboutPivot { m, a, c, l, g };
    let by_hand = TopByHand { m, a, c, l, g };
    let d = gap(&about, &by_hand, 3);
    assert!(d < 1e-13, "{d:e}");
}

#[test]
fn a_body_axis_places_an_attachment_as_a_point_on_the_body_does() {
    let (m, j, l, g) = (0.7, 0.05, 0.8, 9.81);
    let d = gap(&ChainByAxes { m, j, l, g }, &ChainByPoint { m, j, l, g }, 5);
    assert!(d < 1e-13, "{d:e}");
}
