use lagrange::Lagrangian;

// Positive moments, but C > A + B: no mass distribution has them. (A body
// turning about fewer axes, `rot_z` only, may leave the moments it never uses
// at zero, `[0, 0, c]`: the rule applies to a body that turns about all three.)
#[derive(Lagrangian)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = m, inertia = [1, 1, 3], at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
)]
struct Top {
    m: f64,
}

fn main() {}
