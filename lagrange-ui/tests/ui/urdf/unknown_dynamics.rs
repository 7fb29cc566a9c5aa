use lagrange::Lagrangian;

// `dynamics` is `read` or `ignore`.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", dynamics = keep), gravity = [0, 0, -9.81])]
struct Ur5 {}

fn main() {}
