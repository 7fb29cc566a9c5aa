use lagrange::prelude::*;

// `l / (2 - 2)` would put an infinity into the equations.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l / (2 - 2) * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

fn main() {}
