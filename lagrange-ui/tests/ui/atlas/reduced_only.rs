use lagrange::Lagrangian;

// The atlas runs constraints with multipliers: a description emitted only
// in the reduced form is refused at `atlas` (`formulation(multipliers,
// reduced)` is accepted, and runs its multiplier form).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, psi, theta, phi),
    body(ball, mass = 1.0, inertia = [0.4, 0.4, 0.4], at = [x, y, 1.0],
         rotation = euler_zxz(psi, theta, phi)),
    nonholonomic(slip_x = dot(ball.x) - ball.omega_y,
                 slip_y = dot(ball.y) + ball.omega_x),
    formulation(reduced),
    emit(atlas),
)]
struct Ball {}

fn main() {}
