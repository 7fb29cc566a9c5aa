//! Derived contacts (`contact(...)`, `stop(...)`) against closed forms: a
//! sphere thrown sliding that rolls at 5/7 of its speed, a ball's bounces,
//! a block sliding obliquely to a stop (the isotropic cone keeps its
//! direction), a pendulum against a stop at the times its elliptic-integral
//! period gives.

use crate::catalog::elliptic_k;
use lagrange::prelude::*;
use lagrange::{ChangeKind, ContactRun, ContactSettings, ContactState, Contacts, Dop853};

const G: f64 = 9.81;

/// A solid sphere rolling in the vertical plane (x, z), turning about y.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, z, theta),
    body(ball, mass = m, inertia = [0.4 * m * r * r, 0.4 * m * r * r, 0.4 * m * r * r],
         at = [x, 0, z], rotation = rot_y(theta)),
    gravity = [0, 0, -g],
    contact(ground, on = ball, radius = r, normal = [0, 0, 1], restitution = 0.5, friction = 0.3),
)]
pub(crate) struct Sphere {
    pub(crate) m: f64,
    pub(crate) r: f64,
    pub(crate) g: f64,
}

/// A point mass on the floor.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    point(block, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    contact(floor, on = block, normal = [0, 0, 1], restitution = 0, friction = 0.4),
)]
struct Block {
    m: f64,
    g: f64,
}

/// A pendulum against a wall at the vertical, θ ≥ 0.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    stop(wall, theta >= 0, restitution = 0.6),
)]
struct Stopped {
    m: f64,
    l: f64,
    g: f64,
}

fn settings() -> ContactSettings {
    ContactSettings {
        rest_speed: 1e-7,
        ..ContactSettings::default()
    }
}

fn kinds<const N: usize>(run: &ContactRun<f64, N>, kind: fn(&ChangeKind<f64>) -> bool) -> Vec<f64> {
    run.changes
        .iter()
        .filter(|c| kind(&c.kind))
        .map(|c| c.t)
        .collect()
}

#[test]
fn the_derived_rows_are_the_sphere_s_gap_and_slip() {
    let s = Sphere {
        m: 0.3,
        r: 0.1,
        g: G,
    };
    let laws = s.contact_laws();
    assert_eq!(
        (laws[0].name, laws[0].restitution, laws[0].friction),
        ("ground", 0.5, 0.3)
    );
    let q = Vector3::new(0.2, 0.35, 0.7);
    let v = Vector3::new(1.5, -0.4, 2.0);
    let rows = s.contact_rows(0, &q, &v, 0.0).unwrap();
    assert!((rows.gap - 0.25).abs() < 1e-15);
    assert_eq!(rows.normal, Vector3::new(0.0, 1.0, 0.0));
    assert_eq!(rows.normal_bias, 0.0);
    // Slip along x: ẋ − r ω_y with ω_y = θ̇; none along y in the plane.
    assert!((rows.tangents[0] - Vector3::new(1.0, 0.0, -0.1)).norm() < 1e-15);
    assert_eq!(rows.tangents[1], Vector3::zeros());
    assert!(s.contact_rows(1, &q, &v, 0.0).is_none());
}

/// Thrown without spin at v₀: slides until t = 2v₀/(7μg), then rolls at
/// 5/7 v₀.
#[test]
fn a_derived_sphere_rolls_at_five_sevenths() {
    let s = Sphere {
        m: 0.3,
        r: 0.1,
        g: G,
    };
    let (v0, mu) = (2.0, 0.3);
    let run = Simulation::new(&s)
        .integrator(Dop853::tol(1e-13))
        .contact_settings(settings())
        .run_contacts([0.0, s.r, 0.0], [v0, 0.0, 0.0], 0.0..1.0)
        .unwrap();
    let sticks = kinds(&run, |k| matches!(k, ChangeKind::Sticks));
    let t_roll = 2.0 * v0 / (7.0 * mu * G);
    let (_, v) = run.trajectory.final_state();
    eprintln!(
        "derived sphere: rolls {:.1e} from 2v0/(7μg), at {:.1e} from 5/7 v0",
        (sticks[0] - t_roll).abs(),
        (v[0] - 5.0 / 7.0 * v0).abs()
    );
    assert!((sticks[0] - t_roll).abs() < 1e-9);
    assert!((v[0] - 5.0 / 7.0 * v0).abs() < 1e-9);
    assert_eq!(run.states(1.0), [ContactState::Sticking]);
}

/// Dropped from h₀ = 0.5 with e = 0.5: impacts at t₁ (1 + 2e + … + 2eᵏ),
/// at rest at t₁ (1 + e)/(1 − e).
#[test]
fn a_derived_ball_bounces_to_rest() {
    let s = Sphere {
        m: 0.3,
        r: 0.1,
        g: G,
    };
    let (e, h0) = (0.5f64, 0.5);
    let run = Simulation::new(&s)
        .integrator(Dop853::tol(1e-13))
        .contact_settings(settings())
        .run_contacts([0.0, h0 + s.r, 0.0], [0.0; 3], 0.0..1.5)
        .unwrap();
    let t1 = (2.0 * h0 / G).sqrt();
    let impacts = kinds(&run, |k| matches!(k, ChangeKind::Impact { .. }));
    let mut exact = t1;
    for (k, t) in impacts.iter().enumerate() {
        assert!((t - exact).abs() < 1e-9, "impact {k}: {t} vs {exact}");
        exact += 2.0 * t1 * e.powi(k as i32 + 1);
    }
    let rest = run.changes.iter().find_map(|c| match c.kind {
        ChangeKind::Rests { accumulation, .. } => Some(accumulation),
        _ => None,
    });
    let t_rest = t1 * (1.0 + e) / (1.0 - e);
    eprintln!(
        "derived ball: {} impacts, rest {:.1e} from t1(1+e)/(1−e)",
        impacts.len(),
        (rest.unwrap() - t_rest).abs()
    );
    assert!((rest.unwrap() - t_rest).abs() < 1e-9);
}

/// Pushed obliquely at (3, 4) m/s, the block slides straight (Coulomb's
/// isotropic cone opposes the slip) and stops at |v₀|/(μg) after
/// |v₀|²/(2μg), where it sticks.
#[test]
fn a_derived_block_slides_straight_to_a_stop() {
    let b = Block { m: 1.5, g: G };
    let mu = 0.4;
    let run = Simulation::new(&b)
        .integrator(Dop853::tol(1e-13))
        .run_contacts([0.0; 3], [3.0, 4.0, 0.0], 0.0..2.0)
        .unwrap();
    let sticks = kinds(&run, |k| matches!(k, ChangeKind::Sticks));
    let (t_stop, distance) = (5.0 / (mu * G), 25.0 / (2.0 * mu * G));
    let (q, v) = run.trajectory.final_state();
    eprintln!(
        "derived block: stops {:.1e} from |v0|/(μg), {:.1e} from |v0|²/(2μg)",
        (sticks[0] - t_stop).abs(),
        (q.xy().norm() - distance).abs()
    );
    assert!((sticks[0] - t_stop).abs() < 1e-9);
    assert!((q[0] - 0.6 * distance).abs() < 1e-9 && (q[1] - 0.8 * distance).abs() < 1e-9);
    assert!(v.norm() < 1e-12 && q[2].abs() < 1e-12);
}

/// Released at θ₀ against the wall θ ≥ 0 with e = 0.6: the first impact at
/// a quarter period T(θ₀)/4, the next half a period of the rebound's
/// amplitude θ₁ later, 1 − cos θ₁ = e² (1 − cos θ₀).
#[test]
fn a_pendulum_hits_its_stop_when_the_elliptic_period_says() {
    let p = Stopped {
        m: 0.7,
        l: 1.3,
        g: G,
    };
    let (th0, e) = (1.2f64, 0.6);
    let period = |amplitude: f64| 4.0 * (p.l / p.g).sqrt() * elliptic_k((amplitude / 2.0).sin());
    let run = Simulation::new(&p)
        .integrator(Dop853::tol(1e-13))
        .contact_settings(settings())
        .run_contacts([th0], [0.0], 0.0..3.0)
        .unwrap();
    let impacts = kinds(&run, |k| matches!(k, ChangeKind::Impact { .. }));
    let th1 = (1.0 - e * e * (1.0 - th0.cos())).acos();
    let first = period(th0) / 4.0;
    let second = first + period(th1) / 2.0;
    eprintln!(
        "stop: impacts {:.1e} and {:.1e} from the elliptic periods",
        (impacts[0] - first).abs(),
        (impacts[1] - second).abs()
    );
    assert!(
        (impacts[0] - first).abs() < 1e-9,
        "{} vs {first}",
        impacts[0]
    );
    assert!(
        (impacts[1] - second).abs() < 1e-9,
        "{} vs {second}",
        impacts[1]
    );
    let worst = run
        .trajectory
        .positions()
        .iter()
        .map(|q| -q[0])
        .fold(f64::MIN, f64::max);
    assert!(worst < 1e-12, "past the stop by {worst:e}");
}
