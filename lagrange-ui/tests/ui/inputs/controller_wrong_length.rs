use lagrange::prelude::*;

// One input, but the controller returns two values.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    inputs(force),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = force),
)]
pub struct Cart {
    pub m: f64,
}

fn main() {
    let cart = Cart { m: 1.0 };
    let _ = Simulation::new(&cart)
        .feedback(|_, q: &Vector1<f64>, v: &Vector1<f64>| [-q[0], -v[0]])
        .run([1.0], [0.0], 0.0..1.0);
}
