use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    emit(reactions),
)]
struct Pendulum {
    m: f64,
    l: f64,
}

fn main() {}
