use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    holonomic(rod = (bobb.x^2) + (bob.y^2) - (l^2)),
)]
struct Pendulum {
    m: f64,
    l: f64,
}

fn main() {}
