use lagrange::prelude::*;

// Two points placed at each other: no order can lower them.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(a, mass = m, at = [b.x + x, 0]),
    point(b, mass = m, at = [a.x - 1, 0]),
)]
pub struct Cycle {
    pub m: f64,
}

fn main() {}
