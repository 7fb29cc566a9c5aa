use lagrange::Lagrangian;

// Coulomb friction at a joint is not derived yet: refused at its value, with
// what to write instead, rather than dropped.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, damping = 0.1, friction = fc),
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
    fc: f64,
}

fn main() {}
