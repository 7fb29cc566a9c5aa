//! Controlled simulation: the builder, the piecewise driver and its result.

use super::Simulation;
use crate::control::{
    Feedback, InputForces, InputSource, IntoInput, OpenLoop, Sampled, check_input,
};
use crate::error::{Error, Failure};
use crate::event::{Event, Events, Occurrence};
use crate::numeric::Real;
use crate::numeric::func::abs;
use crate::ode::Trajectory;
use crate::ode::{Integrator, Sample, SecondOrder, check_problem};
use crate::system::{Constrained, Driven, Lagrangian, Reduced};
use nalgebra::SVector;
use std::io::Write;
use std::ops::Range;
use std::path::Path;

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
    pub fn feedback<'e, T, F, U, const N: usize, const P: usize>(
        self,
        k: F,
    ) -> ControlledSimulation<'a, 'e, S, I, Feedback<F>, T, N, P>
    where
        T: Real,
        S: Lagrangian<T, N> + Driven<T, N, P>,
        F: Fn(T, &SVector<T, N>, &SVector<T, N>) -> U,
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
    /// [`Error::InvalidSettings`].
    pub fn sampled<'e, T, F, U, const N: usize, const P: usize>(
        self,
        period: f64,
        k: F,
    ) -> ControlledSimulation<'a, 'e, S, I, Sampled<F>, T, N, P>
    where
        T: Real,
        S: Lagrangian<T, N> + Driven<T, N, P>,
        F: FnMut(T, &SVector<T, N>, &SVector<T, N>) -> U,
        U: IntoInput<T, P>,
    {
        self.control(Sampled::new(period, k))
    }

    /// Drives the system with an open-loop signal u(t), evaluated at every
    /// stage; `u` returns `[T; P]` or `SVector<T, P>`.
    pub fn open_loop<'e, T, F, U, const N: usize, const P: usize>(
        self,
        u: F,
    ) -> ControlledSimulation<'a, 'e, S, I, OpenLoop<F>, T, N, P>
    where
        T: Real,
        S: Lagrangian<T, N> + Driven<T, N, P>,
        F: Fn(T) -> U,
        U: IntoInput<T, P>,
    {
        self.control(OpenLoop::new(u))
    }

    /// Drives the system from any [`InputSource`]: an
    /// [`InputTable`](crate::InputTable), or a [`Feedback`], [`Sampled`] or
    /// [`OpenLoop`] built beforehand (the methods above build those with
    /// the closure's argument types inferred from the system).
    pub fn control<'e, T, C, const N: usize, const P: usize>(
        self,
        source: C,
    ) -> ControlledSimulation<'a, 'e, S, I, C, T, N, P>
    where
        T: Real,
        S: Lagrangian<T, N> + Driven<T, N, P>,
        C: InputSource<T, N, P>,
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
pub struct ControlledSimulation<'a, 'e, S, I, C, T: Real, const N: usize, const P: usize> {
    simulation: Simulation<'a, S, I>,
    source: C,
    events: Events<'e, T, N>,
}

impl<'a, 'e, S, I, C, T, const N: usize, const P: usize>
    ControlledSimulation<'a, 'e, S, I, C, T, N, P>
where
    I: Integrator,
    T: Real,
    S: Driven<T, N, P>,
    C: InputSource<T, N, P>,
{
    /// Watches `event` during the run (see [`Simulation::event`]); occurrences
    /// name events by the order they were added, from 0.
    pub fn event(mut self, event: Event<'e, T, N>) -> Self {
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
    /// [`Error::NonFiniteInput`] if an input is NaN or infinite;
    /// [`Error::InvalidSettings`] for a bad sampling period.
    pub fn run(
        &self,
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ControlRun<T, N, P>, Failure<ControlRun<T, N, P>>> {
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
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ControlRun<T, N, P>, Failure<ControlRun<T, N, P>>> {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let terms = sim.system.parameter_terms();
        let dynamics = sim.dynamics::<T>().with_parameter_terms(&terms);
        let prepare = || {
            sim.check_singular_tolerance()?;
            check_problem(span.start, span.end, &q0, &v0)?;
            Ok((q0, v0))
        };
        self.drive(
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
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ControlRun<T, N, P>, Failure<ControlRun<T, N, P>>>
    where
        S: Constrained<T, N, K>,
    {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let terms = sim.system.parameter_terms();
        let dynamics = sim
            .constrained_dynamics::<T, K>()
            .with_parameter_terms(&terms);
        let prepare = || {
            check_problem(span.start, span.end, &q0, &v0)?;
            let (_, q0, v0) = sim.prepare_constrained::<T, N, K>(span.start, q0, v0)?;
            Ok((q0, v0))
        };
        self.drive(
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
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ControlRun<T, N, P>, Failure<ControlRun<T, N, P>>>
    where
        S: Reduced<T, N, K>,
    {
        let sim = &self.simulation;
        let (q0, v0) = (q0.into(), v0.into());
        let terms = sim.system.parameter_terms();
        let dynamics = sim.reduced_dynamics::<T, K>().with_parameter_terms(&terms);
        let prepare = || Ok((q0, sim.prepare_reduced(&dynamics, &span, q0, v0)?));
        self.drive(
            |f| dynamics.with_forcing(f),
            span.clone(),
            (q0, v0),
            prepare,
        )
    }

    /// Integrates piece by piece between the source's breaks (one piece when it
    /// has none), each piece with the dynamics `make` builds from its forcing.
    /// `prepare` checks the settings and gives the initial state to start from
    /// (projected, for the constrained forms). On a failure the run so far (the
    /// pieces, the failed piece's accepted steps, their inputs, the
    /// occurrences; the given initial state alone if none) goes back with the
    /// error.
    fn drive<'s, D: SecondOrder<T, N>>(
        &'s self,
        make: impl Fn(InputForces<'s, S, Piece<'s, C, T, P>, P>) -> D,
        span: Range<T>,
        (q0, v0): (SVector<T, N>, SVector<T, N>),
        prepare: impl FnOnce() -> Result<(SVector<T, N>, SVector<T, N>), Error>,
    ) -> Result<ControlRun<T, N, P>, Failure<ControlRun<T, N, P>>> {
        let started = crate::numeric::clock::Stopwatch::start();
        let mut record = Record {
            whole: None,
            inputs: Vec::new(),
            occurrences: Vec::new(),
            terminated_by: None,
        };
        let outcome =
            prepare().and_then(|(q, v)| self.pieces(&make, span.clone(), q, v, &mut record));
        let mut trajectory = match record.whole {
            Some(w) => w,
            None => {
                let rhs = make(InputForces::new(
                    self.simulation.system,
                    Piece::Live(&self.source),
                ));
                record.inputs = vec![self.source.input(span.start, &q0, &v0)];
                Trajectory::start(span.start, q0, v0, Sample::of(&rhs, span.start, &q0, &v0))
            }
        };
        let mut stats = *trajectory.stats();
        stats.wall_time = started.elapsed();
        trajectory.set_stats(stats);
        let run = ControlRun {
            trajectory,
            inputs: record.inputs,
            occurrences: record.occurrences,
            terminated_by: record.terminated_by,
            coordinates: S::COORDINATES,
            input_names: S::INPUTS,
        };
        match outcome {
            Ok(()) => Ok(run),
            Err(error) => Err(Failure::new(error, run)),
        }
    }

    /// The pieces of [`drive`](Self::drive), recorded into `record`.
    fn pieces<'s, D: SecondOrder<T, N>>(
        &'s self,
        make: &impl Fn(InputForces<'s, S, Piece<'s, C, T, P>, P>) -> D,
        span: Range<T>,
        q0: SVector<T, N>,
        v0: SVector<T, N>,
        record: &mut Record<T, N, P>,
    ) -> Result<(), Error> {
        self.source.check()?;
        let (t0, t1) = (span.start, span.end);
        let system: &'s S = self.simulation.system;
        let integrator = &self.simulation.integrator;
        // Breaks within this of each other (or of t1) are one instant.
        let eps = T::lit(64.0) * T::default_epsilon() * (abs(t0) + abs(t1));
        let held = self.source.held();
        let mut ends_on_break = false;
        let (mut t, mut q, mut v) = (t0, q0, v0);
        loop {
            // A piece cut by an event a round-off before its end leaves t
            // just short of a break: that break is this instant.
            let mut next = self.source.next_break(t0, t);
            while let Some(b) = next
                && b - t <= eps
            {
                next = self.source.next_break(t0, b);
            }
            let end = match next {
                Some(b) if b < t1 - eps => b,
                Some(b) => {
                    ends_on_break = b <= t1 + eps;
                    t1
                }
                None => t1,
            };
            let piece_source = if held {
                let u = self.source.input(t, &q, &v);
                check_input::<S, T, N, P>(t, &q, &v, &u)?;
                Piece::Held(u)
            } else {
                Piece::Live(&self.source)
            };
            let rhs = make(InputForces::new(system, piece_source));
            let (piece, stop) = if self.events.events().is_empty() {
                match integrator.integrate(&rhs, t, end, q, v) {
                    Ok(piece) => (piece, None),
                    Err(f) => {
                        self.record(*f.partial, piece_source, record, false)?;
                        return Err(f.error);
                    }
                }
            } else {
                match self.events.integrate(integrator, &rhs, t, end, q, v) {
                    Ok(run) => {
                        record.occurrences.extend(run.occurrences);
                        (run.trajectory, run.terminated_by)
                    }
                    Err(f) => {
                        record.occurrences.extend(f.partial.occurrences);
                        self.record(f.partial.trajectory, piece_source, record, false)?;
                        return Err(f.error);
                    }
                }
            };
            (q, v) = piece.final_state();
            let reached = *piece.times().last().expect("a trajectory holds its start");
            self.record(piece, piece_source, record, true)?;
            if stop.is_some() {
                record.terminated_by = stop;
                break;
            }
            if end >= t1 {
                break;
            }
            t = reached;
        }
        if held && ends_on_break && record.terminated_by.is_none() {
            // The end time is a sample instant: record the new sample there.
            let trajectory = record
                .whole
                .as_ref()
                .expect("the loop integrates at least one piece");
            let (q, v) = trajectory.final_state();
            let u = self.source.input(t1, &q, &v);
            check_input::<S, T, N, P>(t1, &q, &v, &u)?;
            *record.inputs.last_mut().expect("one input per point") = u;
        }
        Ok(())
    }

    /// Appends a piece and its inputs (one per point; the piece's first point
    /// replaces the last one recorded). With `check` a non-finite input is the
    /// error (after the piece is recorded); a failed piece's inputs are
    /// recorded as they are.
    fn record(
        &self,
        piece: Trajectory<T, N>,
        source: Piece<'_, C, T, P>,
        record: &mut Record<T, N, P>,
        check: bool,
    ) -> Result<(), Error> {
        if record.whole.is_some() {
            record.inputs.pop();
        }
        record.inputs.reserve(piece.len());
        let mut refused = Ok(());
        match source {
            Piece::Held(u) => record.inputs.extend(std::iter::repeat_n(u, piece.len())),
            Piece::Live(_) => {
                let points = piece.times().iter().zip(piece.positions());
                for ((&tk, qk), vk) in points.zip(piece.velocities()) {
                    let u = self.source.input(tk, qk, vk);
                    if check && refused.is_ok() {
                        refused = check_input::<S, T, N, P>(tk, qk, vk, &u);
                    }
                    record.inputs.push(u);
                }
            }
        }
        // The piece is recorded even when one of its inputs is refused: the
        // failure hands back everything computed, one input per point.
        match &mut record.whole {
            Some(w) => w.append(piece),
            None => record.whole = Some(piece),
        }
        refused
    }
}

/// A controlled run as it is recorded, piece by piece.
struct Record<T: Real, const N: usize, const P: usize> {
    whole: Option<Trajectory<T, N>>,
    inputs: Vec<SVector<T, P>>,
    occurrences: Vec<Occurrence<T, N>>,
    terminated_by: Option<usize>,
}

/// The source of one piece of a controlled run: a held sample or the source
/// itself.
#[derive(Debug)]
pub(crate) enum Piece<'c, C, T: Real, const P: usize> {
    Held(SVector<T, P>),
    Live(&'c C),
}

impl<C, T: Real, const P: usize> Clone for Piece<'_, C, T, P> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<C, T: Real, const P: usize> Copy for Piece<'_, C, T, P> {}

impl<C, T, const N: usize, const P: usize> InputSource<T, N, P> for Piece<'_, C, T, P>
where
    T: Real,
    C: InputSource<T, N, P>,
{
    #[inline]
    fn input(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> SVector<T, P> {
        match self {
            Piece::Held(u) => *u,
            Piece::Live(c) => c.input(t, q, v),
        }
    }
}

/// The result of a controlled run: the trajectory, the inputs at its points,
/// and the event occurrences.
#[derive(Clone, Debug)]
pub struct ControlRun<T: Real, const N: usize, const P: usize> {
    trajectory: Trajectory<T, N>,
    inputs: Vec<SVector<T, P>>,
    occurrences: Vec<Occurrence<T, N>>,
    terminated_by: Option<usize>,
    coordinates: [&'static str; N],
    input_names: [&'static str; P],
}

impl<T: Real, const N: usize, const P: usize> ControlRun<T, N, P> {
    /// The motion, concatenated across the restarts (samples, breakpoints,
    /// event actions); its statistics sum the pieces' work.
    pub fn trajectory(&self) -> &Trajectory<T, N> {
        &self.trajectory
    }

    /// The trajectory, dropping the rest.
    pub fn into_trajectory(self) -> Trajectory<T, N> {
        self.trajectory
    }

    /// The inputs at the trajectory's [`times`](Trajectory::times), one per
    /// point: the source's value at the stored time and state for continuous
    /// sources; for held sources the value in force on the step that ends
    /// there, or the new sample at a sample instant (see the
    /// [module docs](crate::control)).
    pub fn inputs(&self) -> &[SVector<T, P>] {
        &self.inputs
    }

    /// The inputs' names ([`Driven::INPUTS`]).
    pub fn input_names(&self) -> &[&'static str; P] {
        &self.input_names
    }

    /// The coordinates' names ([`Lagrangian::COORDINATES`]).
    pub fn coordinate_names(&self) -> &[&'static str; N] {
        &self.coordinates
    }

    /// Event occurrences, in time order.
    pub fn occurrences(&self) -> &[Occurrence<T, N>] {
        &self.occurrences
    }

    /// The terminal event that ended the run, if one did.
    pub fn terminated_by(&self) -> Option<usize> {
        self.terminated_by
    }

    /// Writes the recorded points as CSV: the header
    /// `t,<coordinates>,dot_<coordinates>,<inputs>` (e.g. `t,x,theta,dot_x,dot_theta,force`,
    /// named as in [`Trajectory::write_csv`]) and one row per point, numbers in
    /// the shortest form that reads back exactly.
    ///
    /// # Errors
    /// [`Error::Io`] if writing fails.
    pub fn write_csv(&self, w: impl Write) -> Result<(), Error> {
        self.table_of(crate::table::Table::new(
            &self.trajectory,
            &self.coordinates,
        )?)?
        .write(w)
    }

    /// The run as a [`Table`](crate::Table) with the inputs, the system's
    /// energies at every point and the other columns of
    /// [`Trajectory::table`].
    ///
    /// # Errors
    /// [`Error::InvalidSettings`] if the inputs do not match the points (they
    /// always do for a run built here).
    pub fn table<S: Lagrangian<T, N>>(
        &self,
        sys: &S,
    ) -> Result<crate::table::Table<'_, T, N>, Error> {
        self.table_of(self.trajectory.table(sys))
    }

    fn table_of<'t>(
        &'t self,
        table: crate::table::Table<'t, T, N>,
    ) -> Result<crate::table::Table<'t, T, N>, Error> {
        let names = self.input_names.iter().map(|s| s.to_string()).collect();
        let values = self
            .inputs
            .iter()
            .map(|u| u.iter().copied().collect())
            .collect();
        table.columns(names, values)
    }

    /// [`write_csv`](Self::write_csv) to a new file at `path` (buffered).
    ///
    /// # Errors
    /// As [`write_csv`](Self::write_csv), plus failure to create the file.
    pub fn save_csv(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let file = std::fs::File::create(path)?;
        self.write_csv(std::io::BufWriter::new(file))
    }
}
