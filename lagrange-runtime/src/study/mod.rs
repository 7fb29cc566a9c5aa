//! Work-precision studies: how much accuracy each integrator buys, and at what cost.
//!
//! A study sweeps integrators × settings (tolerances or step sizes) over one
//! initial value problem and measures, for every run,
//!
//! - the error of the positions at the final time against a reference (max norm),
//! - the largest relative drift of the conserved quantity along the run,
//! - the cost: right-hand-side evaluations, steps and wall time.
//!
//! The core knows nothing about systems: it takes a closure that runs one
//! configuration, so the same study drives [`Simulation::run`],
//! [`run_constrained`] and [`run_reduced`] alike. The reference is a closed form
//! q(t) when the problem has one, a trajectory the caller computed, or by default
//! a DOP853 run of the same closure at tolerance 1e-14 — checked against a second
//! run at 1e-13, whose distance estimates the reference's own error (beyond a
//! chaotic system's predictability horizon that estimate is large, and says that
//! no method's error can be measured there).
//!
//! A run that fails (a step budget exhausted on a stiff problem, a Newton
//! failure, a chart singularity) becomes a row holding its typed [`Error`]: a
//! failure is a result of the study, not a reason to stop it.
//!
//! ```
//! use lagrange_runtime::study::{Sweep, WorkPrecision};
//! use lagrange_runtime::{Dopri5, Lagrangian, Rk4, Simulation};
//! # use nalgebra::{Matrix1, Vector1};
//! # struct Oscillator;
//! # impl Lagrangian<f64, 1> for Oscillator {
//! #     const COORDINATES: [&'static str; 1] = ["x"];
//! #     const RHEONOMIC: bool = false;
//! #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
//! #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { -q }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
//! #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { 0.5 * q[0] * q[0] }
//! #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
//! #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
//! #     }
//! # }
//! let sys = Oscillator; // x'' = -x, x(0) = 1, x'(0) = 0
//! let study = WorkPrecision::new(|m| Simulation::new(&sys).integrator(m).run([1.0], [0.0], 0.0..10.0))
//!     .exact(|t| Vector1::new(t.cos()))
//!     .sweep(Sweep::steps("RK4", &[0.1, 0.01], Rk4::step))
//!     .sweep(Sweep::tolerances("DOPRI5", &[1e-6, 1e-10], Dopri5::tol))
//!     .run()?;
//! println!("{}", study.to_markdown());
//! let best = study.cheapest(1e-8).unwrap();
//! assert!(best.measurement().unwrap().error <= 1e-8);
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! [`Simulation::run`]: crate::Simulation::run
//! [`run_constrained`]: crate::Simulation::run_constrained
//! [`run_reduced`]: crate::Simulation::run_reduced

mod method;
#[cfg(feature = "plot")]
mod plot;
mod report;
mod result;

pub use method::{Method, Setting, Sweep};
pub use report::{CSV_COLUMNS, MARKDOWN_COLUMNS};
pub use result::{Measurement, ReferenceKind, Row, Study};

/// The owner named in a study's settings errors.
const STUDY: &str = "work-precision study";

use crate::error::Error;
use crate::error::SettingsError;
use crate::numeric::Real;
use crate::numeric::orientation::{self, Orientation};
use crate::ode::Dop853;
use crate::ode::Trajectory;
use nalgebra::SVector;
use std::time::Duration;

/// Tolerance of the default reference run (DOP853).
pub const REFERENCE_TOLERANCE: f64 = 1e-14;

/// Step budget of the default reference runs: generous, since a reference that
/// stops early leaves the whole study without a yardstick.
const REFERENCE_MAX_STEPS: usize = 50_000_000;

/// The closure that runs one configuration.
type RunFn<'a, T, const N: usize, const Q: usize> =
    Box<dyn Fn(Method) -> Result<Trajectory<T, N, Q>, Error> + 'a>;

/// The progress callback.
type RowFn<'a> = Box<dyn FnMut(&Row) + 'a>;

/// Where the reference positions come from.
enum Reference<'a, const N: usize, const Q: usize> {
    /// DOP853 at the given tolerance through the study's own closure.
    Computed { tolerance: f64, check: bool },
    /// A closed form q(t).
    Exact(Box<dyn Fn(f64) -> SVector<f64, Q> + 'a>),
    /// A trajectory the caller computed (e.g. in f64 for an f32 study).
    Given(Box<Trajectory<f64, N, Q>>),
}

/// A work-precision study under construction: the closure that runs one
/// configuration, the reference, the sweeps. [`run`](Self::run) measures it.
///
/// `T` is the scalar the runs compute in; errors and costs are reported in f64.
/// A configuration with orientations (Q numbers for N velocities) names them
/// with [`orientations`](Self::orientations).
pub struct WorkPrecision<'a, T: Real, const N: usize, const Q: usize = N> {
    run: RunFn<'a, T, N, Q>,
    reference: Reference<'a, N, Q>,
    layout: &'static [Orientation],
    sweeps: Vec<Sweep>,
    repeats: usize,
    repeat_budget: Duration,
    conservative: bool,
    uncertainty: Option<f64>,
    on_row: Option<RowFn<'a>>,
}

impl<'a, T: Real, const N: usize, const Q: usize> WorkPrecision<'a, T, N, Q> {
    /// A study of the problem that `run` integrates with the method it is given.
    /// The closure must integrate the same initial value problem every time; only
    /// the method changes.
    ///
    /// Defaults: a DOP853 reference at [`REFERENCE_TOLERANCE`] (checked against
    /// 1e-13), up to 5 timed repeats per run within 0.2 s, and a conserved
    /// integral (its drift is measured).
    ///
    /// The closure may return any error that converts into [`Error`], such as
    /// the [`Failure`](crate::Failure) of `Simulation::run`: a failed run is a
    /// row with its error, its partial trajectory is not measured.
    pub fn new<E: Into<Error>>(
        run: impl Fn(Method) -> Result<Trajectory<T, N, Q>, E> + 'a,
    ) -> Self {
        Self {
            run: Box::new(move |m| run(m).map_err(Into::into)),
            reference: Reference::Computed {
                tolerance: REFERENCE_TOLERANCE,
                check: true,
            },
            layout: &[],
            sweeps: Vec::new(),
            repeats: 5,
            repeat_budget: Duration::from_millis(200),
            conservative: true,
            uncertainty: None,
            on_row: None,
        }
    }

    /// The reference's own error (e.g. of a trajectory given with
    /// [`reference`](Self::reference), or a published figure): runs whose error
    /// is below it are marked as not resolved. Overrides the estimate of a
    /// computed reference.
    pub fn uncertainty(mut self, uncertainty: f64) -> Self {
        self.uncertainty = Some(uncertainty);
        self
    }

    /// Uses a closed form: `exact(t)` is the exact q(t). It is evaluated only at
    /// the runs' final time, so a solution known only there will do (a periodic
    /// motion after a whole number of periods is back at its initial state).
    pub fn exact(mut self, exact: impl Fn(f64) -> SVector<f64, Q> + 'a) -> Self {
        self.reference = Reference::Exact(Box::new(exact));
        self
    }

    /// Uses a reference trajectory computed by the caller (positions at the final
    /// time are read from its dense output). The way to give an f32 study an
    /// f64 reference.
    pub fn reference(mut self, reference: Trajectory<f64, N, Q>) -> Self {
        self.reference = Reference::Given(Box::new(reference));
        self
    }

    /// Computes the reference with DOP853 at `tolerance` through the study's
    /// closure (the default, at [`REFERENCE_TOLERANCE`]); with `check`, a second
    /// run at 10 × `tolerance` estimates the reference's own error.
    pub fn computed_reference(mut self, tolerance: f64, check: bool) -> Self {
        self.reference = Reference::Computed { tolerance, check };
        self
    }

    /// Names the orientations of a configuration that holds them (a system's
    /// `ORIENTATIONS`, quaternions in q and body-axis ω in v), so that the
    /// positions are compared on the group: an orientation's error is the
    /// angle between the run's rotation and the reference's (the rotation
    /// vector of q_ref⁻¹ ⊗ q), blind to the sign of the quaternion; the other
    /// coordinates are compared as they are. A study with Q ≠ N needs it.
    pub fn orientations(mut self, layout: &'static [Orientation]) -> Self {
        self.layout = layout;
        self
    }

    /// max |q − q_ref| over the coordinates, an orientation's entry the angle
    /// between the two rotations.
    fn distance(&self, q: &SVector<f64, Q>, exact: &SVector<f64, Q>) -> f64 {
        if self.layout.is_empty() {
            return max_distance(q, exact);
        }
        let mut delta = SVector::<f64, N>::zeros();
        orientation::difference(
            self.layout,
            exact.as_slice(),
            q.as_slice(),
            delta.as_mut_slice(),
        );
        let mut error = max_distance(&delta, &SVector::zeros());
        for o in self.layout {
            let angle = delta.fixed_rows::<3>(o.v).norm();
            error = if angle.is_nan() {
                f64::NAN
            } else {
                error.max(angle)
            };
        }
        error
    }

    /// Adds a method's sweep.
    pub fn sweep(mut self, sweep: Sweep) -> Self {
        self.sweeps.push(sweep);
        self
    }

    /// Times each run up to `repeats` times (at least once), repeating only while
    /// the time spent on that run stays below `budget`; the reported wall time is
    /// the median. Cheap runs are noisy, expensive ones are not.
    pub fn repeats(mut self, repeats: usize, budget: Duration) -> Self {
        self.repeats = repeats;
        self.repeat_budget = budget;
        self
    }

    /// Whether the system has a conserved integral (energy or Jacobi integral).
    /// With `false` no drift is reported (a dissipative or driven system).
    pub fn conservative(mut self, conservative: bool) -> Self {
        self.conservative = conservative;
        self
    }

    /// Calls `f` with every row as soon as it is measured (progress reports).
    pub fn on_row(mut self, f: impl FnMut(&Row) + 'a) -> Self {
        self.on_row = Some(Box::new(f));
        self
    }

    /// Runs the reference and every sweep.
    ///
    /// # Errors
    /// [`Error::Settings`] for zero repeats, a non-positive reference
    /// tolerance or one below the scalar's unit round-off ε (2.2e-16 in f64,
    /// which no run attains: refused rather than reported as attained); whatever the reference run reports if it fails (the study
    /// has no yardstick then). A failing *method* run is not an error: its row
    /// holds the error.
    pub fn run(mut self) -> Result<Study, Error> {
        if self.repeats == 0 {
            let setting = "repeats";
            return Err(SettingsError::ZeroCount {
                owner: STUDY,
                setting,
            }
            .into());
        }
        if let Some(u) = self.uncertainty
            && !(u.is_finite() && u >= 0.0)
        {
            return Err(SettingsError::Value {
                owner: STUDY,
                setting: "the reference's uncertainty",
                value: u,
                requirement: "non-negative and finite".into(),
            }
            .into());
        }
        if !orientation::fits(self.layout, Q, N) {
            return Err(SettingsError::Unsupported {
                owner: STUDY,
                needs: format!(
                    "the orientations of a configuration of {Q} numbers with {N} velocities"
                ),
                remedy: "name them with `.orientations(S::ORIENTATIONS)` so that rotations are \
                         compared on the group"
                    .into(),
            }
            .into());
        }
        let (reference_at, reference) = self.prepare_reference()?;
        let uncertainty = self.uncertainty.or(reference.uncertainty());
        let mut rows = Vec::new();
        for sweep in std::mem::take(&mut self.sweeps) {
            for &(setting, method) in sweep.runs() {
                let outcome = self.measure(method, &reference_at, uncertainty.unwrap_or(0.0));
                let row = Row {
                    method: sweep.name().to_string(),
                    setting,
                    outcome,
                };
                if let Some(f) = self.on_row.as_mut() {
                    f(&row);
                }
                rows.push(row);
            }
        }
        Ok(Study {
            reference,
            uncertainty,
            rows,
        })
    }

    /// The reference positions as a function of the final time, and its
    /// description.
    #[allow(clippy::type_complexity)]
    fn prepare_reference(
        &mut self,
    ) -> Result<(Box<dyn Fn(f64) -> Option<State<N, Q>> + 'a>, ReferenceKind), Error> {
        match std::mem::replace(
            &mut self.reference,
            Reference::Computed {
                tolerance: REFERENCE_TOLERANCE,
                check: false,
            },
        ) {
            Reference::Exact(f) => {
                Ok((Box::new(move |t| Some((f(t), None))), ReferenceKind::Exact))
            }
            Reference::Given(traj) => Ok((
                Box::new(move |t| traj.state_at(t).map(|(q, v)| (q, Some(v)))),
                ReferenceKind::Given,
            )),
            Reference::Computed { tolerance, check } => {
                if !(tolerance.is_finite() && tolerance > 0.0) {
                    return Err(SettingsError::Value {
                        owner: STUDY,
                        setting: "reference tolerance",
                        value: tolerance,
                        requirement: "positive and finite".into(),
                    }
                    .into());
                }
                // Below the scalar's unit round-off no run attains the
                // tolerance, and the study would report an accuracy the
                // reference does not have: refused, not clamped.
                let floor = T::default_epsilon().to_f64();
                if tolerance < floor {
                    let requirement = format!(
                        "at least what {} can attain, its unit round-off ε = {floor:e} \
                         (the default is {REFERENCE_TOLERANCE:e})",
                        std::any::type_name::<T>()
                    );
                    return Err(SettingsError::Value {
                        owner: STUDY,
                        setting: "reference tolerance",
                        value: tolerance,
                        requirement,
                    }
                    .into());
                }
                let dop853 = |tol| Method::Dop853(Dop853::tol(tol).max_steps(REFERENCE_MAX_STEPS));
                let started = crate::numeric::clock::Stopwatch::start();
                let traj = (self.run)(dop853(tolerance))?;
                let wall_time = started.elapsed();
                let uncertainty = if check {
                    let coarse = (self.run)(dop853(10.0 * tolerance))?;
                    let f64s = |q: SVector<T, Q>| q.map(|x| x.to_f64());
                    let fine = traj.final_state().0;
                    let coarse = coarse.final_state().0;
                    Some(self.distance(&f64s(fine), &f64s(coarse)))
                } else {
                    None
                };
                let kind = ReferenceKind::Computed {
                    tolerance,
                    evaluations: traj.stats().evaluations,
                    wall_time,
                    uncertainty,
                };
                let at = move |t: f64| {
                    traj.state_at(T::lit(t))
                        .map(|(q, v)| (q.map(|x| x.to_f64()), Some(v.map(|x| x.to_f64()))))
                };
                Ok((Box::new(at), kind))
            }
        }
    }

    /// Runs one configuration (repeated for timing) and measures it.
    fn measure(
        &self,
        method: Method,
        reference_at: &dyn Fn(f64) -> Option<State<N, Q>>,
        uncertainty: f64,
    ) -> Result<Measurement, Error> {
        let started = crate::numeric::clock::Stopwatch::start();
        let traj = (self.run)(method)?;
        let first = started.elapsed();
        let mut times = vec![first];
        let mut spent = first;
        while times.len() < self.repeats && spent < self.repeat_budget {
            let started = crate::numeric::clock::Stopwatch::start();
            // The runs are deterministic: only the time of a repeat is new.
            drop((self.run)(method)?);
            let elapsed = started.elapsed();
            times.push(elapsed);
            spent += elapsed;
        }
        times.sort();
        let wall_time = times[times.len() / 2];

        let t_end = traj.times()[traj.len() - 1].to_f64();
        let (exact, exact_v) = reference_at(t_end).ok_or_else(|| {
            Error::from(SettingsError::Data {
                owner: STUDY,
                problem: format!("the run ends at t = {t_end}, outside the reference"),
            })
        })?;
        let (q, v) = traj.final_state();
        let q = q.map(|x| x.to_f64());
        let v = v.map(|x| x.to_f64());
        let error = self.distance(&q, &exact);
        let size = exact.amax().max(1e-300);
        let size = if size > 1e-300 { size } else { 1.0 };
        let residual = traj
            .residuals()
            .iter()
            .fold(0.0f64, |m, r| m.max(r[0].to_f64()).max(r[1].to_f64()));
        Ok(Measurement {
            error,
            relative_error: error / size,
            velocity_error: exact_v.map(|ev| max_distance(&v, &ev)),
            residual,
            resolved: error.partial_cmp(&uncertainty) != Some(std::cmp::Ordering::Less),
            final_state: (q.iter().copied().collect(), v.iter().copied().collect()),
            drift: self.conservative.then(|| traj.integral_drift().to_f64()),
            stats: *traj.stats(),
            wall_time,
        })
    }
}

/// Reference positions and, when known, velocities at a time.
type State<const N: usize, const Q: usize> = (SVector<f64, Q>, Option<SVector<f64, N>>);

/// max_i |a_i − b_i|, NaN-propagating (a NaN must not pass for a small error).
fn max_distance<T: Real, const N: usize>(a: &SVector<T, N>, b: &SVector<T, N>) -> f64 {
    a.iter().zip(b.iter()).fold(0.0, |m: f64, (x, y)| {
        let d = (*x - *y).to_f64().abs();
        if d.is_nan() || m.is_nan() {
            f64::NAN
        } else {
            m.max(d)
        }
    })
}

#[cfg(test)]
mod tests;
