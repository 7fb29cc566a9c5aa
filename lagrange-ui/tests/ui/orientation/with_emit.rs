use lagrange::Lagrangian;

// `emit(reactions)` combines with a free orientation; the other optional
// outputs (here the Coriolis matrix) do not yet.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(z),
    orientation(turn),
    body(b, mass = m, inertia = [1, 2, 3], at = [0, 0, z], rotation = turn),
    holonomic(floor = z),
    emit(reactions, coriolis),
)]
struct Held {
    m: f64,
}

fn main() {}
