use lagrange::Lagrangian;

// Each misuse of the piecewise forms is one error at its token: an `if`
// without `else`, `==` on floats, a condition that is not a comparison, and
// `clamp` with two arguments.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(p, mass = m, at = [x, y]),
    generalized_force(
        x = if dot(x) > 0 { -m },
        y = if y == 0 { 1 } else { 0 }
    ),
    potential = if x { x } else { 0 } + clamp(y, 1),
)]
struct Block {
    m: f64,
}

fn main() {}
