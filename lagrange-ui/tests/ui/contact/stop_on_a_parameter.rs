use lagrange::Lagrangian;

// A stop bounds a coordinate, not a parameter.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    point(p, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    stop(floor, m >= 0, restitution = 0.5),
)]
struct Block {
    m: f64,
    g: f64,
}

fn main() {}
