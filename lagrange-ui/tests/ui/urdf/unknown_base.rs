use lagrange::Lagrangian;

// The base is fixed (the default) or floating (a free root joint).
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", base = free), gravity = [0, 0, -9.81])]
struct Ur5 {}

fn main() {}
