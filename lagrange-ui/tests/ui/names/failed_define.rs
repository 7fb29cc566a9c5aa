use lagrange::Lagrangian;

// A definition that fails to parse is one error; its uses add none.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    define(r = x +* 2),
    point(p, mass = m, at = [r, 0]),
    potential = m * r,
)]
struct Particle {
    m: f64,
}

fn main() {}
