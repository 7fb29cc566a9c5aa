//! A reduced form that cannot be evaluated at a finite state is a typed error
//! that says why and names the way out, not a NaN blamed on the initial state.

use lagrange::prelude::*;

/// A particle kept on rays from the origin (x ẏ − y ẋ = 0), reduced on the
/// speed ẋ: ẏ = y ẋ / x, which has no solution on the y axis, where the speed
/// and the constraint row are parallel ([U; A] loses rank).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(p, mass = m, at = [x, y]),
    gravity = [0, -g],
    nonholonomic(radial = x * dot(y) - y * dot(x)),
    speeds(u = dot(x)),
    formulation(reduced, multipliers),
)]
pub struct Ray {
    pub m: f64,
    pub g: f64,
}

#[test]
fn reduction_that_cannot_be_solved_is_a_typed_breakdown() {
    let ray = Ray { m: 1.0, g: 9.81 };
    match Simulation::new(&ray).run_reduced([0.0, 1.0], [0.0, 0.5], 0.0..1.0) {
        Err(e @ Error::ReducedFormBreakdown { .. }) => {
            let msg = e.to_string();
            assert!(
                msg.contains("x = 0") && msg.contains("run_constrained"),
                "{msg}"
            );
        }
        other => panic!("expected ReducedFormBreakdown, got {other:?}"),
    }
    // Off the axis the reduced form runs, and agrees with the multiplier form.
    let (q0, v0) = ([0.6, 0.8], [0.3, 0.4]);
    let reduced = Simulation::new(&ray)
        .integrator(Dopri5::tol(1e-11))
        .run_reduced(q0, v0, 0.0..0.1)
        .unwrap();
    let multipliers = Simulation::new(&ray)
        .integrator(Dopri5::tol(1e-11))
        .run_constrained(q0, v0, 0.0..0.1)
        .unwrap();
    let d = (reduced.final_state().0 - multipliers.final_state().0)
        .abs()
        .max();
    assert!(d < 1e-9, "{d}");
}
