use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, 0, 0, 1]),
)]
struct Particle {
    m: f64,
}

fn main() {}
