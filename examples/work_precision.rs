//! Work-precision study of the runtime's integrators on six scenes: which method
//! buys a given accuracy at the lowest cost. Writes a markdown table, a CSV file
//! and a log-log PNG per scene, plus `summary.md` (the cheapest run per target
//! accuracy), to `docs/work-precision/` (or the directory given as argument).
//!
//!     cargo run --release --example work_precision [out_dir]
//!
//! Scenes: the simple pendulum at 170° (error after 10 exact periods, from the
//! complete elliptic integral), the Kepler problem at e = 0.6 (exact orbit from
//! Kepler's equation), the spherical pendulum, the double pendulum on a short and
//! a long horizon (with a Lyapunov-time estimate that says where the reference
//! itself stops meaning anything), the rolling sphere (reduced form), and a stiff
//! spring-pendulum (k/m = 1e6, then a sweep of stiffness up to where explicit
//! methods fail). Last, the pendulum in f32 against f64.

mod catalog;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use catalog::constrained::RollingSphereReduced;
use catalog::study::*;
use catalog::{DoublePendulum, Pendulum, SphericalPendulum};
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use lagrange::study::{Method, Row, Study};
use lagrange::{Dop853, Gauss, Radau5, StormerVerlet};

/// Accuracy targets of the guidance table.
const TARGETS: [f64; 3] = [1e-3, 1e-6, 1e-9];

/// Adaptive methods get a budget large enough for the tightest tolerance on the
/// non-stiff scenes; the stiff scenes keep the default (100 000 steps) on purpose.
const BUDGET: usize = 2_000_000;

/// Timed repeats per run (the median is reported) and the time one run's repeats
/// may take: generous, because the machines this runs on are often shared and a
/// median of many is robust to the odd descheduled run.
const REPEATS: usize = 9;
const REPEAT_BUDGET: Duration = Duration::from_millis(300);

/// 10^-from, ..., 10^-to.
fn tolerances(from: i32, to: i32) -> Vec<f64> {
    (from..=to).map(|k| 10f64.powi(-k)).collect()
}

/// h0, h0/2, ..., h0/2^(n-1).
fn halvings(h0: f64, n: i32) -> Vec<f64> {
    (0..n).map(|k| h0 / 2f64.powi(k)).collect()
}

fn rk4(h0: f64, n: i32) -> Sweep {
    Sweep::steps("RK4", &halvings(h0, n), Rk4::step)
}
fn dopri5(from: i32, to: i32) -> Sweep {
    Sweep::tolerances("DOPRI5", &tolerances(from, to), |t| {
        Dopri5::tol(t).max_steps(BUDGET)
    })
}
fn dop853(from: i32, to: i32) -> Sweep {
    Sweep::tolerances("DOP853", &tolerances(from, to), |t| {
        Dop853::tol(t).max_steps(BUDGET)
    })
}
fn radau5(from: i32, to: i32) -> Sweep {
    Sweep::tolerances("RADAU5", &tolerances(from, to), |t| {
        Radau5::tol(t).max_steps(BUDGET)
    })
}
fn gauss(h0: f64, n: i32) -> Sweep {
    Sweep::steps("Gauss (s=2)", &halvings(h0, n), Gauss::step)
}
fn verlet(h0: f64, n: i32) -> Sweep {
    Sweep::steps("Störmer–Verlet", &halvings(h0, n), StormerVerlet::step)
}

/// Prints every row as it is measured.
fn progress(row: &Row) {
    match &row.outcome {
        Ok(m) => println!(
            "    {:<16} {:<12} error {:9.2e}  drift {:9.2e}  {:>9} evals  {:>10.3} ms",
            row.method,
            row.setting.to_string(),
            m.error,
            m.drift.unwrap_or(f64::NAN),
            m.stats.evaluations,
            m.wall_time.as_secs_f64() * 1e3
        ),
        Err(e) => println!(
            "    {:<16} {:<12} failed: {e}",
            row.method,
            row.setting.to_string()
        ),
    }
}

/// One scene's results and what the docs say about it.
struct Scene {
    slug: &'static str,
    title: String,
    study: Study,
    notes: Vec<String>,
}

fn save(out: &Path, scene: &Scene) -> Result<(), Error> {
    let mut md = format!("# {}\n\n", scene.title);
    for note in &scene.notes {
        md += &format!("{note}\n\n");
    }
    md += &format!("![work-precision diagram]({}.png)\n\n", scene.slug);
    md += &scene.study.to_markdown();
    std::fs::write(out.join(format!("{}.md", scene.slug)), md)?;
    scene
        .study
        .write_csv(out.join(format!("{}.csv", scene.slug)))?;
    scene
        .study
        .plot_png(out.join(format!("{}.png", scene.slug)), &scene.title)
}

fn header(title: &str) -> Instant {
    println!("\n== {title}");
    Instant::now()
}

/// The simple pendulum released from rest at 170°, measured at 10¼ exact periods.
///
/// Why not at 10 periods, where the exact state is simply the initial one: that
/// is a turning point (θ̇ = 0), where θ(t) is flat, so a phase error δt shows only
/// as ½ |θ̈| δt² — the error measure then squares every method's phase error
/// and flatters them (symplectic ones most, whose error is almost all phase).
/// A quarter period later the bob passes the bottom at full speed and the phase
/// error shows at first order. The closed form θ(t) = 2 asin(k sn(K − ω0 t | k²))
/// covers any t; at 10 periods it returns θ0 (checked below).
fn pendulum() -> Result<Scene, Error> {
    let title = "Simple pendulum, amplitude 170°, 10¼ periods";
    let started = header(title);
    let sys = Pendulum::<f64> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let theta0 = 170f64.to_radians();
    let period = pendulum_period(sys.l, sys.g, theta0);
    let t_end = 10.25 * period;
    let closure_check = (pendulum_angle(sys.l, sys.g, theta0, 10.0 * period) - theta0).abs();
    println!("  closed form at 10 periods: |θ − θ0| = {closure_check:.1e}");
    // Gauss needs ∂T/∂q, zero here (M = m l² is constant).
    let study = WorkPrecision::new(|m: Method| {
        Simulation::new(&sys)
            .integrator(m)
            .run([theta0], [0.0], 0.0..t_end)
    })
    .exact(move |t| SVector::from([pendulum_angle(sys.l, sys.g, theta0, t)]))
    .sweep(rk4(0.1, 8))
    .sweep(dopri5(3, 12))
    .sweep(dop853(3, 13))
    .sweep(verlet(0.05, 8))
    .sweep(gauss(0.1, 7))
    .sweep(radau5(3, 10))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "pendulum",
        title: title.into(),
        study,
        notes: vec![format!(
            "θ0 = 170° from rest, l = 1, g = 9.81. Exact period T = 4K(sin(θ0/2))/ω0 = \
             {period:.12} s (K by the arithmetic–geometric mean); the error is |θ − θ_exact| \
             at t_end = 10¼ T = {t_end:.6} s, with θ_exact = 2 asin(k sn(K − ω0 t | k²)) \
             (sn by descending Landen; at 10 T it returns θ0 to {closure_check:.0e}). \
             Measuring at a whole number of periods would put t_end at a turning point, \
             where a phase error δt shows only as ½|θ̈|δt² and every method looks twice \
             its order. M = m l² is constant: Störmer–Verlet is symplectic here."
        )],
    })
}

/// The Kepler problem at e = 0.6 over 10 orbits; exact positions from Kepler's
/// equation. t_end is a pericentre passage, where the speed is largest, so the
/// phase error shows fully.
fn kepler() -> Result<Scene, Error> {
    let title = "Kepler problem, e = 0.6, 10 orbits";
    let started = header(title);
    let sys = Kepler { m: 1.0, k: 1.0 };
    let orbit = KeplerOrbit {
        a: 1.0,
        e: 0.6,
        mu: sys.k / sys.m,
    };
    let (q0, v0) = orbit.initial();
    let t_end = 10.0 * orbit.period();
    let study =
        WorkPrecision::new(|m: Method| Simulation::new(&sys).integrator(m).run(q0, v0, 0.0..t_end))
            .exact(move |t| SVector::from(orbit.position(t)))
            .sweep(rk4(0.05, 8))
            .sweep(dopri5(3, 12))
            .sweep(dop853(3, 13))
            .sweep(verlet(0.02, 8))
            .sweep(gauss(0.05, 7))
            .sweep(radau5(3, 10))
            .repeats(REPEATS, REPEAT_BUDGET)
            .on_row(progress)
            .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "kepler",
        title: title.into(),
        study,
        notes: vec![format!(
            "Cartesian (x, y), V = −k/r, m = k = 1, semi-major axis 1, e = 0.6, from \
             pericentre (r = 0.4, v = 2); t_end = 10 orbits = {t_end:.6}. Exact position: \
             E − e sin E = n t by Newton, x = a(cos E − e), y = a√(1−e²) sin E. Constant M: \
             Störmer–Verlet and Gauss are symplectic; the integral is the energy."
        )],
    })
}

/// C1, the spherical pendulum in (θ, φ): no closed form, DOP853 reference.
fn spherical() -> Result<Scene, Error> {
    let title = "Spherical pendulum (θ, φ), 20 s";
    let started = header(title);
    let sys = SphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let study = WorkPrecision::new(|m: Method| {
        Simulation::new(&sys)
            .integrator(m)
            .run([1.0, 0.0], [0.0, 2.0], 0.0..20.0)
    })
    .sweep(rk4(0.05, 8))
    .sweep(dopri5(3, 12))
    .sweep(dop853(3, 13))
    .sweep(gauss(0.05, 7))
    .sweep(radau5(3, 10))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "spherical",
        title: title.into(),
        study,
        notes: vec![
            "m = l = 1, g = 9.81, θ0 = 1, θ̇0 = 0, φ̇0 = 2 (the bob stays away from the \
             poles, where this chart is singular). M(θ) is not constant, so Störmer–Verlet \
             would not be symplectic and is left out; Gauss runs in (q, p) with the \
             hand-written ∂T/∂q = m l² sin θ cos θ φ̇²."
                .into(),
        ],
    })
}

/// max_i |a_i(t) − b_i(t)| on a grid of `n` + 1 times over [0, t_end].
fn divergence(
    a: &Trajectory<f64, 2>,
    b: &Trajectory<f64, 2>,
    t_end: f64,
    n: usize,
) -> Vec<(f64, f64)> {
    (0..=n)
        .map(|k| {
            let t = t_end * k as f64 / n as f64;
            let (qa, _) = a.state_at(t).expect("inside the span");
            let (qb, _) = b.state_at(t).expect("inside the span");
            (t, (qa - qb).amax())
        })
        .collect()
}

/// The double pendulum's predictability: two DOP853 runs at 1e-13 and 1e-14
/// start identical and separate like e^(λt) once their local errors differ.
/// Returns (λ, time at which they differ by 1e-2 rad, the printed table).
fn lyapunov(sys: &DoublePendulum, q0: [f64; 2], t_end: f64) -> Result<(f64, f64, String), Error> {
    let run = |tol| {
        Simulation::new(sys)
            .integrator(Dop853::tol(tol).max_steps(BUDGET))
            .run(q0, [0.0, 0.0], 0.0..t_end)
    };
    let d = divergence(&run(1e-13)?, &run(1e-14)?, t_end, 600);
    // Least squares ln d = c + λ t over the exponential phase: above the
    // round-off floor, below saturation.
    let fit: Vec<(f64, f64)> = d
        .iter()
        .filter(|(_, x)| (1e-11..1e-3).contains(x))
        .map(|&(t, x)| (t, x.ln()))
        .collect();
    let n = fit.len() as f64;
    let (st, sy) = fit.iter().fold((0.0, 0.0), |(a, b), (t, y)| (a + t, b + y));
    let (mt, my) = (st / n, sy / n);
    let (num, den) = fit.iter().fold((0.0, 0.0), |(a, b), (t, y)| {
        (a + (t - mt) * (y - my), b + (t - mt) * (t - mt))
    });
    let lambda = num / den;
    let horizon = d
        .iter()
        .find(|(_, x)| *x > 1e-2)
        .map_or(f64::INFINITY, |p| p.0);
    let mut table =
        String::from("| t | max_i \\|q_i(tol 1e-13) − q_i(tol 1e-14)\\| |\n|---|---|\n");
    for &(t, x) in d.iter().step_by(50) {
        table += &format!("| {t:.0} | {x:.1e} |\n");
    }
    Ok((lambda, horizon, table))
}

/// The double pendulum from rest at (2, 2) rad: chaotic. Two horizons.
fn double_pendulum() -> Result<Vec<Scene>, Error> {
    let sys = DoublePendulum {
        m1: 1.0,
        m2: 1.0,
        l1: 1.0,
        l2: 1.0,
        g: 9.81,
    };
    let q0 = [2.0, 2.0];
    let started = header("Double pendulum: predictability of the reference");
    let (lambda, horizon, table) = lyapunov(&sys, q0, 60.0)?;
    println!(
        "  λ ≈ {lambda:.2} /s (Lyapunov time {:.2} s); the 1e-13 and 1e-14 references differ by 1e-2 at t = {horizon:.1} s ({:.1} s)",
        1.0 / lambda,
        started.elapsed().as_secs_f64()
    );
    let mut scenes = Vec::new();
    for (slug, t_end) in [
        ("double-pendulum-short", 5.0),
        ("double-pendulum-long", 40.0),
    ] {
        let title = format!("Double pendulum from rest at (2, 2) rad, {t_end} s");
        let started = header(&title);
        let study = WorkPrecision::new(|m: Method| {
            Simulation::new(&sys)
                .integrator(m)
                .run(q0, [0.0, 0.0], 0.0..t_end)
        })
        .sweep(rk4(0.02, 8))
        .sweep(dopri5(3, 12))
        .sweep(dop853(3, 13))
        .sweep(gauss(0.02, 7))
        .sweep(radau5(3, 10))
        .repeats(REPEATS, REPEAT_BUDGET)
        .on_row(progress)
        .run()?;
        println!("  done in {:.1} s", started.elapsed().as_secs_f64());
        let mut notes = vec![format!(
            "m1 = m2 = l1 = l2 = 1, g = 9.81, from rest at θ1 = θ2 = 2 rad (energy well \
             above the chaotic threshold). Two DOP853 runs at 1e-13 and 1e-14 separate at \
             the largest Lyapunov exponent λ ≈ {lambda:.2} /s (Lyapunov time {:.2} s): they \
             differ by 1e-2 rad at t ≈ {horizon:.1} s. Beyond that no reference exists and a \
             method's 'error' only measures chaos; every method's trajectory is then one \
             of many equally valid shadows, and only statistics and conserved quantities \
             (the drift column) mean anything.",
            1.0 / lambda
        )];
        if slug.ends_with("long") {
            notes.push(format!(
                "Divergence of the two references (sampled every 5 s):\n\n{table}"
            ));
        }
        scenes.push(Scene {
            slug,
            title,
            study,
            notes,
        });
    }
    Ok(scenes)
}

/// The world-frame angular velocity of a body with Euler angles z-x-z
/// (ψ, θ, φ) and rates v.
fn omega_world(q: &[f64], v: &[f64]) -> [f64; 3] {
    let (psi, theta) = (q[0], q[1]);
    let (psid, thetad, phid) = (v[0], v[1], v[2]);
    [
        thetad * psi.cos() + phid * theta.sin() * psi.sin(),
        thetad * psi.sin() - phid * theta.sin() * psi.cos(),
        psid + phid * theta.cos(),
    ]
}

/// C5 reduced: the rolling sphere, nonholonomic, in independent speeds.
fn rolling_sphere() -> Result<Scene, Error> {
    let title = "Rolling sphere (C5, reduced form), 10 s";
    let started = header(title);
    let (m, a) = (2.0, 0.3);
    let sys = RollingSphereReduced {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
    };
    let (angles, rates) = ([0.2, 0.9, 0.1], [1.5, -0.7, 4.0]);
    let w = omega_world(&angles, &rates);
    let q0 = [0.0, 0.0, angles[0], angles[1], angles[2]];
    let v0 = [a * w[1], -a * w[0], rates[0], rates[1], rates[2]];
    let study = WorkPrecision::new(|m: Method| {
        Simulation::new(&sys)
            .integrator(m)
            .run_reduced(q0, v0, 0.0..10.0)
    })
    .sweep(rk4(0.05, 8))
    .sweep(dopri5(3, 12))
    .sweep(dop853(3, 13))
    .sweep(radau5(3, 10))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "rolling-sphere",
        title: title.into(),
        study,
        notes: vec![
            "RollingSphereReduced (m = 2, a = 0.3, J = 2/5 m a²) by `run_reduced`: Euler \
             angles (0.2, 0.9, 0.1), rates (1.5, −0.7, 4.0), rolling velocity consistent. The \
             error is over all five coordinates (x, y and the Euler angles). The reduced \
             nonholonomic equations have no Hamiltonian form, so the symplectic Gauss \
             method does not apply (it would stop with a typed error)."
                .into(),
        ],
    })
}

/// The stiff spring-pendulum at k/m = 1e6, full sweeps.
fn stiff() -> Result<Scene, Error> {
    let title = "Stiff spring-pendulum, k/m = 1e6, 5 s";
    let started = header(title);
    let sys = SpringPendulum {
        m: 1.0,
        k: 1e6,
        l: 1.0,
        g: 9.81,
    };
    let (q0, v0) = sys.at_rest(1.0);
    // The adaptive methods keep the default budget of 100 000 steps here.
    let study =
        WorkPrecision::new(|m: Method| Simulation::new(&sys).integrator(m).run(q0, v0, 0.0..5.0))
            .sweep(rk4(4e-3, 7))
            .sweep(Sweep::tolerances("DOPRI5", &tolerances(3, 10), Dopri5::tol))
            .sweep(Sweep::tolerances("DOP853", &tolerances(3, 10), Dop853::tol))
            .sweep(verlet(1.6e-3, 6))
            .sweep(gauss(0.02, 7))
            .sweep(Sweep::tolerances("RADAU5", &tolerances(3, 10), Radau5::tol))
            .repeats(REPEATS, REPEAT_BUDGET)
            .on_row(progress)
            .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "stiff-spring-pendulum",
        title: title.into(),
        study,
        notes: vec![
            "A bob (m = 1) on a spring (k = 1e6, rest length 1) under gravity, Cartesian \
             (x, y), released from rest at 1 rad with the spring at its static stretch: the \
             radial mode (ω = 1000 /s) starts almost unexcited and the motion is the slow \
             swing (ω ≈ 3 /s). Explicit methods are held to h ≲ c/ω by stability whatever \
             the tolerance (RK4: c ≈ 2.8, Störmer–Verlet: c = 2); RADAU5 (L-stable) and \
             Gauss (A-stable) are not. The adaptive methods keep the default budget of \
             100 000 steps."
                .into(),
        ],
    })
}

/// One stiffness: a single setting per method against a RADAU5 reference at
/// 1e-12 (DOP853 at 1e-14 would need millions of steps at k/m = 1e10).
fn stiffness_sweep() -> Result<String, Error> {
    let started = header("Stiff spring-pendulum: cost against stiffness");
    let mut md = String::from(
        "| k/m | method | error in q at t_end | RHS evaluations | steps | wall time | outcome |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for k in [1e4, 1e6, 1e8, 1e10] {
        println!("  k/m = {k:e}");
        let sys = SpringPendulum {
            m: 1.0,
            k,
            l: 1.0,
            g: 9.81,
        };
        let (q0, v0) = sys.at_rest(1.0);
        let run = |m: Method| Simulation::new(&sys).integrator(m).run(q0, v0, 0.0..5.0);
        let reference = run(Radau5::tol(1e-12).max_steps(BUDGET).into())?;
        let study = WorkPrecision::new(run)
            .reference(reference)
            .sweep(Sweep::tolerances("DOPRI5", &[1e-6], Dopri5::tol))
            .sweep(Sweep::tolerances("DOP853", &[1e-6], Dop853::tol))
            .sweep(Sweep::steps("RK4", &[1e-3], Rk4::step))
            .sweep(Sweep::steps("Störmer–Verlet", &[1e-3], StormerVerlet::step))
            .sweep(Sweep::steps("Gauss (s=2)", &[1e-2], Gauss::step))
            .sweep(Sweep::tolerances("RADAU5", &[1e-6], Radau5::tol))
            .repeats(REPEATS, REPEAT_BUDGET)
            .on_row(progress)
            .run()?;
        for row in study.rows() {
            let cells = match &row.outcome {
                Ok(m) => format!(
                    "{:.2e} | {} | {} | {:.2} ms | ok",
                    m.error,
                    m.stats.evaluations,
                    m.stats.steps(),
                    m.wall_time.as_secs_f64() * 1e3
                ),
                Err(e) => format!("– | – | – | – | **{}**", error_name(e)),
            };
            md += &format!("| {k:e} | {} {} | {cells} |\n", row.method, row.setting);
        }
    }
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(md)
}

/// The variant and its message, short enough for a table cell.
fn error_name(e: &Error) -> String {
    let name = match e {
        Error::TooManySteps { .. } => "TooManySteps",
        Error::NonFiniteState { .. } => "NonFiniteState",
        Error::StepSizeUnderflow { .. } => "StepSizeUnderflow",
        Error::NewtonFailure { .. } => "NewtonFailure",
        _ => "error",
    };
    let mut msg = e.to_string();
    if let Some(cut) = msg.find(", q = ") {
        msg.truncate(cut);
    }
    format!("{name}: {msg}")
}

/// The pendulum in f32 and in f64: the same description (`Pendulum<T>`), the same
/// runs; errors against the f64 closed form.
fn precision() -> Result<Scene, Error> {
    let title = "Simple pendulum in f32 and f64, 170°, 10¼ periods";
    let started = header(title);
    let (l, g, theta0) = (1.0, 9.81, 170f64.to_radians());
    let t_end = 10.25 * pendulum_period(l, g, theta0);
    let steps = halvings(0.1, 8);
    let tols = tolerances(3, 12);
    let s64 = Pendulum::<f64> { m: 1.0, l, g };
    let s32 = Pendulum::<f32> {
        m: 1.0,
        l: l as f32,
        g: g as f32,
    };
    let exact = move |t| SVector::from([pendulum_angle(l, g, theta0, t)]);
    // The f32 runs solve the problem whose data are rounded to f32 (θ0 moves by
    // 1e-7 rad, which near the separatrix shifts the period measurably); their
    // reference is that problem's exact solution, so that the error is the
    // integration's own, not the rounding of the data.
    let (l32, g32, theta32) = (l as f32 as f64, g as f32 as f64, theta0 as f32 as f64);
    let exact32 = move |t| SVector::from([pendulum_angle(l32, g32, theta32, t)]);
    let study64 = WorkPrecision::new(|m: Method| {
        Simulation::new(&s64)
            .integrator(m)
            .run([theta0], [0.0], 0.0..t_end)
    })
    .exact(exact)
    .sweep(Sweep::steps("RK4 f64", &steps, Rk4::step))
    .sweep(Sweep::tolerances("DOPRI5 f64", &tols, |t| {
        Dopri5::tol(t).max_steps(BUDGET)
    }))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    let study32 = WorkPrecision::new(|m: Method| {
        Simulation::new(&s32)
            .integrator(m)
            .run([theta0 as f32], [0.0f32], 0.0f32..t_end as f32)
    })
    .exact(exact32)
    .sweep(Sweep::steps("RK4 f32", &steps, Rk4::step))
    .sweep(Sweep::tolerances("DOPRI5 f32", &tols, |t| {
        Dopri5::tol(t).max_steps(BUDGET)
    }))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());

    // Same method, same setting: f32 against f64.
    let mut md = String::from(
        "| method | setting | error f64 | error f32 | evals f64 | evals f32 | time f64 | time f32 | f64 time / f32 time |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for (r64, r32) in study64.rows().iter().zip(study32.rows()) {
        let method = r64.method.trim_end_matches(" f64");
        let cell = |r: &Row| match &r.outcome {
            Ok(m) => (
                format!("{:.2e}", m.error),
                m.stats.evaluations.to_string(),
                format!("{:.3} ms", m.wall_time.as_secs_f64() * 1e3),
            ),
            Err(e) => (format!("**{}**", error_name(e)), "–".into(), "–".into()),
        };
        let ((e64, n64, t64), (e32, n32, t32)) = (cell(r64), cell(r32));
        let ratio = match (r64.measurement(), r32.measurement()) {
            (Some(a), Some(b)) => format!(
                "{:.2}",
                a.wall_time.as_secs_f64() / b.wall_time.as_secs_f64()
            ),
            _ => "–".into(),
        };
        md += &format!(
            "| {method} | {} | {e64} | {e32} | {n64} | {n32} | {t64} | {t32} | {ratio} |\n",
            r64.setting
        );
    }
    Ok(Scene {
        slug: "precision-f32-f64",
        title: title.into(),
        study: study64.merge(study32),
        notes: vec![
            "The generic catalog `Pendulum<T>` run in f64 and in f32 with the same methods \
             and settings (θ0 = 170°, t_end = 10¼ periods); errors against the f64 closed \
             form of the problem each scalar can represent (for f32: θ0, l and g rounded to \
             f32), so the error is the integration's own."
                .into(),
            format!("Side by side:\n\n{md}"),
        ],
    })
}

/// The guidance table: per scene and target accuracy, the three fastest methods
/// (each at its cheapest setting that reaches the target).
fn summary(scenes: &[Scene]) -> String {
    let mut md = String::from(
        "# Work-precision summary (generated)\n\n\
         Per scene and target accuracy (max error of the positions at the final time), \
         the fastest runs that reach it, one per method, each at its cheapest setting: \
         wall time, RHS evaluations.\n\n\
         | scene | target | fastest | second | third |\n|---|---|---|---|---|\n",
    );
    for scene in scenes {
        let floor = scene.study.reference().uncertainty().unwrap_or(0.0);
        for target in TARGETS {
            let cells: Vec<String> = if target < floor {
                vec![format!(
                    "not measurable: the reference is only good to {floor:.0e}"
                )]
            } else {
                let best = scene.study.cheapest_per_method(target);
                if best.is_empty() {
                    vec!["no run reaches it".into()]
                } else {
                    best.iter()
                        .take(3)
                        .map(|r| {
                            let m = r.measurement().expect("cheapest rows succeeded");
                            format!(
                                "{} {} ({:.3} ms, {} evals)",
                                r.method,
                                r.setting,
                                m.wall_time.as_secs_f64() * 1e3,
                                m.stats.evaluations
                            )
                        })
                        .collect()
                }
            };
            let mut cells = cells;
            cells.resize(3, String::new());
            md += &format!(
                "| {} | {target:.0e} | {} |\n",
                scene.title,
                cells.join(" | ")
            );
        }
    }
    md
}

fn main() -> Result<(), Error> {
    let out: PathBuf = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/work-precision"));
    std::fs::create_dir_all(&out)?;
    let started = Instant::now();
    let mut scenes = vec![pendulum()?, kepler()?, spherical()?];
    scenes.extend(double_pendulum()?);
    scenes.push(rolling_sphere()?);
    scenes.push(stiff()?);
    let stiffness = stiffness_sweep()?;
    scenes.push(precision()?);
    for scene in &scenes {
        save(&out, scene)?;
    }
    std::fs::write(
        out.join("stiffness.md"),
        format!(
            "# Stiff spring-pendulum: cost against stiffness\n\n\
             One setting per method (DOPRI5/DOP853/RADAU5 at tolerance 1e-6 with the default \
             budget of 100 000 steps, RK4 and Störmer–Verlet at h = 1e-3, Gauss at h = 1e-2), \
             5 s from rest at 1 rad; reference RADAU5 at 1e-12.\n\n{stiffness}"
        ),
    )?;
    std::fs::write(out.join("summary.md"), summary(&scenes[..scenes.len() - 1]))?;
    println!(
        "\nwrote {} ({:.1} s in all)",
        out.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
