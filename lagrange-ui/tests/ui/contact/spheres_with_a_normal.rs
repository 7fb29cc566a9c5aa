use lagrange::Lagrangian;

// Two spheres meet along the line of their centres: a plane's normal is
// refused at its key.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x1, x2),
    point(a, mass = m, at = [x1, 0, 0]),
    point(b, mass = m, at = [x2, 0, 0]),
    contact(hit, on = a, against = b, normal = [1, 0, 0], restitution = 1),
)]
struct Balls {
    m: f64,
}

fn main() {}
