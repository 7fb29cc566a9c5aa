use lagrange::Lagrangian;

// A body named like a parameter: one error, at the body (not also a cycle
// through the name both stand for).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    body(b, mass = b, inertia = [1, 1, 1], at = [0, 0, 0], rotation = rot_z(theta)),
)]
struct Wheel {
    b: f64,
}

fn main() {}
