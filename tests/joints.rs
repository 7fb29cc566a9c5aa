//! `joint(q, damping = b, armature = Ia)` against closed forms: a damped
//! pendulum's small-amplitude decay rate b/(2 m l²) and damped half-period;
//! a geared pendulum's period 4 √((J + Ia)/(m g c)) K(sin(θ₀/2)) at large
//! amplitude; its inverse dynamics (J + Ia) θ̈ + m g c sin θ + b θ̇; a
//! negative damping computed from the parameters refused before a run.

use crate::catalog::elliptic_k;
use lagrange::prelude::*;
use lagrange::{Dop853, Dynamics, Error};

/// A bob on a massless rod, damped at its pivot (the generic route).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, damping = b),
)]
pub struct DampedPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub b: f64,
}

/// A rod turning about z at its end, driven through a gearbox whose rotor
/// adds `ia` to the rod's inertia about the pivot (a kinematic tree).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    body(rod, mass = m, inertia = [j, j, j], at = [0, 0, 0], com = [0, -c, 0],
         rotation = rot_z(theta)),
    gravity = [0, -g, 0],
    joint(theta, damping = b, armature = ia),
    emit(articulated, inverse_dynamics),
)]
pub struct GearedPendulum {
    pub m: f64,
    pub j: f64,
    pub c: f64,
    pub g: f64,
    pub b: f64,
    pub ia: f64,
}

/// θ̈ + 2σ θ̇ + ω₀² θ = 0 near the bottom, σ = b/(2 m l²): between the zero
/// crossings half a damped period π/ω_d apart, |θ̇| falls by e^(−σπ/ω_d).
/// At θ₀ = 10⁻³ the pendulum's nonlinearity shifts both by ~θ₀²/16.
#[test]
fn damped_pendulum_decays_at_b_over_2ml2() {
    let p = DampedPendulum {
        m: 0.8,
        l: 1.1,
        g: 9.81,
        b: 0.15,
    };
    let sigma = p.b / (2.0 * p.m * p.l * p.l);
    let omega_d = (p.g / p.l - sigma * sigma).sqrt();
    let traj = Simulation::new(&p)
        .integrator(Dop853::tol(1e-13))
        .run([1e-3], [0.0], 0.0..12.0)
        .unwrap();
    let zeros = traj.crossings(|_, q, _| q[0]).unwrap();
    assert!(zeros.len() >= 6, "{} crossings", zeros.len());
    let k = zeros.len() - 1;
    let half = (zeros[k] - zeros[0]) / k as f64;
    let speed = |t: f64| traj.state_at(t).unwrap().1[0].abs();
    let rate = (speed(zeros[0]) / speed(zeros[k])).ln() / (zeros[k] - zeros[0]);
    let want_half = std::f64::consts::PI / omega_d;
    eprintln!(
        "damped pendulum: half-period off by {:.1e}, decay rate by {:.1e} (relative)",
        half / want_half - 1.0,
        rate / sigma - 1.0
    );
    assert!(
        (half / want_half - 1.0).abs() < 1e-7,
        "half-period {half} vs {want_half}"
    );
    assert!(
        (rate / sigma - 1.0).abs() < 1e-7,
        "decay rate {rate} vs {sigma}"
    );
    // Without the joint's damping the energy would stay; with it, it falls.
    let (q, v) = traj.final_state();
    let energy = |q: f64, v: f64| 0.5 * p.m * p.l * p.l * v * v + p.m * p.g * p.l * (1.0 - q.cos());
    let ratio = energy(q[0], v[0]) / energy(1e-3, 0.0);
    assert!(
        (ratio.ln() / 12.0 + 2.0 * sigma).abs() < 0.05 * sigma,
        "energy ratio {ratio}"
    );
}

/// (J + m c² + Ia) θ̈ = −m g c sin θ: the period of a physical pendulum whose
/// inertia about the pivot the rotor raises, at 90°, against the elliptic
/// integral.
#[test]
fn armature_slows_a_pendulum_as_its_inertia_says() {
    let p = GearedPendulum {
        m: 1.2,
        j: 0.03,
        c: 0.4,
        g: 9.81,
        b: 0.0,
        ia: 0.25,
    };
    let th0 = std::f64::consts::FRAC_PI_2;
    let inertia = p.j + p.m * p.c * p.c + p.ia;
    let exact = 4.0 * (inertia / (p.m * p.g * p.c)).sqrt() * elliptic_k((th0 / 2.0).sin());
    let traj = Simulation::new(&p)
        .integrator(Dop853::tol(1e-13))
        .run([th0], [0.0], 0.0..3.2 * exact)
        .unwrap();
    let zeros = traj.crossings(|_, q, _| q[0]).unwrap();
    let k = zeros.len() - 1;
    let measured = 2.0 * (zeros[k] - zeros[0]) / k as f64;
    eprintln!(
        "geared pendulum: period off by {:.1e} (relative)",
        measured / exact - 1.0
    );
    assert!(
        (measured / exact - 1.0).abs() < 1e-9,
        "period {measured} vs {exact}"
    );
}

/// τ = (J + m c² + Ia) θ̈ + m g c sin θ + b θ̇, by recursive Newton–Euler; the
/// articulated q̈ and M's agree, and take τ back to the state's q̈.
#[test]
fn inverse_dynamics_includes_the_losses_and_the_rotor() {
    let p = GearedPendulum {
        m: 1.2,
        j: 0.03,
        c: 0.4,
        g: 9.81,
        b: 0.35,
        ia: 0.25,
    };
    let one = |x: f64| SVector::<f64, 1>::from([x]);
    let (q, v, a) = (one(0.7), one(-1.3), one(2.1));
    let inertia = p.j + p.m * p.c * p.c + p.ia;
    let want = inertia * a[0] + p.m * p.g * p.c * q[0].sin() + p.b * v[0];
    let tau = p.inverse_dynamics(&q, &v, &a, 0.0)[0];
    assert!((tau - want).abs() < 1e-12, "τ = {tau}, not {want}");
    assert!((p.mass_matrix(&q, 0.0)[(0, 0)] - inertia).abs() < 1e-14);
    let gravity = p.gravity_torques(&q, 0.0).unwrap()[0];
    assert!((gravity - p.m * p.g * p.c * q[0].sin()).abs() < 1e-12);
    let dynamics = Dynamics::new(&p);
    let emitted = dynamics.acceleration(0.0, &q, &v).unwrap();
    let through_m = dynamics.acceleration_from_mass_matrix(0.0, &q, &v).unwrap();
    let free = -(p.m * p.g * p.c * q[0].sin() + p.b * v[0]) / inertia;
    assert!((emitted[0] - free).abs() < 1e-12 && (through_m[0] - free).abs() < 1e-12);
    let (accel, _) = p.forward_dynamics(&q, &v, &one(tau), 0.0).unwrap();
    assert!(
        (accel[0] - a[0]).abs() < 1e-12,
        "q̈ = {}, not {}",
        accel[0],
        a[0]
    );
}

/// A damping computed from the parameters is checked before a run.
#[test]
fn negative_damping_from_the_parameters_is_refused() {
    let p = DampedPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
        b: -0.2,
    };
    let err = Simulation::new(&p).run([0.1], [0.0], 0.0..1.0).unwrap_err();
    match err.error {
        Error::NonPhysicalParameter {
            body, entry, value, ..
        } => {
            assert_eq!((body, entry, value), ("theta", "damping", -0.2));
        }
        other => panic!("expected NonPhysicalParameter, got {other:?}"),
    }
}

/// The Panda's file states damping alone (0.003 at each arm joint, 0.3 at
/// each finger, the second mimicking the first).
#[derive(Lagrangian)]
#[lagrange(urdf("robots/panda.urdf", dynamics = read), gravity = [0, 0, -9.81])]
struct PandaRead {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/panda.urdf", dynamics = ignore), gravity = [0, 0, -9.81])]
struct PandaIgnored {}

/// `dynamics = read` adds −b q̇ to Q, and nothing to M or h: the finger's
/// coordinate takes both fingers' 0.3 (the second slides at q̇).
#[test]
fn urdf_dynamics_read_adds_the_files_damping() {
    let (read, ignored) = (PandaRead {}, PandaIgnored {});
    let q = SVector::<f64, 8>::from_fn(|i, _| 0.1 * i as f64 - 0.3);
    let v = SVector::<f64, 8>::from_fn(|i, _| 0.7 - 0.2 * i as f64);
    let b = [0.003, 0.003, 0.003, 0.003, 0.003, 0.003, 0.003, 0.6];
    let gained = read.generalized_forces(&q, &v, 0.0) - ignored.generalized_forces(&q, &v, 0.0);
    for i in 0..8 {
        assert!(
            (gained[i] + b[i] * v[i]).abs() < 1e-15,
            "Q[{i}] gained {}",
            gained[i]
        );
    }
    assert_eq!(read.mass_matrix(&q, 0.0), ignored.mass_matrix(&q, 0.0));
    assert_eq!(read.bias(&q, &v, 0.0), ignored.bias(&q, &v, 0.0));
}
