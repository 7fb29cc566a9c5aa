use lagrange::Lagrangian;

// `spin` is declared but no body turns with it: nothing resists its angular
// velocity, so the mass matrix would be singular at every state.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    orientation(spin),
    point(cart, mass = 1.0, at = [x, 0, 0]),
)]
struct Cart {}

fn main() {}
