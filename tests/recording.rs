//! Output control: what a run keeps of its steps (`Record`), checked against
//! the full recording of the same run, and memory that stays bounded however
//! many steps are taken.

use crate::catalog;

use catalog::{DoublePendulum, Pendulum};
use lagrange::prelude::*;

fn double() -> DoublePendulum {
    DoublePendulum {
        m1: 1.0,
        m2: 1.0,
        l1: 1.0,
        l2: 1.0,
        g: 9.81,
    }
}

fn run(record: Record) -> Trajectory<f64, 2> {
    Simulation::new(&double())
        .integrator(Dopri5::tol(1e-10).record(record))
        .run([2.0, 2.5], [0.0, 0.0], 0.0..5.0)
        .unwrap()
}

#[test]
fn every_kth_step_is_the_full_run_thinned() {
    let full = run(Record::Steps);
    let thin = run(Record::Every(10));
    let steps = full.len() - 1;
    // Points 0, 10, 20, … and the final one.
    assert_eq!(
        thin.len(),
        steps / 10 + 1 + usize::from(!steps.is_multiple_of(10))
    );
    for (k, t) in thin.times().iter().enumerate().take(thin.len() - 1) {
        assert_eq!(*t, full.times()[10 * k]);
        assert_eq!(thin.positions()[k], full.positions()[10 * k]);
        assert_eq!(thin.integrals()[k], full.integrals()[10 * k]);
    }
    assert_eq!(thin.final_state(), full.final_state());
    assert_eq!(thin.times().last(), full.times().last());
    // The work is the same; only what is kept differs.
    assert_eq!(thin.stats().accepted, full.stats().accepted);
    // No segments: no dense output between the stored points.
    assert!(thin.state_at(0.123_456).is_none());
    assert!(thin.segments().is_empty());
}

#[test]
fn interval_output_comes_from_the_dense_output() {
    let full = run(Record::Steps);
    let grid = run(Record::Interval(0.25));
    // t = 0, 0.25, …, 4.75 from the dense output, then the final state at 5.
    assert_eq!(grid.len(), 21);
    let sys = double();
    for (k, &t) in grid.times().iter().enumerate() {
        let expected = if k < 20 { 0.25 * k as f64 } else { 5.0 };
        assert!((t - expected).abs() < 1e-12, "{t}");
        let (q, v) = full.state_at(t).unwrap();
        assert_eq!((grid.positions()[k], grid.velocities()[k]), (q, v));
        // The integral is evaluated at the interpolated state, not copied.
        let i = sys.integral(&q, &v, t);
        assert_eq!(grid.integrals()[k], i);
    }
    assert_eq!(grid.final_state(), full.final_state());
}

#[test]
fn final_only_keeps_two_points_and_memory_stays_bounded() {
    let pendulum = Pendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    // 200 000 fixed steps: the full recording would hold 200 001 points and
    // as many dense segments; these hold 2 and 201.
    let go = |record| {
        Simulation::new(&pendulum)
            .integrator(Rk4::step(1e-5).record(record))
            .run([1.0], [0.0], 0.0..2.0)
            .unwrap()
    };
    let last = go(Record::Final);
    assert_eq!(last.len(), 2);
    assert!(last.memory() < 1024, "{} bytes", last.memory());
    assert_eq!(last.stats().accepted, 200_000);
    let sparse = go(Record::Every(1000));
    assert_eq!(sparse.len(), 201);
    assert!(sparse.memory() < 201 * 64, "{} bytes", sparse.memory());
    let full = go(Record::Steps);
    eprintln!(
        "200 000 steps: {} bytes all steps, {} every 1000th, {} final only",
        full.memory(),
        sparse.memory(),
        last.memory()
    );
    assert_eq!(last.final_state(), sparse.final_state());
    // The conserved quantity is still measured over what was kept.
    assert!(
        sparse.integral_drift() < 1e-10,
        "{}",
        sparse.integral_drift()
    );
}

#[test]
fn thinned_recording_works_through_events() {
    // A pendulum's zero crossings with only every 50th step kept: the
    // occurrences and the final state are those of the full run.
    let pendulum = Pendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let go = |record| {
        Simulation::new(&pendulum)
            .integrator(Dopri5::tol(1e-10).record(record))
            .event(Event::new(|_, q: &Vector1<f64>, _| q[0]).rising())
            .run([1.0], [0.0], 0.0..10.0)
            .unwrap()
    };
    let (full, thin) = (go(Record::Steps), go(Record::Every(50)));
    assert_eq!(full.times(0), thin.times(0));
    assert_eq!(full.trajectory.final_state(), thin.trajectory.final_state());
    assert!(thin.trajectory.len() * 10 < full.trajectory.len());
}

/// The complete table of a constrained run: names, energies that add up to
/// the recorded integral, and the multipliers of the saddle-point solve.
#[test]
fn table_has_energies_and_multipliers() {
    let sys = catalog::constrained::CartesianSphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-10))
        .drift(Drift::projection())
        .run_constrained([0.6, 0.0, -0.8], [0.0, 1.5, 0.0], 0.0..1.0)
        .unwrap();
    let mut buf = Vec::new();
    traj.table(&sys)
        .multipliers(&sys)
        .unwrap()
        .write(&mut buf)
        .unwrap();
    let text = String::from_utf8(buf).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &header[..7],
        ["t", "x", "y", "z", "dot_x", "dot_y", "dot_z"]
    );
    let nu = header.iter().position(|h| h.starts_with("nu_")).unwrap();
    let (kin, pot, int) = (
        header.iter().position(|h| *h == "kinetic").unwrap(),
        header.iter().position(|h| *h == "potential").unwrap(),
        header.iter().position(|h| *h == "integral").unwrap(),
    );
    assert_eq!(header.last(), Some(&"residual_velocity"));
    let dynamics = ConstrainedDynamics::new(&sys);
    for (k, line) in lines.enumerate() {
        let row: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!((row[kin] + row[pot] - row[int]).abs() < 1e-12);
        let sol = dynamics
            .solve(traj.times()[k], &traj.positions()[k], &traj.velocities()[k])
            .unwrap();
        assert_eq!(row[nu], sol.multipliers[0]);
    }
}

/// Bad recording settings are refused before the first step.
#[test]
fn bad_recordings_are_typed_errors() {
    let pendulum = Pendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    for record in [
        Record::Every(0),
        Record::Interval(0.0),
        Record::Interval(f64::NAN),
        Record::Interval(-1.0),
    ] {
        let run = Simulation::new(&pendulum)
            .integrator(Rk4::step(0.1).record(record))
            .run([1.0], [0.0], 0.0..1.0);
        assert!(
            matches!(&run, Err(Failure { error: Error::Settings(m), .. }) if m.to_string().contains("record")),
            "{record:?}: {:?}",
            run.err().map(|f| f.error)
        );
    }
}
