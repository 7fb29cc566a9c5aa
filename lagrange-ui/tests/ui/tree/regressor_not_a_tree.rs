use lagrange::Lagrangian;

// A pendulum of point masses is not a tree of bodies: `regressor` needs one.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    emit(regressor),
)]
struct Pendulum {
    m: f64,
    l: f64,
}

fn main() {}
