use lagrange::Lagrangian;

// Every error is reported, each at its own token, not only the first.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = mass, at = [l * sin(theta), -l * cos(theta)]),
    potential = m * g * foo(theta),
    force(rock, [0, 1]),
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {}
