//! Free rotations: the intermediate-axis flip (also over 200 flips with the
//! symplectic method on the group) and a top spun exactly upright, each with
//! an animation of its scene.

use crate::catalog::free::{
    Brick, EulerTop, QuaternionTop, flip_half_period, sleeping_top_threshold,
};
use crate::catalog::study::TumblingBody;
use crate::figure::Figure;
use crate::gallery_error;
use crate::row::Row;
use lagrange::Posed;
use lagrange::prelude::*;
use std::ops::Range;
use std::time::Instant;

/// Frames of each animation.
const FRAMES: usize = 150;

/// A brick spun about its intermediate axis, nudged: it flips over and back,
/// every half period of the elliptic closed form.
pub(crate) fn intermediate_axis(system: &'static str) -> Result<Row, Error> {
    let brick = Brick::solid(1.0, [0.3, 0.2, 0.1]);
    let w = [0.01, 5.0, 0.01];
    let half = flip_half_period([brick.a, brick.b, brick.c], w);
    let span = 0.0..6.5 * half;
    let q0 = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0];
    let start = Instant::now();
    let traj = Simulation::new(&brick).integrator(Dopri5::tol(1e-10)).run(
        q0,
        [0.0, 0.0, 0.0, w[0], w[1], w[2]],
        span.clone(),
    )?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let flips = traj.crossings(|_, _, v| v[4])?;
    let mean = (flips[flips.len() - 1] - flips[0]) / (flips.len() - 1) as f64;
    let note = format!(
        "{} flips every {mean:.6} s (elliptic closed form {half:.6} s); unit-norm error {:.0e}",
        flips.len(),
        traj.max_unit_error()
    );
    let figure = angular_velocity(&traj, Brick::VELOCITIES, 3, csv(&brick, &traj)?);
    free_row(system, &brick, &traj, span, (note, wall_ms), figure)
}

/// A free body tumbling through 200 intermediate-axis flips with the
/// symplectic Gauss method on the group (`emit(hamiltonian)`): its energy
/// error stays where it started, its world angular momentum and unit norm
/// at round-off.
pub(crate) fn symplectic_tumbling(system: &'static str) -> Result<Row, Error> {
    let (body, w) = (TumblingBody::PLATE, TumblingBody::SPIN);
    let half = flip_half_period([body.i1, body.i2, body.i3], w);
    let span = 0.0..200.0 * half;
    let start = Instant::now();
    let gauss = Gauss::step(0.1).record(lagrange::Record::Every(5));
    let traj =
        Simulation::new(&body)
            .integrator(gauss)
            .run([1.0, 0.0, 0.0, 0.0], w, span.clone())?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let inertia = nalgebra::Vector3::new(body.i1, body.i2, body.i3);
    let momentum = |k: usize| {
        let (q, v) = (&traj.positions()[k], &traj.velocities()[k]);
        let r = lagrange::numeric::orientation::rotation_matrix([q[0], q[1], q[2], q[3]]);
        let r = nalgebra::Matrix3::from_fn(|i, j| r[i][j]);
        r * inertia.component_mul(&nalgebra::Vector3::new(v[0], v[1], v[2]))
    };
    let l0 = momentum(0);
    let moved = (0..traj.len())
        .map(|k| (momentum(k) - l0).norm() / l0.norm())
        .fold(0.0, f64::max);
    let e = traj.integrals();
    let quarter = e.len() / 4;
    let worst = |xs: &[f64]| {
        xs.iter()
            .map(|x| (x - e[0]).abs() / e[0])
            .fold(0.0, f64::max)
    };
    let note = format!(
        "Gauss h = 0.1 over 200 flips: energy error {:.1e} in the first quarter, {:.1e} in the last; \
         world angular momentum kept to {moved:.0e}, unit norm to {:.0e}",
        worst(&e[..quarter]),
        worst(&e[3 * quarter..]),
        traj.max_unit_error()
    );
    let figure = angular_velocity(&traj, TumblingBody::VELOCITIES, 0, csv(&body, &traj)?);
    free_row(system, &body, &traj, span, (note, wall_ms), figure)
}

/// A heavy top spun exactly upright (θ = 0, where Euler angles z-x-z stop)
/// above the sleeping threshold C²n² = 4 A m g l, nudged: it stays up.
pub(crate) fn upright_top(system: &'static str) -> Result<Row, Error> {
    let top = QuaternionTop {
        m: 1.5,
        a: 0.1,
        c: 0.05,
        l: 0.2,
        g: 9.81,
    };
    let threshold = sleeping_top_threshold(top.a, top.c, top.m * top.g * top.l);
    let n = 1.5 * threshold;
    let span = 0.0..4.0;
    let start = Instant::now();
    let traj = Simulation::new(&top).integrator(Dopri5::tol(1e-10)).run(
        [1.0, 0.0, 0.0, 0.0],
        [0.3, 0.0, n],
        span.clone(),
    )?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let lowest = traj
        .positions()
        .iter()
        .map(|q| 1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]))
        .fold(1.0, f64::min);
    let lin = Linearizer::new().tangent(
        &top,
        &Vector4::new(1.0, 0.0, 0.0, 0.0),
        &Vector3::new(0.0, 0.0, n),
        0.0,
    )?;
    let note = format!(
        "spin {n:.1} rad/s = 1.5 × threshold; tilt stays below {:.2}°; largest real part of the tangent linearisation {:.0e}",
        lowest.acos().to_degrees(),
        lin.eigenvalues()[0].re
    );
    let figure = angular_velocity(&traj, QuaternionTop::VELOCITIES, 0, csv(&top, &traj)?);
    free_row(system, &top, &traj, span, (note, wall_ms), figure)
}

/// The same top written in Euler angles z-x-z with `emit(atlas)`, swung over
/// the top through θ = 0 again and again: each pass leaves the user's chart
/// and comes back, and the motion is the quaternion top's.
pub(crate) fn atlas_top(system: &'static str) -> Result<Row, Error> {
    let (m, a, c, l, g) = (1.5, 0.1, 0.05, 0.2, 9.81);
    let top = EulerTop { m, a, c, l, g };
    let (q0, v0) = ([0.2, 0.6, -0.4], [0.0, -14.0, 2.0]);
    let span = 0.0..3.0;
    let start = Instant::now();
    let run = Simulation::new(&top)
        .integrator(Dopri5::tol(1e-10))
        .run_atlas(q0, v0, span.clone())?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let twin = QuaternionTop { m, a, c, l, g };
    let chart = lagrange::numeric::euler::EulerChart::new([2, 0, 2]).expect("z-x-z");
    let w = chart.rates(q0) * Vector3::from(v0);
    let r0 = chart.matrix(q0);
    let quaternion = lagrange::numeric::orientation::from_rotation_matrix(&r0);
    let reference = Simulation::new(&twin).integrator(Dopri5::tol(1e-10)).run(
        quaternion,
        [w[0], w[1], w[2]],
        span.clone(),
    )?;
    let traj = run.charted();
    let apart = (0..traj.len())
        .filter_map(|i| {
            let (q, _) = reference.state_at(traj.times()[i])?;
            let r = lagrange::numeric::orientation::rotation_matrix([q[0], q[1], q[2], q[3]]);
            let r = nalgebra::Matrix3::from_fn(|i, j| r[i][j]);
            Some((run.rotation(i, 0) - r).abs().max())
        })
        .fold(0.0, f64::max);
    let note = format!(
        "{} chart switches (leave below |sin θ| = 0.6, back above 0.8); orientation within {apart:.0e} of the quaternion top",
        run.switches().len()
    );
    let user = run
        .user_trajectory()
        .ok_or_else(|| gallery_error("the atlas run has no point in the user's chart"))?;
    let figure = Figure::of(&user, &EulerTop::<f64>::COORDINATES, &[false; 3], true)?;
    free_row(system, &top, &user, span, (note, wall_ms), figure)
}

/// A row of a run with orientations: its angular velocity plotted, its
/// scene, its still and an animation of the scene.
pub(crate) fn free_row<S, const N: usize, const Q: usize>(
    system: &'static str,
    sys: &S,
    traj: &Trajectory<f64, N, Q>,
    span: Range<f64>,
    (note, wall_ms): (String, f64),
    figure: Figure,
) -> Result<Row, Error>
where
    S: Lagrangian<f64, N, Q> + Posed<f64, N, Q>,
{
    let stats = traj.stats();
    let scene = traj.scene(sys).title(system);
    let times =
        (0..FRAMES).map(|k| span.start + (span.end - span.start) * k as f64 / (FRAMES - 1) as f64);
    let frames = times
        .clone()
        .map(|t| scene.still(t))
        .collect::<Result<Vec<_>, _>>()?;
    let captions = times.map(|t| format!("{system}, t = {t:.2} s")).collect();
    Ok(Row {
        system,
        about: "",
        dof: N,
        span: span.end - span.start,
        accepted: stats.accepted,
        rejected: stats.rejected,
        evaluations: stats.evaluations,
        drift: Some(traj.integral_drift()),
        residuals: None,
        note,
        wall_ms,
        figure: Some(figure),
        scene: Some(scene.to_html()?),
        still: Some(scene.still((span.start + span.end) / 2.0)?),
        frames: Some((frames, captions)),
    })
}

/// The figure of a run with an orientation: its angular velocity in body
/// axes (from index `at` of v) and the drift; the CSV has every column.
pub(crate) fn angular_velocity<const N: usize, const Q: usize>(
    traj: &Trajectory<f64, N, Q>,
    names: [&str; N],
    at: usize,
    csv: String,
) -> Figure {
    let omega: [&str; 3] = [names[at], names[at + 1], names[at + 2]];
    let points: Vec<(f64, [f64; 3], [f64; 3])> = (0..traj.len())
        .map(|k| {
            let v = &traj.velocities()[k];
            (traj.times()[k], [v[at], v[at + 1], v[at + 2]], [0.0; 3])
        })
        .collect();
    let mut figure = Figure::from_points(&omega, &points);
    let i0 = traj.integrals()[0];
    figure.drift = Some(
        traj.integrals()
            .iter()
            .map(|i| (i - i0).abs() / i0.abs().max(1e-300))
            .collect(),
    );
    figure.csv = csv;
    figure
}

/// The run's CSV, every column named by the system.
pub(crate) fn csv<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(
    sys: &S,
    traj: &Trajectory<f64, N, Q>,
) -> Result<String, Error> {
    let mut out = Vec::new();
    traj.table(sys).write(&mut out)?;
    Ok(String::from_utf8_lossy(&out).into_owned())
}
