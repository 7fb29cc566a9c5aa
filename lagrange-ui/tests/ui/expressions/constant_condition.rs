use lagrange::Lagrangian;

// A comparison of constants makes the `if` one of its branches, always.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = if 1 > 2 { -k * x } else { 0 }),
)]
struct Cart {
    m: f64,
    k: f64,
}

// Comparing parameters is fine: constant per run, chosen by the values.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = if k > 1 { -k * x } else { 0 }),
)]
struct Chosen {
    m: f64,
    k: f64,
}

fn main() {}
