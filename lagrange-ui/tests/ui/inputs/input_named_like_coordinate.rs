use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    inputs(force, x),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = force),
)]
struct Cart {
    m: f64,
}

fn main() {}
