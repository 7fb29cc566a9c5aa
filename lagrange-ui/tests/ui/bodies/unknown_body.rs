use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(a),
    body(wheel, mass = m, inertia = [i, i, j], at = [0, 0, 0], rotation = rot_x(a)),
    point(rim, on = wheal, at = [0, r, 0]),
)]
struct Wheel {
    m: f64,
    i: f64,
    j: f64,
    r: f64,
}

fn main() {}
