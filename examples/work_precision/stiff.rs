//! The stiff spring-pendulum: a work-precision scene at k/m = 1e6, and the
//! cost of one setting per method against stiffness.

use super::*;

/// The stiff spring-pendulum at k/m = 1e6, full sweeps.
pub(crate) fn stiff() -> Result<Scene, Error> {
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
pub(crate) fn stiffness_sweep() -> Result<String, Error> {
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
pub(crate) fn error_name(e: &Error) -> String {
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
