use lagrange::Lagrangian;

// A friction bound below zero would push the joint along its slip.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    joint(theta, friction = -0.2),
)]
struct Pendulum {
    m: f64,
    l: f64,
}

fn main() {}
