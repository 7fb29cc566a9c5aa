// Asking for many states at once from a system that does not emit its
// batched programs: one error that says to add `batched` to `emit(...)`.
use lagrange::prelude::*;

#[derive(Lagrangian)]
#[lagrange(coordinates(theta), point(bob, at = [l * sin(theta), -l * cos(theta)], mass = m), gravity = [0, -g], emit(jacobians))]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn main() {
    let p = Pendulum { m: 1.0, l: 1.0, g: 9.81 };
    let x = [SVector::<f64, 1>::new(0.3)];
    let _ = lagrange::batched_accelerations(&p, &x, &x, &x, 0.0);
}
