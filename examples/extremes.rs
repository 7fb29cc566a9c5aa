//! Stability at the extremes, the long studies: too slow for a debug test, so they
//! run here in release mode and print markdown tables (recorded in
//! `docs/extremes.md`).
//!
//! 1. 10⁶ steps of a pendulum: symplectic Störmer–Verlet and Gauss (midpoint,
//!    s = 2) keep the energy error bounded, RK4's grows linearly.
//! 2. A spring pendulum with k/m = 10⁸: Radau5 against the explicit methods.
//! 3. The Cartesian pendulum and the rolling sphere over 10⁴ periods with each
//!    drift control: constraint residuals, energy drift, cost.
//!
//!     cargo run --release --example extremes

mod catalog;

use std::time::{Duration, Instant};

use catalog::Pendulum;
use catalog::constrained::{CartesianSphericalPendulum, RollingSphere};
use catalog::extremes::SpringPendulum;
use lagrange::ode::{Integrator, SecondOrder};
use lagrange::prelude::*;
use lagrange::{Dop853, Dynamics, Gauss, Radau5, Stats, StormerVerlet};

fn main() {
    long_horizon();
    stiff_spring();
    constrained_long_runs();
}

/// Adds the work of one chunk of a run to the running total.
fn add(total: &mut Stats, s: &Stats) {
    total.accepted += s.accepted;
    total.rejected += s.rejected;
    total.evaluations += s.evaluations;
    total.jacobians += s.jacobians;
    total.factorizations += s.factorizations;
    total.wall_time += s.wall_time;
}

/// Least-squares slope of log10(y) against log10(x): the growth exponent.
fn loglog_slope(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .map(|&(x, y)| (x.log10(), y.log10()))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

const DECADES: [usize; 5] = [100, 1_000, 10_000, 100_000, 1_000_000];

/// The largest relative energy error within the first 10², …, 10⁶ steps of a
/// fixed-step method. The run is cut into chunks (a restart of a one-step method
/// at a step boundary changes nothing but the rounding of t) so that no more than
/// 10⁵ steps of dense output are held at once.
fn energy_errors<I: Integrator>(method: I, h: f64) -> (Vec<f64>, Stats) {
    let sys = Pendulum::<f64> {
        m: 1.0,
        l: 1.0,
        g: 1.0,
    };
    let dynamics = Dynamics::new(&sys);
    let (mut q, mut v) = (Vector1::new(1.0), Vector1::new(0.0));
    let e0 = sys.integral(&q, &v, 0.0);
    let mut bounds = vec![0usize, 100, 1_000, 10_000];
    bounds.extend((1..=10).map(|k| k * 100_000));
    let (mut worst, mut out, mut total) = (0.0f64, Vec::new(), Stats::default());
    for w in bounds.windows(2) {
        let (t0, t1) = (w[0] as f64 * h, w[1] as f64 * h);
        let traj = method.integrate(&dynamics, t0, t1, q, v).unwrap();
        worst = traj
            .integrals()
            .iter()
            .fold(worst, |m, e| m.max(((e - e0) / e0).abs()));
        add(&mut total, traj.stats());
        (q, v) = traj.final_state();
        if DECADES.contains(&w[1]) {
            out.push(worst);
        }
    }
    (out, total)
}

fn long_horizon() {
    let h = 0.1;
    println!("## 1. Pendulum, 10⁶ steps of h = {h} (ω₀ = 1, θ₀ = 1 rad, ~7 500 periods)\n");
    println!(
        "max |E − E₀|/|E₀| over the first n steps; growth = log-log slope over 10³..10⁶ steps.\n"
    );
    println!("| method | 10² | 10³ | 10⁴ | 10⁵ | 10⁶ | growth | evaluations | wall |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let rows: [(&str, (Vec<f64>, Stats)); 4] = [
        ("Störmer–Verlet", energy_errors(StormerVerlet::step(h), h)),
        (
            "Gauss midpoint (s = 1)",
            energy_errors(Gauss::midpoint(h), h),
        ),
        ("Gauss s = 2", energy_errors(Gauss::step(h), h)),
        ("RK4", energy_errors(Rk4::step(h), h)),
    ];
    for (name, (errs, stats)) in rows {
        let pts: Vec<(f64, f64)> = DECADES[1..]
            .iter()
            .zip(&errs[1..])
            .map(|(&n, &e)| (n as f64, e))
            .collect();
        let cells: Vec<String> = errs.iter().map(|e| format!("{e:.2e}")).collect();
        println!(
            "| {name} | {} | {:.2} | {} | {:.2} s |",
            cells.join(" | "),
            loglog_slope(&pts),
            stats.evaluations,
            stats.wall_time.as_secs_f64()
        );
    }
    println!();
}

fn stiff_spring() {
    let sys = SpringPendulum {
        m: 1.0,
        k: 1e8,
        l0: 1.0,
        g: 9.81,
    };
    let th0 = 0.5f64;
    let q0 = [sys.l0 + sys.m * sys.g * th0.cos() / sys.k, th0];
    let t_end = 10.0;
    let reference = rigid_reference(&sys, th0, t_end);
    stiff_header(th0, t_end);
    // The pivot ratio of M = diag(m, m r²) is no singularity measure in mixed units,
    // and rejected trial stages of the explicit methods reach r ~ 10⁶ (see the
    // notes in docs/extremes.md): the check is switched off, M is regular for r ≠ 0.
    let sim = Simulation::new(&sys).singular_tolerance(0.0);
    macro_rules! timed {
        ($name:expr, $method:expr) => {
            timed!($name, $method, sim.clone())
        };
        ($name:expr, $method:expr, $sim:expr) => {{
            let start = Instant::now();
            let r = $sim.integrator($method).run(q0, [0.0; 2], 0.0..t_end);
            stiff_row($name, r, start.elapsed(), reference);
        }};
    }
    timed!("Radau5 tol 1e-6", Radau5::tol(1e-6));
    timed!("Radau5 tol 1e-8", Radau5::tol(1e-8));
    timed!("Radau5 tol 1e-10", Radau5::tol(1e-10));
    timed!(
        "Dopri5 tol 1e-6, cap 10⁴ steps",
        Dopri5::tol(1e-6).max_steps(10_000)
    );
    timed!(
        "Dopri5 tol 1e-6, no cap",
        Dopri5::tol(1e-6).max_steps(usize::MAX)
    );
    timed!(
        "Dopri5 tol 1e-3, no cap",
        Dopri5::tol(1e-3).max_steps(usize::MAX)
    );
    timed!(
        "Dop853 tol 1e-6, cap 10⁴ steps",
        Dop853::tol(1e-6).max_steps(10_000)
    );
    timed!(
        "Dop853 tol 1e-6, no cap",
        Dop853::tol(1e-6).max_steps(usize::MAX)
    );
    // With the default singular tolerance 1e-12 a rejected trial stage stops the run.
    let default_check = Simulation::new(&sys);
    timed!(
        "Dopri5 tol 1e-6, no cap, default singular tolerance",
        Dopri5::tol(1e-6).max_steps(usize::MAX),
        default_check.clone()
    );
    timed!(
        "Dop853 tol 1e-6, no cap, default singular tolerance",
        Dop853::tol(1e-6).max_steps(usize::MAX),
        default_check.clone()
    );
    timed!("RK4 h = 10⁻³ (h ω_r = 10)", Rk4::step(1e-3));
    timed!("RK4 h = 2·10⁻⁴ (h ω_r = 2)", Rk4::step(2e-4));
    println!();
}

/// θ at `t_end` of the rigid pendulum of length l₀ the stiff spring follows.
fn rigid_reference(sys: &SpringPendulum, th0: f64, t_end: f64) -> f64 {
    let rigid = Pendulum::<f64> {
        m: sys.m,
        l: sys.l0,
        g: sys.g,
    };
    Simulation::new(&rigid)
        .integrator(lagrange::Dop853::tol(1e-13))
        .run([th0], [0.0], 0.0..t_end)
        .unwrap()
        .final_state()
        .0[0]
}

fn stiff_header(th0: f64, t_end: f64) {
    println!(
        "## 2. Spring pendulum, k/m = 10⁸ (ω_r = 10⁴ rad/s against ω ≈ 3.1 rad/s), \
         θ₀ = {th0}, 0..{t_end} s\n"
    );
    println!(
        "θ error: against a rigid pendulum of length l₀ (the spring stretches by ~m g/k = 10⁻⁷).\n"
    );
    println!(
        "| method | outcome | accepted | rejected | evaluations | Jacobians | LU | θ error | energy drift | wall |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
}

/// One row of the stiff-spring table: the work, and when the run completes the
/// θ error against `reference` and the energy drift.
fn stiff_row(
    name: &str,
    r: Result<Trajectory<f64, 2>, Failure<Trajectory<f64, 2>>>,
    wall: Duration,
    reference: f64,
) {
    match r {
        Ok(traj) => {
            let s = traj.stats();
            println!(
                "| {name} | completes | {} | {} | {} | {} | {} | {:.1e} | {:.1e} | {:.1} ms |",
                s.accepted,
                s.rejected,
                s.evaluations,
                s.jacobians,
                s.factorizations,
                (traj.final_state().0[1] - reference).abs(),
                traj.integral_drift(),
                wall.as_secs_f64() * 1e3
            )
        }
        // The steps accepted before the failure come back with it.
        Err(f) => {
            let s = f.partial.stats();
            println!(
                "| {name} | {} | {} | {} | {} | {} | {} | | | {:.1} ms |",
                short(&f.error),
                s.accepted,
                s.rejected,
                s.evaluations,
                s.jacobians,
                s.factorizations,
                wall.as_secs_f64() * 1e3
            )
        }
    }
}

/// The variant and where it stopped, without the state dump.
fn short(e: &Error) -> String {
    match e {
        Error::TooManySteps { t, max_steps, .. } => {
            format!("TooManySteps ({max_steps}) at t = {t:.3}")
        }
        Error::StepSizeUnderflow { t, h } => {
            format!("StepSizeUnderflow (h = {h:.1e}) at t = {t:.3}")
        }
        Error::NonFiniteState { t, .. } => format!("NonFiniteState at t = {t:.3}"),
        Error::SingularMassMatrix { t, .. } => format!("SingularMassMatrix at t = {t:.3}"),
        other => other.to_string(),
    }
}

/// Residuals and energy of one long constrained run, at the checkpoints.
struct LongRun {
    /// (periods, |Φ|∞ at that time, |G q̇ + g|∞ at that time, max energy drift so far)
    checkpoints: Vec<(usize, f64, f64, f64)>,
    max_residuals: [f64; 2],
    stats: Stats,
    error: Option<String>,
}

/// Integrates `dynamics` for 10⁴ periods in chunks of 100 periods (restarting
/// Dopri5 from the last state: the run never holds more than a chunk of dense
/// output) and records the residuals at 10, 100, 1 000 and 10 000 periods.
fn long_constrained<F: SecondOrder<f64, N>, const N: usize>(
    dynamics: &F,
    q0: SVector<f64, N>,
    v0: SVector<f64, N>,
    period: f64,
) -> LongRun {
    let method = Dopri5::tol(1e-10).max_steps(usize::MAX);
    let e0 = dynamics.integral(0.0, &q0, &v0);
    let (mut q, mut v) = (q0, v0);
    let mut run = LongRun {
        checkpoints: Vec::new(),
        max_residuals: [0.0; 2],
        stats: Stats::default(),
        error: None,
    };
    let mut drift = 0.0f64;
    let mut bounds = vec![0usize, 10];
    bounds.extend((1..=100).map(|k| k * 100));
    for w in bounds.windows(2) {
        let (t0, t1) = (w[0] as f64 * period, w[1] as f64 * period);
        let traj = match method.integrate(dynamics, t0, t1, q, v) {
            Ok(traj) => traj,
            Err(f) => {
                run.error = Some(short(&f.error));
                break;
            }
        };
        drift = traj
            .integrals()
            .iter()
            .fold(drift, |m, e| m.max(((e - e0) / e0).abs()));
        let r = traj.max_residuals();
        run.max_residuals = [
            run.max_residuals[0].max(r[0]),
            run.max_residuals[1].max(r[1]),
        ];
        add(&mut run.stats, traj.stats());
        (q, v) = traj.final_state();
        if [10, 100, 1_000, 10_000].contains(&w[1]) {
            let [phi, vel] = *traj.residuals().last().unwrap();
            run.checkpoints.push((w[1], phi, vel, drift));
        }
    }
    run
}

fn print_long_run(system: &str, drift: &str, run: &LongRun) {
    let cell = |k: usize| {
        run.checkpoints
            .get(k)
            .map_or("—".to_string(), |c| format!("{:.1e} / {:.1e}", c.1, c.2))
    };
    // Growth exponent of a residual over the checkpoints (10..10⁴ periods).
    let growth = |i: usize| {
        let pts: Vec<(f64, f64)> = run
            .checkpoints
            .iter()
            .map(|c| (c.0 as f64, if i == 0 { c.1 } else { c.2 }))
            .collect();
        if pts.len() < 2 || pts.iter().any(|p| p.1 <= 0.0) {
            "—".to_string()
        } else {
            format!("{:.2}", loglog_slope(&pts))
        }
    };
    let energy = run
        .checkpoints
        .last()
        .map_or("—".to_string(), |c| format!("{:.1e}", c.3));
    println!(
        "| {system} | {drift} | {} | {} | {} | {} | {:.1e} / {:.1e} | {} / {} | {energy} | {} | {} | {:.2} s |{}",
        cell(0),
        cell(1),
        cell(2),
        cell(3),
        run.max_residuals[0],
        run.max_residuals[1],
        growth(0),
        growth(1),
        run.stats.accepted,
        run.stats.evaluations,
        run.stats.wall_time.as_secs_f64(),
        run.error
            .as_ref()
            .map_or(String::new(), |e| format!(" stopped: {e}"))
    );
}

/// The world-frame angular velocity of a z-x-z rotation.
fn omega_world(q: &[f64], v: &[f64]) -> Vector3<f64> {
    let (psi, theta) = (q[0], q[1]);
    let (psid, thetad, phid) = (v[0], v[1], v[2]);
    Vector3::new(
        thetad * psi.cos() + phid * theta.sin() * psi.sin(),
        thetad * psi.sin() - phid * theta.sin() * psi.cos(),
        psid + phid * theta.cos(),
    )
}

fn constrained_long_runs() {
    let drifts = [
        ("None", Drift::None),
        (
            "Baumgarte α = β = 10",
            Drift::Baumgarte {
                alpha: 10.0,
                beta: 10.0,
            },
        ),
        ("projection (tol 1e-12)", Drift::projection()),
        (
            "projection (tol 1e-14)",
            Drift::Projection {
                tol: 1e-14,
                max_iter: 10,
            },
        ),
    ];
    println!("## 3. Constrained long runs, 10⁴ periods, Dopri5 tol 1e-10\n");
    println!(
        "Cells: |Φ|∞ / |G q̇ + g|∞ at the end of 10, 10², 10³, 10⁴ periods; max over the run; \
         growth exponents of both (log-log slope over the checkpoints); max relative energy \
         drift; work.\n"
    );
    println!(
        "| system | drift control | 10 | 10² | 10³ | 10⁴ | max | growth | energy drift | steps | evaluations | wall |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");

    let pendulum = CartesianSphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let th0 = 1.0f64;
    let q0 = Vector3::new(th0.sin(), 0.0, -th0.cos());
    let v0 = Vector3::new(0.0, 1.5, 0.0);
    let period = 2.0 * std::f64::consts::PI * (pendulum.l / pendulum.g).sqrt();
    for (name, drift) in drifts {
        let dynamics = ConstrainedDynamics::<_, f64, 1>::new(&pendulum).drift(drift);
        let run = long_constrained(&dynamics, q0, v0, period);
        print_long_run("Cartesian pendulum", name, &run);
    }

    let (m, a) = (2.0, 0.3);
    let sphere = RollingSphere {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
    };
    let (angles, rates) = ([0.2, 0.9, 0.1], [1.5, -0.7, 4.0]);
    let w = omega_world(&angles, &rates);
    let q0 = SVector::<f64, 6>::from([0.0, 0.0, a, angles[0], angles[1], angles[2]]);
    let v0 = SVector::<f64, 6>::from([a * w[1], -a * w[0], 0.0, rates[0], rates[1], rates[2]]);
    let period = 2.0 * std::f64::consts::PI / w.norm();
    for (name, drift) in drifts {
        let dynamics = ConstrainedDynamics::<_, f64, 3>::new(&sphere).drift(drift);
        let run = long_constrained(&dynamics, q0, v0, period);
        print_long_run("rolling sphere", name, &run);
    }
    println!();
    println!(
        "Pendulum: l = 1, g = 9.81, θ₀ = 1 rad, v₀ = 1.5 m/s across, period unit \
         2π√(l/g) = {:.4} s. Sphere: m = 2, a = 0.3, ω = {:.3} rad/s, period unit 2π/|ω| = {:.4} s.",
        2.0 * std::f64::consts::PI * (pendulum.l / pendulum.g).sqrt(),
        w.norm(),
        period
    );
}
