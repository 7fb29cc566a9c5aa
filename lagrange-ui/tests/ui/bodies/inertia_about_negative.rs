use lagrange::Lagrangian;

// Given about the pivot, the moment about the centre of mass is
// 0.4 − 2 · 0.5² = −0.1: checked after the parallel-axis shift.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    body(stick, mass = 2, inertia = [0.4, 0.4, 0.1], at = [0, 0, 0], about = [0, 0, 0],
         com = [0, 0, -0.5], rotation = rot_x(theta)),
    gravity = [0, 0, -g],
)]
struct Stick {
    g: f64,
}

fn main() {}
