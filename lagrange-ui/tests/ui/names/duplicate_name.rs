use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, l),
    point(p, mass = m, at = [x, l]),
)]
struct Particle {
    m: f64,
    l: f64,
}

fn main() {}
