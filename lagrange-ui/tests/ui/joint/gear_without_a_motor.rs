use lagrange::Lagrangian;

// A gear with nothing behind it scales nothing.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    joint(theta, damping = 0.1, gear = 50),
)]
struct Pendulum {
    m: f64,
    l: f64,
}

fn main() {}
