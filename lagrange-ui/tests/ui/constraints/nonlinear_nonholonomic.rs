use lagrange::Lagrangian;

// A constraint quadratic in the velocities is not of the form A(q,t) q̇ + b = 0.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(p, mass = m, at = [x, y]),
    nonholonomic(speed_limit = x * dot(x) + dot(x) * dot(y) - 1),
)]
struct Skate {
    m: f64,
}

fn main() {}
