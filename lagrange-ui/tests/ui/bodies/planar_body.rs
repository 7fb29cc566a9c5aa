use lagrange::Lagrangian;

// Rigid bodies are spatial; a planar centre is rejected with a hint.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, a),
    body(plate, mass = m, inertia = [i, i, i], at = [x, 0], rotation = rot_z(a)),
    point(corner, on = plate, at = [1, 1]),
)]
struct Plate {
    m: f64,
    i: f64,
}

fn main() {}
