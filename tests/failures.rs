//! Every failure hands back what was computed before it: the typed error in a
//! `Failure` with the partial result. Checked per kind of failure and per way
//! to run: the partial trajectory ends at the last accepted step (where the
//! error says when that is the step), is monotone and finite, and equals an
//! uninterrupted run with the same settings up to there.

use crate::catalog;

use catalog::control::CartPole;
use catalog::{Pendulum, SphericalPendulum};
use lagrange::prelude::*;

/// Monotone times, finite states, at least the initial point.
fn sound<const N: usize>(partial: &Trajectory<f64, N>) {
    let times = partial.times();
    assert!(!times.is_empty());
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    for (q, v) in partial.positions().iter().zip(partial.velocities()) {
        assert!(q.iter().chain(v.iter()).all(|x| x.is_finite()));
    }
}

/// The partial trajectory is the beginning of the complete one, bit for bit.
fn prefix_of<const N: usize>(partial: &Trajectory<f64, N>, whole: &Trajectory<f64, N>) {
    assert!(partial.len() <= whole.len());
    for k in 0..partial.len() {
        assert_eq!(partial.times()[k], whole.times()[k]);
        assert_eq!(partial.positions()[k], whole.positions()[k]);
        assert_eq!(partial.velocities()[k], whole.velocities()[k]);
    }
}

fn pendulum() -> Pendulum<f64> {
    Pendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    }
}

#[test]
fn out_of_steps_keeps_every_accepted_step() {
    let sys = pendulum();
    let run = |max_steps| {
        Simulation::new(&sys)
            .integrator(Dopri5::tol(1e-10).max_steps(max_steps))
            .run([1.0], [0.0], 0.0..20.0)
    };
    let whole = run(100_000).unwrap();
    let Err(Failure {
        error: Error::TooManySteps { t, max_steps, .. },
        partial,
    }) = run(60)
    else {
        panic!("expected TooManySteps");
    };
    assert_eq!(max_steps, 60);
    assert_eq!(*partial.times().last().unwrap(), t);
    sound(&partial);
    prefix_of(&partial, &whole);
    // The statistics of the work done come back too.
    assert_eq!(partial.stats().accepted, partial.len() - 1);
    assert!(partial.stats().steps() >= 60);
    // Dense output over the partial span works as on a complete run.
    let mid = 0.5 * t;
    let (a, b) = (partial.state_at(mid).unwrap(), whole.state_at(mid).unwrap());
    assert_eq!(a, b);
}

#[test]
fn a_singular_mass_matrix_mid_run_keeps_the_steps_before_it() {
    // Through the pole of a spherical pendulum: M = diag(m l², m l² sin²θ).
    let sys = SphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    // Released at θ0 in a plane through the pole, it reaches θ = 0 after a
    // quarter period √(l/g) K(sin θ0/2), which a step of a 200th lands on.
    let th0: f64 = 0.3;
    let k = (th0 / 2.0).sin();
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..10 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    let quarter = (sys.l / sys.g).sqrt() * std::f64::consts::PI / (2.0 * a);
    let h = quarter / 200.0;
    let result = Simulation::new(&sys).integrator(Rk4::step(h)).run(
        [th0, 0.0],
        [0.0, 0.0],
        0.0..2.0 * quarter,
    );
    let Err(Failure {
        error: Error::SingularMassMatrix { t, .. },
        partial,
    }) = result
    else {
        panic!(
            "expected SingularMassMatrix, got {:?}",
            result.err().map(|f| f.error)
        );
    };
    sound(&partial);
    let last = *partial.times().last().unwrap();
    assert!(
        last <= t && t - last <= h * 1.000001,
        "last step {last}, error at {t}"
    );
    assert!(partial.len() > 150);
}

#[test]
fn a_failed_newton_iteration_in_rattle_keeps_the_steps_before_it() {
    let sys = catalog::constrained::CartesianSphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let x0 = Vector3::new(0.6, 0.0, -0.8);
    let v0 = Vector3::new(0.0, 4.0, 0.0);
    // Two Newton iterations cannot reach the tolerance on this step.
    let result = lagrange::Rattle::step(0.05)
        .max_iterations(2)
        .integrate(&sys, 0.0, 5.0, x0, v0);
    let Err(Failure { error, partial }) = result else {
        panic!("expected a failure");
    };
    assert!(matches!(error, Error::NewtonFailure { .. }), "{error}");
    sound(&partial);
}

#[test]
fn a_nan_input_mid_run_keeps_the_run_and_its_inputs() {
    let cart = CartPole::standard();
    let result = Simulation::new(&cart)
        .integrator(Dopri5::tol(1e-9))
        .feedback(|t, _, _| [if t < 0.5 { 0.1 } else { f64::NAN }])
        .run([0.0, 0.1], [0.0; 2], 0.0..2.0);
    let Err(Failure {
        error: Error::NonFiniteInput { t, .. },
        partial,
    }) = result
    else {
        panic!("expected NonFiniteInput");
    };
    assert!((0.5..=2.0).contains(&t), "{t}");
    let traj = partial.trajectory();
    sound(traj);
    assert!(*traj.times().last().unwrap() <= t);
    assert_eq!(partial.inputs().len(), traj.len(), "one input per point");
    assert!(
        partial
            .inputs()
            .iter()
            .all(|u| u[0] == 0.1 || u[0].is_nan())
    );
}

#[test]
fn an_event_run_that_fails_keeps_its_occurrences() {
    let sys = pendulum();
    // Zero crossings of θ counted until the step budget runs out.
    let result = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-10).max_steps(300))
        .event(Event::new(|_, q: &Vector1<f64>, _| q[0]))
        .run([1.0], [0.0], 0.0..100.0);
    let Err(Failure {
        error: Error::TooManySteps { t, .. },
        partial,
    }) = result
    else {
        panic!("expected TooManySteps");
    };
    sound(&partial.trajectory);
    assert_eq!(*partial.trajectory.times().last().unwrap(), t);
    assert!(!partial.occurrences.is_empty());
    assert!(partial.occurrences.iter().all(|o| o.t <= t));
}

#[test]
fn a_failure_converts_into_the_bare_error_with_question_mark() {
    fn run() -> Result<(), Error> {
        let sys = pendulum();
        Simulation::new(&sys)
            .integrator(Dopri5::tol(1e-10).max_steps(5))
            .run([1.0], [0.0], 0.0..20.0)?;
        Ok(())
    }
    assert!(matches!(run(), Err(Error::TooManySteps { .. })));
    // And it is a std::error::Error with the same message.
    let f = Simulation::new(&pendulum())
        .integrator(Dopri5::tol(1e-10).max_steps(5))
        .run([1.0], [0.0], 0.0..20.0)
        .unwrap_err();
    let boxed: Box<dyn std::error::Error> = Box::new(f);
    assert!(boxed.to_string().contains(".max_steps(5)"), "{boxed}");
}
