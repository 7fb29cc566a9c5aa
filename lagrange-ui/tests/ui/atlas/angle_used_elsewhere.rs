use lagrange::Lagrangian;

// The potential reads the nutation angle itself: in the second chart there
// is no such coordinate. The error points at `theta` in the potential.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = 1.0, inertia = [0.8, 0.8, 0.5], at = [0, 0, 0],
         rotation = euler_zxz(psi, theta, phi)),
    potential = 4.0 * cos(theta),
    emit(atlas),
)]
struct Top {}

fn main() {}
