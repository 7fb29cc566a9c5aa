use lagrange::Lagrangian;

// A joint names a coordinate; `l` is a parameter.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(l, damping = 0.1),
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {}
