use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, dot(x)]),
)]
struct Particle {
    m: f64,
}

fn main() {}
