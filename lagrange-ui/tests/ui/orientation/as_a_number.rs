use lagrange::Lagrangian;

// An orientation is a rotation, not a number.
#[derive(Lagrangian)]
#[lagrange(
    orientation(turn),
    body(b, mass = m, inertia = [1, 2, 3], at = [0, 0, turn], rotation = turn),
)]
struct Spinner {
    m: f64,
}

fn main() {}
