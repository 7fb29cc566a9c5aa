//! Two spheres meeting (`contact(.., against = other, ..)`), frictionless,
//! against the closed forms of a collision: the impact time from the gap
//! and the closing speed, Newton's law along the line of centres, momentum
//! kept, the tangential velocities untouched, and the energy lost
//! ½ μ (1 − e²) u², μ the reduced mass and u the closing speed.

use lagrange::prelude::*;
use lagrange::{ChangeKind, ContactRun, Contacts, Dop853};

/// Two balls on a line, no gravity.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x1, x2),
    point(a, mass = m1, at = [x1, 0, 0]),
    point(b, mass = m2, at = [x2, 0, 0]),
    contact(hit, on = a, radius = r1, against = b, against_radius = r2, restitution = 0.7),
)]
struct Line {
    m1: f64,
    m2: f64,
    r1: f64,
    r2: f64,
}

/// Two equal billiard balls on a table (the plane z = 0), elastic.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(xa, ya, xb, yb),
    point(cue, mass = m, at = [xa, ya, 0]),
    point(object, mass = m, at = [xb, yb, 0]),
    contact(kiss, on = cue, radius = r, against = object, against_radius = r, restitution = 1),
)]
struct Billiards {
    m: f64,
    r: f64,
}

fn impacts<const N: usize>(run: &ContactRun<f64, N>) -> Vec<f64> {
    (run.changes.iter())
        .filter(|c| matches!(c.kind, ChangeKind::Impact { .. }))
        .map(|c| c.t)
        .collect()
}

#[test]
fn the_gap_of_two_spheres_is_their_centres_distance_less_the_radii() {
    let s = Line {
        m1: 1.0,
        m2: 2.0,
        r1: 0.1,
        r2: 0.2,
    };
    let laws = s.contact_laws();
    assert_eq!((laws[0].name, laws[0].restitution), ("hit", 0.7));
    let rows = (s.contact_rows(0, &Vector2::new(1.0, -0.5), &Vector2::new(0.3, 0.1), 0.0))
        .expect("one contact");
    assert!((rows.gap - 1.2).abs() < 1e-15);
    // ∂|x1 − x2|/∂(x1, x2) with x1 > x2: (1, −1); the line of centres does
    // not turn on a line, so no bias.
    assert_eq!(rows.normal, Vector2::new(1.0, -1.0));
    assert_eq!(rows.normal_bias, 0.0);
    // Frictionless: no slip rows.
    assert_eq!(rows.tangents, [Vector2::zeros(); 2]);
}

/// Ball 1 at 0 moving at 3 m/s towards ball 2 at 2 m moving at −1 m/s: they
/// touch when the gap 2 − 0.3 closes at 4 m/s, and leave with Newton's law.
#[test]
fn a_head_on_collision_keeps_momentum_and_obeys_newton() {
    let (m1, m2, e) = (1.0, 2.0, 0.7);
    let s = Line {
        m1,
        m2,
        r1: 0.1,
        r2: 0.2,
    };
    let (u1, u2) = (3.0, -1.0);
    let run = Simulation::new(&s)
        .integrator(Dop853::tol(1e-13))
        .run_contacts([0.0, 2.0], [u1, u2], 0.0..1.0)
        .unwrap();
    let hits = impacts(&run);
    assert_eq!(hits.len(), 1, "{:?}", run.changes);
    let t_hit = (2.0 - 0.3) / (u1 - u2);
    let (q, v) = run.trajectory.final_state();
    let total = m1 * u1 + m2 * u2;
    let v1 = (total - m2 * e * (u1 - u2)) / (m1 + m2);
    let v2 = (total + m1 * e * (u1 - u2)) / (m1 + m2);
    eprintln!(
        "head-on: impact {:.1e} from the gap's closing, speeds {:.1e} and {:.1e} from Newton's law",
        (hits[0] - t_hit).abs(),
        (v[0] - v1).abs(),
        (v[1] - v2).abs()
    );
    assert!((hits[0] - t_hit).abs() < 1e-12);
    assert!((v[0] - v1).abs() < 1e-12 && (v[1] - v2).abs() < 1e-12);
    // Where they are at t = 1: each from the contact point at its new speed.
    let at_hit = [u1 * t_hit, 2.0 + u2 * t_hit];
    assert!((q[0] - (at_hit[0] + v1 * (1.0 - t_hit))).abs() < 1e-12);
    assert!((q[1] - (at_hit[1] + v2 * (1.0 - t_hit))).abs() < 1e-12);
    // Energy lost: ½ μ (1 − e²) u².
    let energy = |v: &[f64]| 0.5 * (m1 * v[0] * v[0] + m2 * v[1] * v[1]);
    let lost = energy(&[u1, u2]) - energy(&[v[0], v[1]]);
    let reduced = m1 * m2 / (m1 + m2);
    let expected = 0.5 * reduced * (1.0 - e * e) * (u1 - u2).powi(2);
    assert!((lost - expected).abs() < 1e-12, "{lost} vs {expected}");
}

/// The cue ball at 2 m/s along x, its line offset by b = 0.03 m from the
/// object ball's centre (radii 0.0286 m): at contact the line of centres n
/// makes sin φ = b / 2r with x; elastic and equal masses, the object ball
/// leaves along n with the cue ball's normal speed, the cue ball keeps its
/// tangential speed, and the two leave at right angles.
#[test]
fn an_oblique_billiard_shot_leaves_at_right_angles() {
    let (m, r, speed, b) = (0.17, 0.0286, 2.0, 0.03);
    let s = Billiards { m, r };
    let run = Simulation::new(&s)
        .integrator(Dop853::tol(1e-13))
        .run_contacts([-0.5, b, 0.0, 0.0], [speed, 0.0, 0.0, 0.0], 0.0..0.5)
        .unwrap();
    let hits = impacts(&run);
    assert_eq!(hits.len(), 1, "{:?}", run.changes);
    // Contact at xa = −√(4r² − b²): the cue ball's centre 2r from the other's.
    let reach = (4.0 * r * r - b * b).sqrt();
    let t_hit = (0.5 - reach) / speed;
    let n = Vector2::new(-reach, b) / (2.0 * r);
    let u = Vector2::new(speed, 0.0);
    let normal_speed = u.dot(&n);
    let cue = u - n * normal_speed;
    let object = n * normal_speed;
    let (_, v) = run.trajectory.final_state();
    let (got_cue, got_object) = (Vector2::new(v[0], v[1]), Vector2::new(v[2], v[3]));
    eprintln!(
        "billiards: impact {:.1e} from the geometry, velocities {:.1e} and {:.1e}, angle {:.1e} from 90°",
        (hits[0] - t_hit).abs(),
        (got_cue - cue).norm(),
        (got_object - object).norm(),
        got_cue.dot(&got_object).abs()
    );
    assert!((hits[0] - t_hit).abs() < 1e-12);
    assert!((got_cue - cue).norm() < 1e-12 && (got_object - object).norm() < 1e-12);
    assert!(got_cue.dot(&got_object).abs() < 1e-12);
    let energy = 0.5 * m * (got_cue.norm_squared() + got_object.norm_squared());
    assert!((energy - 0.5 * m * speed * speed).abs() < 1e-13);
}
