use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(a, b),
    body(rod, mass = m, inertia = [m, m, m], at = [0, 0, 0], rotation = rot_z(a) * rot_y(b)),
    holonomic(level = b),
    emit(articulated),
)]
struct Rod {
    m: f64,
}

fn main() {}
