use lagrange::Lagrangian;

// Constant arguments outside a function's domain would put NaN or an
// infinity into the equations.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    potential = k * sqrt(-2) * pow(x, 2) + ln(0) * x + (0^(-1)) * x,
)]
struct Cart {
    m: f64,
    k: f64,
}

fn main() {}
