//! `emit(reactions)`: the Cartesian reactions on the points a constraint
//! names, and each constraint's generalized reaction G_αᵀ ν_α, for
//! constraints written on points and on coordinates alike.

use lagrange::ConstrainedDynamics;
use lagrange::prelude::*;
use nalgebra::Vector2;

/// A pendulum's rod written on the coordinates (x, y), with no point named.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    holonomic(rod = (x^2) + (y^2) - (l^2)),
    emit(reactions),
)]
struct RodOnCoordinates {
    m: f64,
    l: f64,
    g: f64,
}

/// The same rod written on the bob, so that its reaction is also a force on
/// a point.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    holonomic(rod = (bob.x^2) + (bob.y^2) - (l^2)),
    emit(reactions),
)]
struct RodOnPoint {
    m: f64,
    l: f64,
    g: f64,
}

/// A constraint on coordinates has a reaction too: `generalized_reactions`
/// gives G_αᵀ ν_α, here (the coordinates Cartesian) the rod's pull on the
/// bob, m (|v|²/l + g cos θ) towards the pivot, equal to the point form's
/// Cartesian reaction; `REACTION_POINTS` is empty and says so.
#[test]
fn constraint_on_coordinates_has_a_generalized_reaction() {
    let (m, l, g) = (1.3, 0.8, 9.81);
    let on_q = RodOnCoordinates { m, l, g };
    let on_p = RodOnPoint { m, l, g };
    assert!(RodOnCoordinates::REACTION_POINTS.is_empty());
    assert_eq!(RodOnPoint::REACTION_POINTS, ["bob"]);
    for (theta, omega) in [(0.0, 0.0), (0.7, 1.9), (-2.5, -0.4)] {
        let (s, c) = f64::sin_cos(theta);
        let q = Vector2::new(l * s, -l * c);
        let v = Vector2::new(l * c * omega, l * s * omega);
        let nu_q = ConstrainedDynamics::<_, f64, 1>::new(&on_q)
            .solve(0.0, &q, &v)
            .unwrap()
            .multipliers;
        let nu_p = ConstrainedDynamics::<_, f64, 1>::new(&on_p)
            .solve(0.0, &q, &v)
            .unwrap()
            .multipliers;
        let [r] = on_q.generalized_reactions(&q, 0.0, &nu_q);
        let tension = m * (l * omega * omega + g * c);
        let expected = -q / l * tension;
        assert!(
            (r - expected).norm() < 1e-12 * tension.abs().max(1.0),
            "θ = {theta}: {r:?} vs {expected:?}"
        );
        let [cartesian] = on_p.reactions(&q, &v, 0.0, &nu_p);
        let [generalized] = on_p.generalized_reactions(&q, 0.0, &nu_p);
        assert!((cartesian.xy() - r).norm() < 1e-12 * tension.abs().max(1.0));
        assert!((generalized - r).norm() < 1e-12 * tension.abs().max(1.0));
    }
}
