use lagrange::Lagrangian;

// The motor names a parameter, not one of the inputs.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    inputs(u),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    generalized_force(theta = u),
    joint(theta, motor = l, gear = 20),
)]
struct Pendulum {
    m: f64,
    l: f64,
}

fn main() {}
