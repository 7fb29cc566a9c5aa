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

/// A run with a quaternion comes back bit for bit: its dense output keeps
/// where the quaternion sits (normalised where it is read), so `state_at`
/// between the points is the same number after the round trip, and so is
/// the unit norm there.
#[test]
fn a_run_with_orientations_reads_back_bit_for_bit() {
    let top = common::rigid::HeavyTop {
        a: 0.8,
        c: 0.5,
        mgl: 2.0,
    };
    let (theta0, spin) = (0.6_f64, 6.0);
    let q0 = sv([(theta0 / 2.0).cos(), (theta0 / 2.0).sin(), 0.0, 0.0]);
    let traj = Simulation::new(&top)
        .integrator(Dopri5::tol(1e-6))
        .run(q0, sv([0.3, 0.0, spin]), 0.0..3.0)
        .unwrap();
    let json = serde_json::to_string(&traj).unwrap();
    let back: Trajectory<f64, 3, 4> = serde_json::from_str(&json).unwrap();
    assert_eq!(back.segments(), traj.segments());
    let mut worst_norm: f64 = 0.0;
    for k in 0..=997 {
        let t = 3.0 * f64::from(k) / 997.0;
        let (q, v) = traj.state_at(t).unwrap();
        let (qb, vb) = back.state_at(t).unwrap();
        for (a, b) in q.iter().chain(&v).zip(qb.iter().chain(&vb)) {
            assert_eq!(a.to_bits(), b.to_bits(), "t = {t}");
        }
        worst_norm = worst_norm.max((qb.norm() - 1.0).abs());
    }
    assert!(worst_norm < 1e-15, "{worst_norm:e}");
    // A layout that does not fit q and v is refused, not read out of bounds.
    let bad = json.replacen(
        "\"orientations\":[{\"q\":0,\"v\":0}]",
        "\"orientations\":[{\"q\":2,\"v\":2}]",
        1,
    );
    assert_ne!(bad, json);
    let err = serde_json::from_str::<Trajectory<f64, 3, 4>>(&bad).unwrap_err();
    assert!(err.to_string().contains("do not fit"), "{err}");
}

/// serde_json (with `float_roundtrip`, as this crate's tests and the
/// README's advice use it) reads back every finite f64 it writes exactly,
/// down to subnormals and the extremes.
#[test]
fn json_floats_round_trip_exactly() {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut values = vec![f64::MIN_POSITIVE, 5e-324, f64::MAX, -0.0, 0.1, 1.0 / 3.0];
    for _ in 0..20_000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let f = f64::from_bits(x);
        if f.is_finite() {
            values.push(f);
        }
    }
    for f in values {
        let back: f64 = serde_json::from_str(&serde_json::to_string(&f).unwrap()).unwrap();
        assert_eq!(back.to_bits(), f.to_bits(), "{f:e}");
    }
}
