use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    inputs(load),
    point(cart, mass = m + load, at = [x, 0]),
    generalized_force(x = load),
)]
struct Cart {
    m: f64,
}

fn main() {}
