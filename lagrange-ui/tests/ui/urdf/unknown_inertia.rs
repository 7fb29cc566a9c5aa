use lagrange::Lagrangian;

// An unphysical inertia is repaired or used as written, nothing else.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", inertia = clamp), gravity = [0, 0, -9.81])]
struct Ur5 {}

fn main() {}
