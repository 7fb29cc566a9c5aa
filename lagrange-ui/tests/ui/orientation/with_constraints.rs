use lagrange::Lagrangian;

// Constraints on a free orientation are not supported yet: one error, at the
// orientation, naming what does not combine.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(z),
    orientation(turn),
    body(b, mass = m, inertia = [1, 2, 3], at = [0, 0, z], rotation = turn),
    holonomic(floor = z),
)]
struct Held {
    m: f64,
}

fn main() {}
