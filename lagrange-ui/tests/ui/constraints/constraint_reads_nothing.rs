use lagrange::Lagrangian;

// A holonomic constraint without coordinates constrains nothing; a
// nonholonomic one without velocities is a condition on the configuration.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    holonomic(fixed = l - 1),
    nonholonomic(still = x - y),
)]
struct Bob {
    m: f64,
    l: f64,
}

// A speed without velocities is no speed.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    nonholonomic(roll = dot(x) - dot(y)),
    speeds(u = x),
)]
struct Speed {
    m: f64,
}

fn main() {}
