use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    inputs(lift),
    define(pivot = lift / 2),
    point(bob, mass = m, at = [l * sin(theta), pivot - l * cos(theta)]),
    gravity = [0, -g],
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {}
