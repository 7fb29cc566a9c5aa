use lagrange::Lagrangian;

// A coordinate in the inertia or in the centre of mass: each error names
// what must be constant, not "a mass".
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, theta),
    body(arm, mass = m, inertia = [x, 1, 1], at = [0, 0, 0], com = [0, theta, 0], rotation = rot_x(theta)),
    point(slider, mass = m, at = [x, 0, 0]),
)]
struct Arm {
    m: f64,
}

fn main() {}
