//! Event closures take their scalar and dimension from the simulation they
//! are given to: indexing the state needs no annotation, and a method on a
//! component needs the scalar named once (the form `Event::new`'s docs show).

mod common;

use common::{Pendulum, SphericalPendulum, sv};
use lagrange_runtime::{Dopri5, Event, Simulation};

#[test]
fn event_closures_infer_from_the_simulation() {
    let sys = SphericalPendulum::standard();
    // Built and not run: the system alone fixes the event's types.
    let _watching = Simulation::new(&sys).event(Event::new(|_, _, v| v[0]));
    let _also = Simulation::new(&sys)
        .event(Event::new(|_, q, _| q[1] - 0.5).rising())
        .event(Event::new(|_, _, v| v[0]).falling().terminal());
    // A method on a component: the scalar named once, on the time.
    let run = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-10))
        .event(Event::new(|_: f64, q, _| q[1].cos()))
        .run(sv([1.0, 0.0]), sv([0.0, 2.0]), 0.0..3.0)
        .unwrap();
    // cos φ vanishes where φ passes π/2 + kπ.
    for o in &run.occurrences {
        assert!(o.q[1].cos().abs() < 1e-9, "{o:?}");
    }
    assert!(!run.occurrences.is_empty());
}

#[test]
fn action_closures_infer_too() {
    // The crate docs' bouncing example as written, on a pendulum: the bob
    // bounces off the wall at θ = 0.
    let sys = Pendulum::standard();
    let run = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-10))
        .event(
            Event::new(|_, q, _| q[0])
                .falling()
                .action(|_, _, v| *v *= -0.9),
        )
        .event(Event::new(|_, _, v| v[0]).falling())
        .run(sv([1.0]), sv([0.0]), 0.0..5.0)
        .unwrap();
    let bounces: Vec<_> = run.of(0).collect();
    assert!(bounces.len() >= 2);
    for b in bounces {
        assert!((b.v_after[0] + 0.9 * b.v[0]).abs() < 1e-12);
    }
}
