//! [`ControlledSimulation::run_atlas`]: a system written in Euler angles,
//! driven by its inputs through every orientation.

use super::ControlledSimulation;
use super::controlled::{ControlRun, Driver};
use crate::atlas::{self, AtlasRun, Charted, Charts, Held, TwinForcing};
use crate::control::{InputForces, InputSource, check_input};
use crate::error::{Error, Failure, check_tolerance};
use crate::numeric::Real;
use crate::ode::{Integrator, check_problem};
use crate::system::{Driven, DrivenAtlas};
use nalgebra::SVector;
use std::ops::Range;

impl<S, I, C, T, const N: usize, const P: usize> ControlledSimulation<'_, '_, S, I, C, T, N, P>
where
    I: Integrator,
    T: Real,
    S: Driven<T, N, P>,
    C: InputSource<T, N, P>,
{
    /// [`Simulation::run_atlas`](crate::Simulation::run_atlas) with the
    /// inputs applied, as [`run`](Self::run) applies them: every source
    /// ([`feedback`](crate::Simulation::feedback),
    /// [`sampled`](crate::Simulation::sampled),
    /// [`open_loop`](crate::Simulation::open_loop), an
    /// [`InputTable`](crate::InputTable)) and the events, which read the
    /// user's coordinates as in
    /// [`EventSimulation::run_atlas`](crate::EventSimulation::run_atlas).
    ///
    /// The source sees the user's coordinates. In the user's chart they are
    /// the state itself; while a rotation is in its second chart they are
    /// its user's angles nearest those it had when it left the user's
    /// chart, and their rates E⁻¹ ω ([`AtlasRun::user_state`] reads the
    /// same). So a controller written for the user's description runs
    /// unchanged, and one that reads only the angles, or no state, is
    /// smooth through the user's singular set. The rates of the first and
    /// last angle grow as 1/s near that set (s the conditioning, |cos θ|
    /// for yaw–pitch–roll) and on the set itself are not defined: there
    /// they read NaN, and a controller that passes them on stops the run
    /// with [`Error::NonFiniteInput`]. In the second chart the inputs'
    /// generalized forces are the free twin's (`DrivenAtlas`), the same
    /// forces in its coordinates. The recorded inputs
    /// ([`AtlasRun::inputs`]) are the source's at each point, as
    /// [`ControlRun::inputs`](crate::ControlRun::inputs).
    ///
    /// # Errors
    /// As [`Simulation::run_atlas`](crate::Simulation::run_atlas) and
    /// [`run`](Self::run).
    pub fn run_atlas<const F: usize>(
        &self,
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<AtlasRun<T, N, P>, Failure<AtlasRun<T, N, P>>>
    where
        S: DrivenAtlas<T, N, P, F>,
    {
        let sim = self.simulation();
        let (q0, v0) = (q0.into(), v0.into());
        let charts = Charts::new(S::EULER);
        let into = |t, q: &SVector<T, N>, v: &SVector<T, N>| charts.user_view(t, q, v);
        let back = |t, held: &SVector<T, N>, q: &mut SVector<T, N>, v: &mut SVector<T, N>| {
            atlas::back_to_charts(&charts, t, held, q, v)
        };
        let user = self.events.events();
        let events = atlas::watched(user, &charts, S::EULER, &into, &back);
        let source = UserView {
            charts: &charts,
            inner: self.source(),
        };
        let driver = Driver {
            simulation: sim,
            source: &source,
            events: &events,
        };
        let terms = sim.system.parameter_terms();
        let dynamics = sim.dynamics::<T>().with_parameter_terms(&terms);
        let prepare = || {
            sim.check_singular_tolerance::<T, N, N>()?;
            check_problem(span.start, span.end, &q0, &v0)?;
            let tolerance = sim.constraints.consistency_tolerance;
            check_tolerance("consistency tolerance", tolerance)?;
            let c = &sim.constraints;
            let settings = (tolerance, c.drift, c.least_squares);
            atlas::check_start::<S, T, N, F>(sim.system, span.start, (&q0, &v0), settings)?;
            if !atlas::layout_agrees(sim.system) {
                return Err(Error::InvalidSettings(
                    "the system's Atlas twin does not have the documented layout".into(),
                ));
            }
            let (mut q, mut v) = (q0, v0);
            charts.enter_regular(span.start, &mut q, &mut v)?;
            Ok((q, v))
        };
        let make = |f| Charted::<S, T, N, F, _>::new(dynamics.with_forcing(f), &charts);
        let finish = |run: ControlRun<T, N, P>| {
            let held = Held {
                trajectory: run.trajectory,
                inputs: run.inputs,
                input_names: run.input_names,
                occurrences: run.occurrences,
                terminated_by: run.terminated_by,
            };
            atlas::finish(held, &charts, S::EULER, user.len())
        };
        match driver.drive(make, span.clone(), (q0, v0), prepare) {
            Ok(run) => Ok(finish(run)),
            Err(f) => Err(f.map(finish)),
        }
    }
}

/// A source read on the user's coordinates: the state held in the charts of
/// its time, viewed in the user's chart.
struct UserView<'c, C, T: Real> {
    charts: &'c Charts<T>,
    inner: &'c C,
}

impl<C, T, const N: usize, const P: usize> InputSource<T, N, P> for UserView<'_, C, T>
where
    T: Real,
    C: InputSource<T, N, P>,
{
    fn input(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> SVector<T, P> {
        let (q, v) = self.charts.user_view(t, q, v);
        self.inner.input(t, &q, &v)
    }
    fn next_break(&self, start: T, after: T) -> Option<T> {
        self.inner.next_break(start, after)
    }
    fn held(&self) -> bool {
        self.inner.held()
    }
    fn breaks_within(&self, start: T, end: T) -> Option<f64> {
        self.inner.breaks_within(start, end)
    }
    fn check(&self) -> Result<(), Error> {
        self.inner.check()
    }
}

/// In the second chart the inputs (read on the user's coordinates by the
/// source) act on the twin through its own forces.
impl<S, C, T, const N: usize, const P: usize, const F: usize> TwinForcing<S, T, N, F>
    for InputForces<'_, S, C, P>
where
    T: Real,
    S: DrivenAtlas<T, N, P, F>,
    C: InputSource<T, N, P>,
{
    fn free_force(
        &self,
        system: &S,
        t: T,
        (q, v): (&SVector<T, N>, &SVector<T, N>),
        (qf, vf): (&SVector<T, F>, &SVector<T, N>),
    ) -> Result<SVector<T, N>, Error> {
        let u = self.source().input(t, q, v);
        check_input::<S, T, N, P, N>(t, q, v, &u)?;
        Ok(system.free_input_forces(qf, vf, &u, t))
    }
}
