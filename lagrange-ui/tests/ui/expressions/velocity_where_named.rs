use lagrange::Lagrangian;

// Each error names the item the velocity may not appear in.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, a),
    body(b, mass = m, inertia = [1, 1, 1], at = [x, dot(y), 0], rotation = rot_z(a + dot(a))),
    point(p, mass = m, at = [x, y, 0]),
    holonomic(rail = y - dot(x)),
    potential = m * dot(y),
)]
struct Slider {
    m: f64,
}

fn main() {}
