//! Piecewise forces in the description language (`sign`, `min`, `max`,
//! `clamp`, `if a > b { .. } else { .. }`) against closed forms, with the
//! switches paired with events where the integrator must not step across them.

use lagrange::prelude::*;

/// A block sliding on a floor with Coulomb friction μ m g against the motion.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(block, mass = m, at = [x, 0]),
    generalized_force(x = -mu * m * g * sign(dot(x))),
)]
struct Coulomb {
    m: f64,
    mu: f64,
    g: f64,
}

/// The same friction written as a conditional.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(block, mass = m, at = [x, 0]),
    generalized_force(x = if dot(x) > 0 { -mu * m * g } else { mu * m * g }),
)]
struct CoulombIf {
    m: f64,
    mu: f64,
    g: f64,
}

/// A mass pulled back by an actuator that saturates: F = clamp(−k x, −F_max, F_max).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, 0]),
    generalized_force(x = clamp(-k * x, -f_max, f_max)),
    emit(jacobians),
)]
struct Saturated {
    m: f64,
    k: f64,
    f_max: f64,
}

/// A ball falling onto a one-sided spring floor: the spring acts only below
/// x = 0 (a contact), so V = m g x + k min(x, 0)²/2 is continuous with a
/// continuous force.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(ball, mass = m, at = [0, x]),
    gravity = [0, -g],
    potential = k * (min(x, 0)^2) / 2,
)]
struct Contact {
    m: f64,
    g: f64,
    k: f64,
}

/// Quadratic drag on forward motion only, max(ẋ, 0) ẋ, with emitted Jacobians.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y),
    point(p, mass = m, at = [x, y]),
    generalized_force(x = -c * max(dot(x), 0) * dot(x), y = -k * y),
    emit(jacobians),
)]
struct OneWayDrag {
    m: f64,
    c: f64,
    k: f64,
}

/// The block decelerates at μg and stops at t* = v0/(μg), x* = v0²/(2μg).
/// Stepping across ẋ = 0 would make the friction flip sign every step, so the
/// run ends with a terminal event on ẋ falling through zero, located on the
/// dense output of the smooth piece before the switch.
#[test]
fn coulomb_friction_stops_where_the_closed_form_says() {
    let (m, mu, g, v0) = (2.0, 0.3, 9.81, 1.7);
    let stop = v0 / (mu * g);
    for run in [
        Simulation::new(&Coulomb { m, mu, g })
            .integrator(Dopri5::tol(1e-12))
            .event(
                Event::new(|_, _, v: &Vector1<f64>| v[0])
                    .falling()
                    .terminal(),
            )
            .run([0.0], [v0], 0.0..10.0)
            .unwrap(),
        Simulation::new(&CoulombIf { m, mu, g })
            .integrator(Dopri5::tol(1e-12))
            .event(
                Event::new(|_, _, v: &Vector1<f64>| v[0])
                    .falling()
                    .terminal(),
            )
            .run([0.0], [v0], 0.0..10.0)
            .unwrap(),
    ] {
        assert_eq!(run.terminated_by, Some(0));
        let t = run.times(0)[0];
        let (q, _) = run.trajectory.final_state();
        // The step that reaches the switch has its last stages on the far
        // side, where the friction has flipped: the event is located within
        // that step's local error (5e-11 here at tol 1e-12), not to round-off.
        assert!((t - stop).abs() < 1e-9, "stop at {t}, closed form {stop}");
        let x_stop = v0 * v0 / (2.0 * mu * g);
        assert!((q[0] - x_stop).abs() < 1e-9, "{} vs {x_stop}", q[0]);
    }
}

/// From x0 = 3 (k x0 = 3 > F_max = 1) the force is −F_max until x = 1:
/// x = 3 − t²/2 (m = 1), reached at t = 2 with ẋ = −2; then harmonic,
/// x = cos t' − 2 sin t' (ω = 1) until x = −1 at t' ≈ 0.93.
#[test]
fn saturated_actuator_follows_both_regimes() {
    let sys = Saturated {
        m: 1.0,
        k: 1.0,
        f_max: 1.0,
    };
    let run = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .event(Event::new(|_, q: &Vector1<f64>, _| q[0] - 1.0).falling())
        .run([3.0], [0.0], 0.0..2.5)
        .unwrap();
    let t1 = run.times(0)[0];
    assert!((t1 - 2.0).abs() < 1e-10, "{t1}");
    let (q, v) = run.trajectory.final_state();
    let tp: f64 = 0.5;
    let (x, xd) = (tp.cos() - 2.0 * tp.sin(), -tp.sin() - 2.0 * tp.cos());
    assert!(
        (q[0] - x).abs() < 1e-9 && (v[0] - xd).abs() < 1e-9,
        "{q} {v}"
    );
    // The emitted Jacobian of the saturated force: 0 in saturation, −k inside.
    let (jq, _) = sys
        .rhs_jacobians(
            &Vector1::new(3.0),
            &Vector1::new(0.0),
            &Vector1::zeros(),
            0.0,
        )
        .unwrap();
    assert_eq!(jq[(0, 0)], 0.0);
    let (jq, _) = sys
        .rhs_jacobians(
            &Vector1::new(0.5),
            &Vector1::new(0.0),
            &Vector1::zeros(),
            0.0,
        )
        .unwrap();
    assert_eq!(jq[(0, 0)], -1.0);
}

/// A continuous one-sided contact conserves energy through the bounce.
#[test]
fn one_sided_contact_conserves_energy() {
    let sys = Contact {
        m: 0.5,
        g: 9.81,
        k: 2000.0,
    };
    let run = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-11))
        .run([1.0], [0.0], 0.0..3.0)
        .unwrap();
    // It bounced: below the floor at some point, back above later.
    let xs: Vec<f64> = run.positions().iter().map(|q| q[0]).collect();
    assert!(xs.iter().any(|&x| x < -0.01));
    assert!(xs.last().unwrap() > &0.0 || xs.iter().rev().any(|&x| x > 0.5));
    assert!(run.integral_drift() < 1e-7, "{:e}", run.integral_drift());
}

/// The emitted Jacobians of a piecewise force equal central differences away
/// from the switch ẋ = 0, on both sides.
#[test]
fn piecewise_force_jacobians_match_central_differences() {
    let sys = OneWayDrag {
        m: 1.5,
        c: 0.7,
        k: 3.0,
    };
    let h = 1e-6;
    for vx in [-1.3, -0.2, 0.4, 2.1] {
        let q = Vector2::new(0.3, -0.8);
        let v = Vector2::new(vx, 0.5);
        let (_, jv) = sys.rhs_jacobians(&q, &v, &Vector2::zeros(), 0.0).unwrap();
        let rhs = |v: &Vector2<f64>| sys.mass_matrix_and_rhs(&q, v, 0.0).1;
        for j in 0..2 {
            let mut e = Vector2::zeros();
            e[j] = h;
            let fd = (rhs(&(v + e)) - rhs(&(v - e))) / (2.0 * h);
            assert!(
                (jv.column(j) - fd).amax() < 1e-7,
                "ẋ = {vx}: {} vs {fd}",
                jv.column(j)
            );
        }
    }
}

/// A dead zone written with `&&`, and the same with `||` and `!`.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, 0]),
    generalized_force(x = if x > -d && x < d { 0 } else { -k * x }),
)]
struct DeadZone {
    m: f64,
    d: f64,
    k: f64,
}

#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x),
    point(p, mass = m, at = [x, 0]),
    generalized_force(x = if !(x <= -d || x >= d) { 0 } else { -k * x }),
)]
struct DeadZoneOr {
    m: f64,
    d: f64,
    k: f64,
}

#[test]
fn conditions_join_with_and_or_not() {
    let (m, d, k) = (1.0, 0.5, 3.0);
    let (a, b) = (DeadZone { m, d, k }, DeadZoneOr { m, d, k });
    for x in [-1.0, -0.5, -0.2, 0.0, 0.3, 0.5, 0.9] {
        let q = Vector1::new(x);
        let v = Vector1::zeros();
        let fa = a.generalized_forces(&q, &v, 0.0)[0];
        let fb = b.generalized_forces(&q, &v, 0.0)[0];
        let expected = if x > -d && x < d { 0.0 } else { -k * x };
        assert_eq!((fa, fb), (expected, expected), "x = {x}");
    }
}
