use lagrange::Lagrangian;

// Friction between two spheres is not derived yet: refused at the key,
// never dropped silently.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x1, x2),
    point(a, mass = m, at = [x1, 0, 0]),
    point(b, mass = m, at = [x2, 0, 0]),
    contact(hit, on = a, radius = r, against = b, against_radius = r, restitution = 1, friction = 0.3),
)]
struct Balls {
    m: f64,
    r: f64,
}

fn main() {}
