use lagrange::Lagrangian;

#[derive(Lagrangian)]
#[lagrange(point(p, mass = m, at = [1, 2]))]
struct Nothing {
    m: f64,
}

fn main() {}
