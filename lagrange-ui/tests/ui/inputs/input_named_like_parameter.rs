use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    inputs(k),
    point(cart, mass = m, at = [x, 0]),
    potential = k * (x^2) / 2,
)]
struct Spring {
    m: f64,
    k: f64,
}

fn main() {}
