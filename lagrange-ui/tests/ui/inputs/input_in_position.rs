use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    inputs(shift),
    point(bob, mass = m, at = [l * sin(theta) + shift, -l * cos(theta)]),
    gravity = [0, -g],
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {
    use lagrange::Driven;
    use lagrange::nalgebra::SVector;
    let p = Pendulum { m: 1.0, l: 1.0, g: 9.81 };
    let z = SVector::<f64, 1>::zeros();
    let _ = p.input_forces(&z, &z, &z, 0.0);
}
