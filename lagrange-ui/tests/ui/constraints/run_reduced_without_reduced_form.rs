use lagrange::prelude::*;

// A knife edge in the multiplier form only; `run_reduced` needs the reduced form.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, theta),
    body(sled, mass = m, inertia = [0, 0, i], at = [x, y, 0], rotation = rot_z(theta)),
    nonholonomic(edge = -sin(theta) * dot(x) + cos(theta) * dot(y)),
)]
pub struct Sled {
    pub m: f64,
    pub i: f64,
}

fn main() {
    let sled = Sled { m: 1.0, i: 0.1 };
    let _ = Simulation::new(&sled).run_reduced([0.0; 3], [1.0, 0.0, 0.5], 0.0..1.0);
}
