use lagrange::Lagrangian;

// A literal negative damping coefficient feeds energy in.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    dissipation = -0.3 * pow(dot(x), 2) / 2,
)]
struct Cart {
    m: f64,
}

// Positive coefficients, but the coupling makes D indefinite.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(cart, mass = m, at = [x, y]),
    dissipation = pow(dot(x), 2) + pow(dot(y), 2) + 3 * dot(x) * dot(y),
)]
struct Coupled {
    m: f64,
}

// A parameter coefficient (possibly negative on purpose, a self-exciting
// model) and a state-dependent one (van der Pol) are left alone.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    dissipation = c * (pow(x, 2) - 1) * pow(dot(x), 2) / 2,
)]
struct VanDerPol {
    m: f64,
    c: f64,
}

fn main() {}
