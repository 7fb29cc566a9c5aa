//! The pendulum in f32 and in f64 with the same methods and settings.

use super::*;
use crate::stiff::error_name;

/// The pendulum in f32 and in f64: the same description (`Pendulum<T>`), the same
/// runs; errors against the f64 closed form.
pub(crate) fn precision() -> Result<Scene, Error> {
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

    let md = side_by_side(&study64, &study32);
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

/// Same method, same setting: f32 against f64, as a markdown table.
fn side_by_side(study64: &Study, study32: &Study) -> String {
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
    md
}
