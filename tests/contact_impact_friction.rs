//! Coulomb friction at the event-driven run's impacts, against the closed
//! forms of a solid sphere (m, r, I = 0.4 m r²) striking the floor at normal
//! speed w with slip u = ẋ − r θ̇: Newton's law gives the normal impulse
//! P = m (1 + e) w; the tangential one stops the slip, −u/W with
//! W = 1/m + r²/I = 3.5/m, where the cone holds it (|u|/W ≤ μ P), and is
//! −μ P sign(u) otherwise. Also: the kinetic energy never rises, and a
//! frictionless impact keeps the slip.

use lagrange::prelude::*;
use lagrange::{ChangeKind, ContactRun, Dop853};

// The sphere of `tests/contact.rs`: e = 0.5, μ = 0.3 at the floor.
use crate::contact::Sphere as Struck;

const BALL: Struck = Struck {
    m: 0.3,
    r: 0.1,
    g: 9.81,
};

/// Thrown from just above the floor at (vx, vz) with spin ω: the first
/// impact, and the velocities just after it (ẋ and θ̇ are constant in
/// the flight that follows).
fn struck(vx: f64, vz: f64, spin: f64) -> (f64, [f64; 3], f64) {
    let run: ContactRun<f64, 3> = Simulation::new(&BALL)
        .integrator(Dop853::tol(1e-13))
        .run_contacts([0.0, BALL.r + 1e-3, 0.0], [vx, vz, spin], 0.0..0.05)
        .unwrap();
    let (t, before) = (run.changes.iter())
        .find_map(|c| match c.kind {
            ChangeKind::Impact { before, .. } => Some((c.t, before)),
            _ => None,
        })
        .expect("an impact");
    let (_, v) = run.trajectory.state_at(t + 1e-3).unwrap();
    (-before, [v[0], v[1], v[2]], t)
}

#[test]
fn a_sphere_struck_with_little_slip_leaves_rolling() {
    let (w, v, _) = struck(2.0, -3.0, 0.0);
    let u = 2.0;
    // Sticking impact: ẋ⁺ = ẋ − u/3.5, θ̇⁺ = ẋ⁺ / r (the slip stopped).
    let x_rate = 2.0 - u / 3.5;
    eprintln!(
        "sticking impact: ẋ⁺ {:.1e} off, slip after {:.1e}",
        (v[0] - x_rate).abs(),
        (v[0] - BALL.r * v[2]).abs()
    );
    assert!((v[0] - x_rate).abs() < 1e-9, "{v:?}");
    assert!((v[2] - x_rate / BALL.r).abs() < 1e-8, "{v:?}");
    assert!(w > 3.0);
}

#[test]
fn a_sphere_struck_with_much_slip_slides_through_the_impact() {
    let (w, v, _) = struck(10.0, -3.0, 0.0);
    // Sliding impact: Δẋ = −μ (1 + e) w, Δθ̇ = r μ m (1 + e) w / I.
    let impulse = 0.3 * 1.5 * w;
    eprintln!(
        "sliding impact: ẋ⁺ {:.1e} off, θ̇⁺ {:.1e} off",
        (v[0] - (10.0 - impulse)).abs(),
        (v[2] - impulse / (0.4 * BALL.r)).abs()
    );
    assert!((v[0] - (10.0 - impulse)).abs() < 1e-9, "{v:?}");
    assert!((v[2] - impulse / (0.4 * BALL.r)).abs() < 1e-8, "{v:?}");
}

/// Sticking and sliding, with and against the spin: the kinetic energy
/// after an impact is never above the energy before.
#[test]
fn no_impact_gains_energy() {
    for (vx, vz, spin) in [
        (2.0, -3.0, 0.0),
        (10.0, -3.0, 0.0),
        (1.0, -2.0, -40.0),
        (-3.0, -1.0, 25.0),
    ] {
        let (w, v, _) = struck(vx, vz, spin);
        let energy = |x: f64, z: f64, s: f64| {
            0.5 * BALL.m * (x * x + z * z) + 0.5 * 0.4 * BALL.m * BALL.r * BALL.r * s * s
        };
        // Just before: ẋ, w and the spin as thrown (free flight keeps them).
        let before = energy(vx, w, spin);
        let after = energy(v[0], v[1], v[2]);
        assert!(
            after <= before * (1.0 + 1e-12),
            "{vx} {vz} {spin}: {before} → {after}"
        );
    }
}
