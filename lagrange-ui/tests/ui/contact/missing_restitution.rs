use lagrange::Lagrangian;

// No silent default for the restitution: the contact's name says what is missing.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    point(p, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    contact(floor, on = p, normal = [0, 0, 1], friction = 0.3),
)]
struct Block {
    m: f64,
    g: f64,
}

fn main() {}
