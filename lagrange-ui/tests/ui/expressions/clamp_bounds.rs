use lagrange::Lagrangian;

// Reversed (or equal) literal bounds make `clamp` a constant.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = -k * clamp(x, 1, -1) - c * dot(x).clamp(0.5, 0.5)),
)]
struct Cart {
    m: f64,
    k: f64,
    c: f64,
}

fn main() {}
