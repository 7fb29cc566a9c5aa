use lagrange::Lagrangian;

// Points have no axes; `axis_w` is not an axis.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a),
    point(p, mass = m, at = [sin(a), 0, -cos(a)]),
    body(b, mass = m, inertia = [1, 1, 1], at = [0, 0, 0], rotation = rot_x(a)),
    potential = m * p.axis_x.z + m * b.axis_w.z,
)]
struct Axes {
    m: f64,
}

fn main() {}
