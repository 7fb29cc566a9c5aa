//! Items are lowered in dependency order, whatever the order written: a body
//! placed at a point of another body, a definition using a point, a point before
//! the body it sits on. And `com` places a body's centre of mass in its own axes.

use lagrange::prelude::*;

/// A double pendulum of two rods written "backwards": the second rod hangs from
/// the tip of the first, declared later; the definition of the bob height uses a
/// point. `com` puts each rod's centre half-way along it from its pivot.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a, b),
    define(height = tip2.z),
    body(rod2, mass = m, inertia = [i, i, 0], at = [tip1.x, tip1.y, tip1.z],
         com = [0, 0, -l / 2], rotation = rot_y(b)),
    point(tip1, on = rod1, at = [0, 0, -l]),
    point(tip2, on = rod2, at = [0, 0, -l]),
    body(rod1, mass = m, inertia = [i, i, 0], at = [0, 0, 0], com = [0, 0, -l / 2],
         rotation = rot_y(a)),
    potential = k * height,
)]
pub struct Backwards {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub k: f64,
}

/// The same pendulum in the usual order, centres written out.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a, b),
    body(rod1, mass = m, inertia = [i, i, 0],
         at = [-l / 2 * sin(a), 0, -l / 2 * cos(a)], rotation = rot_y(a)),
    body(rod2, mass = m, inertia = [i, i, 0],
         at = [-l * sin(a) - l / 2 * sin(b), 0, -l * cos(a) - l / 2 * cos(b)],
         rotation = rot_y(b)),
    potential = k * (-l * cos(a) - l * cos(b)),
)]
pub struct Forwards {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub k: f64,
}

#[test]
fn order_written_does_not_matter() {
    let (m, l, i, k) = (1.3, 0.7, 0.05, 2.0);
    let back = Backwards { m, l, i, k };
    let fwd = Forwards { m, l, i, k };
    for (a, b, va, vb) in [(0.3, -1.1, 0.4, 2.0), (2.0, 0.5, -1.0, 0.3)] {
        let (q, v) = (Vector2::new(a, b), Vector2::new(va, vb));
        let (m1, r1) = back.mass_matrix_and_rhs(&q, &v, 0.0);
        let (m2, r2) = fwd.mass_matrix_and_rhs(&q, &v, 0.0);
        assert!((m1 - m2).abs().max() < 1e-13, "{m1} vs {m2}");
        assert!((r1 - r2).abs().max() < 1e-12, "{r1} vs {r2}");
        let e1 = back.integral(&q, &v, 0.0);
        let e2 = fwd.integral(&q, &v, 0.0);
        assert!((e1 - e2).abs() < 1e-12);
    }
}
