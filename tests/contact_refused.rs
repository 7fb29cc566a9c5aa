//! A system with contacts or stops runs by `run_contacts` alone: every other
//! run path (the plain run, the constrained forms, events, controllers)
//! refuses it at its start, where it would otherwise let the ball fall
//! through the floor without a word. (The atlas's runs make the same check,
//! but a description with `emit(atlas)` and contacts does not compile yet:
//! its twin's free orientation takes no contacts.)

use lagrange::prelude::*;
use lagrange::{ContactError, ContactFault, Event};

/// A ball on a vertical line above a floor, pushed by an input.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(z),
    inputs(push),
    point(ball, mass = m, at = [0, 0, z]),
    force(ball, [0, 0, push]),
    gravity = [0, 0, -g],
    contact(floor, on = ball, normal = [0, 0, 1], restitution = 0.5),
)]
struct Ball {
    m: f64,
    g: f64,
}

/// A bead held on a rail x = 0 by a holonomic constraint, above a floor.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, z),
    point(bead, mass = m, at = [x, 0, z]),
    holonomic(rail = x),
    gravity = [0, 0, -g],
    contact(floor, on = bead, normal = [0, 0, 1], restitution = 0.5),
)]
struct Bead {
    m: f64,
    g: f64,
}

const BALL: Ball = Ball { m: 0.5, g: 9.81 };

/// The refusal every run path must give: the contact's name, the start,
/// and the advice to run with `run_contacts`.
fn refused(error: &Error, name: &str) {
    assert!(
        matches!(error, Error::Contact(ContactError { contact, t, fault: ContactFault::NeedsContactRun, .. })
            if contact == name && *t == 0.0),
        "{error}"
    );
    assert!(error.to_string().contains("run_contacts"), "{error}");
}

#[test]
fn the_contact_run_itself_stops_the_ball_on_the_floor() {
    let run = Simulation::new(&BALL)
        .run_contacts([1.0], [0.0], 0.0..1.0)
        .unwrap();
    let lowest = run
        .trajectory
        .positions()
        .iter()
        .map(|q| q[0])
        .fold(f64::MAX, f64::min);
    assert!(lowest > -1e-9, "{lowest}");
    assert_eq!(BALL_CONTACTS, ["floor"]);
}

const BALL_CONTACTS: &[&str] = <Ball as Lagrangian<f64, 1>>::CONTACTS;

#[test]
fn a_plain_run_refuses_a_system_with_contacts() {
    let e = Simulation::new(&BALL)
        .run([1.0], [0.0], 0.0..1.0)
        .unwrap_err();
    refused(&e.error, "floor");
    assert_eq!(e.partial.len(), 1, "nothing past the start");
}

#[test]
fn a_run_with_events_refuses_a_system_with_contacts() {
    let e = Simulation::new(&BALL)
        .event(Event::new(|_, q, _| q[0] - 0.5).falling())
        .run([1.0], [0.0], 0.0..1.0)
        .unwrap_err();
    refused(&e.error, "floor");
}

#[test]
fn controlled_runs_refuse_a_system_with_contacts() {
    let feedback = Simulation::new(&BALL)
        .feedback(|_, q: &SVector<f64, 1>, _: &SVector<f64, 1>| [-q[0]])
        .run([1.0], [0.0], 0.0..1.0)
        .unwrap_err();
    refused(&feedback.error, "floor");
    let sampled = Simulation::new(&BALL)
        .sampled(0.01, |_, q: &SVector<f64, 1>, _: &SVector<f64, 1>| [-q[0]])
        .run([1.0], [0.0], 0.0..1.0)
        .unwrap_err();
    refused(&sampled.error, "floor");
}

#[test]
fn the_constrained_forms_refuse_a_system_with_contacts() {
    let bead = Bead { m: 0.5, g: 9.81 };
    let sim = Simulation::new(&bead);
    refused(
        &sim.run([0.0, 1.0], [0.0, 0.0], 0.0..1.0).unwrap_err().error,
        "floor",
    );
    let e = sim
        .run_constrained([0.0, 1.0], [0.0, 0.0], 0.0..1.0)
        .unwrap_err();
    refused(&e.error, "floor");
}
