//! The user-facing entry point: system + integrator + initial state → trajectory.

use crate::dynamics::{DEFAULT_SINGULAR_TOLERANCE, Dynamics};
use crate::error::Error;
use crate::ode::{Dopri5, Integrator};
use crate::real::Real;
use crate::system::Lagrangian;
use crate::trajectory::Trajectory;
use nalgebra::SVector;
use std::ops::Range;

/// A configured simulation of a [`Lagrangian`] system.
///
/// ```
/// # use lagrange_runtime::{Lagrangian, Simulation, Dopri5, Rk4};
/// # use nalgebra::{SMatrix, SVector, Vector1, Matrix1};
/// # struct Pendulum;
/// # impl Lagrangian<f64, 1> for Pendulum {
/// #     const COORDINATES: [&'static str; 1] = ["theta"];
/// #     const RHEONOMIC: bool = false;
/// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
/// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
/// #     fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-q[0].sin()) }
/// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
/// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
/// #     }
/// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
/// #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { -q[0].cos() }
/// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
/// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
/// #     }
/// # }
/// let sys = Pendulum;
/// let traj = Simulation::new(&sys)
///     .integrator(Dopri5::tol(1e-10))
///     .run([1.0], [0.0], 0.0..10.0)?;
/// assert!(traj.integral_drift() < 1e-8);
///
/// let coarse = Simulation::new(&sys)
///     .integrator(Rk4::step(1e-2))
///     .singular_tolerance(1e-10)
///     .run([1.0], [0.0], 0.0..1.0)?;
/// assert_eq!(coarse.len(), 101);
/// # Ok::<(), lagrange_runtime::Error>(())
/// ```
#[derive(Debug)]
pub struct Simulation<'a, S, I = Dopri5> {
    system: &'a S,
    integrator: I,
    singular_tolerance: f64,
}

impl<S, I: Clone> Clone for Simulation<'_, S, I> {
    fn clone(&self) -> Self {
        Self {
            system: self.system,
            integrator: self.integrator.clone(),
            singular_tolerance: self.singular_tolerance,
        }
    }
}

impl<'a, S> Simulation<'a, S> {
    /// A simulation of `system` with the default integrator ([`Dopri5::default`],
    /// tolerance 1e-8) and singular tolerance (1e-12).
    pub fn new(system: &'a S) -> Self {
        Self {
            system,
            integrator: Dopri5::default(),
            singular_tolerance: DEFAULT_SINGULAR_TOLERANCE,
        }
    }
}

impl<'a, S, I: Integrator> Simulation<'a, S, I> {
    /// Chooses the integrator.
    pub fn integrator<J: Integrator>(self, integrator: J) -> Simulation<'a, S, J> {
        Simulation {
            system: self.system,
            integrator,
            singular_tolerance: self.singular_tolerance,
        }
    }

    /// Sets the threshold on the mass matrix's pivot ratio min L_ii² / max L_ii²
    /// below which the run stops with [`Error::SingularMassMatrix`].
    pub fn singular_tolerance(mut self, tolerance: f64) -> Self {
        self.singular_tolerance = tolerance;
        self
    }

    /// The forward dynamics this simulation integrates.
    pub fn dynamics<T: Real>(&self) -> Dynamics<'a, S, T> {
        Dynamics::new(self.system).with_singular_tolerance(T::lit(self.singular_tolerance))
    }

    /// Integrates from (q0, v0) at `span.start` to `span.end`.
    ///
    /// # Errors
    /// [`Error::InvalidSettings`] for a bad singular tolerance, integrator setting,
    /// time span or initial state; otherwise whatever the dynamics or the
    /// integrator report ([`Error::SingularMassMatrix`], [`Error::NonFiniteState`],
    /// [`Error::StepSizeUnderflow`], [`Error::TooManySteps`]).
    pub fn run<T: Real, const N: usize>(
        &self,
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<Trajectory<T, N>, Error>
    where
        S: Lagrangian<T, N>,
    {
        let tol = self.singular_tolerance;
        if !(tol.is_finite() && tol >= 0.0) {
            return Err(Error::InvalidSettings(format!(
                "singular tolerance must be non-negative and finite, got {tol}"
            )));
        }
        self.integrator
            .integrate(&self.dynamics(), span.start, span.end, q0.into(), v0.into())
    }
}
