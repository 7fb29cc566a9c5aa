use lagrange::Lagrangian;

// `limits` is `stops` (without the option they are watched).
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", limits = walls), gravity = [0, 0, -9.81])]
struct Ur5 {}

fn main() {}
