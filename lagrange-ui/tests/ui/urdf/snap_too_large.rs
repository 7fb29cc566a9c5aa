use lagrange::Lagrangian;

// A snap tolerance of a radian would turn a joint's 0.3 rad into 0.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", snap = 1.0), gravity = [0, 0, -9.81])]
struct Ur5 {}

fn main() {}
