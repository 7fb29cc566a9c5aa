//! The `serde` feature on every run result: a trajectory (also a thinned
//! one), an event run with its occurrences, and a controlled run with its
//! inputs serialize without the recorder's internal state, and those that
//! deserialize come back equal.
#![cfg(feature = "serde")]

mod common;

use common::{Oscillator, Pendulum, sv};
use lagrange_runtime::{
    Dopri5, Event, EventRun, Occurrence, Record, Simulation, Stats, Trajectory,
};
use serde_json::Value;

/// The recorder's internal fields, which no JSON of a result may carry.
const INTERNAL: [&str; 3] = ["steps_seen", "next_output", "pending"];

/// Every object key anywhere in `value`.
fn keys(value: &Value, out: &mut Vec<String>) {
    match value {
        Value::Object(map) => {
            for (k, v) in map {
                out.push(k.clone());
                keys(v, out);
            }
        }
        Value::Array(items) => items.iter().for_each(|v| keys(v, out)),
        _ => {}
    }
}

fn no_internal_fields(json: &str) -> Vec<String> {
    let mut all = Vec::new();
    keys(&serde_json::from_str(json).unwrap(), &mut all);
    for internal in INTERNAL {
        assert!(
            !all.iter().any(|k| k == internal),
            "`{internal}` in {json:.300}"
        );
    }
    all
}

#[test]
fn trajectories_serialize_without_recorder_state_and_round_trip() {
    let sys = Pendulum::standard();
    for record in [Record::Steps, Record::Every(7), Record::Interval(0.1)] {
        let traj = Simulation::new(&sys)
            .integrator(Dopri5::tol(1e-9).record(record))
            .run(sv([1.0]), sv([0.0]), 0.0..2.0)
            .unwrap();
        let json = serde_json::to_string(&traj).unwrap();
        no_internal_fields(&json);
        let back: Trajectory<f64, 1> = serde_json::from_str(&json).unwrap();
        assert_eq!(back.times(), traj.times());
        assert_eq!(back.positions(), traj.positions());
        assert_eq!(back.velocities(), traj.velocities());
        assert_eq!(back.recording(), record);
        assert_eq!(back.state_at(1.234), traj.state_at(1.234));
        let stats: Stats =
            serde_json::from_str(&serde_json::to_string(traj.stats()).unwrap()).unwrap();
        assert_eq!(&stats, traj.stats());
    }
}

#[test]
fn event_runs_and_occurrences_round_trip() {
    let sys = Pendulum::standard();
    let run = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-10))
        .event(Event::new(|_, q, _| q[0]))
        .event(Event::new(|_, _, v| v[0]).falling().terminal())
        .run(sv([1.0]), sv([0.5]), 0.0..10.0)
        .unwrap();
    assert_eq!(run.terminated_by, Some(1));
    let json = serde_json::to_string(&run).unwrap();
    let keys = no_internal_fields(&json);
    for key in ["trajectory", "occurrences", "terminated_by", "q_after"] {
        assert!(keys.iter().any(|k| k == key), "no `{key}` in {json:.300}");
    }
    let back: EventRun<f64, 1> = serde_json::from_str(&json).unwrap();
    assert_eq!(back.occurrences, run.occurrences);
    assert_eq!(back.terminated_by, run.terminated_by);
    assert_eq!(back.trajectory.times(), run.trajectory.times());
    let first = serde_json::to_string(&run.occurrences[0]).unwrap();
    let occurrence: Occurrence<f64, 1> = serde_json::from_str(&first).unwrap();
    assert_eq!(occurrence, run.occurrences[0]);
}

#[test]
fn control_runs_serialize_with_their_inputs() {
    // A unit mass pushed by one force (the shared oscillator without its spring).
    let cart = Oscillator { m: 1.0, k: 0.0 };
    let run = Simulation::new(&cart)
        .integrator(Dopri5::tol(1e-10))
        .sampled(0.1, |_, q, v| [-q[0] - 2.0 * v[0]])
        .event(Event::new(|_, q, _| q[0] - 0.5).falling())
        .run([1.0], [0.0], 0.0..2.0)
        .unwrap();
    let json = serde_json::to_string(&run).unwrap();
    no_internal_fields(&json);
    let value: Value = serde_json::from_str(&json).unwrap();
    let inputs = value["inputs"].as_array().expect("the inputs");
    assert_eq!(inputs.len(), run.trajectory().len());
    assert_eq!(inputs[0], serde_json::json!([-1.0]));
    assert_eq!(value["input_names"], serde_json::json!(["force"]));
    assert_eq!(value["coordinates"], serde_json::json!(["x"]));
    assert_eq!(
        value["occurrences"].as_array().unwrap().len(),
        run.occurrences().len()
    );
    assert!(value["trajectory"]["times"].is_array());
}
