use lagrange::Lagrangian;

// A joint's damping is not negative (it would feed energy in): the error is
// at the number.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, damping = -0.3),
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {}
