//! The `serde` feature: a trajectory survives a JSON round trip bit for bit
//! (dense output included), and a study's rows serialize with their errors as
//! messages.
#![cfg(feature = "serde")]

mod common;

use common::SphericalPendulum;
use lagrange_runtime::{Dopri5, Record, Simulation, Trajectory};
use nalgebra::Vector2;

#[test]
fn trajectory_round_trip() {
    let sys = SphericalPendulum::standard();
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-9))
        .run(Vector2::new(1.0, 0.0), Vector2::new(0.0, 2.0), 0.0..2.0)
        .unwrap();
    let json = serde_json::to_string(&traj).unwrap();
    let back: Trajectory<f64, 2> = serde_json::from_str(&json).unwrap();
    assert_eq!(back.times(), traj.times());
    assert_eq!(back.positions(), traj.positions());
    assert_eq!(back.stats(), traj.stats());
    assert_eq!(back.recording(), Record::Steps);
    // The dense output comes back too.
    assert_eq!(back.state_at(1.234_5), traj.state_at(1.234_5));
}

#[test]
fn study_rows_serialize_with_errors_as_messages() {
    use lagrange_runtime::study::{Method, Sweep};
    use lagrange_runtime::{Rk4, WorkPrecision};
    let sys = common::Oscillator { m: 1.0, k: 4.0 };
    let study = WorkPrecision::new(|m: Method| {
        Simulation::new(&sys).integrator(m).run(
            nalgebra::Vector1::new(1.0),
            nalgebra::Vector1::new(0.0),
            0.0..1.0,
        )
    })
    .exact(|t| nalgebra::Vector1::new((2.0 * t).cos()))
    .sweep(Sweep::steps("RK4", &[0.1, 0.001], |h| {
        Rk4::step(h).max_steps(50)
    }))
    .repeats(1, std::time::Duration::from_millis(10))
    .run()
    .unwrap();
    let json = serde_json::to_string(&study).unwrap();
    // The step 0.001 needs 1000 steps: its row is the budget error, as text.
    assert!(json.contains("\"Ok\""), "{json}");
    assert!(
        json.contains("needs 1000 steps but the step budget is 50"),
        "{json}"
    );
}
