use lagrange::Lagrangian;

// Constraints on a free orientation run in the multiplier form; the reduced
// form (`speeds`, `formulation(reduced)`) does not take one yet: one error,
// at the orientation, naming what does not combine and what does.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    orientation(turn),
    body(b, mass = m, inertia = [1, 1, 1], at = [x, y, z], rotation = turn),
    holonomic(height = z - 1),
    nonholonomic(slip_x = dot(x) - b.omega_y, slip_y = dot(y) + b.omega_x),
    speeds(u = dot(x)),
    formulation(reduced),
)]
struct Rolled {
    m: f64,
}

fn main() {}
