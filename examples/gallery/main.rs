//! The main job: simulate every catalog system on built-in defaults and print, per
//! system, the integrator's work, the drift of its conserved quantity, the
//! constraint residuals and the wall time.
//!
//!     cargo run --release --example gallery

#[path = "../catalog/mod.rs"]
mod catalog;
mod control;
mod figure;
mod output;
mod plot;

use std::time::Instant;

use catalog::constrained::*;
use catalog::*;
use lagrange::prelude::*;

pub(crate) struct Row {
    system: &'static str,
    dof: usize,
    span: f64,
    accepted: usize,
    rejected: usize,
    evaluations: usize,
    drift: Option<f64>,
    residuals: Option<[f64; 2]>,
    note: String,
    wall_ms: f64,
    /// What the index page draws and saves of the run.
    figure: Option<figure::Figure>,
}

/// The coordinate names of a system (for plots and CSV headers).
pub(crate) fn coords<S: Lagrangian<f64, N>, const N: usize>(_: &S) -> [&'static str; N] {
    S::COORDINATES
}

/// One gallery row from a run of any formulation (the closure integrates).
pub(crate) fn row<const N: usize, E: Into<Error>>(
    system: &'static str,
    names: &[&str; N],
    span: std::ops::Range<f64>,
    conservative: bool,
    integrate: impl FnOnce() -> Result<Trajectory<f64, N>, E>,
    note: impl FnOnce(&Trajectory<f64, N>) -> String,
) -> Result<Row, Error> {
    let start = Instant::now();
    let traj = integrate().map_err(Into::into)?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let stats = traj.stats();
    let residuals = traj.max_residuals();
    Ok(Row {
        system,
        dof: N,
        span: span.end - span.start,
        accepted: stats.accepted,
        rejected: stats.rejected,
        evaluations: stats.evaluations,
        drift: conservative.then(|| traj.integral_drift()),
        residuals: (residuals != [0.0; 2]).then_some(residuals),
        note: note(&traj),
        wall_ms,
        figure: Some(figure::Figure::of(&traj, names, conservative)?),
    })
}

pub(crate) const TOL: f64 = 1e-10;

/// An unconstrained system with DOPRI5.
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
    let run_span = span.clone();
    row(
        system,
        &coords(sys),
        span,
        conservative,
        || {
            Simulation::new(sys)
                .integrator(Dopri5::tol(TOL))
                .run(q0, v0, run_span)
        },
        note,
    )
}

fn main() -> Result<(), Error> {
    let mut rows = Vec::new();

    let pendulum = Pendulum::<f64> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let th0 = 179f64.to_radians();
    let exact = 4.0 * (pendulum.l / pendulum.g).sqrt() * elliptic_k((th0 / 2.0).sin());
    let period = std::cell::Cell::new(f64::NAN);
    rows.push(row(
        "simple pendulum, 179°, period by events",
        &coords(&pendulum),
        0.0..20.0,
        true,
        || {
            // Rising zero crossings of θ, located on the dense output while stepping.
            let run = Simulation::new(&pendulum)
                .integrator(Dopri5::tol(TOL))
                .event(Event::new(|_, q: &Vector1<f64>, _| q[0]).rising())
                .run([th0], [0.0], 0.0..20.0)?;
            if let [a, b, ..] = run.times(0)[..] {
                period.set(b - a);
            }
            Ok::<_, Error>(run.trajectory)
        },
        |_| {
            format!(
                "period {:.9} s, exact 4√(l/g)K: rel. error {:.1e}",
                period.get(),
                (period.get() - exact).abs() / exact
            )
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

    constrained_rows(&mut rows)?;
    control::rows(&mut rows)?;

    let out = output_dir()?;
    print_table(&rows);
    let find = |name: &str| rows.iter().find(|r| r.system == name);
    let animations = output::Animations {
        double_pendulum: find("double pendulum").map(|r| (r, double.l1, double.l2)),
        rolling_disk: find("rolling disk, steady circle").map(|r| (r, 0.5)),
        cavity: find(CAVITY).map(|r| (r, 1.0)),
    };
    let index = output::write(&out, &rows, &animations)?;
    println!("\nplots, animations and CSV files: {}", index.display());
    Ok(())
}

/// `--out DIR`, or `target/gallery` under the current directory.
fn output_dir() -> Result<std::path::PathBuf, Error> {
    let mut args = std::env::args().skip(1);
    match (args.next().as_deref(), args.next()) {
        (None, _) => Ok("target/gallery".into()),
        (Some("--out"), Some(dir)) => Ok(dir.into()),
        _ => Err(Error::InvalidSettings(
            "usage: cargo run --release --example gallery [-- --out DIR]".into(),
        )),
    }
}

/// The summary as a markdown table that fits 100 columns; the checks each row
/// passes are in index.html.
fn print_table(rows: &[Row]) {
    println!("lagrange gallery: DOPRI5 at rtol = atol = 1e-10, f64\n");
    println!(
        "| {:<42} | {:>3} | {:>6} | {:>7} | {:>7} | {:>7} | {:>6} |",
        "system", "dof", "steps", "evals", "drift", "resid.", "ms"
    );
    println!(
        "|{}|{}|{}|{}|{}|{}|{}|",
        "-".repeat(44),
        "-".repeat(4) + ":",
        "-".repeat(7) + ":",
        "-".repeat(8) + ":",
        "-".repeat(8) + ":",
        "-".repeat(8) + ":",
        "-".repeat(7) + ":"
    );
    for r in rows {
        let drift = r.drift.map_or("—".to_string(), |d| format!("{d:.1e}"));
        let res = r
            .residuals
            .map_or("—".to_string(), |[p, v]| format!("{:.0e}", p.max(v)));
        let name: String = r.system.chars().take(42).collect();
        println!(
            "| {:<42} | {:>3} | {:>6} | {:>7} | {:>7} | {:>7} | {:>6.1} |",
            name, r.dof, r.accepted, r.evaluations, drift, res, r.wall_ms
        );
    }
    println!(
        "\ndrift: max |I(t) − I(0)| / |I(0)| of T + V (or the Jacobi integral); resid.: largest"
    );
    println!("|Φ| or |G q̇ + g| along the run; — where it does not apply.");
}

/// What each gallery system demonstrates, for the index page.
pub(crate) fn about(system: &str) -> &'static str {
    const ABOUT: &[(&str, &str)] = &[
        (
            "simple pendulum, 179°, period by events",
            "events located on the dense output; the period against the elliptic-integral closed form",
        ),
        (
            "C1 spherical pendulum (θ, φ)",
            "minimal coordinates; p_φ conserved (cyclic coordinate)",
        ),
        (
            "C2 ellipsoid with growing axes",
            "rheonomic position maps ξ(q, t)",
        ),
        (
            "C3 dumbbell (rod, free)",
            "a rigid rod as two particles; free fall of the centre of mass",
        ),
        ("C7 heavy particle, vertical plane", "the textbook parabola"),
        (
            "double pendulum",
            "chaos with the energy kept to the tolerance",
        ),
        (
            "5-link pendulum (relative angles)",
            "a longer chain, relative angles",
        ),
        (
            "damped driven pendulum",
            "dissipation and a time-dependent force",
        ),
        (
            "C1 spherical pendulum, Cartesian + λ",
            "holonomic constraint with a multiplier, drift projection, the rod tension",
        ),
        (
            "C3 rod as a constraint (6 coords + λ)",
            "the dumbbell again, the rod as a constraint",
        ),
        (
            "C4 body as three particles",
            "rigid-body inertia tensor against three particles",
        ),
        (
            "C5 rolling sphere, multipliers",
            "nonholonomic rolling with multipliers",
        ),
        (
            "C5 rolling sphere, reduced (Maggi)",
            "the same sphere in reduced form (independent speeds)",
        ),
        (
            "C6 tops joined by an untwistable thread",
            "a nonholonomic coupling of two rigid bodies",
        ),
        (
            "C8 polar, quasi-velocity x ẏ − y ẋ",
            "Gibbs–Appell equations on a quasi-velocity",
        ),
        (
            "C9 sphere on a turning plane",
            "rheonomic rolling; the velocity turns at 2Ω/7",
        ),
        (
            "rolling disk, steady circle",
            "steady circular rolling from the closed-form condition",
        ),
        (
            "C10 point in a spherical cavity, e = 0.7",
            "impacts by events, then sliding on the wall with a multiplier",
        ),
        ("Chaplygin sleigh", "a knife edge in reduced form"),
        (
            "two-link arm, computed-torque tracking",
            "a controller in a closure, inverse dynamics from the model",
        ),
        (
            "cart-pole, LQR from the linearisation",
            "LQR gain from the symbolic linearisation, continuous feedback",
        ),
        (
            "cart-pole, LQR sampled at 100 Hz (ZOH)",
            "the same gain, sampled with zero-order hold",
        ),
        (
            "rolling disk upright, critical spin",
            "critical spin from the eigenvalues against √(g/3a); wobble above it",
        ),
        (
            "Whipple bicycle at 5 m/s, roll-rate kick",
            "weave and capsize speeds against the published benchmark; self-stability",
        ),
    ];
    ABOUT
        .iter()
        .find(|(name, _)| *name == system)
        .map_or("", |(_, about)| about)
}

/// The cavity row's name (its animation is looked up by it).
const CAVITY: &str = "C10 point in a spherical cavity, e = 0.7";

/// C10: a point in a spherical cavity, impacts with restitution 0.7 until the
/// bounces die out, then sliding on the wall with a multiplier.
fn cavity_row() -> Result<Row, Error> {
    use catalog::cavity::Cavity;
    let cavity = Cavity::new(1.0, 9.81, 1.0, 0.7);
    let start = Instant::now();
    let run = cavity.simulate(
        Vector3::new(0.3, 0.0, 0.2),
        Vector3::new(0.5, 2.0, 1.0),
        0.0..8.0,
    )?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let mut stats = lagrange::Stats::default();
    let mut outside = 0.0f64;
    for phase in &run.phases {
        stats.add(phase.trajectory().stats());
    }
    for (_, q, _) in run.points() {
        outside = outside.max(q.norm() - cavity.r);
    }
    let points: Vec<(f64, [f64; 3], [f64; 3])> = run
        .points()
        .map(|(t, q, v)| (t, [q[0], q[1], q[2]], [v[0], v[1], v[2]]))
        .collect();
    Ok(Row {
        system: CAVITY,
        dof: 3,
        span: 8.0,
        accepted: stats.accepted,
        rejected: stats.rejected,
        evaluations: stats.evaluations,
        drift: None,
        residuals: None,
        note: format!(
            "{} impacts, sliding from t = {:.3}, max |x| − R = {outside:.1e}",
            run.impacts.len(),
            run.slides.first().copied().unwrap_or(f64::NAN)
        ),
        wall_ms,
        figure: Some(figure::Figure::from_points(&["x", "y", "z"], &points)),
    })
}

/// Constrained systems, rigid bodies and quasi-velocities (issue 3).
fn constrained_rows(rows: &mut Vec<Row>) -> Result<(), Error> {
    let cart = CartesianSphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let (th, thd, phd) = (1.0f64, 0.0, 2.0);
    let x0 = [th.sin(), 0.0, -th.cos()];
    let v0 = [th.cos() * thd, th.sin() * phd, th.sin() * thd];
    rows.push(row(
        "C1 spherical pendulum, Cartesian + λ",
        &coords(&cart),
        0.0..20.0,
        true,
        || {
            Simulation::new(&cart)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .run_constrained(x0, v0, 0.0..20.0)
        },
        |tr| {
            let (x, v) = tr.final_state();
            let dynamics = ConstrainedDynamics::new(&cart);
            match dynamics.solve(20.0, &x, &v) {
                Ok(sol) => format!(
                    "tension(20) = {:.6}",
                    cart.reactions(&x, &v, 20.0, &sol.multipliers)[0].norm()
                ),
                Err(e) => e.to_string(),
            }
        },
    )?);

    let pair = RodPair {
        m1: 1.0,
        m2: 2.0,
        l: 1.0,
        gx: 0.0,
        gy: 0.0,
        gz: -9.81,
    };
    rows.push(row(
        "C3 rod as a constraint (6 coords + λ)",
        &coords(&pair),
        0.0..1.5,
        true,
        || {
            Simulation::new(&pair)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .run_constrained(
                    [0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
                    [1.0, 0.0, 2.0, 1.0, 1.0, 2.0],
                    0.0..1.5,
                )
        },
        |_| String::new(),
    )?);

    let particles = ThreeParticleBody::example(9.81);
    let body = particles.as_body();
    let (q0, v0) = (
        [0.0, 0.0, 1.0, 0.3, 1.1, -0.4],
        [0.2, 0.1, 3.0, 0.7, -0.5, 2.0],
    );
    let reference = Simulation::new(&body)
        .integrator(Dopri5::tol(TOL))
        .run(q0, v0, 0.0..2.0)?;
    rows.push(run(
        "C4 body as three particles",
        &particles,
        q0,
        v0,
        0.0..2.0,
        true,
        |tr| {
            let gap = (tr.final_state().0 - reference.final_state().0).amax();
            format!("vs inertia-tensor body: {gap:.1e}")
        },
    )?);

    let (m, a) = (2.0, 0.3);
    let sphere = RollingSphere {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
    };
    let reduced = RollingSphereReduced {
        m,
        j: sphere.j,
        a,
        g: 9.81,
    };
    let speeds = [1.5, -0.7, 4.0];
    let start = [0.0, 0.0, 0.2, 0.9, 0.1];
    let reduced_traj = Simulation::new(&reduced)
        .integrator(Dopri5::tol(TOL))
        .run_reduced(
            start,
            [0.0, 0.0, speeds[0], speeds[1], speeds[2]],
            0.0..10.0,
        )?;
    let v5 = reduced_traj.velocities()[0];
    rows.push(row(
        "C5 rolling sphere, multipliers",
        &coords(&sphere),
        0.0..10.0,
        true,
        || {
            Simulation::new(&sphere)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .run_constrained(
                    [0.0, 0.0, a, start[2], start[3], start[4]],
                    [v5[0], v5[1], 0.0, v5[2], v5[3], v5[4]],
                    0.0..10.0,
                )
        },
        |tr| {
            let (qf, _) = tr.final_state();
            let (qr, _) = reduced_traj.final_state();
            let gap = (0..2)
                .map(|i| (qf[i] - qr[i]).abs())
                .chain((2..5).map(|i| (qf[i + 1] - qr[i]).abs()))
                .fold(0.0, f64::max);
            format!("vs reduced form: {gap:.1e}")
        },
    )?);
    rows.push(row(
        "C5 rolling sphere, reduced (Maggi)",
        &coords(&reduced),
        0.0..10.0,
        true,
        || {
            Simulation::new(&reduced)
                .integrator(Dopri5::tol(TOL))
                .run_reduced(
                    start,
                    [0.0, 0.0, speeds[0], speeds[1], speeds[2]],
                    0.0..10.0,
                )
        },
        |tr| {
            let (q, _) = tr.final_state();
            format!("centre ({:.4}, {:.4}), straight line", q[0], q[1])
        },
    )?);

    let tops = ThreadedTops {
        m: 1.0,
        a: 0.3,
        b: 0.2,
        c: 0.5,
        l: 0.4,
        d: 2.0,
        g: 9.81,
    };
    let (th1, th2) = (0.4f64, 0.7f64);
    rows.push(row(
        "C6 tops joined by an untwistable thread",
        &coords(&tops),
        0.0..5.0,
        true,
        || {
            Simulation::new(&tops)
                .integrator(Dopri5::tol(TOL))
                .drift(Drift::projection())
                .run_constrained(
                    [0.0, th1, 0.0, 0.5, th2, 0.0],
                    [
                        1.0,
                        0.2,
                        10.0 - th1.cos(),
                        -0.5,
                        -0.1,
                        -10.0 + 0.5 * th2.cos(),
                    ],
                    0.0..5.0,
                )
        },
        |_| String::new(),
    )?);

    let polar = PolarQuasiVelocity {
        m: 1.3,
        k: 2.0,
        s: 0.4,
    };
    rows.push(row(
        "C8 polar, quasi-velocity x ẏ − y ẋ",
        &coords(&polar),
        0.0..5.0,
        false,
        || {
            Simulation::new(&polar)
                .integrator(Dopri5::tol(TOL))
                .run_reduced([1.0, 0.3], [0.2, 0.9], 0.0..5.0)
        },
        |_| "Gibbs–Appell; transverse force: no integral".to_string(),
    )?);

    let (m, a, big_omega) = (1.0, 0.2, 3.0);
    let turntable = SphereOnTurntable {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
        big_omega,
    };
    rows.push(row(
        "C9 sphere on a turning plane",
        &coords(&turntable),
        0.0..10.0,
        false,
        || {
            Simulation::new(&turntable)
                .integrator(Dopri5::tol(TOL))
                .run_reduced(
                    [1.0, 0.5, 0.3, 1.2, 0.0],
                    [0.0, 0.0, 0.8, -0.4, 2.0],
                    0.0..10.0,
                )
        },
        |tr| {
            let v = tr.velocities();
            let (v0, v1) = (v[0], v[v.len() - 1]);
            let turned =
                (v1[1].atan2(v1[0]) - v0[1].atan2(v0[0])).rem_euclid(std::f64::consts::TAU);
            let expected = (2.0 * big_omega / 7.0 * 10.0).rem_euclid(std::f64::consts::TAU);
            format!("velocity turned {turned:.6} rad (2Ωt/7: {expected:.6})")
        },
    )?);

    let (m, a) = (1.0, 0.5);
    let disk = RollingDisk {
        m,
        a,
        b: m * a * a / 4.0,
        c: m * a * a / 2.0,
        g: 9.81,
    };
    let theta0 = 0.3;
    let (q0, v0) = disk.steady_circle(theta0, 2.0);
    rows.push(row(
        "rolling disk, steady circle",
        &coords(&disk),
        0.0..3.0,
        true,
        || {
            Simulation::new(&disk)
                .integrator(Dopri5::tol(TOL))
                .run_reduced(q0, v0, 0.0..3.0)
        },
        |tr| format!("tilt(3) − tilt(0) = {:.1e}", tr.final_state().0[3] - theta0),
    )?);

    let sleigh = ChaplyginSleigh {
        m: 1.0,
        i: 0.2,
        b: 0.5,
    };
    rows.push(cavity_row()?);

    rows.push(row(
        "Chaplygin sleigh",
        &coords(&sleigh),
        0.0..60.0,
        true,
        || {
            Simulation::new(&sleigh)
                .integrator(Dopri5::tol(TOL))
                .run_reduced([0.0, 0.0, 0.0], [0.3, 0.0, 2.0], 0.0..60.0)
        },
        |tr| format!("turn rate(60) = {:.1e}", tr.final_state().1[2]),
    )?);
    Ok(())
}
