//! One integrator value that stands for any of the runtime's integrators, so that
//! a study can hand "the configuration to run" to a closure: [`Integrator`] has a
//! generic method and cannot be a trait object.

use crate::error::{Error, Failure, SettingsError};
use crate::mechanics::Rattle;
use crate::numeric::Real;
use crate::ode::{Continuation, Trajectory, failed_at_start};
use crate::ode::{Dop853, Dopri5, Gauss, Integrator, Radau5, Rk4, SecondOrder, StormerVerlet};
use nalgebra::SVector;
use std::fmt;

/// Any of the runtime's integrators, with its settings.
///
/// It implements [`Integrator`] itself, so a study's closure passes it on
/// unchanged: `|m| Simulation::new(&sys).integrator(m).run(q0, v0, span)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Classic fixed-step RK4.
    Rk4(Rk4),
    /// Dormand–Prince 5(4), adaptive.
    Dopri5(Dopri5),
    /// Dormand–Prince 8(5,3), adaptive.
    Dop853(Dop853),
    /// Velocity Verlet, fixed step.
    StormerVerlet(StormerVerlet),
    /// Gauss–Legendre collocation in (q, p), fixed step.
    Gauss(Gauss),
    /// Radau IIA of order 5, adaptive, for stiff systems.
    Radau5(Radau5),
    /// RATTLE, fixed step, for holonomic constraints with a constant mass
    /// matrix. It steps the constraints themselves, not accelerations: a
    /// `Simulation` runs it in the multiplier form (`run`, or
    /// `run_constrained`) of a system without events or inputs; anywhere
    /// else (an unconstrained system, the reduced form, events, inputs) the
    /// run fails with [`SettingsError::Unsupported`], a study's row with it.
    Rattle(Rattle),
}

macro_rules! from_integrator {
    ($($name:ident),*) => {$(
        impl From<$name> for Method {
            fn from(m: $name) -> Self {
                Method::$name(m)
            }
        }
    )*};
}
from_integrator!(Rk4, Dopri5, Dop853, StormerVerlet, Gauss, Radau5, Rattle);

impl Integrator for Method {
    fn continue_run<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        from: Continuation<T>,
        t0: T,
        t1: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>> {
        match self {
            Method::Rk4(m) => m.continue_run(rhs, from, t0, t1, q0, v0),
            Method::Dopri5(m) => m.continue_run(rhs, from, t0, t1, q0, v0),
            Method::Dop853(m) => m.continue_run(rhs, from, t0, t1, q0, v0),
            Method::StormerVerlet(m) => m.continue_run(rhs, from, t0, t1, q0, v0),
            Method::Gauss(m) => m.continue_run(rhs, from, t0, t1, q0, v0),
            Method::Radau5(m) => m.continue_run(rhs, from, t0, t1, q0, v0),
            Method::Rattle(_) => Err(failed_at_start(rhs, t0, q0, v0, rattle_elsewhere())),
        }
    }

    fn max_steps(&self) -> usize {
        match self {
            Method::Rk4(m) => m.max_steps(),
            Method::Dopri5(m) => m.max_steps(),
            Method::Dop853(m) => m.max_steps(),
            Method::StormerVerlet(m) => m.max_steps(),
            Method::Gauss(m) => m.max_steps(),
            Method::Radau5(m) => m.max_steps(),
            Method::Rattle(m) => m.step_budget(),
        }
    }

    /// Itself, so that a run of a constrained system finds RATTLE in it.
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
}

/// RATTLE asked to integrate accelerations alone: a run that cannot hand it
/// the constraints.
fn rattle_elsewhere() -> Error {
    SettingsError::Unsupported {
        owner: "RATTLE",
        needs: "a system's holonomic constraints themselves, in the multiplier form of a run \
                without events or inputs"
            .into(),
        remedy: "run a constrained system with `run` or `run_constrained` and no events, \
                 inputs or watched position limits; choose another integrator otherwise"
            .into(),
    }
    .into()
}

/// The swept parameter of one run: a fixed step size or a tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum Setting {
    /// Step size h of a fixed-step method.
    Step(f64),
    /// Tolerance (rtol = atol) of an adaptive method.
    Tolerance(f64),
}

impl Setting {
    /// The number: h or the tolerance.
    pub fn value(&self) -> f64 {
        match *self {
            Setting::Step(x) | Setting::Tolerance(x) => x,
        }
    }

    /// `"step"` or `"tolerance"`, the CSV's name for the kind.
    pub fn kind(&self) -> &'static str {
        match self {
            Setting::Step(_) => "step",
            Setting::Tolerance(_) => "tolerance",
        }
    }
}

impl fmt::Display for Setting {
    /// `h = 1e-2` or `tol = 1e-8`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Setting::Step(h) => write!(f, "h = {h:e}"),
            Setting::Tolerance(t) => write!(f, "tol = {t:e}"),
        }
    }
}

/// One method's sweep: a name (the table's and the legend's label) and the runs,
/// each a [`Setting`] with the integrator configured for it.
///
/// ```
/// use lagrange_runtime::study::Sweep;
/// use lagrange_runtime::{Dopri5, Rk4};
/// let rk4 = Sweep::steps("RK4", &[0.1, 0.05, 0.025], Rk4::step);
/// let dopri = Sweep::tolerances("DOPRI5", &[1e-4, 1e-8], |tol| Dopri5::tol(tol).max_steps(10_000));
/// assert_eq!(rk4.runs().len(), 3);
/// # let _ = dopri;
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    name: String,
    runs: Vec<(Setting, Method)>,
}

impl Sweep {
    /// An empty sweep; add runs with [`with`](Self::with).
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            runs: Vec::new(),
        }
    }

    /// Adds one run.
    pub fn with(mut self, setting: Setting, method: impl Into<Method>) -> Self {
        self.runs.push((setting, method.into()));
        self
    }

    /// A fixed-step method at each of `steps`: `make(h)` configures it.
    pub fn steps<M: Into<Method>>(
        name: impl Into<String>,
        steps: &[f64],
        make: impl Fn(f64) -> M,
    ) -> Self {
        steps
            .iter()
            .fold(Self::new(name), |s, &h| s.with(Setting::Step(h), make(h)))
    }

    /// An adaptive method at each of `tolerances`: `make(tol)` configures it.
    pub fn tolerances<M: Into<Method>>(
        name: impl Into<String>,
        tolerances: &[f64],
        make: impl Fn(f64) -> M,
    ) -> Self {
        tolerances.iter().fold(Self::new(name), |s, &tol| {
            s.with(Setting::Tolerance(tol), make(tol))
        })
    }

    /// The label.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The runs, in order.
    pub fn runs(&self) -> &[(Setting, Method)] {
        &self.runs
    }
}
