use lagrange::Lagrangian;

// Names of the wrong kind are reported as what they are.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, a),
    body(hub, mass = m, inertia = [1, 1, 1], at = [x, 0, 0], rotation = rot_z(a)),
    point(tip, mass = m, at = [x, 1, 0]),
    point(rim, on = tip, at = [1, 0, 0]),
    force(x, [1, 0, 0]),
    generalized_force(m = 1),
    potential = m * pow(x.y, 2),
)]
struct Wheel {
    m: f64,
}

fn main() {}
