use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, 0]),
)]
struct Particle {
    m: f64,
    links: usize,
}

fn main() {}
