use lagrange::Lagrangian;

// The regressor's Y π covers the bodies' parameters, not a rotor's Ia q̈.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, armature = ia),
    emit(regressor),
)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
    ia: f64,
}

fn main() {}
