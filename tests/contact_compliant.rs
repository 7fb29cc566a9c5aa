//! Compliant contacts (`Simulation::compliant_contacts`): the spring and
//! damper give each contact its restitution exactly on an isolated impact
//! at any stiffness; a ball at rest sinks by m g / k; and as the stiffness
//! grows, the bounces converge to the rigid closed forms.

use crate::catalog::contact::{BALL_RESTITUTION, BLOCK_FRICTION, Ball, SlidingBlock};
use lagrange::prelude::*;
use lagrange::{ChangeKind, Compliant, ContactRun, ContactState, Dop853, Radau5};

const G: f64 = 9.81;

fn compliant<S: lagrange::Contacts<f64, N>, const N: usize>(
    system: &S,
    k: f64,
    (q0, v0): ([f64; N], [f64; N]),
    end: f64,
) -> ContactRun<f64, N> {
    Simulation::new(system)
        .integrator(Dop853::tol(1e-12))
        .compliant_contacts(Compliant::stiffness(k))
        .run_contacts(q0, v0, 0.0..end)
        .unwrap()
}

#[test]
fn an_isolated_impact_leaves_at_e_times_its_speed_at_any_stiffness() {
    // Without gravity, thrown at the floor at 1 m/s.
    let ball = Ball {
        m: 0.3,
        r: 0.1,
        g: 0.0,
    };
    for k in [1e3, 1e5, 1e7] {
        let run = compliant(&ball, k, ([0.0, 0.11, 0.0], [0.0, -1.0, 0.0]), 0.2);
        let (q, v) = run.trajectory.final_state();
        assert!((v[1] - BALL_RESTITUTION).abs() < 1e-9, "k = {k}: {}", v[1]);
        assert!(q[1] > ball.r, "apart again");
        let kinds: Vec<_> = run.changes.iter().map(|c| c.kind).collect();
        assert_eq!(kinds, [ChangeKind::Closes, ChangeKind::LiftsOff], "k = {k}");
        assert_eq!(run.states(0.2), [ContactState::Apart]);
    }
}

#[test]
fn a_ball_at_rest_sinks_by_its_weight_over_the_stiffness() {
    let ball = Ball {
        m: 0.3,
        r: 0.1,
        g: G,
    };
    let k = 1e4;
    let run = compliant(&ball, k, ([0.0, ball.r, 0.0], [0.0; 3]), 3.0);
    let (q, v) = run.trajectory.final_state();
    assert!(
        (ball.r - q[1] - ball.m * G / k).abs() < 1e-12,
        "{}",
        ball.r - q[1]
    );
    assert!(v.norm() < 1e-12);
    let forces = run.forces(&ball, 3.0, &q, &v).unwrap();
    assert!((forces[0].normal - ball.m * G).abs() < 1e-9);
}

#[test]
fn bounces_converge_to_the_rigid_ones_as_the_stiffness_grows() {
    let ball = Ball {
        m: 0.3,
        r: 0.1,
        g: G,
    };
    let (h0, e) = (0.5, BALL_RESTITUTION);
    let t1 = (2.0 * h0 / G).sqrt();
    // The rigid second impact: t₁ + 2 e t₁.
    let second = t1 * (1.0 + 2.0 * e);
    let mut errors = Vec::new();
    for k in [1e3, 1e4, 1e5, 1e6] {
        let run = compliant(&ball, k, ([0.0, h0 + ball.r, 0.0], [0.0; 3]), 1.0);
        let touches: Vec<f64> = (run.changes.iter())
            .filter(|c| c.kind == ChangeKind::Closes)
            .map(|c| c.t)
            .collect();
        assert!(
            (touches[0] - t1).abs() < 1e-9,
            "the first touch is the free fall's"
        );
        errors.push((touches[1] - second).abs());
    }
    eprintln!("second touch against the rigid one, k = 1e3..1e6: {errors:?}");
    // The contact lasts about π √(m/k): a tenfold stiffness, about √10 less.
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((2.0..5.0).contains(&ratio), "{errors:?}");
    }
}

#[test]
fn a_block_slides_to_the_rigid_stop_and_creeps_no_further() {
    let block = SlidingBlock {
        m: 1.5,
        a: 0.2,
        g: G,
    };
    let distance = 25.0 / (2.0 * BLOCK_FRICTION * G);
    let k = 1e5;
    // Resting on its spring at the start: sunk by m g / k.
    let sunk = -block.m * G / k;
    // Held by friction, the regularised law is a stiff damper (μ λₙ / ε
    // per unit slip): an explicit method stalls there, Radau5 does not.
    let run = Simulation::new(&block)
        .integrator(Radau5::tol(1e-10))
        .compliant_contacts(Compliant::stiffness(k))
        .run_contacts([0.0, 0.0, sunk], [3.0, 4.0, 0.0], 0.0..1.6)
        .unwrap();
    let (q, v) = run.trajectory.final_state();
    let travelled = q[0].hypot(q[1]);
    eprintln!(
        "compliant block: travelled {travelled}, rigid {distance}, speed left {}",
        v.norm()
    );
    assert!(
        (travelled - distance).abs() < 1e-6,
        "{travelled} vs {distance}"
    );
    assert!((0.8 * q[0] - 0.6 * q[1]).abs() < 1e-12, "off its line");
}

#[test]
fn bad_models_are_refused() {
    let ball = Ball {
        m: 0.3,
        r: 0.1,
        g: G,
    };
    let failure = Simulation::new(&ball)
        .compliant_contacts(Compliant::stiffness(-1.0))
        .run_contacts([0.0, 0.2, 0.0], [0.0; 3], 0.0..1.0)
        .unwrap_err();
    assert!(
        failure.error.to_string().contains("stiffness"),
        "{}",
        failure.error
    );
}
