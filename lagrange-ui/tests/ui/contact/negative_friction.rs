use lagrange::Lagrangian;

// Coulomb's coefficient is not negative: the error is at the number.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    point(p, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    contact(floor, on = p, normal = [0, 0, 1], restitution = 0.5, friction = -0.2),
)]
struct Block {
    m: f64,
    g: f64,
}

fn main() {}
