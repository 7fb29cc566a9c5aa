use lagrange::Lagrangian;

// Newton's coefficient lies in [0, 1]: the error is at the number.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    point(p, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    contact(floor, on = p, normal = [0, 0, 1], restitution = 1.5),
)]
struct Block {
    m: f64,
    g: f64,
}

fn main() {}
