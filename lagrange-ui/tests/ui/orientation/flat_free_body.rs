use lagrange::Lagrangian;

// A free body whose inertia has a zero moment: nothing resists turning about
// that axis, so M would be singular at every state.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    orientation(turn),
    body(rod, mass = 1.0, inertia = [0.5, 0.5, 0], at = [x, y, z], rotation = turn),
)]
struct Rod {}

// With a point mass off its axis the body is no longer alone on its
// orientation: this one is accepted (the masses decide).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    orientation(turn),
    body(rod, mass = 1.0, inertia = [0.5, 0.5, 0], at = [x, y, z], rotation = turn),
    point(weight, mass = 0.1, on = rod, at = [0.1, 0, 0]),
)]
struct Weighted {}

fn main() {}
