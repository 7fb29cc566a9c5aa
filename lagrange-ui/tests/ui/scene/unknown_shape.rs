use lagrange::Lagrangian;

// `cone` is no shape: the error lists the ones there are.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a),
    body(wheel, mass = m, inertia = [1, 2, 1], at = [0, 0, r], rotation = rot_y(a)),
    shape(wheel, cone(radius = r, length = 0.1)),
)]
struct Wheel {
    m: f64,
    r: f64,
}

fn main() {}
