//! What a failed run reports: a `Failure` prints a line or two whatever the
//! length of its partial run, keeps that run in `partial`, is a
//! `std::error::Error` whose source is the typed `Error`, and clones; the
//! step-budget error names the setting that ran out.

mod common;

use common::{Pendulum, sv};
use lagrange_runtime::{
    Dopri5, Error, Event, EventRun, Failure, Gauss, Rk4, Simulation, StormerVerlet, Trajectory,
};

/// A pendulum run out of steps after `max_steps` accepted ones.
fn out_of_steps(max_steps: usize) -> Failure<Trajectory<f64, 1>> {
    Simulation::new(&Pendulum::standard())
        .integrator(Dopri5::tol(1e-12).max_steps(max_steps))
        .run(sv([1.0]), sv([0.0]), 0.0..1e6)
        .unwrap_err()
}

#[test]
fn debug_and_display_are_short_whatever_the_run() {
    let short = out_of_steps(10);
    let long = out_of_steps(20_000);
    assert_eq!(long.partial.len(), 20_001);
    for failure in [&short, &long] {
        let (debug, display) = (format!("{failure:?}"), failure.to_string());
        assert!(debug.len() < 400, "{} bytes: {debug}", debug.len());
        assert!(display.len() < 600, "{} bytes: {display}", display.len());
        assert!(display.lines().count() <= 3, "{display}");
        // The error, and how far the run got.
        let last = *failure.partial.times().last().unwrap();
        let points = format!("{} points", failure.partial.len());
        for text in [&debug, &display] {
            assert!(
                text.contains("TooManySteps") || text.contains("step budget"),
                "{text}"
            );
            assert!(text.contains(&points), "{text}");
            assert!(text.contains(&format!("t = {last}")), "{text}");
        }
    }
}

#[test]
fn question_mark_in_main_prints_the_summary_and_the_run_stays_available() {
    fn main_like() -> Result<(), Box<dyn std::error::Error>> {
        out_of_steps(20_000);
        Simulation::new(&Pendulum::standard())
            .integrator(Dopri5::tol(1e-12).max_steps(20_000))
            .run(sv([1.0]), sv([0.0]), 0.0..1e6)?;
        Ok(())
    }
    let boxed = main_like().unwrap_err();
    // What `main` prints on an error is the Debug form.
    let printed = format!("{boxed:?}");
    assert!(printed.len() < 400, "{} bytes", printed.len());
    // The typed error is the source; the failure itself downcasts back.
    let source = boxed.source().expect("a failure has a source");
    assert!(matches!(
        source.downcast_ref::<Error>(),
        Some(Error::TooManySteps {
            max_steps: 20_000,
            ..
        })
    ));
    let failure = boxed
        .downcast_ref::<Failure<Trajectory<f64, 1>>>()
        .expect("the failure itself");
    assert_eq!(failure.partial.len(), 20_001);
}

#[test]
fn event_runs_report_the_same_way() {
    let failure: Failure<EventRun<f64, 1>> = Simulation::new(&Pendulum::standard())
        .integrator(Dopri5::tol(1e-12).max_steps(5_000))
        .event(Event::new(|_, q, _| q[0]))
        .run(sv([1.0]), sv([0.0]), 0.0..1e6)
        .unwrap_err();
    assert!(!failure.partial.occurrences.is_empty());
    let debug = format!("{failure:?}");
    assert!(debug.len() < 400, "{debug}");
    assert!(debug.contains("5001 points"), "{debug}");
    let source = std::error::Error::source(&failure).unwrap();
    assert_eq!(source.to_string(), failure.error.to_string());
}

#[test]
fn errors_and_failures_clone() {
    let failure = out_of_steps(50);
    let copy = failure.clone();
    assert_eq!(copy.partial.times(), failure.partial.times());
    assert_eq!(copy.error.to_string(), failure.error.to_string());
    let io: Error = std::io::Error::other("disk full").into();
    let io_copy = io.clone();
    assert_eq!(io_copy.to_string(), io.to_string());
    assert_eq!(io.to_string(), "i/o error: disk full");
    let Error::Io(inner) = io_copy else {
        panic!("an i/o error")
    };
    assert_eq!(inner.kind(), std::io::ErrorKind::Other);
}

#[test]
fn the_step_budget_error_names_its_setting() {
    // An adaptive method runs out where it is.
    let adaptive = out_of_steps(60).error.to_string();
    assert!(adaptive.contains(".max_steps(60)"), "{adaptive}");
    assert!(adaptive.contains("ran out at t = "), "{adaptive}");
    // A fixed-step method refuses up front, at the start time.
    let sys = Pendulum::standard();
    let verlet = Simulation::new(&sys)
        .integrator(StormerVerlet::step(1e-3).max_steps(100))
        .run(sv([1.0]), sv([0.0]), 0.0..1.0)
        .unwrap_err();
    // 1 s at 1e-3 needs 1,000 steps: the error says so and names the setting
    // that would allow them.
    assert!(matches!(
        verlet.error,
        Error::TooManySteps {
            max_steps: 100,
            needed: Some(1000),
            ..
        }
    ));
    let message = verlet.error.to_string();
    assert!(message.contains("needs 1000 steps"), "{message}");
    assert!(message.contains(".max_steps(1000)"), "{message}");
    assert!(message.contains("t = 0"), "{message}");
    let gauss = Simulation::new(&sys)
        .integrator(Gauss::step(1e-3).max_steps(100))
        .run(sv([1.0]), sv([0.0]), 0.0..1.0)
        .unwrap_err()
        .error
        .to_string();
    assert!(gauss.contains("budget is 100"), "{gauss}");
    assert!(gauss.contains(".max_steps(1000)"), "{gauss}");
    // RK4 says the same (it shares the fixed-step count).
    let rk4 = Simulation::new(&sys)
        .integrator(Rk4::step(1e-3).max_steps(100))
        .run(sv([1.0]), sv([0.0]), 0.0..1.0)
        .unwrap_err()
        .error
        .to_string();
    assert!(rk4.contains("needs 1000 steps"), "{rk4}");
}
