use lagrange::Lagrangian;

// The normal is read when the code is derived: numbers only.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    point(p, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    contact(floor, on = p, normal = [0, 0, g], restitution = 0.5),
)]
struct Block {
    m: f64,
    g: f64,
}

fn main() {}
