use lagrange::Lagrangian;

// A torque on a point (it turns a body), a torque of two components, and an
// unknown option.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    body(wheel, mass = 1.0, inertia = [1, 1, 2], at = [0, 0, 0], rotation = rot_z(theta)),
    point(rim, on = wheel, at = [1, 0, 0]),
    torque(rim, [0, 0, 1]),
    torque(wheel, [0, 1]),
)]
struct Wheel {}

#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    body(wheel, mass = 1.0, inertia = [1, 1, 2], at = [0, 0, 0], rotation = rot_z(theta)),
    torque(wheel, [0, 0, 1], frame = body),
)]
struct Option {}

fn main() {}
