use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, 0]),
    gravitation = [0, -9.81],
)]
struct Particle {
    m: f64,
}

fn main() {}
