use lagrange::Lagrangian;

// A shape on a body the description does not declare.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a),
    body(wheel, mass = m, inertia = [1, 2, 1], at = [0, 0, r], rotation = rot_y(a)),
    shape(wheeel, sphere(radius = r)),
)]
struct Wheel {
    m: f64,
    r: f64,
}

fn main() {}
