//! [`Simulation::run_atlas`] with an input source: a system written in Euler
//! angles, driven by its inputs through every orientation.

use super::atlas::AtlasRuns;
use super::drive::Driver;
use super::options::{Control, EventSlot};
use super::{ControlRun, Simulation};
use crate::atlas::{self, AtlasRun, Charted, Charts, Held, TwinForcing};
use crate::control::{InputForces, InputSource, check_input};
use crate::error::{Error, Failure};
use crate::event::Events;
use crate::numeric::Real;
use crate::ode::Integrator;
use crate::system::{Driven, DrivenAtlas};
use nalgebra::SVector;
use std::ops::Range;

/// A controlled atlas run: the inputs applied as [`Simulation::run`] applies
/// them, read on the user's coordinates (see [`Simulation::run_atlas`]).
impl<'e, S, I, C, E, T, const N: usize, const P: usize, const F: usize> AtlasRuns<T, N, F>
    for Simulation<'_, S, I, Control<C, T, N, P, N>, E>
where
    I: Integrator,
    T: Real,
    S: DrivenAtlas<T, N, P, F>,
    C: InputSource<T, N, P>,
    E: EventSlot<'e, T, N, N>,
{
    type Output = AtlasRun<T, N, P>;

    fn run_through_charts(
        &self,
        q0: SVector<T, N>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<Self::Output, Failure<Self::Output>> {
        self.events
            .read(|user| self.drive_through_charts(user, q0, v0, span))
    }
}

impl<S, I, C, E, T, const N: usize, const P: usize> Simulation<'_, S, I, Control<C, T, N, P, N>, E>
where
    I: Integrator,
    T: Real,
    S: Driven<T, N, P>,
    C: InputSource<T, N, P>,
{
    /// The controlled driver through the charts, watching the user's events.
    fn drive_through_charts<const F: usize>(
        &self,
        user: &Events<'_, T, N>,
        q0: SVector<T, N>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<AtlasRun<T, N, P>, Failure<AtlasRun<T, N, P>>>
    where
        S: DrivenAtlas<T, N, P, F>,
    {
        let charts = Charts::new(S::EULER);
        let into = |t, q: &SVector<T, N>, v: &SVector<T, N>| charts.user_view(t, q, v);
        let back = |t, held: &SVector<T, N>, q: &mut SVector<T, N>, v: &mut SVector<T, N>| {
            atlas::back_to_charts(&charts, t, held, q, v)
        };
        let user = user.events();
        let events = atlas::watched(user, &charts, S::EULER, &into, &back);
        let source = UserView {
            charts: &charts,
            inner: self.source(),
        };
        let driver = Driver {
            integrator: &self.integrator,
            system: self.system,
            source: &source,
            events: &events,
            limits: &[],
        };
        let terms = self.system.parameter_terms();
        let dynamics = self.dynamics::<T>().with_parameter_terms(&terms);
        let prepare = || {
            self.atlas_checks::<T, N, F>(&span, &q0, &v0)?;
            let mut q = q0;
            let mut v = v0;
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
