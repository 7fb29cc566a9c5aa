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
//! itself stops meaning anything), the rolling sphere (reduced form), a tumbling
//! body whose orientation is a quaternion (errors on the group), and a stiff
//! spring-pendulum (k/m = 1e6, then a sweep of stiffness up to where explicit
//! methods fail). Last, the pendulum in f32 against f64.

#[path = "../catalog/mod.rs"]
mod catalog;
mod precision;
mod scenes;
mod stiff;
mod summary;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use catalog::constrained::RollingSphereReduced;
use catalog::free::flip_half_period;
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

fn main() -> Result<(), Error> {
    let out: PathBuf = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/work-precision"));
    std::fs::create_dir_all(&out)?;
    let started = Instant::now();
    let mut scenes = vec![scenes::pendulum()?, scenes::kepler()?, scenes::spherical()?];
    scenes.extend(scenes::double_pendulum()?);
    scenes.push(scenes::rolling_sphere()?);
    scenes.extend(scenes::tumbling()?);
    scenes.push(stiff::stiff()?);
    let stiffness = stiff::stiffness_sweep()?;
    scenes.push(precision::precision()?);
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
    std::fs::write(
        out.join("summary.md"),
        summary::summary(&scenes[..scenes.len() - 1]),
    )?;
    println!(
        "\nwrote {} ({:.1} s in all)",
        out.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
