use lagrange::Lagrangian;

// `emit(reactions)` and `emit(coriolis)` combine with a free orientation;
// Hamilton's form does not (the symplectic Gauss method integrates (q, p) in
// coordinates, and a quaternion has no conjugate momentum there).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(z),
    orientation(turn),
    body(b, mass = m, inertia = [1, 2, 3], at = [0, 0, z], rotation = turn),
    holonomic(floor = z),
    emit(reactions, coriolis, hamiltonian),
)]
struct Held {
    m: f64,
}

fn main() {}
