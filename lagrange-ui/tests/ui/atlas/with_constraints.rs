use lagrange::Lagrangian;

// Nonholonomic constraints are not covered by the atlas: one error, at `atlas`.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, psi, theta, phi),
    body(disk, mass = 1.0, inertia = [0.25, 0.25, 0.5], at = [x, y, 0],
         rotation = euler_zxz(psi, theta, phi)),
    nonholonomic(roll = dot(x) - cos(psi) * dot(phi)),
    emit(atlas),
)]
struct Disk {}

fn main() {}
