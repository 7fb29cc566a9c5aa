//! A URDF robot's joint limits are watched: a prismatic carriage falling
//! under gravity through its lower limit stops with `Error::JointLimit`
//! naming the joint, at the time s = g t²/2 gives, in a plain and an event run, with adaptive and fixed steps; with
//! `LimitPolicy::Ignore` it falls through.

use lagrange::prelude::*;

#[derive(Lagrangian)]
#[lagrange(urdf = "tests/data/slider.urdf", gravity = [0, 0, -9.81])]
struct Slider {}

/// The fall of 0.5 m from rest: s = g t²/2.
fn closed_form() -> f64 {
    (2.0 * 0.5 / 9.81f64).sqrt()
}

/// The run's error is the limit of `drop`, crossed at the closed form's time
/// to 1e-9 s, on or just past −0.5; the trajectory kept ends before it.
fn stopped_at_the_limit(error: &Error, kept_until: f64) {
    let Error::JointLimit {
        joint,
        coordinate,
        value,
        lower,
        upper,
        t,
    } = *error
    else {
        panic!("{error}")
    };
    assert_eq!((joint, coordinate, lower, upper), ("drop", 0, -0.5, 0.5));
    println!(
        "crossing at t = {t}, {:.1e} from s = g t²/2",
        (t - closed_form()).abs()
    );
    assert!(
        (t - closed_form()).abs() < 1e-9,
        "t = {t}, {}",
        closed_form()
    );
    assert!(value <= -0.5 && value > -0.5 - 1e-9, "{value}");
    assert!(kept_until < t && kept_until > 0.0, "{kept_until}");
    assert!(error.to_string().contains("joint `drop`"), "{error}");
}

#[test]
fn a_run_stops_where_the_carriage_leaves_its_limits() {
    assert_eq!(Slider::JOINT_LIMITS, [(-0.5, 0.5)]);
    let failure = Simulation::new(&Slider {})
        .integrator(Dopri5::tol(1e-10))
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap_err();
    let kept = *failure.partial.times().last().unwrap();
    stopped_at_the_limit(&failure.error, kept);
}

#[test]
fn event_runs_and_fixed_steps_stop_there_too() {
    let failure = Simulation::new(&Slider {})
        .integrator(Dopri5::tol(1e-10))
        .event(Event::new(|_, q, _| q[0] - 10.0))
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap_err();
    let kept = *failure.partial.trajectory.times().last().unwrap();
    stopped_at_the_limit(&failure.error, kept);
    let fixed_step = Simulation::new(&Slider {})
        .integrator(Rk4::step(0.01))
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap_err();
    let kept = *fixed_step.partial.times().last().unwrap();
    stopped_at_the_limit(&fixed_step.error, kept);
}

#[test]
fn the_opt_out_runs_through_the_limit() {
    let traj = Simulation::new(&Slider {})
        .integrator(Dopri5::tol(1e-10))
        .joint_limits(LimitPolicy::Ignore)
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap();
    let (q, _) = traj.final_state();
    assert!((q[0] + 9.81 / 2.0).abs() < 1e-9, "{}", q[0]);
}

/// A start already past a limit is refused at the start time.
#[test]
fn a_start_outside_the_limits_stops_at_once() {
    let failure = Simulation::new(&Slider {})
        .run([0.6], [0.0], 0.0..1.0)
        .unwrap_err();
    let Error::JointLimit { t, value, .. } = failure.error else {
        panic!("{}", failure.error)
    };
    assert_eq!((t, value), (0.0, 0.6));
}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/solo12.urdf", base = floating), gravity = [0, 0, -9.81])]
struct Solo {}

/// On a free root q holds the base's position, the joints, then the base's
/// quaternion: each watched limit names the entry of q that is its joint's,
/// with the file's bounds, and the free base has none.
#[test]
fn limits_index_q_on_a_free_root() {
    let limits = Solo {}.position_limits();
    assert_eq!(limits.len(), 12);
    let names = <Solo as Lagrangian<f64, 18, 19>>::COORDINATES;
    for l in limits {
        assert_eq!(names[l.coordinate], l.joint);
        // JOINT_LIMITS follows the coordinates, which q begins with.
        assert_eq!((l.lower, l.upper), Solo::JOINT_LIMITS[l.coordinate]);
    }
    assert!(limits.iter().all(|l| !l.joint.starts_with("base_")));
}

/// An event that bounces the carriage at its lower limit comes first: the
/// limit is watched only up to a step's first stopping event, so the run
/// bounces (impacts at 0.319, 0.638, 0.798 and 0.878 s with restitution
/// 1/2) instead of stopping.
#[test]
fn an_event_that_bounces_at_the_limit_comes_first() {
    let run = Simulation::new(&Slider {})
        .integrator(Dopri5::tol(1e-10))
        .event(
            Event::new(|_, q, _| q[0] + 0.5)
                .falling()
                .action(|_, _, v| *v *= -0.5),
        )
        .run([0.0], [0.0], 0.0..0.9)
        .unwrap();
    let impacts = run.times(0);
    assert_eq!(impacts.len(), 4, "{impacts:?}");
    assert!((impacts[0] - closed_form()).abs() < 1e-9);
    assert!((impacts[1] - 2.0 * closed_form()).abs() < 1e-9);
}

#[derive(Lagrangian)]
#[lagrange(
    urdf = "tests/data/slider.urdf",
    gravity = [0, 0, -9.81],
    inputs(push),
    generalized_force(drop = push)
)]
struct Pushed {}

/// A controlled run stops there too: pushed down with 2 · 9.81 N on 2 kg,
/// the carriage falls at 2g and leaves its limit at √(2 · 0.5 / 2g); with
/// an event watched as well, and sampled (pieces between samples).
#[test]
fn controlled_runs_stop_there_too() {
    let at = (0.5 / 9.81f64).sqrt();
    let check = |error: &Error| {
        let Error::JointLimit {
            joint, t, value, ..
        } = *error
        else {
            panic!("{error}")
        };
        assert_eq!(joint, "drop");
        assert!((t - at).abs() < 1e-9, "{t} vs {at}");
        assert!(value <= -0.5 && value > -0.5 - 1e-9, "{value}");
    };
    let open = Simulation::new(&Pushed {})
        .integrator(Dopri5::tol(1e-10))
        .open_loop(|_| [-2.0 * 9.81])
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap_err();
    check(&open.error);
    let watched = Simulation::new(&Pushed {})
        .integrator(Dopri5::tol(1e-10))
        .open_loop(|_| [-2.0 * 9.81])
        .event(Event::new(|_, q, _| q[0] - 10.0))
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap_err();
    check(&watched.error);
    let sampled = Simulation::new(&Pushed {})
        .integrator(Dopri5::tol(1e-10))
        .sampled(0.01, |_, _, _| [-2.0 * 9.81])
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap_err();
    check(&sampled.error);
}

#[derive(Lagrangian)]
#[lagrange(urdf("tests/data/slider.urdf", limits = stops), gravity = [0, 0, -9.81])]
struct EndStops {}

/// With `limits = stops` the limits are plastic stops that `run_contacts`
/// enforces: the carriage falls, meets its lower stop when s = g t²/2
/// says, at g t, and stays there; every other run refuses the description.
#[test]
fn with_limits_as_stops_the_carriage_lands_on_its_end_stop() {
    assert_eq!(EndStops::CONTACTS, ["drop_lower", "drop_upper"]);
    let run = Simulation::new(&EndStops {})
        .integrator(lagrange::Dop853::tol(1e-12))
        .run_contacts([0.0], [0.0], 0.0..1.0)
        .unwrap();
    let landing = run.changes.first().expect("the landing");
    let lagrange::ChangeKind::Impact { before, after } = landing.kind else {
        panic!("{:?}", landing.kind)
    };
    assert_eq!(landing.contact, 0);
    assert!((landing.t - closed_form()).abs() < 1e-9, "{}", landing.t);
    assert!((before + 9.81 * closed_form()).abs() < 1e-9, "{before}");
    assert!(after.abs() < 1e-12);
    let (q, v) = run.trajectory.final_state();
    assert!((q[0] + 0.5).abs() < 1e-12 && v[0].abs() < 1e-12, "{q} {v}");
    let refused = Simulation::new(&EndStops {})
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap_err();
    assert!(
        refused.error.to_string().contains("run_contacts"),
        "{}",
        refused.error
    );
}

/// The file's `<limit effort="100">` bounds the push: asked for 300 N up,
/// the carriage gets 100 N and rises at (100 − 2 g)/2 m/s², and the run
/// says when the push was held at its limit. A sampled controller's
/// stretch runs exactly from sample to sample.
#[test]
fn input_limits_hold_the_push_at_the_joints_effort() {
    assert_eq!(Pushed::JOINT_EFFORTS, [100.0]);
    let effort = Pushed::JOINT_EFFORTS[0];
    let run = Simulation::new(&Pushed {})
        .integrator(Dopri5::tol(1e-12))
        .feedback(|_, _, _| [300.0])
        .input_limits([-effort], [effort])
        .run([0.0], [0.0], 0.0..0.1)
        .unwrap();
    let rise = (effort - 2.0 * 9.81) / 2.0;
    let (q, _) = run.trajectory().final_state();
    assert!((q[0] - 0.5 * rise * 0.01).abs() < 1e-12, "{}", q[0]);
    assert!(run.inputs().iter().all(|u| u[0] == effort));
    let held = run.saturations();
    assert_eq!(held.len(), 1);
    assert_eq!((held[0].input, held[0].upper), (0, true));
    assert_eq!((held[0].from, held[0].to), (0.0, 0.1));

    // Asked for 300 − 6000 t N, sampled every 10 ms: held at 100 N for the
    // samples at 0, 10, 20 and 30 ms, free from the one at 40 ms (60 N),
    // and held at −100 N from the one at 70 ms (−120 N) to the end.
    let sampled = Simulation::new(&Pushed {})
        .integrator(Dopri5::tol(1e-12))
        .sampled(0.01, |t, _, _| [300.0 - 6000.0 * t])
        .input_limits([-effort], [effort])
        .run([0.0], [0.0], 0.0..0.1)
        .unwrap();
    let held = sampled.saturations();
    assert_eq!(held.len(), 2, "{held:?}");
    assert_eq!((held[0].from, held[0].upper), (0.0, true));
    assert!((held[0].to - 0.04).abs() < 1e-15, "{}", held[0].to);
    assert!(
        !held[1].upper && (held[1].from - 0.07).abs() < 1e-15,
        "{held:?}"
    );
    assert_eq!(held[1].to, 0.1);
}

#[test]
fn input_limits_out_of_order_are_refused() {
    let failure = Simulation::new(&Pushed {})
        .feedback(|_, _, _| [0.0])
        .input_limits([1.0], [-1.0])
        .run([0.0], [0.0], 0.0..0.1)
        .unwrap_err();
    assert!(
        failure.error.to_string().contains("input limits"),
        "{}",
        failure.error
    );
}

/// `<limit velocity="10">` as the motor's no-load speed: asked for 300 N
/// up, the carriage gets 100 (1 − ẋ/10) N, so 2 ẍ = 100 − 2 g − 10 ẋ and
/// ẋ = v∞ (1 − e^(−5t)) with v∞ = (100 − 2 g)/10 — under continuous
/// feedback and between a sampled controller's samples alike; the push is
/// held at its narrowed limit throughout.
#[test]
fn speed_limits_narrow_the_push_along_the_motors_torque_speed_line() {
    assert_eq!(Pushed::JOINT_VELOCITIES, [10.0]);
    let (effort, no_load) = (Pushed::JOINT_EFFORTS[0], Pushed::JOINT_VELOCITIES[0]);
    let v_inf = (effort - 2.0 * 9.81) * no_load / effort;
    let exact = |t: f64| v_inf * (1.0 - (-5.0 * t).exp());
    let live = Simulation::new(&Pushed {})
        .integrator(Dopri5::tol(1e-12))
        .feedback(|_, _, _| [300.0])
        .input_limits([-effort], [effort])
        .speed_limits([0], [no_load])
        .run([0.0], [0.0], 0.0..0.15)
        .unwrap();
    let sampled = Simulation::new(&Pushed {})
        .integrator(Dopri5::tol(1e-12))
        .sampled(0.01, |_, _, _| [300.0])
        .input_limits([-effort], [effort])
        .speed_limits([0], [no_load])
        .run([0.0], [0.0], 0.0..0.15)
        .unwrap();
    for run in [&live, &sampled] {
        let (_, v) = run.trajectory().final_state();
        assert!(
            (v[0] - exact(0.15)).abs() < 1e-9,
            "{} vs {}",
            v[0],
            exact(0.15)
        );
        let held = run.saturations();
        assert_eq!(held.len(), 1, "{held:?}");
        assert!(
            held[0].upper && held[0].from == 0.0 && held[0].to == 0.15,
            "{held:?}"
        );
    }
    // The recorded push is the narrowed one: 100 (1 − ẋ/10).
    let (_, v) = live.trajectory().final_state();
    let last = live.inputs().last().unwrap()[0];
    assert!((last - effort * (1.0 - v[0] / no_load)).abs() < 1e-12);
}

/// Pushing down while the carriage rises brakes it with the whole effort:
/// a bound against the motion is not narrowed.
#[test]
fn braking_against_the_motion_takes_the_whole_effort() {
    let run = Simulation::new(&Pushed {})
        .integrator(Dopri5::tol(1e-12))
        .feedback(|_, _, _| [-300.0])
        .input_limits([-100.0], [100.0])
        .speed_limits([0], [10.0])
        .run([0.0], [5.0], 0.0..0.01)
        .unwrap();
    assert_eq!(run.inputs()[0][0], -100.0);
    let bad = Simulation::new(&Pushed {})
        .feedback(|_, _, _| [0.0])
        .input_limits([-100.0], [100.0])
        .speed_limits([0], [0.0])
        .run([0.0], [0.0], 0.0..0.01);
    assert!(bad.is_err());
    // A joint index past the velocities is refused, not ignored.
    let past = Simulation::new(&Pushed {})
        .feedback(|_, _, _| [0.0])
        .input_limits([-100.0], [100.0])
        .speed_limits([1], [10.0])
        .run([0.0], [0.0], 0.0..0.01)
        .unwrap_err();
    assert!(past.error.to_string().contains("joints"), "{}", past.error);
}
