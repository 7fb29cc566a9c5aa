use lagrange::Lagrangian;

// An armature is a constant: it may not read the coordinates.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, armature = 0.1 * theta),
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {}
