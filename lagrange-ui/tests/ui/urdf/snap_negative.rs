use lagrange::Lagrangian;

// A tolerance cannot be negative; `snap = 0` is the way to keep every angle.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", snap = -1e-6), gravity = [0, 0, -9.81])]
struct Ur5 {}

fn main() {}
