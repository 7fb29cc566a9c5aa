use lagrange::Lagrangian;

// A nonholonomic row that reads an Euler angle's rate alone (`dot(psi)`) is
// refused at `psi` as well: the rate is a coordinate's, which the second
// chart does not have.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(ball, mass = 1.0, inertia = [0.4, 0.4, 0.4], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    holonomic(height = ball.z - 1.0),
    nonholonomic(slip_x = dot(ball.x) - ball.omega_y,
                 spin = dot(psi)),
    emit(atlas),
)]
struct Ball {}

fn main() {}
