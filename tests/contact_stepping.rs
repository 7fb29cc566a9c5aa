//! The time-stepping contact run (`MoreauJean`) against the closed forms
//! the event-driven run meets to round-off: where the scheme is exact (a
//! sphere that starts to roll keeps its angular momentum about the contact
//! point, so it rolls at exactly 5/7 of its speed; a block on the floor loses
//! μ g h per step), to round-off; elsewhere within a few steps, converging
//! at order one as the step is halved. And a box tossed onto the floor, the
//! scene the event-driven run cannot finish, coming to rest flat on it.

use crate::catalog::contact::{BALL_FRICTION, BALL_RESTITUTION, Ball, StoppedPendulum, TossedBox};
use crate::catalog::contact::{BLOCK_FRICTION, SlidingBlock};
use lagrange::error::ContactFault;
use lagrange::prelude::*;
use lagrange::{ChangeKind, ContactRun, ContactState, Dop853, MoreauJean};

const G: f64 = 9.81;
const BALL: Ball = Ball {
    m: 0.3,
    r: 0.1,
    g: G,
};

fn stepped<S: lagrange::Contacts<f64, N>, const N: usize>(
    system: &S,
    h: f64,
    (q0, v0): ([f64; N], [f64; N]),
    end: f64,
) -> ContactRun<f64, N> {
    Simulation::new(system)
        .integrator(MoreauJean::step(h))
        .run_contacts(q0, v0, 0.0..end)
        .unwrap()
}

fn first<const N: usize>(run: &ContactRun<f64, N>, kind: fn(&ChangeKind<f64>) -> bool) -> f64 {
    run.changes
        .iter()
        .find(|c| kind(&c.kind))
        .expect("the change")
        .t
}

#[test]
fn a_sphere_thrown_sliding_rolls_at_exactly_five_sevenths() {
    let v0 = 2.0;
    let rolls_at = 2.0 * v0 / (7.0 * BALL_FRICTION * G);
    for h in [1e-2, 1e-3] {
        let run = stepped(&BALL, h, ([0.0, BALL.r, 0.0], [v0, 0.0, 0.0]), 1.0);
        let (q, v) = run.trajectory.final_state();
        // Impulses at the contact point keep the angular momentum about it.
        assert!((v[0] - 5.0 / 7.0 * v0).abs() < 1e-12, "h = {h}: {}", v[0]);
        assert!((v[0] - BALL.r * v[2]).abs() < 1e-12, "rolling");
        assert!((q[1] - BALL.r).abs() < 1e-12, "on the floor: {}", q[1]);
        let sticks = run
            .changes
            .iter()
            .find(|c| c.kind == ChangeKind::Sticks)
            .unwrap();
        assert!(
            (sticks.t - rolls_at).abs() <= h,
            "h = {h}: {} vs {rolls_at}",
            sticks.t
        );
        assert_eq!(run.states(1.0), [ContactState::Sticking]);
    }
}

#[test]
fn a_block_stops_where_friction_says_to_within_a_step() {
    let block = SlidingBlock {
        m: 2.0,
        a: 0.2,
        g: G,
    };
    let (v0, angle) = (3.0, 0.6f64);
    let dir = [angle.cos(), angle.sin()];
    let stop_time = v0 / (BLOCK_FRICTION * G);
    let distance = v0 * v0 / (2.0 * BLOCK_FRICTION * G);
    let mut errors = Vec::new();
    for h in [4e-3, 2e-3, 1e-3] {
        let run = stepped(&block, h, ([0.0; 3], [v0 * dir[0], v0 * dir[1], 0.0]), 1.0);
        let (q, v) = run.trajectory.final_state();
        assert_eq!(v, nalgebra::Vector3::zeros(), "stopped");
        assert!(q[2].abs() < 1e-15, "on the floor: {}", q[2]);
        // The cone keeps the slip's direction.
        assert!((q[1] * dir[0] - q[0] * dir[1]).abs() < 1e-12);
        let travelled = q[0].hypot(q[1]);
        let error = (travelled - distance).abs();
        assert!(error < BLOCK_FRICTION * G * h * h, "h = {h}: {error:e}");
        let sticks = first(&run, |k| *k == ChangeKind::Sticks);
        assert!((sticks - stop_time).abs() <= h, "h = {h}");
        errors.push(error);
    }
    assert!(errors.iter().all(|e| *e < 1e-4));
}

#[test]
fn a_ball_bounces_to_rest_near_its_accumulation_time() {
    let h0 = 0.5;
    let e = BALL_RESTITUTION;
    let t1 = (2.0 * h0 / G).sqrt();
    let rest_at = t1 * (1.0 + e) / (1.0 - e);
    let mut first_errors = Vec::new();
    for h in [2e-3, 1e-3, 5e-4] {
        let run = stepped(&BALL, h, ([0.0, h0 + BALL.r, 0.0], [0.0; 3]), 2.0);
        let impacts: Vec<f64> = run
            .changes
            .iter()
            .filter(|c| matches!(c.kind, ChangeKind::Impact { .. }))
            .map(|c| c.t)
            .collect();
        let expected = |k: usize| t1 + 2.0 * t1 * (1..=k).map(|j| e.powi(j as i32)).sum::<f64>();
        for (k, t) in impacts.iter().take(3).enumerate() {
            assert!(
                (t - expected(k)).abs() <= 2.0 * h,
                "h = {h}, impact {k}: {t}"
            );
        }
        first_errors.push((impacts[0] - t1).abs());
        eprintln!("h = {h}: first impact off by {:e}", (impacts[0] - t1).abs());
        // At rest on the floor well after the accumulation time, sunk by
        // less than a step's fall.
        let (q, v) = run.trajectory.final_state();
        assert!(v.norm() < 1e-12, "h = {h}: {v:?}");
        assert!(
            q[1] <= BALL.r && BALL.r - q[1] < G * h * h,
            "h = {h}: {}",
            q[1]
        );
        let (_, late) = run.trajectory.state_at(rest_at + 0.1).unwrap();
        assert!(
            late.norm() < 1e-9,
            "h = {h}: still moving at {}",
            rest_at + 0.1
        );
    }
}

#[test]
fn a_pendulum_meets_its_stop_converging_at_order_one() {
    let p = StoppedPendulum {
        m: 0.7,
        l: 1.3,
        g: G,
    };
    let exact = Simulation::new(&p)
        .integrator(Dop853::tol(1e-12))
        .run_contacts([1.0], [0.0], 0.0..3.0)
        .unwrap();
    let impact = |run: &ContactRun<f64, 1>| first(run, |k| matches!(k, ChangeKind::Impact { .. }));
    let reference = impact(&exact);
    let probe = reference + 0.3;
    let (_, v_exact) = exact.trajectory.state_at(probe).unwrap();
    let mut errors = Vec::new();
    for h in [4e-3, 2e-3, 1e-3, 5e-4] {
        let run = stepped(&p, h, ([1.0], [0.0]), 3.0);
        assert!((impact(&run) - reference).abs() <= h);
        let (_, v) = run.trajectory.state_at(probe).unwrap();
        errors.push((v[0] - v_exact[0]).abs() / h);
    }
    eprintln!("error / h after the first impact: {errors:?}");
    // Order one: the error after the impact stays below a fixed multiple
    // of the step.
    assert!(errors.iter().all(|e| *e < 10.0), "{errors:?}");
}

/// The box: 0.4 m wide, 0.2 m high, 1 kg.
const BOX: TossedBox = TossedBox {
    m: 1.0,
    a: 0.4,
    b: 0.2,
    g: G,
};

fn tossed() -> ([f64; 3], [f64; 3]) {
    ([0.0, 0.5, 0.7], [1.5, 1.0, -6.0])
}

#[test]
fn a_tossed_box_settles_flat_on_the_floor() {
    let run = stepped(&BOX, 1e-3, tossed(), 3.0);
    let (q, v) = run.trajectory.final_state();
    assert!(v.norm() < 1e-9, "still moving: {v:?}");
    // Flat on a face: θ a multiple of π/2, the centre at half that face's
    // height above the floor, to within a step's sinking.
    let quarter = (q[2] / std::f64::consts::FRAC_PI_2).round();
    // Moreau–Jean keeps what each corner sank at its last impact (it
    // corrects velocities, not positions): the box rests a few μm deep and
    // tilted by their difference (2.1e-5 rad, 8 μm across its 0.4 m).
    assert!(
        (q[2] - quarter * std::f64::consts::FRAC_PI_2).abs() < 5e-5,
        "θ = {}",
        q[2]
    );
    let half = if quarter as i64 % 2 == 0 {
        BOX.b / 2.0
    } else {
        BOX.a / 2.0
    };
    assert!((q[1] - half).abs() < 1e-5, "z = {}", q[1]);
    // It landed, bounced on corners and came to rest with two corners held.
    let impacts = run
        .changes
        .iter()
        .filter(|c| matches!(c.kind, ChangeKind::Impact { .. }))
        .count();
    assert!(impacts >= 3, "{impacts} impacts");
    let resting = run
        .states(3.0)
        .iter()
        .filter(|s| **s != ContactState::Apart)
        .count();
    assert_eq!(resting, 2);
    // No corner ever sank deeper than a step's travel at the landing speed
    // (about 7 m/s).
    let deepest = deepest_corner(&run);
    assert!(deepest > -7e-3, "sank to {deepest}");
    // Its energy fell at the impacts and never rose by more than the
    // smooth steps' O(h²) wobble.
    let energy = run.trajectory.integrals();
    let rises = energy
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(0.0f64, f64::max);
    assert!(rises < 1e-3 * energy[0].abs(), "energy rose by {rises}");
}

/// The lowest any corner went, over the recorded steps.
fn deepest_corner(run: &ContactRun<f64, 3>) -> f64 {
    let (a, b) = (BOX.a / 2.0, BOX.b / 2.0);
    run.trajectory
        .positions()
        .iter()
        .map(|q| {
            let (s, c) = q[2].sin_cos();
            [(a, b), (-a, b), (-a, -b), (a, -b)]
                .iter()
                .map(|(x, z)| q[1] - x * s + z * c)
                .fold(f64::INFINITY, f64::min)
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn too_few_sweeps_stop_with_the_run_so_far() {
    // Resting flat, two corners share the weight along dependent rows:
    // one sweep of Gauss–Seidel does not settle it.
    let flat = ([0.0, BOX.b / 2.0, 0.0], [0.0; 3]);
    let failure = Simulation::new(&BOX)
        .integrator(MoreauJean::step(1e-3).sweeps(1).tolerance(1e-14))
        .run_contacts(flat.0, flat.1, 0.0..1.0)
        .unwrap_err();
    match failure.error {
        lagrange::Error::Contact(ref e) => {
            assert!(
                matches!(e.fault, ContactFault::ImpulsesUnsettled { sweeps: 1, .. }),
                "{e}"
            );
            assert!(e.to_string().contains("MoreauJean::sweeps"));
        }
        ref other => panic!("{other}"),
    }
    assert!(!failure.partial.trajectory.is_empty());
}

#[test]
fn a_start_below_the_floor_is_refused() {
    let failure = Simulation::new(&BALL)
        .integrator(MoreauJean::step(1e-3))
        .run_contacts([0.0, 0.05, 0.0], [0.0; 3], 0.0..1.0)
        .unwrap_err();
    let lagrange::Error::Contact(e) = failure.error else {
        panic!("{}", failure.error)
    };
    assert!(matches!(e.fault, ContactFault::Penetrates { .. }));
}

/// The catalog's box without friction: the two schemes then model the same
/// impacts (the event-driven run's are frictionless), so the time stepper
/// must converge to the event-driven motion.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, z, theta),
    body(block, mass = m, inertia = [m * b * b / 12, m * (a * a + b * b) / 12, m * a * a / 12],
         at = [x, 0, z], rotation = rot_y(theta)),
    gravity = [0, 0, -g],
    point(c1, mass = 0, at = [x + a / 2 * cos(theta) + b / 2 * sin(theta), 0,
                             z - a / 2 * sin(theta) + b / 2 * cos(theta)]),
    point(c2, mass = 0, at = [x - a / 2 * cos(theta) + b / 2 * sin(theta), 0,
                             z + a / 2 * sin(theta) + b / 2 * cos(theta)]),
    point(c3, mass = 0, at = [x - a / 2 * cos(theta) - b / 2 * sin(theta), 0,
                             z + a / 2 * sin(theta) - b / 2 * cos(theta)]),
    point(c4, mass = 0, at = [x + a / 2 * cos(theta) - b / 2 * sin(theta), 0,
                             z - a / 2 * sin(theta) - b / 2 * cos(theta)]),
    contact(corner1, on = c1, normal = [0, 0, 1], restitution = 0.2),
    contact(corner2, on = c2, normal = [0, 0, 1], restitution = 0.2),
    contact(corner3, on = c3, normal = [0, 0, 1], restitution = 0.2),
    contact(corner4, on = c4, normal = [0, 0, 1], restitution = 0.2),
)]
struct SmoothBox {
    m: f64,
    a: f64,
    b: f64,
    g: f64,
}

#[test]
fn without_friction_the_box_converges_to_the_event_driven_motion() {
    let smooth = SmoothBox {
        m: 1.0,
        a: 0.4,
        b: 0.2,
        g: G,
    };
    let (q0, v0) = ([0.0, 0.4, 0.5], [1.0, -2.0, 3.0]);
    let exact = Simulation::new(&smooth)
        .integrator(Dop853::tol(1e-12))
        .run_contacts(q0, v0, 0.0..0.6)
        .unwrap();
    let impacts = |run: &ContactRun<f64, 3>| {
        (run.changes.iter())
            .filter(|c| matches!(c.kind, ChangeKind::Impact { .. }))
            .count()
    };
    assert!(impacts(&exact) >= 2, "the probe must follow impacts");
    let (q_exact, _) = exact.trajectory.final_state();
    let mut errors = Vec::new();
    for h in [2e-3, 1e-3, 5e-4, 2.5e-4] {
        let run = stepped(&smooth, h, (q0, v0), 0.6);
        let (q, _) = run.trajectory.final_state();
        errors.push((q - q_exact).amax());
    }
    eprintln!("box without friction, largest error in q at 0.6 s: {errors:?}");
    // Order one: each halving of the step at least a third off the error,
    // and the finest within a few millimetres.
    for pair in errors.windows(2) {
        assert!(pair[1] < 0.75 * pair[0], "{errors:?}");
    }
    assert!(errors[3] < 5e-3, "{errors:?}");
}

/// With friction too: the event-driven run's impacts carry Coulomb's
/// friction in the same velocity-level law as the time stepper's, so the
/// tossed box, landing on a corner and bouncing onto the others, is
/// approached as the step shrinks. Steps of 0.5 ms and more take another
/// branch at a corner's bounce (3e-3 m off at 0.6 s); from 0.25 ms down
/// the error falls (5.8e-5, 1.8e-5, 3.3e-5, 7.2e-6 m, not monotonically:
/// each step size meets the corner's chatter at its own grid).
#[test]
fn with_friction_the_box_converges_to_the_event_driven_motion() {
    let (q0, v0) = ([0.0, 0.4, 0.5], [1.0, -2.0, 3.0]);
    let exact = Simulation::new(&BOX)
        .integrator(Dop853::tol(1e-12))
        .run_contacts(q0, v0, 0.0..0.6)
        .unwrap();
    let impacts = (exact.changes.iter())
        .filter(|c| matches!(c.kind, ChangeKind::Impact { .. }))
        .count();
    assert!(impacts >= 2, "the probe must follow impacts");
    let (q_exact, _) = exact.trajectory.final_state();
    let mut errors = Vec::new();
    for h in [2.5e-4, 1.25e-4, 6.25e-5, 3.125e-5] {
        let run = stepped(&BOX, h, (q0, v0), 0.6);
        let (q, _) = run.trajectory.final_state();
        errors.push((q - q_exact).amax());
    }
    eprintln!("box with friction, largest error in q at 0.6 s: {errors:?}");
    assert!(errors.iter().all(|e| *e < 1e-4), "{errors:?}");
    assert!(errors[3] < 2e-5, "{errors:?}");
}

/// A contact the run reports in force stays on its surface: after a
/// corner's impact moves another corner away (it leaves with a positive
/// normal speed, its impulse zero), that corner opens instead of being
/// kept "sticking" while its gap grows (to 6 mm before it was mended). The
/// tossed box at a loose tolerance (10⁻⁶), whose rocking takes that path;
/// the contacts in force drift by about 10⁻⁸ m there.
#[test]
fn a_contact_reported_in_force_is_on_its_surface() {
    use lagrange::Contacts;
    let run = Simulation::new(&BOX)
        .integrator(Dop853::tol(1e-6))
        .run_contacts(tossed().0, tossed().1, 0.0..0.8)
        .unwrap();
    let mut worst: f64 = 0.0;
    for k in 0..=400 {
        let t = 0.8 * k as f64 / 400.0;
        let (q, v) = run.trajectory.state_at(t).unwrap();
        for (i, state) in run.states(t).iter().enumerate() {
            if matches!(state, ContactState::Sticking | ContactState::Sliding) {
                worst = worst.max(BOX.contact_rows(i, &q, &v, t).unwrap().gap.abs());
            }
        }
    }
    eprintln!(
        "tossed box at tol 1e-6: the contacts in force are off their surface by {worst:.1e} m at most"
    );
    assert!(
        worst < 1e-6,
        "a contact in force is {worst} m off its surface"
    );
}
