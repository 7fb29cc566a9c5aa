use lagrange::Lagrangian;

// A ball in Euler angles bouncing on a floor: the atlas runs through the
// charts' singular sets, the contacts run event by event, and no run does
// both yet.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(ball, mass = 1.0, inertia = [0.4, 0.4, 0.4], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -9.81],
    contact(floor, on = ball, normal = [0, 0, 1], radius = 0.1, restitution = 0.5, friction = 0.3),
    emit(atlas),
)]
struct Ball {}

fn main() {}
