use lagrange::Lagrangian;

// `coordinates = [x, y]` is one error with the fix, not one per use of x, y.
#[derive(Lagrangian)]
#[lagrange(
    coordinates = [x, y],
    point(p, mass = m, at = [x, y]),
)]
struct Particle {
    m: f64,
}

fn main() {}
