use lagrange::Lagrangian;

// `urdf(...)` takes one option, `snap`.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", snp = 1e-6), gravity = [0, 0, -9.81])]
struct Ur5 {}

fn main() {}
