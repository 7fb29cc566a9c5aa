use lagrange::Lagrangian;

// A misspelt `coordinates` is one error at the key, not also "no coordinates"
// and unknown symbols wherever x is used.
#[derive(Lagrangian)]
#[lagrange(
    cordinates(x),
    point(p, mass = m, at = [x, 0]),
    potential = m * x,
)]
struct Particle {
    m: f64,
}

fn main() {}
