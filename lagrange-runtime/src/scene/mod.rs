//! See the bodies move: a 3D scene of a derived system's runs as one
//! self-contained HTML page.
//!
//! Every `#[derive(Lagrangian)]` description reports the world pose of its
//! bodies and the positions of its points ([`Posed`]); a [`Scene`] samples
//! them along one or more trajectories and writes a page that plays the
//! motion (play/pause, a time slider, speed, an orbiting camera, the time and
//! a linked plot of chosen coordinates), one colour per run. The page needs no
//! network and no other file: the viewer (Canvas 2D) is in it.
//!
//! ```
//! # use lagrange_runtime::{Dopri5, Lagrangian, Simulation};
//! # use lagrange_runtime::pose::{Anchor, BodyInertia, BodyPose, Posed, Shape, Solid};
//! # use nalgebra::{Matrix1, Matrix3, SVector, Vector1, Vector3};
//! # struct Pendulum;
//! # impl Lagrangian<f64, 1> for Pendulum {
//! #     const COORDINATES: [&'static str; 1] = ["theta"];
//! #     const RHEONOMIC: bool = false;
//! #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
//! #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-q[0].sin()) }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
//! #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { -q[0].cos() }
//! #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
//! #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
//! #     }
//! # }
//! # impl Posed<f64, 1> for Pendulum {
//! #     const BODIES: &'static [&'static str] = &[];
//! #     const POINTS: &'static [&'static str] = &["bob"];
//! #     const POINT_BODIES: &'static [Option<usize>] = &[None];
//! #     fn poses(&self, q: &SVector<f64, 1>, _: f64, _: &mut [BodyPose<f64>], p: &mut [Vector3<f64>]) {
//! #         p[0] = Vector3::new(q[0].sin(), -q[0].cos(), 0.0);
//! #     }
//! #     fn inertias(&self, _: &mut [BodyInertia<f64>]) {}
//! #     fn shapes(&self, out: &mut dyn FnMut(Shape<f64>)) {
//! #         out(Shape { on: Anchor::Point(0), at: Vector3::zeros(), solid: Solid::Sphere { radius: 0.1 } });
//! #     }
//! # }
//! // θ'' = −sin θ, by hand here; #[derive(Lagrangian)] writes both impls.
//! let traj = Simulation::new(&Pendulum).integrator(Dopri5::tol(1e-10)).run([1.0], [0.0], 0.0..10.0)?;
//! traj.scene(&Pendulum).write_html(std::env::temp_dir().join("pendulum.html"))?;
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! Frames are sampled from the dense output at the display rate (30 per second
//! of simulated time by default, [`Scene::fps`]), not at the step points, and
//! at most [`MAX_FRAMES`] per run: a page's size is bounded by the number of
//! runs, bodies, points and plotted coordinates, whatever the number of steps.
//! Positions are written with about five significant digits of the scene's
//! size, rotations as quaternions with five decimals.
//!
//! The page exposes `window.lagrangeScene` (`setTime(t)`, `frameCount`,
//! `bodyWorldPosition(name, run)`, `pointWorldPosition(name, run)`,
//! `bodyScreenPosition(name, run)`, `pixelHash()`) for tests and tools.

mod html;
mod sample;
mod shapes;
mod still;

pub use sample::MAX_FRAMES;
pub use still::{Segment, View};

use crate::error::SettingsError;
use std::borrow::Cow;
use std::path::Path;

use crate::atlas::AtlasRun;
use crate::error::Error;
use crate::numeric::Real;
use crate::ode::Trajectory;
use crate::pose::Posed;
use crate::system::Lagrangian;

/// The colours of the runs, in order (then repeated).
const PALETTE: [&str; 6] = [
    "#3a6fb0", "#d0542c", "#3b9a4b", "#8a5bb5", "#c99a1a", "#3aa6a6",
];

/// One run of a scene with its label, colour and opacity.
struct Run<'a, T: Real, const N: usize, const Q: usize> {
    /// Borrowed, or built for the scene (a run through the atlas in the
    /// user's coordinates).
    traj: Cow<'a, Trajectory<T, N, Q>>,
    label: String,
    color: String,
    opacity: f64,
}

/// A scene of one system's runs, written as one HTML page; see the
/// [module docs](self).
pub struct Scene<'a, T: Real, const N: usize, S, const Q: usize = N> {
    sys: &'a S,
    runs: Vec<Run<'a, T, N, Q>>,
    title: String,
    plot: Option<Vec<String>>,
    fps: f64,
    side_by_side: bool,
}

impl<'a, T: Real, const N: usize, const Q: usize, S: Posed<T, N, Q> + Lagrangian<T, N, Q>>
    Scene<'a, T, N, S, Q>
{
    /// A scene of `sys` with no run yet.
    pub fn new(sys: &'a S) -> Self {
        Scene {
            sys,
            runs: Vec::new(),
            title: "lagrange scene".to_string(),
            plot: None,
            fps: 30.0,
            side_by_side: false,
        }
    }

    /// Adds a run, drawn in the next colour of the palette; the first run is
    /// opaque, the ones overlaid on it a little transparent.
    pub fn run(self, traj: &'a Trajectory<T, N, Q>, label: impl Into<String>) -> Self {
        self.add(Cow::Borrowed(traj), label.into())
    }

    fn add(mut self, traj: Cow<'a, Trajectory<T, N, Q>>, label: String) -> Self {
        let k = self.runs.len();
        self.runs.push(Run {
            traj,
            label,
            color: PALETTE[k % PALETTE.len()].to_string(),
            opacity: if k == 0 { 1.0 } else { 0.6 },
        });
        self
    }

    /// The colour (`#rrggbb`) and opacity (0 to 1) of the last run added.
    pub fn style(mut self, color: &str, opacity: f64) -> Self {
        if let Some(r) = self.runs.last_mut() {
            r.color = color.to_string();
            r.opacity = opacity;
        }
        self
    }

    /// The page's title.
    pub fn title(mut self, title: impl Into<String>) -> Self {
        self.title = title.into();
        self
    }

    /// The coordinates the linked plot shows, by name (default: the first
    /// four that are not cyclic, else the first four).
    pub fn plot(mut self, coordinates: &[&str]) -> Self {
        self.plot = Some(coordinates.iter().map(|c| c.to_string()).collect());
        self
    }

    /// Draws the runs after the first beside it rather than where they are:
    /// each moved horizontally under the first one's centroid, a lane to its
    /// left, so that runs that travel apart (a bicycle at two speeds) stay in
    /// view together. Display only: the hook reports the true positions.
    pub fn side_by_side(mut self, on: bool) -> Self {
        self.side_by_side = on;
        self
    }

    /// Frames per second of simulated time (default 30), within [`MAX_FRAMES`] a run.
    pub fn fps(mut self, fps: f64) -> Self {
        self.fps = fps;
        self
    }

    /// The page as a string.
    ///
    /// # Errors
    /// [`Error::Settings`] for no run, an empty trajectory, a bad frame
    /// rate, a style that is not `#rrggbb` with an opacity in [0, 1], an
    /// unknown coordinate to plot or a shape size that is not positive;
    /// [`Error::NonFinitePose`] for a NaN or ∞ in a pose.
    pub fn to_html(&self) -> Result<String, Error> {
        self.check()?;
        let plotted = self.plotted()?;
        let mut frames = Vec::new();
        for r in &self.runs {
            frames.push(sample::sample(self.sys, &r.traj, self.fps, &plotted)?);
        }
        let drawn = shapes::drawn(self.sys, &frames[0].centres)?;
        let names: Vec<&str> = plotted.iter().map(|&j| S::COORDINATES[j]).collect();
        let planar = frames.iter().all(|f| is_planar(f, S::BODIES.len()));
        let scene = html::Static {
            title: &self.title,
            bodies: S::BODIES,
            points: S::POINTS,
            shapes: &drawn,
            plot: &names,
            planar,
            side_by_side: self.side_by_side,
        };
        let runs: Vec<html::RunData> = self
            .runs
            .iter()
            .zip(&frames)
            .map(|(r, f)| html::RunData {
                label: &r.label,
                color: &r.color,
                opacity: r.opacity,
                frames: f,
            })
            .collect();
        Ok(html::page(&scene, &runs))
    }

    /// A still of the first run without a browser: every shape's edges at
    /// time `t` and the paths of the bodies and points over the run, as
    /// segments on the picture plane (x right, y up) seen from the page's
    /// starting view, for drawing with other tools.
    ///
    /// # Errors
    /// As [`Scene::to_html`] for the shapes and the run.
    pub fn still(&self, t: f64) -> Result<Vec<Segment>, Error> {
        self.still_from(t, View::Camera)
    }

    /// [`still`](Self::still) seen from `view`: the page's starting camera
    /// or one of the coordinate planes.
    ///
    /// # Errors
    /// As [`Scene::still`].
    pub fn still_from(&self, t: f64, view: View) -> Result<Vec<Segment>, Error> {
        self.check()?;
        still::segments(self.sys, &self.runs[0].traj, t, view)
    }

    /// Writes the page to `path`.
    ///
    /// # Errors
    /// As [`Scene::to_html`], and [`Error::Io`] if the file cannot be written.
    pub fn write_html(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let page = self.to_html()?;
        std::fs::write(path, page)?;
        Ok(())
    }

    fn check(&self) -> Result<(), Error> {
        let bad = |problem: String| {
            Err(SettingsError::Data {
                owner: "scene",
                problem,
            }
            .into())
        };
        if self.runs.is_empty() {
            return bad("a scene needs a run: add one with `.run(&trajectory, \"label\")`".into());
        }
        if !(self.fps > 0.0 && self.fps.is_finite()) {
            return bad(format!(
                "a scene's frame rate must be positive, not {}",
                self.fps
            ));
        }
        for r in &self.runs {
            if r.traj.is_empty() {
                return bad(format!("run `{}` has no points", r.label));
            }
            let hex = r.color.len() == 7
                && r.color.starts_with('#')
                && r.color[1..].chars().all(|c| c.is_ascii_hexdigit());
            if !hex || !(0.0..=1.0).contains(&r.opacity) {
                return bad(format!(
                    "run `{}`: a style is a colour `#rrggbb` and an opacity in [0, 1], not `{}` and {}",
                    r.label, r.color, r.opacity
                ));
            }
        }
        Ok(())
    }

    /// The indices of the plotted coordinates.
    fn plotted(&self) -> Result<Vec<usize>, Error> {
        let Some(names) = &self.plot else {
            // Cyclic coordinates (a rolling wheel's angle, a heading) often
            // grow without bound and would flatten the others' curves.
            let shaped: Vec<usize> = (0..N).filter(|&j| !S::CYCLIC[j]).take(4).collect();
            return Ok(if shaped.is_empty() {
                (0..N.min(4)).collect()
            } else {
                shaped
            });
        };
        names
            .iter()
            .map(|n| {
                S::COORDINATES.iter().position(|c| c == n).ok_or_else(|| {
                    Error::from(SettingsError::Data {
                        owner: "scene",
                        problem: format!(
                            "cannot plot `{n}`: the coordinates are {:?}",
                            S::COORDINATES
                        ),
                    })
                })
            })
            .collect()
    }
}

/// Whether the description is planar: no body, every point in z = 0; shown
/// in its plane with y up.
fn is_planar(f: &sample::Frames, bodies: usize) -> bool {
    bodies == 0 && f.points.chunks(3).all(|p| p[2] == 0.0)
}

impl<T: Real, const N: usize, const Q: usize> Trajectory<T, N, Q> {
    /// A [`Scene`] of this run of `sys`, to write as a page:
    /// `traj.scene(&sys).write_html("run.html")?`. Add runs to overlay with
    /// [`Scene::run`].
    pub fn scene<'a, S: Posed<T, N, Q> + Lagrangian<T, N, Q>>(
        &'a self,
        sys: &'a S,
    ) -> Scene<'a, T, N, S, Q> {
        Scene::new(sys).run(self, "run")
    }
}

impl<'a, T: Real, const N: usize, S: Posed<T, N> + Lagrangian<T, N>> Scene<'a, T, N, S> {
    /// Adds a run through the atlas, drawn in the user's coordinates: at
    /// each stored point every rotation's angles read in the user's chart
    /// (a rotation has angles in any chart), whatever chart the run
    /// computed it in; frames at the stored points. Its trajectory as
    /// computed ([`AtlasRun::charted`]) holds the second chart's angles
    /// where a rotation is in it, which the description's poses would draw
    /// as a different rotation: that is why a scene takes the run, not its
    /// points.
    pub fn atlas_run<const P: usize>(
        self,
        run: &AtlasRun<T, N, P>,
        label: impl Into<String>,
    ) -> Self {
        self.add(Cow::Owned(run.user_points().0), label.into())
    }
}

impl<T: Real, const N: usize, const P: usize> AtlasRun<T, N, P> {
    /// A [`Scene`] of this run of `sys`, drawn as [`Scene::atlas_run`]
    /// draws it (each rotation in the user's chart at every point).
    pub fn scene<'a, S: Posed<T, N> + Lagrangian<T, N>>(&self, sys: &'a S) -> Scene<'a, T, N, S> {
        Scene::new(sys).atlas_run(self, "run")
    }
}
