use lagrange::Lagrangian;

// `push` is declared but nothing reads it: every controller on it would
// silently do nothing.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    inputs(push),
    point(cart, mass = m, at = [x, 0]),
    potential = k * pow(x, 2) / 2,
)]
struct Cart {
    m: f64,
    k: f64,
}

fn main() {}
