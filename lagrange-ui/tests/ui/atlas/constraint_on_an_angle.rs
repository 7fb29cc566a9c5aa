use lagrange::Lagrangian;

// A holonomic constraint written on an Euler angle: in the second chart
// there is no such coordinate. The error points at `theta` in the
// constraint; write it on points of the body instead.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(top, mass = 1.0, inertia = [0.8, 0.8, 0.5], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    holonomic(tilt = theta - 0.3),
    emit(atlas),
)]
struct Top {}

fn main() {}
