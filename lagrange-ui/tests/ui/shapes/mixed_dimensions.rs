use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, 0, 0]),
    gravity = [0, -g],
)]
struct Particle {
    m: f64,
    g: f64,
}

fn main() {}
