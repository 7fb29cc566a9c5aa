//! `complete_state` in every form: a starting state on the constraints from a
//! guess, whether the description runs with multipliers, in reduced form, or
//! has no constraints.

use lagrange::linear::Linearizer;
use lagrange::prelude::*;

/// A pendulum in Cartesian coordinates, kept in reduced form: the speed is
/// the angular momentum per unit mass w = x ẏ − y ẋ.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    holonomic(rod = (x^2) + (y^2) - (l^2)),
    speeds(w = x * dot(y) - y * dot(x)),
    formulation(reduced),
)]
struct ReducedPendulum {
    m: f64,
    l: f64,
    g: f64,
}

/// The same pendulum with a multiplier.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    holonomic(rod = (x^2) + (y^2) - (l^2)),
)]
struct MultiplierPendulum {
    m: f64,
    l: f64,
    g: f64,
}

#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(coordinates(x), point(p, mass = m, at = [x, 0]), potential = (x^2) / 2)]
struct Free {
    m: f64,
}

#[test]
fn reduced_form_state_is_completed_on_its_holonomic_constraint() {
    let sys = ReducedPendulum {
        m: 1.0,
        l: 2.0,
        g: 9.81,
    };
    // x held at 1.2; y from the guess −1.0 onto the circle: y = −1.6.
    let guess = (Vector2::new(1.2, -1.0), Vector2::new(0.5, 0.3));
    let (q, v) = Linearizer::new()
        .coordinates(&["x"])
        .complete_state(&sys, guess.0, guess.1, 0.0)
        .unwrap();
    assert_eq!(q[0], 1.2);
    assert!((q[1] + 1.6).abs() < 1e-14, "{q}");
    // The velocity is tangent to the circle and keeps the guess's speed w.
    assert!((q.dot(&v)).abs() < 1e-13, "{q} {v}");
    let w = |q: &Vector2<f64>, v: &Vector2<f64>| q[0] * v[1] - q[1] * v[0];
    assert!((w(&q, &v) - w(&q, &guess.1)).abs() < 1e-13);
    // The run accepts it as it is.
    let traj = Simulation::new(&sys).run(q, v, 0.0..1.0).unwrap();
    assert!(traj.max_residuals()[0] < 1e-8);
}

#[test]
fn every_form_completes_the_same_positions() {
    let (reduced, multipliers) = (
        ReducedPendulum {
            m: 1.0,
            l: 2.0,
            g: 9.81,
        },
        MultiplierPendulum {
            m: 1.0,
            l: 2.0,
            g: 9.81,
        },
    );
    let guess = (Vector2::new(-0.7, -1.5), Vector2::new(0.2, 0.1));
    let settings = Linearizer::new().coordinates(&["x"]);
    let (qr, _) = settings
        .complete_state(&reduced, guess.0, guess.1, 0.0)
        .unwrap();
    let (qm, vm) = settings
        .complete_state(&multipliers, guess.0, guess.1, 0.0)
        .unwrap();
    assert!((qr - qm).amax() < 1e-15, "{qr} {qm}");
    assert!(qm.dot(&vm).abs() < 1e-13);
    // The free function with default settings, and an unconstrained system,
    // whose state is complete as given.
    let (qd, _) =
        lagrange::linear::complete_state(&reduced, guess.0, guess.1, 0.0, &[], &[]).unwrap();
    assert!((qd.norm() - 2.0).abs() < 1e-13);
    let free = Linearizer::new()
        .complete_state(&Free { m: 1.0 }, Vector1::new(0.3), Vector1::new(-1.0), 0.0)
        .unwrap();
    assert_eq!(free, (Vector1::new(0.3), Vector1::new(-1.0)));
}

/// Bad choices in the reduced form are typed errors, not a failed Newton.
#[test]
fn reduced_form_refuses_a_singular_or_oversized_choice() {
    let sys = ReducedPendulum {
        m: 1.0,
        l: 2.0,
        g: 9.81,
    };
    // At (2, 0) the rod fixes x, not y: y cannot be the dependent coordinate.
    let e = Linearizer::new()
        .coordinates(&["x"])
        .complete_state(&sys, Vector2::new(2.0, 0.0), Vector2::zeros(), 0.0)
        .unwrap_err();
    assert!(
        matches!(
            e,
            lagrange::Error::Linear(lagrange::LinearError::SingularPartition { .. })
        ),
        "{e:?}"
    );
    let e = Linearizer::new()
        .coordinates(&["x", "y"])
        .complete_state(&sys, Vector2::new(1.0, -1.0), Vector2::zeros(), 0.0)
        .unwrap_err();
    assert!(e.to_string().contains("at most 1"), "{e}");
    let nan =
        Linearizer::new().complete_state(&sys, Vector2::new(f64::NAN, -1.0), Vector2::zeros(), 0.0);
    assert!(
        matches!(nan, Err(lagrange::Error::NonFiniteState { .. })),
        "{nan:?}"
    );
}
