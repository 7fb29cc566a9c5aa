//! Every recording mode against every kind of run: plain, with events, under a
//! sampled controller (with and without events), constrained, reduced and
//! RATTLE. A thinned recording must hold points of the same motion as the full
//! one (the same steps, read from the same dense output), on its own grid,
//! with increasing times, ending at the end of the run; and the budgets refuse
//! a run that would never end before it starts.

mod common;

use common::constrained::CartesianPendulum;
use common::driven::Skate;
use common::{Ball, Oscillator, Pendulum};
use lagrange_runtime::{
    ControlRun, Dopri5, Error, Event, Events, Failure, Rattle, Record, SettingsError, Simulation,
    Trajectory,
};
use nalgebra::{SVector, Vector1, Vector3};

const MODES: [Record; 3] = [Record::Every(3), Record::Interval(0.03), Record::Final];

/// The thinned recording `thin` of a run against the full recording `full` of
/// the same run: increasing times from the same start to the same end, each
/// point on the full run's dense output, and the mode's own times.
fn check_against<const N: usize>(
    name: &str,
    mode: Record,
    full: &Trajectory<f64, N>,
    thin: &Trajectory<f64, N>,
) {
    let (ft, tt) = (full.times(), thin.times());
    assert_eq!(tt[0], ft[0], "{name} {mode:?}: start");
    assert_eq!(tt.last(), ft.last(), "{name} {mode:?}: end");
    assert!(
        tt.windows(2).all(|w| w[0] < w[1]),
        "{name} {mode:?}: times not increasing: {tt:?}"
    );
    for (k, &t) in tt.iter().enumerate() {
        let (q, v) = full.state_at(t).expect("inside the span");
        let err = (q - thin.positions()[k])
            .amax()
            .max((v - thin.velocities()[k]).amax());
        assert!(
            err < 1e-12,
            "{name} {mode:?}: point {k} at t = {t} is off by {err:e}"
        );
    }
    let inner = &tt[..tt.len() - 1];
    match mode {
        Record::Interval(dt) => {
            for (k, &t) in inner.iter().enumerate() {
                assert_eq!(t, tt[0] + k as f64 * dt, "{name}: grid point {k}");
            }
            let last = tt[tt.len() - 1];
            let gap = last - inner[inner.len() - 1];
            assert!(gap <= dt * (1.0 + 1e-12), "{name}: a grid point missing");
        }
        Record::Every(_) => assert!(
            inner.iter().all(|t| ft.contains(t)),
            "{name}: a point that is not a step end"
        ),
        Record::Final => assert_eq!(tt.len(), 2, "{name}: Final"),
        Record::Steps => {}
    }
}

/// Runs `run` with the full recording and with every thinned mode, and checks
/// each against the full one.
fn every_mode<const N: usize>(
    name: &str,
    run: impl Fn(Record) -> Trajectory<f64, N>,
) -> Trajectory<f64, N> {
    let full = run(Record::Steps);
    for mode in MODES {
        check_against(name, mode, &full, &run(mode));
    }
    full
}

#[test]
fn plain_constrained_reduced_and_rattle_runs() {
    let pendulum = Pendulum::standard();
    every_mode("plain", |r| {
        Simulation::new(&pendulum)
            .integrator(Dopri5::tol(1e-10).record(r))
            .run([1.0], [0.0], 0.0..3.0)
            .unwrap()
    });
    let bob = CartesianPendulum::<1>::standard();
    let (q0, v0) = bob.state(1.2, 0.5);
    every_mode("constrained", |r| {
        Simulation::new(&bob)
            .integrator(Dopri5::tol(1e-10).record(r))
            .run_constrained(q0, v0, 0.0..3.0)
            .unwrap()
    });
    every_mode("RATTLE", |r| {
        Rattle::step(0.01)
            .record(r)
            .integrate(&bob, 0.0, 3.0, q0, v0)
            .unwrap()
    });
    let skate = Skate { m: 2.0, j: 0.5 };
    let (sq, sv) = (Vector3::new(0.0, 0.0, 0.3), Vector3::new(0.0, 0.0, 1.0));
    every_mode("reduced", |r| {
        Simulation::new(&skate)
            .integrator(Dopri5::tol(1e-10).record(r))
            .run_reduced(sq, sv, 0.0..3.0)
            .unwrap()
    });
}

/// The height of a ball dropped from rest at h0, bouncing with restitution e,
/// at time t: free flight between the impacts.
fn exact_height(h0: f64, g: f64, e: f64, t: f64) -> f64 {
    let mut start = (2.0 * h0 / g).sqrt();
    if t <= start {
        return h0 - 0.5 * g * t * t;
    }
    let mut speed = e * g * start;
    while t > start + 2.0 * speed / g {
        start += 2.0 * speed / g;
        speed *= e;
    }
    let s = t - start;
    speed * s - 0.5 * g * s * s
}

#[test]
fn a_bouncing_ball_recorded_on_a_grid_stays_on_its_flight() {
    let (g, e, h0, dt) = (9.81, 0.8, 1.5, 0.01);
    let ball = Ball { g };
    let run = |r: Record| {
        Simulation::new(&ball)
            .integrator(Dopri5::tol(1e-11).record(r))
            .event(
                Event::new(|_, q, _| q[0])
                    .falling()
                    .action(move |_, _, v: &mut SVector<f64, 1>| *v *= -e),
            )
            .run([h0], [0.0], 0.0..4.0)
            .unwrap()
    };
    let grid = run(Record::Interval(dt));
    assert_eq!(grid.occurrences.len(), 7, "impacts");
    let times = grid.trajectory.times();
    assert_eq!(times.len(), 401);
    let mut worst: f64 = 0.0;
    for (k, (&t, q)) in times.iter().zip(grid.trajectory.positions()).enumerate() {
        assert_eq!(t, k as f64 * dt, "grid time {k}");
        worst = worst.max((q[0] - exact_height(h0, g, e, t)).abs());
    }
    println!("ball on Interval({dt}): worst height error {worst:.1e}");
    assert!(worst < 1e-9, "{worst:e}");
    let full = run(Record::Steps).trajectory;
    for mode in MODES {
        check_against("events", mode, &full, &run(mode).trajectory);
    }
}

/// A double integrator under a held law sampled every 0.1 s.
fn sampled(r: Record, with_bounce: bool) -> ControlRun<f64, 1, 1> {
    let s = Oscillator { m: 1.0, k: 0.0 };
    let sim = Simulation::new(&s).integrator(Dopri5::tol(1e-10).record(r));
    let mut run = sim
        .sampled(0.1, |_, q: &Vector1<f64>, v: &Vector1<f64>| {
            [-4.0 * (q[0] - 0.2) - v[0]]
        })
        .events(Events::new());
    if with_bounce {
        let floor = Event::new(|_, q: &Vector1<f64>, _| q[0] + 0.1).falling();
        run = run.event(floor.action(|_, _, v| *v *= -0.5));
    }
    run.run([1.0], [0.0], 0.0..2.0).unwrap()
}

#[test]
fn a_sampled_controller_keeps_one_grid_and_its_inputs() {
    for bounce in [false, true] {
        let full = sampled(Record::Steps, bounce);
        for mode in MODES {
            let thin = sampled(mode, bounce);
            let name = if bounce { "sampled, events" } else { "sampled" };
            check_against(name, mode, full.trajectory(), thin.trajectory());
            // One input per point: the sample held at that time, read off the
            // full recording (whose points include every sample instant).
            assert_eq!(thin.inputs().len(), thin.trajectory().len());
            for (k, &t) in thin.trajectory().times().iter().enumerate() {
                let j = full.trajectory().times().partition_point(|&s| s <= t);
                let held = full.inputs()[j.min(full.inputs().len()) - 1];
                assert_eq!(thin.inputs()[k], held, "{name} {mode:?}: input at {t}");
            }
        }
        let grid = sampled(Record::Interval(0.03), bounce);
        let times = grid.trajectory().times();
        assert_eq!(times.len(), 68, "0, 0.03, …, 1.98 and the end 2.0");
    }
}

#[test]
fn crossings_refuse_a_thinned_recording() {
    let pendulum = Pendulum::standard();
    let run = |r| {
        Simulation::new(&pendulum)
            .integrator(Dopri5::tol(1e-10).record(r))
            .run([1.0], [0.0], 0.0..10.0)
            .unwrap()
    };
    assert_eq!(
        run(Record::Steps).crossings(|_, q, _| q[0]).unwrap().len(),
        9
    );
    for mode in MODES {
        let e = run(mode).crossings(|_, q, _| q[0]).unwrap_err();
        assert!(
            matches!(&e, Error::Settings(m) if m.to_string().contains("Record::Steps")),
            "{e}"
        );
    }
}

#[test]
fn an_interval_that_would_never_end_is_refused_before_the_run() {
    let pendulum = Pendulum::standard();
    let e = Simulation::new(&pendulum)
        .integrator(Dopri5::tol(1e-8).record(Record::Interval(1e-9)))
        .run([1.0], [0.0], 0.0..100.0)
        .unwrap_err();
    let Failure { error, partial } = e;
    let message = error.to_string();
    assert!(
        matches!(
            error,
            Error::Settings(SettingsError::Budget { owner: "record", asked, .. })
                if asked == 1e11 + 2.0
        ) && message.contains("1.000e11 times")
            && message.contains("bytes"),
        "{message}"
    );
    assert_eq!(partial.len(), 1, "nothing integrated");
}

#[test]
fn the_step_budget_bounds_a_whole_sampled_or_event_run() {
    let s = Oscillator { m: 1.0, k: 0.0 };
    // 10¹⁵ samples: refused before any work, naming the settings to change.
    let e = Simulation::new(&s)
        .integrator(Dopri5::tol(1e-8))
        .sampled(1e-9, |_, _, _| [0.0])
        .run([1.0], [0.0], 0.0..1e6)
        .unwrap_err();
    let message = e.error.to_string();
    assert!(
        message.contains("1.000e15") && message.contains("max_steps"),
        "{message}"
    );
    // A bouncing ball whose pieces each stay within the budget still stops
    // once the whole run has spent it, with what it computed.
    let ball = Ball { g: 9.81 };
    let e = Simulation::new(&ball)
        .integrator(Dopri5::tol(1e-10).max_steps(40))
        .event(
            Event::new(|_, q, _| q[0])
                .falling()
                .action(|_, _, v: &mut SVector<f64, 1>| *v *= -0.9),
        )
        .run([1.5], [0.0], 0.0..20.0)
        .unwrap_err();
    assert!(
        matches!(e.error, Error::TooManySteps { max_steps: 40, .. }),
        "{}",
        e.error
    );
    let steps = e.partial.trajectory.stats().steps();
    assert!((40..80).contains(&steps), "{steps} steps");
}

/// The CSV keeps the stored points bit for bit (Rust's shortest round-trip
/// form) and, as documented, nothing between them.
#[test]
fn a_csv_reads_back_its_points_bit_for_bit() {
    let sys = Pendulum::standard();
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-9))
        .run(SVector::from([1.0]), SVector::from([0.3]), 0.0..2.0)
        .unwrap();
    let mut csv = Vec::new();
    traj.write_csv(&mut csv, &["theta"]).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,theta,dot_theta,integral,residual_position,residual_velocity"
    );
    let mut rows = 0;
    for (k, line) in lines.enumerate() {
        let x: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(x[0].to_bits(), traj.times()[k].to_bits());
        assert_eq!(x[1].to_bits(), traj.positions()[k][0].to_bits());
        assert_eq!(x[2].to_bits(), traj.velocities()[k][0].to_bits());
        assert_eq!(x[3].to_bits(), traj.integrals()[k].to_bits());
        rows += 1;
    }
    assert_eq!(rows, traj.len());
}
