use lagrange::Lagrangian;

// `coordinates()` underlines itself.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(),
    point(p, mass = m, at = [1, 2]),
)]
struct Particle {
    m: f64,
}

fn main() {}
