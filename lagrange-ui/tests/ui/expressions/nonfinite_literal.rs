use lagrange::prelude::*;

// `1e400` is beyond f64 (an infinity) and `1e-400` below it (a zero): the
// equations would carry either silently.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(heavy, mass = 1e400, at = [x, 0]),
    point(light, mass = 1e-400, at = [x, 1]),
    gravity = [0, -9.81],
)]
pub struct Carts {}

fn main() {}
