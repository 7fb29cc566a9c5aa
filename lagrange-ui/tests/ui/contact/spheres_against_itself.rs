use lagrange::Lagrangian;

// A sphere cannot meet itself: `against` must name a second point or body.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x1, x2),
    point(a, mass = m, at = [x1, 0, 0]),
    point(b, mass = m, at = [x2, 0, 0]),
    contact(hit, on = a, against = a, restitution = 1),
)]
struct Balls {
    m: f64,
}

fn main() {}
