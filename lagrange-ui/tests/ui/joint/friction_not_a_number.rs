use lagrange::Lagrangian;

// A joint's friction bound is a number written out, as a contact's μ is
// (it is read when the code is derived, into the contact's law).
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
