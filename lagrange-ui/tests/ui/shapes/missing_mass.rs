use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(p, at = [x, 0]),
)]
struct Particle {
    m: f64,
}

fn main() {}
