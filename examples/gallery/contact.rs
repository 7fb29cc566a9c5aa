//! Unilateral contacts (`contact(...)`, `stop(...)`), run event by event by
//! `run_contacts`, each against its closed form: a ball bouncing to rest, a
//! ball thrown with backspin that rolls back, a block sliding to a stop, a
//! pendulum against a stop; and a box tossed onto the floor on its four
//! corners, run by Moreau–Jean's time stepping.

use std::cell::OnceCell;

use crate::catalog::contact::{
    BALL_FRICTION, BALL_RESTITUTION, BLOCK_FRICTION, Ball, STOP_RESTITUTION, SlidingBlock,
    StoppedPendulum, TossedBox,
};
use crate::catalog::elliptic_k;
use crate::row::{Row, row};
use lagrange::prelude::*;
use lagrange::{ChangeKind, ContactRun, ContactSettings, Dop853, MoreauJean, Posed};

const G: f64 = 9.81;
const BALL: Ball = Ball {
    m: 0.3,
    r: 0.1,
    g: G,
};

/// The integrator of the contact rows: tight, since the notes compare
/// event times with closed forms.
fn integrator() -> Dop853 {
    // Recorded every 5 ms from the dense output: a free flight is a few
    // steps long, and its recorded steps alone would draw a bounce's
    // parabola as a few straight chords.
    Dop853::tol(1e-12).record(Record::Interval(0.005))
}

/// Rest when an impact would leave below 1e-7 m/s: far below the bounce
/// speeds, so the Zeno accumulation is reached by the series, not cut short.
fn settings() -> ContactSettings {
    ContactSettings {
        rest_speed: 1e-7,
        ..ContactSettings::default()
    }
}

/// A gallery row from a contact run: the row keeps its trajectory (and
/// scene); the note reads the run's changes.
fn contact_row<S, const N: usize>(
    system: &'static str,
    sys: &S,
    span: std::ops::Range<f64>,
    run: impl FnOnce() -> Result<ContactRun<f64, N>, Failure<ContactRun<f64, N>>>,
    note: impl FnOnce(&ContactRun<f64, N>) -> String,
) -> Result<Row, Error>
where
    S: Lagrangian<f64, N> + Posed<f64, N>,
{
    let kept = OnceCell::new();
    row(
        system,
        sys,
        span,
        false,
        || run().map(|r| kept.get_or_init(|| r).trajectory.clone()),
        |_| kept.get().map_or_else(String::new, note),
    )
}

/// The times of the changes of one kind.
fn times<const N: usize>(run: &ContactRun<f64, N>, kind: fn(&ChangeKind<f64>) -> bool) -> Vec<f64> {
    (run.changes.iter())
        .filter(|c| kind(&c.kind))
        .map(|c| c.t)
        .collect()
}

/// Dropped from h₀ = 0.5 m with e = 0.5: the bounces shrink geometrically and
/// accumulate at t₁ (1 + e)/(1 − e), where the ball comes to rest.
pub(crate) fn bouncing_ball(system: &'static str) -> Result<Row, Error> {
    let (h0, e) = (0.5, BALL_RESTITUTION);
    let span = 0.0..1.5;
    contact_row(
        system,
        &BALL,
        span.clone(),
        || {
            Simulation::new(&BALL)
                .integrator(integrator())
                .contact_settings(settings())
                .run_contacts([0.0, h0 + BALL.r, 0.0], [0.0; 3], span.clone())
        },
        |run| {
            let impacts = times(run, |k| matches!(k, ChangeKind::Impact { .. }));
            let rest = run.changes.iter().find_map(|c| match c.kind {
                ChangeKind::Rests { accumulation, .. } => Some(accumulation),
                _ => None,
            });
            let t1 = (2.0 * h0 / G).sqrt();
            let exact = t1 * (1.0 + e) / (1.0 - e);
            match rest {
                Some(t) => format!(
                    "{} impacts, at rest at t = {t:.6} s against t₁(1+e)/(1−e) = {exact:.6} s (error {:.1e})",
                    impacts.len(),
                    (t - exact).abs()
                ),
                None => format!("{} impacts, never at rest", impacts.len()),
            }
        },
    )
}

/// Thrown at v₀ = 2 m/s with backspin ω₀ = 80 rad/s (r ω₀ > 5v₀/2): it
/// slips until t = 2(v₀ + rω₀)/(7μg), then rolls back at (5v₀ − 2rω₀)/7.
pub(crate) fn backspin_ball(system: &'static str) -> Result<Row, Error> {
    let (v0, spin) = (2.0, 80.0);
    let span = 0.0..1.5;
    contact_row(
        system,
        &BALL,
        span.clone(),
        || {
            Simulation::new(&BALL)
                .integrator(integrator())
                .contact_settings(settings())
                .run_contacts([0.0, BALL.r, 0.0], [v0, 0.0, -spin], span.clone())
        },
        |run| {
            let r = BALL.r;
            let (t_roll, v_roll) = (
                2.0 * (v0 + r * spin) / (7.0 * BALL_FRICTION * G),
                (5.0 * v0 - 2.0 * r * spin) / 7.0,
            );
            let sticks = times(run, |k| matches!(k, ChangeKind::Sticks));
            let (_, v) = run.trajectory.final_state();
            match sticks.first() {
                Some(t) => format!(
                    "rolls from t = {t:.6} s (2(v₀+rω₀)/(7μg): error {:.1e}) at {:.6} m/s ((5v₀−2rω₀)/7: error {:.1e})",
                    (t - t_roll).abs(),
                    v[0],
                    (v[0] - v_roll).abs()
                ),
                None => "never rolls".into(),
            }
        },
    )
}

/// Pushed obliquely at (3, 4) m/s: the isotropic cone keeps its direction,
/// and it stops at |v₀|/(μg) after |v₀|²/(2μg).
pub(crate) fn sliding_block(system: &'static str) -> Result<Row, Error> {
    let block = SlidingBlock {
        m: 1.5,
        a: 0.2,
        g: G,
    };
    let span = 0.0..1.6;
    contact_row(
        system,
        &block,
        span.clone(),
        || {
            Simulation::new(&block)
                .integrator(integrator())
                .run_contacts([0.0; 3], [3.0, 4.0, 0.0], span.clone())
        },
        |run| {
            let mu = BLOCK_FRICTION;
            let (t_stop, distance) = (5.0 / (mu * G), 25.0 / (2.0 * mu * G));
            let sticks = times(run, |k| matches!(k, ChangeKind::Sticks));
            let (q, _) = run.trajectory.final_state();
            match sticks.first() {
                Some(t) => format!(
                    "stops at t = {t:.6} s (|v₀|/(μg): error {:.1e}) after {:.6} m (|v₀|²/(2μg): error {:.1e})",
                    (t - t_stop).abs(),
                    q.xy().norm(),
                    (q.xy().norm() - distance).abs()
                ),
                None => "never stops".into(),
            }
        },
    )
}

/// Released at θ₀ = 1.2 against the stop θ ≥ 0: the first impact a quarter
/// of the elliptic period T(θ₀) later, the next half a period of the
/// rebound's amplitude θ₁ after it, 1 − cos θ₁ = e² (1 − cos θ₀).
pub(crate) fn stopped_pendulum(system: &'static str) -> Result<Row, Error> {
    let p = StoppedPendulum {
        m: 0.7,
        l: 1.3,
        g: G,
    };
    let (th0, e) = (1.2f64, STOP_RESTITUTION);
    let span = 0.0..3.0;
    contact_row(
        system,
        &p,
        span.clone(),
        || {
            Simulation::new(&p)
                .integrator(integrator())
                .contact_settings(settings())
                .run_contacts([th0], [0.0], span.clone())
        },
        |run| {
            let period =
                |amplitude: f64| 4.0 * (p.l / p.g).sqrt() * elliptic_k((amplitude / 2.0).sin());
            let th1 = (1.0 - e * e * (1.0 - th0.cos())).acos();
            let first = period(th0) / 4.0;
            let exact = [first, first + period(th1) / 2.0];
            let impacts = times(run, |k| matches!(k, ChangeKind::Impact { .. }));
            let worst = (impacts.iter().zip(exact))
                .map(|(t, x)| (t - x).abs())
                .fold(0.0, f64::max);
            format!(
                "{} impacts; the first two at {:.6} s and {:.6} s, against T(θ₀)/4 and + T(θ₁)/2 (error {worst:.1e})",
                impacts.len(),
                exact[0],
                exact[1]
            )
        },
    )
}

/// Tossed at (1.5, −6) m/s from 0.5 m, turning at 1 rad/s, onto its four
/// corners by Moreau–Jean at h = 1 ms: friction grips the landing corners,
/// it rocks, and it rests flat. The note says where, how deep a corner
/// sank, and where the event-driven run (located events, impacts with the
/// same friction) leaves it.
pub(crate) fn tossed_box(system: &'static str) -> Result<Row, Error> {
    let b = TossedBox {
        m: 1.0,
        a: 0.4,
        b: 0.2,
        g: G,
    };
    let (q0, v0) = ([0.0, 0.5, 0.7], [1.5, 1.0, -6.0]);
    let span = 0.0..3.0;
    contact_row(
        system,
        &b,
        span.clone(),
        || {
            Simulation::new(&b)
                .integrator(MoreauJean::step(1e-3))
                .run_contacts(q0, v0, span.clone())
        },
        |run| {
            let impacts = times(run, |k| matches!(k, ChangeKind::Impact { .. }));
            let settled = run.changes.last().map_or(0.0, |c| c.t);
            let (q, _) = run.trajectory.final_state();
            let events = Simulation::new(&b)
                .integrator(Dop853::tol(1e-12))
                .run_contacts(q0, v0, span.clone());
            let elsewhere = match events {
                Ok(e) => format!("x = {:.3} m", e.trajectory.final_state().0[0]),
                Err(f) => format!("no rest ({})", f.error),
            };
            let (sx, cz) = (b.a / 2.0, b.b / 2.0);
            let deepest = (run.trajectory.positions().iter())
                .flat_map(|q| {
                    let (s, c) = q[2].sin_cos();
                    [(sx, cz), (-sx, cz), (-sx, -cz), (sx, -cz)].map(|(x, z)| q[1] - x * s + z * c)
                })
                .fold(f64::INFINITY, f64::min);
            format!(
                "{} impacts; at rest from t = {settled:.3} s at x = {:.3} m, turned {:.4} quarter turns; \
                 deepest corner {:.2} mm; event-driven: {elsewhere}",
                impacts.len(),
                q[0],
                q[2] / std::f64::consts::FRAC_PI_2,
                -deepest * 1e3
            )
        },
    )
}
