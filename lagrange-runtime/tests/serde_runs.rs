//! The `serde` feature on every run result: a trajectory (also a thinned
//! one), an event run with its occurrences, and a controlled run with its
//! inputs serialize without the recorder's internal state, and those that
//! deserialize come back equal.
#![cfg(feature = "serde")]

mod common;

use common::{Pendulum, sv};
use lagrange_runtime::{
    Dopri5, Driven, Event, EventRun, Lagrangian, Occurrence, Record, Simulation, Stats, Trajectory,
};
use nalgebra::{Matrix1, Vector1};
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

/// A unit mass pushed by one force.
struct Cart;

impl Lagrangian<f64, 1> for Cart {
    const COORDINATES: [&'static str; 1] = ["x"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> {
        Matrix1::new(1.0)
    }
    fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
        t: f64,
    ) -> (Matrix1<f64>, Vector1<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 {
        0.5 * v[0] * v[0]
    }
    fn potential_energy(&self, _: &Vector1<f64>, _: f64) -> f64 {
        0.0
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t)
    }
}

impl Driven<f64, 1, 1> for Cart {
    const INPUTS: [&'static str; 1] = ["force"];
    fn input_forces(
        &self,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        u: &Vector1<f64>,
        _: f64,
    ) -> Vector1<f64> {
        *u
    }
    fn input_jacobians(
        &self,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        _: &Vector1<f64>,
        _: f64,
    ) -> (Matrix1<f64>, Matrix1<f64>, Matrix1<f64>) {
        (Matrix1::identity(), Matrix1::zeros(), Matrix1::zeros())
    }
}

#[test]
fn control_runs_serialize_with_their_inputs() {
    let run = Simulation::new(&Cart)
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
