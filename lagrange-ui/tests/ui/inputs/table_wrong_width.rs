use lagrange::prelude::*;

// One input declared, but the table has two columns.
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
    let table = InputTable::hold(vec![0.0, 1.0], vec![[1.0, 2.0], [0.0, 0.0]]).unwrap();
    let _ = Simulation::new(&cart).control(table).run([1.0], [0.0], 0.0..1.0);
}
