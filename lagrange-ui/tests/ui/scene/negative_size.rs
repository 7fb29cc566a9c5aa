use lagrange::Lagrangian;

// A literal size must be positive.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a),
    body(wheel, mass = m, inertia = [1, 2, 1], at = [0, 0, r], rotation = rot_y(a)),
    shape(wheel, cylinder(radius = r, length = -0.05, axis = y)),
)]
struct Wheel {
    m: f64,
    r: f64,
}

fn main() {}
