//! Controlled simulation: the builder ([`ControlledSimulation`]), the
//! piecewise driver (`drive`) and its result ([`ControlRun`], `run`).

mod drive;

pub(crate) use drive::Driver;
mod run;

pub use run::ControlRun;

use super::Simulation;
use crate::control::{Feedback, InputSource, IntoInput, OpenLoop, Sampled};
use crate::error::{Failure, unit_quaternions};
use crate::event::{Event, Events};
use crate::numeric::Real;
use crate::ode::{Integrator, check_problem};
use crate::system::{Constrained, Driven, Lagrangian, Reduced};
use nalgebra::SVector;
use std::ops::Range;

impl<'a, S, I: Integrator> Simulation<'a, S, I> {
    /// Drives the system with continuous feedback u = `k(t, q, q̇)`, evaluated
    /// inside the right-hand side at every stage. `k` returns `[T; P]` or
    /// `SVector<T, P>` with P the number of the system's
    /// [inputs](Driven::INPUTS): returning another number of inputs does not
    /// compile. `k` must be a pure function of its arguments (the integrator
    /// calls it at trial states, several times per step).
    ///
    /// ```
    /// # use lagrange_runtime::{Driven, Dopri5, Lagrangian, Simulation};
    /// # use nalgebra::{Matrix1, SMatrix, Vector1};
    /// # struct Cart;
    /// # impl Lagrangian<f64, 1> for Cart {
    /// #     const COORDINATES: [&'static str; 1] = ["x"];
    /// #     const RHEONOMIC: bool = false;
    /// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
    /// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
    /// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    /// #     }
    /// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
    /// #     fn potential_energy(&self, _: &Vector1<f64>, _: f64) -> f64 { 0.0 }
    /// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 { self.kinetic_energy(q, v, t) }
    /// # }
    /// # impl Driven<f64, 1, 1> for Cart {
    /// #     const INPUTS: [&'static str; 1] = ["force"];
    /// #     fn input_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, u: &Vector1<f64>, _: f64) -> Vector1<f64> { *u }
    /// #     fn input_jacobians(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: &Vector1<f64>, _: f64)
    /// #         -> (SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>) {
    /// #         (SMatrix::identity(), SMatrix::zeros(), SMatrix::zeros())
    /// #     }
    /// # }
    /// // A unit mass under critically damped PD control: x = (1 + t) e^{−t}.
    /// let run = Simulation::new(&Cart)
    ///     .integrator(Dopri5::tol(1e-12))
    ///     .feedback(|_, q, v| [-q[0] - 2.0 * v[0]])
    ///     .run([1.0], [0.0], 0.0..3.0)?;
    /// let (x, _) = run.trajectory().final_state();
    /// assert!((x[0] - 4.0 * (-3.0f64).exp()).abs() < 1e-10);
    /// assert_eq!(run.inputs()[0][0], -1.0); // u at t = 0
    /// let mut csv = Vec::new();
    /// run.write_csv(&mut csv)?;
    /// assert!(String::from_utf8(csv).unwrap().starts_with("t,x,dot_x,force,integral,"));
    /// # Ok::<(), lagrange_runtime::Error>(())
    /// ```
    pub fn feedback<'e, T, F, U, const N: usize, const P: usize, const Q: usize>(
        self,
        k: F,
    ) -> ControlledSimulation<'a, 'e, S, I, Feedback<F>, T, N, P, Q>
    where
        T: Real,
        S: Lagrangian<T, N, Q> + Driven<T, N, P, Q>,
        F: Fn(T, &SVector<T, Q>, &SVector<T, N>) -> U,
        U: IntoInput<T, P>,
    {
        self.control(Feedback::new(k))
    }

    /// Drives the system with a sampled controller and zero-order hold: u_k =
    /// `k(t_k, q_k, q̇_k)` at t_k = t₀ + k·`period`, held until the next sample;
    /// the integrator restarts at every sample instant (see the
    /// [module docs](crate::control)). `k` may keep state between samples
    /// (`FnMut`): it is called once per sample, in time order. A period that is
    /// not positive and finite makes the run fail with
    /// [`Error::InvalidSettings`](crate::error::Error::InvalidSettings).
    pub fn sampled<'e, T, F, U, const N: usize, const P: usize, const Q: usize>(
        self,
        period: f64,
        k: F,
    ) -> ControlledSimulation<'a, 'e, S, I, Sampled<F>, T, N, P, Q>
    where
        T: Real,
        S: Lagrangian<T, N, Q> + Driven<T, N, P, Q>,
        F: FnMut(T, &SVector<T, Q>, &SVector<T, N>) -> U,
        U: IntoInput<T, P>,
    {
        self.control(Sampled::new(period, k))
    }

    /// Drives the system with an open-loop signal u(t), evaluated at every
    /// stage; `u` returns `[T; P]` or `SVector<T, P>`.
    pub fn open_loop<'e, T, F, U, const N: usize, const P: usize, const Q: usize>(
        self,
        u: F,
    ) -> ControlledSimulation<'a, 'e, S, I, OpenLoop<F>, T, N, P, Q>
    where
        T: Real,
        S: Lagrangian<T, N, Q> + Driven<T, N, P, Q>,
        F: Fn(T) -> U,
        U: IntoInput<T, P>,
    {
        self.control(OpenLoop::new(u))
    }

    /// Drives the system from any [`InputSource`]: an
    /// [`InputTable`](crate::InputTable), or a [`Feedback`], [`Sampled`] or
    /// [`OpenLoop`] built beforehand (the methods above build those with
    /// the closure's argument types inferred from the system).
    pub fn control<'e, T, C, const N: usize, const P: usize, const Q: usize>(
        self,
        source: C,
    ) -> ControlledSimulation<'a, 'e, S, I, C, T, N, P, Q>
    where
        T: Real,
        S: Lagrangian<T, N, Q> + Driven<T, N, P, Q>,
        C: InputSource<T, N, P, Q>,
    {
        ControlledSimulation {
            simulation: self,
            source,
            events: Events::new(),
        }
    }
}

/// A [`Simulation`] whose system is driven by an [`InputSource`]; built by
/// [`Simulation::feedback`], [`Simulation::sampled`], [`Simulation::open_loop`]
/// or [`Simulation::control`]. Configure the simulation (integrator, drift, ...)
/// before choosing the control; add events here.
#[derive(Debug)]
pub struct ControlledSimulation<
    'a,
    'e,
    S,
    I,
    C,
    T: Real,
    const N: usize,
    const P: usize,
    const Q: usize = N,
> {
    simulation: Simulation<'a, S, I>,
    source: C,
    pub(super) events: Events<'e, T, N, Q>,
}

impl<'a, 'e, S, I, C, T, const N: usize, const P: usize, const Q: usize>
    ControlledSimulation<'a, 'e, S, I, C, T, N, P, Q>
where
    I: Integrator,
    T: Real,
    S: Driven<T, N, P, Q>,
    C: InputSource<T, N, P, Q>,
{
    /// Watches `event` during the run (see [`Simulation::event`]); occurrences
    /// name events by the order they were added, from 0.
    pub fn event(mut self, event: Event<'e, T, N, Q>) -> Self {
        self.events = self.events.with(event);
        self
    }

    /// Sets how many events may stop and restart the integration (see
    /// [`Events::max_events`]); with a held source the budget applies per
    /// sample interval.
    pub fn max_events(mut self, n: usize) -> Self {
        self.events = self.events.max_events(n);
        self
    }

    /// The simulation without its control.
    pub fn simulation(&self) -> &Simulation<'a, S, I> {
        &self.simulation
    }

    /// The input source.
    pub fn source(&self) -> &C {
        &self.source
    }

    /// [`Simulation::run`] with the inputs applied: in the form the system's
    /// description asked for (for a constrained derived system the multiplier
    /// form, else the reduced form), like [`Simulation::run`].
    ///
    /// # Errors
    /// As [`Simulation::run`] (and [`Events::integrate`] with events);
    /// [`Error::NonFiniteInput`](crate::error::Error::NonFiniteInput) if an input is NaN or infinite;
    /// [`Error::InvalidSettings`](crate::error::Error::InvalidSettings) for a bad sampling period.
    pub fn run(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ControlRun<T, N, P, Q>, Failure<ControlRun<T, N, P, Q>>> {
        let start = super::form::Start {
            builder: self,
            q0: q0.into(),
            v0: v0.into(),
            span,
        };
        self.simulation.system.visit_form(start)
    }

    /// [`run`](Self::run) with the unconstrained dynamics (refused at compile
    /// time for a constrained system).
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn run_unconstrained(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ControlRun<T, N, P, Q>, Failure<ControlRun<T, N, P, Q>>> {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let terms = sim.system.parameter_terms();
        let dynamics = sim.dynamics::<T>().with_parameter_terms(&terms);
        let prepare = || {
            sim.check_singular_tolerance()?;
            check_problem(span.start, span.end, &q0, &v0)?;
            Ok((unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q0)?, v0))
        };
        self.driver().drive(
            |f| dynamics.with_forcing(f),
            span.clone(),
            (q0, v0),
            prepare,
        )
    }

    /// [`Simulation::run_constrained`] with the inputs applied: the same
    /// consistency check (or projection) of the initial state and drift control.
    ///
    /// # Errors
    /// As [`Simulation::run_constrained`] and [`run`](Self::run).
    pub fn run_constrained<const K: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ControlRun<T, N, P, Q>, Failure<ControlRun<T, N, P, Q>>>
    where
        S: Constrained<T, N, K, Q>,
    {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let terms = sim.system.parameter_terms();
        let dynamics = sim
            .constrained_dynamics::<T, K>()
            .with_parameter_terms(&terms);
        let prepare = || {
            check_problem(span.start, span.end, &q0, &v0)?;
            let (_, q0, v0) = sim.prepare_constrained::<T, N, K, Q>(span.start, q0, v0)?;
            Ok((q0, v0))
        };
        self.driver().drive(
            |f| dynamics.with_forcing(f),
            span.clone(),
            (q0, v0),
            prepare,
        )
    }

    /// [`Simulation::run_reduced`] with the inputs applied: F* gains Wᵀ ΔQ.
    ///
    /// # Errors
    /// As [`Simulation::run_reduced`] and [`run`](Self::run).
    pub fn run_reduced<const K: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ControlRun<T, N, P, Q>, Failure<ControlRun<T, N, P, Q>>>
    where
        S: Reduced<T, N, K, Q>,
    {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let terms = sim.system.parameter_terms();
        let dynamics = sim.reduced_dynamics::<T, K>().with_parameter_terms(&terms);
        let prepare = || sim.prepare_reduced(&dynamics, &span, q0, v0);
        self.driver().drive(
            |f| dynamics.with_forcing(f),
            span.clone(),
            (q0, v0),
            prepare,
        )
    }
}
