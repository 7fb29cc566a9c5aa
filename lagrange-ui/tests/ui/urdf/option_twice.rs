use lagrange::Lagrangian;

// Each option once: which `base` would hold?
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", base = fixed, base = floating), gravity = [0, 0, -9.81])]
struct Ur5 {}

fn main() {}
