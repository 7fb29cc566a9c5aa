use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(a),
    body(plate, mass = m, inertia = [i, i, 2 * i], at = [0, 0, 0],
         rotation = rot_z(a) * [[cos(a), -sin(a)], [sin(a), cos(a)]]),
)]
struct Plate {
    m: f64,
    i: f64,
}

fn main() {}
