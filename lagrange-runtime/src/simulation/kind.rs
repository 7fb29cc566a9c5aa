//! What a builder's options make of a run: the integrator alone (a
//! [`Trajectory`]), the event driver (an [`EventRun`]), or the piecewise
//! driver of a controlled run (a [`ControlRun`], with the events' occurrences).
//! Each takes any [`Formulation`], which has already checked the start.

use super::drive::Driver;
use super::formulation::Formulation;
use super::options::{Control, EventSlot, NoEvents, Unforced};
use super::{ControlRun, Simulation};
use crate::control::InputSource;
use crate::error::Failure;
use crate::event::{EventRun, Events, LimitPolicy, Limited, watched};
use crate::mechanics::NoForcing;
use crate::numeric::Real;
use crate::ode::{Continuation, Integrator, Trajectory, failed_at_start};
use crate::study::Method;
use crate::system::{Driven, Lagrangian};
use nalgebra::SVector;
use std::ops::Range;

/// What a run of a [`Simulation`] with these options returns, and how it
/// integrates a formulation. Implemented for every combination of the
/// option slots; not meant to be implemented elsewhere.
#[diagnostic::on_unimplemented(
    message = "this simulation's options do not fit a run of {N} velocities and {Q} coordinates in `{T}`",
    label = "the events, the input source and the system must agree",
    note = "an input source must give the system's inputs (`InputSource<T, N, P, Q>`, see any error at `feedback`, `sampled`, `open_loop` or `control`), and events must be written for the same system and scalar"
)]
pub trait Runs<T: Real, const N: usize, const Q: usize> {
    /// The run's result: [`Trajectory`], [`EventRun`] or [`ControlRun`].
    type Output;

    /// Checks the start with `form` and integrates it over `span`.
    #[doc(hidden)]
    fn run_form<F: Formulation<T, N, Q>>(
        &self,
        form: &F,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<Self::Output, Failure<Self::Output>>;
}

impl<S, I, T, const N: usize, const Q: usize> Runs<T, N, Q>
    for Simulation<'_, S, I, Unforced, NoEvents>
where
    S: Lagrangian<T, N, Q>,
    I: Integrator,
    T: Real,
{
    type Output = Trajectory<T, N, Q>;

    fn run_form<F: Formulation<T, N, Q>>(
        &self,
        form: &F,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<Self::Output, Failure<Self::Output>> {
        let limits = watched(self.system.position_limits(), self.settings.limits);
        if let Some(Method::Rattle(rattle)) = method_in(&self.integrator)
            && let Some(run) = form.rattle(rattle, limits, &span, (q0, v0))
        {
            return run;
        }
        let dynamics = form.dynamics(NoForcing);
        let (q, v) = (form.start(&span, q0, v0))
            .map_err(|e| failed_at_start(&dynamics, span.start, q0, v0, e))?;
        let limited = Limited::new(&dynamics, limits, LimitPolicy::Stop);
        self.integrator
            .integrate(&limited, span.start, span.end, q, v)
    }
}

impl<'e, S, I, T, const N: usize, const Q: usize> Runs<T, N, Q>
    for Simulation<'_, S, I, Unforced, Events<'e, T, N, Q>>
where
    S: Lagrangian<T, N, Q>,
    I: Integrator,
    T: Real,
{
    type Output = EventRun<T, N, Q>;

    fn run_form<F: Formulation<T, N, Q>>(
        &self,
        form: &F,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<Self::Output, Failure<Self::Output>> {
        let dynamics = form.dynamics(NoForcing);
        let (q, v) = form.start(&span, q0, v0).map_err(|e| {
            failed_at_start(&dynamics, span.start, q0, v0, e).map(EventRun::unstarted)
        })?;
        let limits = watched(self.system.position_limits(), self.settings.limits);
        let from = Continuation::start(span.start);
        let t0 = span.start;
        let t1 = span.end;
        (self.events).continue_run(&self.integrator, (&dynamics, limits), from, t0, t1, q, v)
    }
}

impl<'e, S, I, C, E, T, const N: usize, const P: usize, const Q: usize> Runs<T, N, Q>
    for Simulation<'_, S, I, Control<C, T, N, P, Q>, E>
where
    S: Driven<T, N, P, Q>,
    I: Integrator,
    C: InputSource<T, N, P, Q>,
    E: EventSlot<'e, T, N, Q>,
    T: Real,
{
    type Output = ControlRun<T, N, P, Q>;

    fn run_form<F: Formulation<T, N, Q>>(
        &self,
        form: &F,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<Self::Output, Failure<Self::Output>> {
        let limits = watched(self.system.position_limits(), self.settings.limits);
        self.events.read(|events| {
            let driver = Driver {
                integrator: &self.integrator,
                system: self.system,
                source: &self.control.source,
                events,
                limits,
            };
            let start = || form.start(&span, q0, v0);
            driver.drive(|f| form.dynamics(f), span.clone(), (q0, v0), start)
        })
    }
}

/// The study's [`Method`] an integrator is, if it is one (RATTLE among them).
fn method_in<I: Integrator>(integrator: &I) -> Option<&Method> {
    integrator.as_any()?.downcast_ref::<Method>()
}
