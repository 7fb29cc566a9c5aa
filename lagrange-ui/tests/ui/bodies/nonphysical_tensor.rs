use lagrange::Lagrangian;

// Positive diagonal, but the product Ixy = 2 makes the tensor indefinite.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(plate, mass = m, inertia = [1, 1, 1, 2, 0, 0], at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
)]
struct Plate {
    m: f64,
}

fn main() {}
