use lagrange::Lagrangian;

// `level` is read, but only by a potential term without the coordinates:
// it drops out of every generalized force.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    inputs(level),
    point(cart, mass = m, at = [x, 0]),
    potential = k * pow(x, 2) / 2 + level,
)]
struct Cart {
    m: f64,
    k: f64,
}

fn main() {}
