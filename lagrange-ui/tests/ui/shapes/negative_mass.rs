use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(cart, mass = -2, at = [x, 0]),
    potential = k * pow(x, 2) / 2,
)]
struct Cart {
    k: f64,
}

fn main() {}
