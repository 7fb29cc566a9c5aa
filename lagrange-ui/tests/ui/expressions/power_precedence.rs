use lagrange::Lagrangian;

// Rust parses `k * x^2` as `(k * x)^2`: the macro refuses to guess.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, 0]),
    potential = k * x^2 / 2,
)]
struct Oscillator {
    m: f64,
    k: f64,
}

fn main() {}
