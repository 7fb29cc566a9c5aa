//! The main job: simulate every catalog system that runs today on built-in
//! defaults and print, per system, the integrator's work, the drift of its
//! conserved quantity and the wall time.
//!
//!     cargo run --release --example gallery

mod catalog;

use std::time::Instant;

use catalog::*;
use lagrange::prelude::*;

struct Row {
    system: &'static str,
    dof: usize,
    span: f64,
    accepted: usize,
    rejected: usize,
    evaluations: usize,
    drift: Option<f64>,
    note: String,
    wall_ms: f64,
}

fn run<S, const N: usize>(
    system: &'static str,
    sys: &S,
    q0: [f64; N],
    v0: [f64; N],
    span: std::ops::Range<f64>,
    conservative: bool,
    note: impl FnOnce(&Trajectory<f64, N>) -> String,
) -> Result<Row, Error>
where
    S: Lagrangian<f64, N>,
{
    let start = Instant::now();
    let traj = Simulation::new(sys).integrator(Dopri5::tol(1e-10)).run(
        SVector::from(q0),
        SVector::from(v0),
        span.clone(),
    )?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let stats = traj.stats();
    Ok(Row {
        system,
        dof: N,
        span: span.end - span.start,
        accepted: stats.accepted,
        rejected: stats.rejected,
        evaluations: stats.evaluations,
        drift: conservative.then(|| traj.integral_drift()),
        note: note(&traj),
        wall_ms,
    })
}

fn main() -> Result<(), Error> {
    let mut rows = Vec::new();

    let pendulum = Pendulum::<f64> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    rows.push(run(
        "simple pendulum, 179° (f64)",
        &pendulum,
        [179f64.to_radians()],
        [0.0],
        0.0..20.0,
        true,
        |tr| {
            let crossings = tr.crossings(|_, q, _| q[0]);
            format!("{} zero crossings", crossings.len())
        },
    )?);

    let spherical = SphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    rows.push(run(
        "C1 spherical pendulum (θ, φ)",
        &spherical,
        [1.0, 0.0],
        [0.0, 2.0],
        0.0..20.0,
        true,
        |tr| {
            let (q, v) = tr.final_state();
            let p0 = (1.0f64).sin().powi(2) * 2.0;
            let p1 = q[0].sin().powi(2) * v[1];
            format!("p_φ drift {:.1e}", ((p1 - p0) / p0).abs())
        },
    )?);

    let ellipsoid = GrowingEllipsoid {
        m: 1.0,
        a: 1.0,
        b: 0.8,
        c: 0.6,
        g: 9.81,
    };
    rows.push(run(
        "C2 ellipsoid with growing axes",
        &ellipsoid,
        [1.0, 0.3],
        [0.2, 1.0],
        1.0..4.0,
        false,
        |_| "rheonomic: no integral".to_string(),
    )?);

    let dumbbell = Dumbbell {
        m1: 1.0,
        m2: 2.0,
        l: 1.0,
        gx: 0.0,
        gy: 0.0,
        gz: -9.81,
    };
    rows.push(run(
        "C3 dumbbell (rod, free)",
        &dumbbell,
        [0.0, 0.0, 0.0, 0.3, 0.0],
        [1.0, 0.0, 2.0, 1.5, 0.7],
        0.0..1.5,
        true,
        |tr| {
            let (q, _) = tr.final_state();
            format!(
                "z_C(1.5) = {:.6} (exact {:.6})",
                q[2],
                2.0 * 1.5 - 9.81 * 1.5 * 1.5 / 2.0
            )
        },
    )?);

    let particle = HeavyParticle { m: 1.0, g: 9.81 };
    rows.push(run(
        "C7 heavy particle, vertical plane",
        &particle,
        [0.0, 0.0],
        [1.0, 3.0],
        0.0..1.0,
        true,
        |_| "parabola y + B = (2A/g)√(h − gz − A²)".to_string(),
    )?);

    let double = DoublePendulum {
        m1: 1.0,
        m2: 1.0,
        l1: 1.0,
        l2: 1.0,
        g: 9.81,
    };
    rows.push(run(
        "double pendulum",
        &double,
        [2.0, 2.5],
        [0.0, 0.0],
        0.0..20.0,
        true,
        |_| "chaotic".to_string(),
    )?);

    let chain = Chain5 {
        m: 1.0,
        l: 0.5,
        g: 9.81,
    };
    rows.push(run(
        "5-link pendulum (relative angles)",
        &chain,
        [1.0, 0.2, -0.2, 0.3, 0.1],
        [0.0; 5],
        0.0..10.0,
        true,
        |_| String::new(),
    )?);

    let driven = DrivenPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
        c: 0.3,
        a: 1.2,
        w: 2.0,
        f: 0.5,
    };
    rows.push(run(
        "damped driven pendulum",
        &driven,
        [0.5],
        [0.0],
        0.0..20.0,
        false,
        |tr| format!("θ(20) = {:.6}", tr.final_state().0[0]),
    )?);

    println!("lagrange gallery — DOPRI5 at rtol = atol = 1e-10, f64\n");
    println!(
        "| {:<36} | {:>3} | {:>5} | {:>6} | {:>5} | {:>7} | {:>11} | {:>8} | note",
        "system", "dof", "span", "steps", "rej", "f evals", "drift", "wall ms"
    );
    println!("|{}|", "-".repeat(120));
    for r in &rows {
        let drift = r
            .drift
            .map(|d| format!("{d:.2e}"))
            .unwrap_or_else(|| "—".to_string());
        println!(
            "| {:<36} | {:>3} | {:>5.1} | {:>6} | {:>5} | {:>7} | {:>11} | {:>8.2} | {}",
            r.system,
            r.dof,
            r.span,
            r.accepted,
            r.rejected,
            r.evaluations,
            drift,
            r.wall_ms,
            r.note
        );
    }
    println!(
        "\ndrift: max |I(t) − I(0)| / |I(0)| of the conserved quantity (T + V, or the Jacobi integral)."
    );
    Ok(())
}
