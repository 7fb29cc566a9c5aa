//! Parameters that give a body a mass or an inertia no body has are refused
//! before any run starts, with `Error::NonPhysicalParameter` naming the body,
//! the entry and its value (literal values are compile errors instead, pinned
//! in `lagrange-ui/tests/ui/bodies`). Each way to run is checked: plain,
//! with events, with inputs, in the multiplier and the reduced form.

use lagrange::prelude::*;

/// A rotor turning about its x axis only: M = A stays positive whatever C is,
/// so before the check a negative C ran and returned Ok.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    body(rotor, mass = m, inertia = [a, b, c], at = [0, 0, 0], rotation = rot_x(theta)),
)]
struct Rotor {
    m: f64,
    a: f64,
    b: f64,
    c: f64,
}

/// A free top: it turns about all three axes, so its moments must satisfy the
/// triangle inequalities; the tensor form is checked as a whole.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = m, inertia = [a, a, c], at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
    body(plate, mass = m, inertia = [a, a, c, p, 0, 0], at = [0, 0, 0],
         rotation = euler_zxz(psi, theta, phi)),
)]
struct Tops {
    m: f64,
    a: f64,
    c: f64,
    p: f64,
}

/// A pendulum's inertia given about its pivot (`about`), moved to the centre
/// of mass: I_com,xx = a − m l².
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    body(stick, mass = m, inertia = [a, a, c], at = [0, 0, 0], about = [0, 0, 0],
         com = [0, 0, -l], rotation = rot_x(theta)),
    gravity = [0, 0, -g],
)]
struct Stick {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// A pendulum on a thread (multipliers) with a pushed cart (an input).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    inputs(push),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    holonomic(thread = (x^2) + (y^2) - (l^2)),
    generalized_force(x = push),
)]
struct Thread {
    m: f64,
    l: f64,
    g: f64,
}

/// The same pendulum in the reduced form.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    holonomic(thread = (x^2) + (y^2) - (l^2)),
    formulation(reduced),
)]
struct ReducedThread {
    m: f64,
    l: f64,
    g: f64,
}

/// The error's body, entry and value, or a panic naming what came instead.
fn refused<P>(result: Result<P, Failure<P>>) -> (&'static str, &'static str, f64) {
    match result {
        Err(Failure {
            error:
                Error::NonPhysicalParameter {
                    body, entry, value, ..
                },
            ..
        }) => (body, entry, value),
        Err(f) => panic!("expected NonPhysicalParameter, got {}", f.error),
        Ok(_) => panic!("expected NonPhysicalParameter, the run succeeded"),
    }
}

#[test]
fn a_negative_moment_is_refused_though_m_stays_positive() {
    let bad = Rotor {
        m: 1.0,
        a: 1.0,
        b: 1.0,
        c: -0.5,
    };
    assert_eq!(
        refused(Simulation::new(&bad).run([0.1], [0.0], 0.0..1.0)),
        ("rotor", "C", -0.5)
    );
    let e = bad.check_parameters().unwrap_err();
    assert!(e.to_string().contains("`rotor`: C = -0.5"), "{e}");
    // A linearisation checks the parameters first too.
    let op = lagrange::linear::OperatingPoint::new(
        nalgebra::SVector::<f64, 1>::new(0.1),
        nalgebra::SVector::<f64, 1>::zeros(),
    );
    let linear = lagrange::linear::Linearizer::new().unconstrained(&bad, &op);
    assert!(
        matches!(
            linear,
            Err(lagrange::Error::NonPhysicalParameter { entry: "C", .. })
        ),
        "{linear:?}"
    );
    let event = Event::new(|_, q: &nalgebra::SVector<f64, 1>, _| q[0]);
    let run = Simulation::new(&bad)
        .event(event)
        .run([0.1], [0.0], 0.0..1.0);
    assert_eq!(refused(run), ("rotor", "C", -0.5));
    // Turning about x only, the rotor may leave B and C at zero (only A is
    // read); so may it carry moments that break A + B >= C.
    let planar = Rotor {
        m: 1.0,
        a: 1.0,
        b: 0.0,
        c: 3.0,
    };
    assert!(Simulation::new(&planar).run([0.1], [0.0], 0.0..1.0).is_ok());
}

#[test]
fn a_negative_mass_is_refused() {
    let bad = Rotor {
        m: -1.0,
        a: 1.0,
        b: 1.0,
        c: 1.0,
    };
    assert_eq!(
        refused(Simulation::new(&bad).run([0.1], [0.0], 0.0..1.0)),
        ("rotor", "mass", -1.0)
    );
}

#[test]
fn moments_of_a_spinning_top_obey_the_triangle_inequality() {
    let tops = |a, c, p| Tops { m: 1.0, a, c, p };
    let (q0, v0) = ([0.0, 0.5, 0.0], [0.0, 0.0, 1.0]);
    assert!(
        Simulation::new(&tops(1.0, 1.5, 0.0))
            .run(q0, v0, 0.0..0.5)
            .is_ok()
    );
    // A + A >= C fails for the principal form first.
    assert_eq!(
        refused(Simulation::new(&tops(1.0, 3.0, 0.0)).run(q0, v0, 0.0..0.5)),
        ("top", "C", 3.0)
    );
    // A product too large for the diagonal: the second-moment matrix
    // tr(I)/2·E − I = [[0.75, -2, 0], [-2, 0.75, 0], [0, 0, 0.25]] has the
    // eigenvalue 0.75 − 2.
    let (body, entry, value) = refused(Simulation::new(&tops(1.0, 1.5, 2.0)).run(q0, v0, 0.0..0.5));
    assert_eq!((body, entry), ("plate", "inertia tensor"));
    assert!((value - (0.75 - 2.0)).abs() < 1e-12, "{value}");
}

#[test]
fn an_inertia_about_the_pivot_is_checked_at_the_centre_of_mass() {
    let stick = |a| Stick {
        m: 2.0,
        a,
        c: 0.1,
        l: 0.5,
        g: 9.81,
    };
    assert!(
        Simulation::new(&stick(0.6))
            .run([0.1], [0.0], 0.0..1.0)
            .is_ok()
    );
    // I_com,xx = 0.4 − 2 · 0.25 = −0.1.
    let (body, entry, value) = refused(Simulation::new(&stick(0.4)).run([0.1], [0.0], 0.0..1.0));
    assert_eq!((body, entry), ("stick", "Ixx"));
    assert!((value + 0.1).abs() < 1e-12, "{value}");
}

#[test]
fn constrained_reduced_and_controlled_runs_check_too() {
    let (q0, v0) = ([1.0, 0.0], [0.0, 0.0]);
    let thread = Thread {
        m: -1.0,
        l: 1.0,
        g: 9.81,
    };
    assert_eq!(
        refused(Simulation::new(&thread).run(q0, v0, 0.0..1.0)),
        ("bob", "mass", -1.0)
    );
    let controlled = Simulation::new(&thread)
        .open_loop(|_| [0.0])
        .run(q0, v0, 0.0..1.0);
    assert_eq!(refused(controlled), ("bob", "mass", -1.0));
    let reduced = ReducedThread {
        m: -1.0,
        l: 1.0,
        g: 9.81,
    };
    assert_eq!(
        refused(Simulation::new(&reduced).run(q0, v0, 0.0..1.0)),
        ("bob", "mass", -1.0)
    );
    let fine = ReducedThread {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    assert!(Simulation::new(&fine).run(q0, v0, 0.0..1.0).is_ok());
}
