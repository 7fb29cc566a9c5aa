use lagrange::Lagrangian;

// An input given as a generalized force on an Euler angle: in the second
// chart there is no such coordinate to push. The error points at `pitch`
// in the generalized force; a torque from points of the body is the way.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(yaw, pitch, roll),
    inputs(tau),
    body(load, mass = 1.0, inertia = [0.1, 0.2, 0.25], at = [0, 0, 0],
         rotation = euler_zyx(yaw, pitch, roll)),
    generalized_force(pitch = tau),
    emit(atlas),
)]
struct Payload {}

fn main() {}
