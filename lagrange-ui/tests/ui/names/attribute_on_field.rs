use lagrange::Lagrangian;

#[derive(Lagrangian)]
struct Pendulum {
    #[lagrange(coordinates(theta), point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]))]
    m: f64,
    l: f64,
}

fn main() {}
