use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(a),
    body(wheel, mass = m, inertia = [i, i], at = [0, 0, 0], rotation = rot_x(a)),
)]
struct Wheel {
    m: f64,
    i: f64,
}

fn main() {}
