use lagrange::Lagrangian;

// An orientation's angular velocity is not a coordinate `generalized_force`
// can name.
#[derive(Lagrangian)]
#[lagrange(
    orientation(att),
    inputs(tz),
    body(sat, mass = 1.0, inertia = [1, 2, 3], at = [0, 0, 0], rotation = att),
    generalized_force(att.wz = tz),
)]
struct Satellite {}

fn main() {}
