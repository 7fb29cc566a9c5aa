//! `joint(q, friction = fc)`, a joint's Coulomb friction, exact: a slider
//! that stops at t = m v₀/fc after m v₀²/(2 fc); a spring–mass whose
//! amplitude falls by 2 fc/k every half period π √(m/k) until the spring
//! can no longer overcome fc; a ramped force that breaks it loose at
//! a t = fc; a pendulum that sticks below m g l sin θ = fc and slides above
//! it; the time-stepping and compliant schemes on the same oscillator; a
//! URDF's `<dynamics friction>` read.

use lagrange::prelude::*;
use lagrange::{
    ChangeKind, Compliant, ContactRun, ContactState, Contacts, Dop853, MoreauJean, Radau5,
};

/// A cart on a rail, its bearing's friction bounded by 0.5 N.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    joint(x, friction = 0.5),
)]
struct Slider {
    m: f64,
}

/// The cart on a spring, friction 0.3 N.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    potential = k / 2 * (x^2),
    joint(x, friction = 0.3),
)]
struct CoulombSpring {
    m: f64,
    k: f64,
}

/// The cart pushed by a force growing as a·t.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    generalized_force(x = a * t),
    joint(x, friction = 0.5),
)]
struct Pushed {
    m: f64,
    a: f64,
}

/// A pendulum whose pivot holds up to 0.5 N·m.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, friction = 0.5, damping = 0.0),
)]
struct StickyPendulum {
    m: f64,
    l: f64,
    g: f64,
}

fn exact<S: Contacts<f64, N>, const N: usize>(
    s: &S,
    (q0, v0): ([f64; N], [f64; N]),
    end: f64,
) -> ContactRun<f64, N> {
    Simulation::new(s)
        .integrator(Dop853::tol(1e-13))
        .run_contacts(q0, v0, 0.0..end)
        .unwrap()
}

fn times<const N: usize>(run: &ContactRun<f64, N>, kind: fn(&ChangeKind<f64>) -> bool) -> Vec<f64> {
    run.changes
        .iter()
        .filter(|c| kind(&c.kind))
        .map(|c| c.t)
        .collect()
}

#[test]
fn the_derived_law_and_rows_are_a_dry_friction_on_the_coordinate() {
    let s = Slider { m: 2.0 };
    let laws = s.contact_laws();
    assert_eq!(
        laws,
        [lagrange::ContactLaw::dry_friction("x_friction", 0.5)]
    );
    assert_eq!(<Slider as Lagrangian<f64, 1>>::CONTACTS, ["x_friction"]);
    let rows = s
        .contact_rows(0, &SVector::from([0.3]), &SVector::from([1.0]), 0.0)
        .unwrap();
    assert_eq!((rows.gap, rows.normal[0]), (0.0, 0.0));
    assert_eq!((rows.tangents[0][0], rows.tangents[1][0]), (1.0, 0.0));
}

/// m ẍ = −fc while it slides: it stops at t = m v₀/fc after m v₀²/(2 fc),
/// and friction holds it there.
#[test]
fn a_slider_stops_at_m_v0_over_fc() {
    let s = Slider { m: 2.0 };
    let (v0, fc) = (3.0, 0.5);
    let run = exact(&s, ([0.0], [v0]), 20.0);
    let stops = times(&run, |k| matches!(k, ChangeKind::Sticks));
    let (q, v) = run.trajectory.final_state();
    let (t_stop, distance) = (s.m * v0 / fc, s.m * v0 * v0 / (2.0 * fc));
    eprintln!(
        "slider: stops {:.1e} s from m v0/fc, {:.1e} m from m v0²/(2fc)",
        (stops[0] - t_stop).abs(),
        (q[0] - distance).abs()
    );
    assert_eq!(stops.len(), 1);
    assert!((stops[0] - t_stop).abs() < 1e-9);
    assert!((q[0] - distance).abs() < 1e-9);
    assert!(v[0].abs() < 1e-12);
    assert_eq!(run.states(20.0), [ContactState::Sticking]);
    assert_eq!(run.states(1.0), [ContactState::Sliding]);
}

/// From x₀ at rest, each half period π √(m/k) the cart turns at
/// |xₙ| = |x₀| − 2n fc/k on alternate sides, until the spring's k |xₙ|
/// is within fc: there it sticks (x₀ = 1, fc/k = 0.075: at n = 7,
/// x = +0.05, turned back from x₆ = 0.1 short of the centre, t = 7π/2).
#[test]
fn a_coulomb_oscillator_loses_2fc_over_k_each_half_period() {
    let s = CoulombSpring { m: 1.0, k: 4.0 };
    let run = exact(&s, ([1.0], [0.0]), 12.0);
    let half = std::f64::consts::PI * (s.m / s.k).sqrt();
    let mut worst: f64 = 0.0;
    for n in 1..=7 {
        let want = (-1f64).powi(n) * (1.0 - 0.15 * n as f64);
        let (q, _) = run.trajectory.state_at(n as f64 * half).unwrap();
        worst = worst.max((q[0] - want).abs());
    }
    let stops = times(&run, |k| matches!(k, ChangeKind::Sticks));
    eprintln!(
        "Coulomb oscillator: turning points off by {worst:.1e} m, stop by {:.1e} s",
        (stops[0] - 7.0 * half).abs()
    );
    assert!(worst < 1e-9);
    assert_eq!(stops.len(), 1);
    assert!((stops[0] - 7.0 * half).abs() < 1e-9);
    assert!((run.trajectory.final_state().0[0] - 0.05).abs() < 1e-9);
    // Friction holds the spring's pull, k·0.05 = 0.2 < 0.3, inside the bound.
    let (q, v) = run.trajectory.final_state();
    let force = run.forces(&s, 12.0, &q, &v).unwrap()[0];
    assert!((force.tangential[0] - 0.2).abs() < 1e-9, "{force:?}");
    assert_eq!(force.normal, 0.0);
}

/// Held until a t reaches fc (t = 0.25 s); then m ẍ = a (t − t_s).
#[test]
fn a_ramped_force_breaks_it_loose_at_fc() {
    let s = Pushed { m: 1.5, a: 2.0 };
    let run = exact(&s, ([0.0], [0.0]), 1.0);
    let slips = times(&run, |k| matches!(k, ChangeKind::Slips));
    let ts = 0.5 / s.a;
    let (q, _) = run.trajectory.final_state();
    let want = s.a * (1.0 - ts).powi(3) / (6.0 * s.m);
    eprintln!(
        "ramped slider: slips {:.1e} s from fc/a, at t = 1 {:.1e} m off",
        (slips[0] - ts).abs(),
        (q[0] - want).abs()
    );
    assert!((slips[0] - ts).abs() < 1e-9);
    assert!((q[0] - want).abs() < 1e-9);
    assert_eq!(run.states(0.1), [ContactState::Sticking]);
}

/// Gravity's torque m g l sin θ₀ against fc = 0.5: held just below the
/// threshold, turned just above it.
#[test]
fn a_pendulum_sticks_below_m_g_l_sin_theta_equal_to_fc() {
    let p = StickyPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let threshold = (0.5 / (p.m * p.g * p.l)).asin();
    let held = exact(&p, ([0.999 * threshold], [0.0]), 2.0);
    assert!(held.changes.is_empty(), "{:?}", held.changes);
    assert_eq!(held.trajectory.final_state().0[0], 0.999 * threshold);
    let turned = exact(&p, ([1.001 * threshold], [0.0]), 2.0);
    assert_eq!(turned.states(0.0), [ContactState::Sliding]);
    assert!(turned.trajectory.final_state().0[0] < threshold);
}

/// The time stepper and the compliant model on the oscillator: both stop
/// where the exact run does, to their orders (the compliant friction then
/// creeps back over fc/(k ε), far beyond the run's span; its regularised
/// friction is stiff, fc/ε against the mass, and wants an implicit method).
#[test]
fn stepped_and_compliant_oscillators_stop_where_the_exact_one_does() {
    let s = CoulombSpring { m: 1.0, k: 4.0 };
    let stepped = Simulation::new(&s)
        .integrator(MoreauJean::step(1e-4))
        .run_contacts([1.0], [0.0], 0.0..12.0)
        .unwrap();
    let compliant = Simulation::new(&s)
        .integrator(Radau5::tol(1e-8))
        .compliant_contacts(Compliant::stiffness(1e5).slip_speed(1e-5))
        .run_contacts([1.0], [0.0], 0.0..12.0)
        .unwrap();
    let at_rest = |run: &ContactRun<f64, 1>| run.trajectory.final_state().0[0] - 0.05;
    eprintln!(
        "Coulomb oscillator at rest: stepped (h = 1e-4) {:.1e} m off, compliant {:.1e} m off",
        at_rest(&stepped),
        at_rest(&compliant)
    );
    assert!(at_rest(&stepped).abs() < 1e-5);
    assert!(at_rest(&compliant).abs() < 1e-4);
    assert_eq!(stepped.states(12.0), [ContactState::Sticking]);
}

/// `dynamics = read` turns the Z1's `<dynamics friction>` into dry friction
/// on each moving joint's coordinate (the gripper's 1.0 too), beside its
/// damping; the arm released under gravity slides and loses energy.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/z1.urdf", dynamics = read), gravity = [0, 0, -9.81])]
struct Z1Read {}

#[test]
fn urdf_dynamics_read_adds_the_files_friction() {
    let arm = Z1Read {};
    let laws = arm.contact_laws();
    let bounds: Vec<f64> = laws.iter().map(|l| l.friction).collect();
    assert!(laws.iter().all(|l| l.is_dry_friction()));
    assert_eq!(bounds, [1.0, 2.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
    let q0 = [0.2, 1.0, -1.2, 0.3, 0.1, 0.2, 0.0];
    let run = Simulation::new(&arm)
        .integrator(Dop853::tol(1e-9))
        .run_contacts(q0, [0.0; 7], 0.0..0.3)
        .unwrap();
    let energy = |q: &SVector<f64, 7>, v: &SVector<f64, 7>| {
        arm.kinetic_energy(q, v, 0.0) + arm.potential_energy(q, 0.0)
    };
    let (q, v) = run.trajectory.final_state();
    let start = energy(&SVector::from(q0), &SVector::zeros());
    assert!(energy(&q, &v) < start, "{} vs {start}", energy(&q, &v));
    assert!(v.norm() > 0.0);
}
