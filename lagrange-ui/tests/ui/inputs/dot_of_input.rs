use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    inputs(u),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = c * (dot(u) - dot(x))),
)]
struct Cart {
    m: f64,
    c: f64,
}

fn main() {}
