use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    inputs(reel),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    holonomic(thread = (x^2) + (y^2) - ((l + reel)^2)),
)]
struct Winch {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {}
