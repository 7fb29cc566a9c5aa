//! Event-driven contact runs (`Simulation::run_contacts`) on the catalog's
//! contact scenes, the Rust side of the MuJoCo comparison
//! (`peer/mujoco/contact_scenes.py`, BENCHMARKS.md "Contact beside MuJoCo"):
//! a ball bouncing to rest, a sphere thrown sliding (no spin, and with
//! backspin) that rolls, a block sliding obliquely to a stop, a pendulum
//! against a stop; and a box tossed onto the floor on its four corners.
//! Each scene runs event by event at the tolerance the tests use (Dop853
//! 1e-13) and at looser ones, and by Moreau–Jean's time stepping at steps
//! of 1e-2 to 1e-4 s; before timing, a table of each run's errors
//! against the closed forms and its own time per simulated second goes to
//! stderr, so that "error vs time per simulated second" has both sides.
//!
//!     cargo bench -p lagrange-bench --bench contact
//!
//! The runs record only their final state (`Record::Final`), as the MuJoCo
//! side times `mj_step` without recording; the error pass records every step
//! to read the largest penetration.

#[allow(dead_code)]
#[path = "../../examples/catalog/contact.rs"]
mod contact;

use contact::{
    BALL_FRICTION, BALL_RESTITUTION, BLOCK_FRICTION, Ball, STOP_RESTITUTION, SlidingBlock,
    StoppedPendulum, TossedBox,
};
use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::error::Failure;
use lagrange::prelude::*;
use lagrange::{
    ChangeKind, Compliant, ContactRun, ContactSettings, Contacts, Dop853, MoreauJean, Radau5,
};
use std::hint::black_box;
use std::time::Instant;

const G: f64 = 9.81;
const BALL: Ball = Ball {
    m: 0.3,
    r: 0.1,
    g: G,
};
const BLOCK: SlidingBlock = SlidingBlock {
    m: 1.5,
    a: 0.2,
    g: G,
};
const PENDULUM: StoppedPendulum = StoppedPendulum {
    m: 0.7,
    l: 1.3,
    g: G,
};

const BOX: TossedBox = TossedBox {
    m: 1.0,
    a: 0.4,
    b: 0.2,
    g: G,
};

/// How a scene is run: event by event with Dop853 at a tolerance, or by
/// Moreau–Jean's time stepping with a step.
#[derive(Clone, Copy, Debug)]
enum Scheme {
    Events(f64),
    Stepping(f64),
    /// Compliant contacts of stiffness k, integrated by Dop853 (tol 1e-9)
    /// or, when `stiff`, Radau5 (tol 1e-8).
    Compliant {
        k: f64,
        stiff: bool,
    },
}

impl Scheme {
    fn label(self) -> String {
        match self {
            Scheme::Events(tol) => format!("dop853 tol {tol:.0e}"),
            Scheme::Stepping(h) => format!("moreau-jean h {h:.0e}"),
            Scheme::Compliant { k, stiff: false } => format!("compliant k {k:.0e} dop853"),
            Scheme::Compliant { k, stiff: true } => format!("compliant k {k:.0e} radau5"),
        }
    }
}

/// The schemes: the event-driven run at the tests' tolerance (1e-13) and
/// looser; Moreau–Jean at steps from 1e-2 to 1e-4 s; compliant contacts
/// from 1e3 to 1e7 N/m, explicit and implicit.
const SCHEMES: [Scheme; 14] = [
    Scheme::Events(1e-13),
    Scheme::Events(1e-9),
    Scheme::Events(1e-6),
    Scheme::Stepping(1e-2),
    Scheme::Stepping(1e-3),
    Scheme::Stepping(1e-4),
    Scheme::Compliant {
        k: 1e3,
        stiff: false,
    },
    Scheme::Compliant {
        k: 1e5,
        stiff: false,
    },
    Scheme::Compliant {
        k: 1e7,
        stiff: false,
    },
    Scheme::Compliant {
        k: 1e3,
        stiff: true,
    },
    Scheme::Compliant {
        k: 1e4,
        stiff: true,
    },
    Scheme::Compliant {
        k: 1e5,
        stiff: true,
    },
    Scheme::Compliant {
        k: 1e6,
        stiff: true,
    },
    Scheme::Compliant {
        k: 1e7,
        stiff: true,
    },
];

/// Runs `system` from (q0, v0) over [0, end] by `scheme`, recording
/// `record`; a run that fails hands back what it computed, its error on
/// stderr (the compliant friction is stiff once it holds, which an explicit
/// method reports).
fn run<S: Contacts<f64, N>, const N: usize>(
    system: &S,
    (scheme, record): (Scheme, Record),
    (q0, v0): ([f64; N], [f64; N]),
    end: f64,
) -> ContactRun<f64, N> {
    let outcome = attempt(system, (scheme, record), (q0, v0), end);
    outcome.unwrap_or_else(|failure| {
        if record == Record::Steps {
            eprintln!("  ({}: {})", scheme.label(), failure.error);
        }
        *failure.partial
    })
}

fn attempt<S: Contacts<f64, N>, const N: usize>(
    system: &S,
    (scheme, record): (Scheme, Record),
    (q0, v0): ([f64; N], [f64; N]),
    end: f64,
) -> Result<ContactRun<f64, N>, Failure<ContactRun<f64, N>>> {
    let compliant = |k| Compliant::stiffness(k);
    match scheme {
        Scheme::Compliant { k, stiff: false } => Simulation::new(system)
            .integrator(Dop853::tol(1e-9).record(record))
            .compliant_contacts(compliant(k))
            .run_contacts(q0, v0, 0.0..end),
        Scheme::Compliant { k, stiff: true } => Simulation::new(system)
            .integrator(Radau5::tol(1e-8).record(record))
            .compliant_contacts(compliant(k))
            .run_contacts(q0, v0, 0.0..end),
        Scheme::Events(tol) => Simulation::new(system)
            .integrator(Dop853::tol(tol).record(record))
            .contact_settings(settings())
            .run_contacts(q0, v0, 0.0..end),
        Scheme::Stepping(h) => Simulation::new(system)
            .integrator(MoreauJean::step(h).record(record))
            .contact_settings(settings())
            .run_contacts(q0, v0, 0.0..end),
    }
}

/// Complete elliptic integral of the first kind by the AGM (as the catalog's
/// `elliptic_k`, which lives in the catalog's `mod.rs`).
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..60 {
        let (an, bn) = ((a + b) / 2.0, (a * b).sqrt());
        a = an;
        b = bn;
        if (a - b).abs() < 1e-17 {
            break;
        }
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The tests' settings: rest when an impact would leave below 1e-7 m/s.
fn settings() -> ContactSettings {
    ContactSettings {
        rest_speed: 1e-7,
        ..ContactSettings::default()
    }
}

fn times<const N: usize>(run: &ContactRun<f64, N>, kind: fn(&ChangeKind<f64>) -> bool) -> Vec<f64> {
    (run.changes.iter())
        .filter(|c| kind(&c.kind))
        .map(|c| c.t)
        .collect()
}

/// A prepared run: runs the scene and returns its errors against the closed
/// forms (name, value).
type Runner = Box<dyn Fn() -> Vec<(&'static str, f64)>>;

/// One scene: its name, span, a run at a tolerance, and the errors of a run
/// against the closed forms (name, value).
struct Scene {
    name: &'static str,
    span: f64,
    run: fn(Scheme, Record) -> Runner,
}

/// Dropped from h₀ = 0.5 with e = 0.5: impacts at t₁(1 + 2e + … + 2e^(k−1)),
/// the k-th rebound to e^(2k) h₀, at rest at t₁(1 + e)/(1 − e).
fn ball(scheme: Scheme, record: Record) -> Runner {
    Box::new(move || {
        let (h0, e) = (0.5f64, BALL_RESTITUTION);
        let run = run(
            &BALL,
            (scheme, record),
            ([0.0, h0 + BALL.r, 0.0], [0.0; 3]),
            1.5,
        );
        let t1 = (2.0 * h0 / G).sqrt();
        // A compliant contact's touch is a closing, not an impact.
        let impacts = times(&run, |k| {
            matches!(k, ChangeKind::Impact { .. } | ChangeKind::Closes)
        });
        let (mut exact, mut time_error) = (t1, 0.0f64);
        for (k, t) in impacts.iter().take(5).enumerate() {
            time_error = time_error.max((t - exact).abs());
            exact += 2.0 * t1 * e.powi(k as i32 + 1);
        }
        // The k-th rebound's apex from the flight between impacts k and k+1.
        let height_error = (impacts.windows(2).take(3).enumerate())
            .map(|(k, w)| (G / 8.0 * (w[1] - w[0]).powi(2) - e.powi(2 * k as i32 + 2) * h0).abs())
            .fold(0.0, f64::max);
        // The event-driven run says where the bounces accumulate; the time
        // stepper's ball rests at its last impact or closing.
        let rest = run
            .changes
            .iter()
            .find_map(|c| match c.kind {
                ChangeKind::Rests { accumulation, .. } => Some(accumulation),
                _ => None,
            })
            .or(run.changes.last().map(|c| c.t));
        let depth = (run.trajectory.positions().iter())
            .map(|q| BALL.r - q[1])
            .fold(0.0, f64::max);
        vec![
            ("impact times (first 5)", time_error),
            ("bounce heights (first 3)", height_error),
            (
                "rest time",
                (rest.unwrap_or(f64::NAN) - t1 * (1.0 + e) / (1.0 - e)).abs(),
            ),
            ("penetration", depth),
        ]
    })
}

/// Thrown at v₀ = 2 m/s with spin ω₀ (backspin for ω₀ > 0): slips until
/// t = 2(v₀ + rω₀)/(7μg), then rolls at (5v₀ − 2rω₀)/7.
fn sphere(spin: f64) -> impl Fn(Scheme, Record) -> Runner {
    move |scheme, record| {
        Box::new(move || {
            let (v0, r, mu) = (2.0, BALL.r, BALL_FRICTION);
            let state = ([0.0, r, 0.0], [v0, 0.0, -spin]);
            let run = run(&BALL, (scheme, record), state, 1.5);
            let sticks = times(&run, |k| matches!(k, ChangeKind::Sticks));
            let (_, v) = run.trajectory.final_state();
            let depth = (run.trajectory.positions().iter())
                .map(|q| r - q[1])
                .fold(0.0, f64::max);
            vec![
                (
                    "roll time",
                    (sticks.first().copied().unwrap_or(f64::NAN)
                        - 2.0 * (v0 + r * spin) / (7.0 * mu * G))
                        .abs(),
                ),
                (
                    "roll speed",
                    (v[0] - (5.0 * v0 - 2.0 * r * spin) / 7.0).abs(),
                ),
                ("penetration", depth),
            ]
        })
    }
}

/// Pushed at (3, 4) m/s: stops at |v₀|/(μg) after |v₀|²/(2μg), straight.
fn block(scheme: Scheme, record: Record) -> Runner {
    Box::new(move || {
        let mu = BLOCK_FRICTION;
        let run = run(&BLOCK, (scheme, record), ([0.0; 3], [3.0, 4.0, 0.0]), 1.6);
        let sticks = times(&run, |k| matches!(k, ChangeKind::Sticks));
        let (q, _) = run.trajectory.final_state();
        let depth = (run.trajectory.positions().iter())
            .map(|q| -q[2])
            .fold(0.0, f64::max);
        vec![
            (
                "stop time",
                (sticks.first().copied().unwrap_or(f64::NAN) - 5.0 / (mu * G)).abs(),
            ),
            (
                "stop distance",
                (q.xy().norm() - 25.0 / (2.0 * mu * G)).abs(),
            ),
            ("off the line", (0.8 * q[0] - 0.6 * q[1]).abs()),
            ("penetration", depth),
        ]
    })
}

/// Released at θ₀ = 1.2 against θ ≥ 0 with e = 0.6: impacts at T(θ₀)/4 and
/// T(θ₀)/4 + T(θ₁)/2, 1 − cos θ₁ = e²(1 − cos θ₀).
fn pendulum(scheme: Scheme, record: Record) -> Runner {
    Box::new(move || {
        let p = PENDULUM;
        let (th0, e) = (1.2f64, STOP_RESTITUTION);
        let run = run(&p, (scheme, record), ([th0], [0.0]), 3.0);
        let period = |a: f64| 4.0 * (p.l / p.g).sqrt() * elliptic_k((a / 2.0).sin());
        let th1 = (1.0 - e * e * (1.0 - th0.cos())).acos();
        let first = period(th0) / 4.0;
        let exact = [first, first + period(th1) / 2.0];
        let impacts = times(&run, |k| {
            matches!(k, ChangeKind::Impact { .. } | ChangeKind::Closes)
        });
        let error = (0..2)
            .map(|k| (impacts.get(k).copied().unwrap_or(f64::NAN) - exact[k]).abs())
            .fold(0.0, f64::max);
        let depth = (run.trajectory.positions().iter())
            .map(|q| -q[0])
            .fold(0.0, f64::max);
        vec![("impact times (first 2)", error), ("penetration", depth)]
    })
}

/// Tossed at (1.5, −6) m/s from 0.5 m, turning at 1 rad/s: it lands on a
/// corner, rocks and settles flat. No closed form: the errors are how far
/// from flat and at rest it ends (θ off a quarter turn, the centre off its
/// resting height, the final speed) and how deep a corner sank; an
/// event-driven run that cannot finish reports the time it reached as NaN
/// errors and that time.
fn tossed_box(scheme: Scheme, record: Record) -> Runner {
    Box::new(move || {
        let state = ([0.0, 0.5, 0.7], [1.5, 1.0, -6.0]);
        let run = run(&BOX, (scheme, record), state, 3.0);
        let reached = *run.trajectory.times().last().unwrap();
        let (q, v) = run.trajectory.final_state();
        let quarter = std::f64::consts::FRAC_PI_2;
        let turns = (q[2] / quarter).round();
        let height = if turns as i64 % 2 == 0 { BOX.b } else { BOX.a } / 2.0;
        let (a, b) = (BOX.a / 2.0, BOX.b / 2.0);
        let depth = (run.trajectory.positions().iter())
            .flat_map(|q| {
                let (s, c) = q[2].sin_cos();
                [(a, b), (-a, b), (-a, -b), (a, -b)].map(|(x, z)| x * s - z * c - q[1])
            })
            .fold(0.0, f64::max);
        let finished = |x: f64| if reached < 3.0 { f64::NAN } else { x };
        vec![
            ("off flat (rad)", finished((q[2] - turns * quarter).abs())),
            ("off its height", finished((q[1] - height).abs())),
            ("speed left", finished(v.norm())),
            ("penetration", depth),
            ("time reached", reached),
        ]
    })
}

fn scenes() -> Vec<Scene> {
    vec![
        Scene {
            name: "ball",
            span: 1.5,
            run: ball,
        },
        Scene {
            name: "sphere_slide",
            span: 1.5,
            run: |scheme, record| sphere(0.0)(scheme, record),
        },
        Scene {
            name: "sphere_backspin",
            span: 1.5,
            run: |scheme, record| sphere(80.0)(scheme, record),
        },
        Scene {
            name: "block",
            span: 1.6,
            run: block,
        },
        Scene {
            name: "pendulum",
            span: 3.0,
            run: pendulum,
        },
        Scene {
            name: "box",
            span: 3.0,
            run: tossed_box,
        },
    ]
}

/// The closed-form errors of every scene at every tolerance, and each run's
/// time per simulated second (median of 7 batches of ≥ 50 ms, final state
/// recorded only), as a markdown table on stderr.
fn report() {
    eprintln!("\n| scene | scheme | quantity | error | µs per run | µs per simulated s |");
    eprintln!("|---|---|---|---|---|---|");
    for scene in scenes() {
        for scheme in SCHEMES {
            let errors = (scene.run)(scheme, Record::Steps)();
            let timed = (scene.run)(scheme, Record::Final);
            let mut batches = Vec::new();
            for _ in 0..7 {
                let (start, mut n) = (Instant::now(), 0u32);
                while start.elapsed().as_secs_f64() < 0.05 {
                    black_box(timed());
                    n += 1;
                }
                batches.push(start.elapsed().as_secs_f64() / f64::from(n));
            }
            batches.sort_by(f64::total_cmp);
            let per_run = batches[3] * 1e6;
            for (quantity, error) in errors {
                eprintln!(
                    "| {} | {} | {quantity} | {error:.1e} | {per_run:.1} | {:.1} |",
                    scene.name,
                    scheme.label(),
                    per_run / scene.span
                );
            }
        }
    }
    eprintln!();
}

fn bench(c: &mut Criterion) {
    report();
    for scene in scenes() {
        let mut group = c.benchmark_group(format!("contact_{}_{}s", scene.name, scene.span));
        for scheme in SCHEMES {
            let run = (scene.run)(scheme, Record::Final);
            group.bench_function(scheme.label(), |b| b.iter(|| black_box(run())));
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
