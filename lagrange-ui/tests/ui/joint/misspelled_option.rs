use lagrange::Lagrangian;

// A misspelled option: the error suggests the one meant.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, armatur = 0.01),
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {}
