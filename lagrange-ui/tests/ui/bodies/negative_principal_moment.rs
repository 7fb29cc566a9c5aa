use lagrange::Lagrangian;

// The rotor turns about its x axis only, so M = A stays positive and the
// system would run: but no rigid body has a negative moment of inertia.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    body(rotor, mass = m, inertia = [1, 1, -0.5], at = [0, 0, 0], rotation = rot_x(theta)),
)]
struct Rotor {
    m: f64,
}

fn main() {}
