use lagrange::Lagrangian;

// `phi` moves nothing: a zero row of M is an error at the coordinate.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, phi),
    point(p, mass = m, at = [x, 0]),
    potential = k * (phi^2) / 2,
)]
struct Cart {
    m: f64,
    k: f64,
}

fn main() {}
