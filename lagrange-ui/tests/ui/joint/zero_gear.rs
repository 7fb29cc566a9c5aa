use lagrange::Lagrangian;

// A gear ratio of zero would cut the motor off.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    inputs(u),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    joint(theta, motor = u, gear = 0),
)]
struct Pendulum {
    m: f64,
    l: f64,
}

fn main() {}
