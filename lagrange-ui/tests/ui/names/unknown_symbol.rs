use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [len * sin(theta), -l * cos(theta)]),
)]
struct Pendulum {
    m: f64,
    l: f64,
}

fn main() {}
