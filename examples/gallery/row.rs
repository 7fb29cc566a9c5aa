//! A gallery row: what one run of a catalog system reports (work, drift,
//! residuals, a note, wall time) and keeps to draw; and the entries, each a
//! system's name, what it demonstrates and the function that runs it.

use std::time::Instant;

use crate::figure::Figure;
use lagrange::Posed;
use lagrange::prelude::*;

/// The tolerance every row integrates to (rtol = atol).
pub(crate) const TOL: f64 = 1e-10;

/// One gallery system: its name (the row's and the files'), what it
/// demonstrates (for the index page), and how it runs (given its name).
pub(crate) struct Entry {
    pub name: &'static str,
    pub about: &'static str,
    pub run: fn(&'static str) -> Result<Row, Error>,
}

pub(crate) struct Row {
    pub system: &'static str,
    /// What the system demonstrates (the entry's `about`).
    pub about: &'static str,
    pub dof: usize,
    pub span: f64,
    pub accepted: usize,
    pub rejected: usize,
    pub evaluations: usize,
    pub drift: Option<f64>,
    pub residuals: Option<[f64; 2]>,
    pub note: String,
    pub wall_ms: f64,
    /// What the index page draws and saves of the run.
    pub figure: Option<Figure>,
    /// The run's 3D scene, a self-contained HTML page.
    pub scene: Option<String>,
    /// The scene at mid-run, as segments for the table's picture.
    pub still: Option<Vec<lagrange::scene::Segment>>,
    /// The scene at successive times, for an animation, with each frame's
    /// caption.
    pub frames: Option<(Vec<Vec<lagrange::scene::Segment>>, Vec<String>)>,
}

/// A system's coordinates as the plots and CSV headers name them, and which
/// of them are cyclic (`Lagrangian::CYCLIC`: the plots show their rates apart).
pub(crate) struct Coords<const N: usize> {
    pub names: [&'static str; N],
    pub cyclic: [bool; N],
}

/// The coordinates of a system.
pub(crate) fn coords<S: Lagrangian<f64, N>, const N: usize>(_: &S) -> Coords<N> {
    Coords {
        names: S::COORDINATES,
        cyclic: S::CYCLIC,
    }
}

/// One gallery row from a run of any formulation (the closure integrates),
/// with the run's scene.
pub(crate) fn row<S, const N: usize, E: Into<Error>>(
    system: &'static str,
    sys: &S,
    span: std::ops::Range<f64>,
    conservative: bool,
    integrate: impl FnOnce() -> Result<Trajectory<f64, N>, E>,
    note: impl FnOnce(&Trajectory<f64, N>) -> String,
) -> Result<Row, Error>
where
    S: Lagrangian<f64, N> + Posed<f64, N>,
{
    let coords = &coords(sys);
    let start = Instant::now();
    let traj = integrate().map_err(Into::into)?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let stats = traj.stats();
    let residuals = traj.max_residuals();
    Ok(Row {
        system,
        about: "",
        dof: N,
        span: span.end - span.start,
        accepted: stats.accepted,
        rejected: stats.rejected,
        evaluations: stats.evaluations,
        drift: conservative.then(|| traj.integral_drift()),
        residuals: (residuals != [0.0; 2]).then_some(residuals),
        note: note(&traj),
        wall_ms,
        figure: Some(Figure::of(
            &traj,
            &coords.names,
            &coords.cyclic,
            conservative,
        )?),
        scene: Some(traj.scene(sys).title(system).to_html()?),
        still: Some(traj.scene(sys).still((span.start + span.end) / 2.0)?),
        frames: None,
    })
}

/// An unconstrained system with DOPRI5.
pub(crate) fn run<S, const N: usize>(
    system: &'static str,
    sys: &S,
    (q0, v0): ([f64; N], [f64; N]),
    span: std::ops::Range<f64>,
    conservative: bool,
    note: impl FnOnce(&Trajectory<f64, N>) -> String,
) -> Result<Row, Error>
where
    S: Lagrangian<f64, N> + Posed<f64, N>,
{
    let run_span = span.clone();
    row(
        system,
        sys,
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
