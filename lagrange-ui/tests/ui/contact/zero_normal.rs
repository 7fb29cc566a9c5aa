use lagrange::Lagrangian;

// A plane needs a direction: a zero normal is refused at it.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    point(p, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    contact(floor, on = p, normal = [0, 0, 0], restitution = 0.5),
)]
struct Block {
    m: f64,
    g: f64,
}

fn main() {}
