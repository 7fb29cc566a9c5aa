//! The contact runs of the builder.

use super::{Control, NoEvents, Simulation, Unforced};
use crate::contact::{ContactRun, run_contacts};
use crate::control::{HeldForces, InputForces, InputSource};
use crate::error::Error;
use crate::error::Failure;
use crate::mechanics::{Forcing, NoForcing};
use crate::numeric::Real;
use crate::ode::Integrator;
use crate::system::Contacts;
use crate::system::Driven;
use nalgebra::SVector;
use std::ops::Range;

impl<S, I: Integrator> Simulation<'_, S, I, Unforced, NoEvents> {
    /// Integrates a system with unilateral contacts ([`Contacts`]) from
    /// (q0, v0) at `span.start` to `span.end`, event by event: impacts by
    /// Newton's law, contacts in force as constraints whose normal force
    /// stays compressive, Coulomb friction sliding and sticking (see
    /// [`contact`](crate::contact)). The thresholds are
    /// [`contact_settings`](Self::contact_settings)'; the integrator is this
    /// simulation's, restarted at every change.
    ///
    /// With [`MoreauJean`](crate::MoreauJean) as the integrator the run is
    /// time-stepped instead: one impulse problem per fixed step over the
    /// contacts closed at its midpoint, friction at impacts, the changes on
    /// the step's grid (guide chapter 12, "Many contacts: time stepping").
    /// `max_changes` does not bound it (its steps are counted beforehand,
    /// against `MoreauJean::max_steps`). With
    /// [`compliant_contacts`](Self::compliant_contacts) the contacts are
    /// springs and dampers, and any integrator runs the motion in one piece.
    ///
    /// # Errors
    /// A [`Failure`] with the run so far: [`Error::Settings`] for a bad
    /// setting, span, state or law (e outside [0, 1], μ < 0);
    /// [`Error::Contact`] for a start that penetrates, Painlevé's paradox,
    /// an impact or a choice of modes without answer;
    /// [`Error::TooManyEvents`] past the budget of changes,
    /// [`Error::EventsAccumulate`] for changes that pile up at one instant;
    /// with `MoreauJean`, `ContactFault::ImpulsesUnsettled` for a step whose
    /// impulses did not settle; whatever the dynamics and the integrator
    /// report.
    ///
    /// [`Error::Settings`]: crate::Error::Settings
    /// [`Error::Contact`]: crate::Error::Contact
    /// [`Error::TooManyEvents`]: crate::Error::TooManyEvents
    /// [`Error::EventsAccumulate`]: crate::Error::EventsAccumulate
    pub fn run_contacts<T: Real, const N: usize, const Q: usize>(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ContactRun<T, N, Q>, Failure<ContactRun<T, N, Q>>>
    where
        S: Contacts<T, N, Q>,
    {
        self.contact_run(&NoForcing, Ok(()), (q0.into(), v0.into(), span))
    }
}

impl<S, I: Integrator, C, E> Simulation<'_, S, I, C, E> {
    /// The contact run of this simulation's system, integrator and contact
    /// settings, driven by `forcing`; `refused` is an error found before it.
    fn contact_run<T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>(
        &self,
        forcing: &F,
        refused: Result<(), Error>,
        state: (SVector<T, Q>, SVector<T, N>, Range<T>),
    ) -> Result<ContactRun<T, N, Q>, Failure<ContactRun<T, N, Q>>>
    where
        S: Contacts<T, N, Q>,
    {
        let singular = T::lit(self.settings.tolerances.singular);
        run_contacts(
            (self.system, forcing, refused),
            &self.integrator,
            (self.settings.contacts, self.settings.compliant),
            singular,
            state,
        )
    }
}

impl<S, I: Integrator, C, T: Real, const N: usize, const P: usize, const Q: usize>
    Simulation<'_, S, I, Control<C, T, N, P, Q>, NoEvents>
{
    /// [`run_contacts`](Simulation::run_contacts) driven by this
    /// simulation's input source: a motor's torque at a joint with
    /// friction, a legged robot's PD control with its feet on the ground.
    /// The inputs' forces join Q − h at every evaluation, through any of
    /// the three schemes; [`input_limits`](Self::input_limits) and
    /// [`speed_limits`](Self::speed_limits) clamp them. A continuous source
    /// ([`feedback`](Self::feedback), [`open_loop`](Self::open_loop), an
    /// interpolated [`InputTable`](crate::InputTable)) is evaluated at every
    /// stage; a held one ([`sampled`](Self::sampled), a hold table) is
    /// sampled at its instants and held between them: the event-driven and
    /// compliant runs stop there, the time stepper takes the sample at the
    /// step start nearest each instant (choose a step that divides the
    /// sample period). The run records the motion and the
    /// contacts' changes, not the inputs; [`ContactRun::forces_with`] gives
    /// the contact forces at a state given the input there.
    ///
    /// # Errors
    /// Those of [`run_contacts`](Simulation::run_contacts); also
    /// [`Error::Settings`] for the source's own settings, and
    /// [`Error::NonFiniteInput`] for an input that is NaN or infinite.
    ///
    /// [`ContactRun::forces_with`]: crate::ContactRun::forces_with
    pub fn run_contacts(
        &self,
        q0: impl Into<SVector<T, Q>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ContactRun<T, N, Q>, Failure<ContactRun<T, N, Q>>>
    where
        S: Contacts<T, N, Q> + Driven<T, N, P, Q>,
        C: InputSource<T, N, P, Q>,
    {
        let source = &self.control.source;
        let state = (q0.into(), v0.into(), span);
        if source.held() {
            let forcing = HeldForces::new(self.system, source);
            self.contact_run(&forcing, source.check(), state)
        } else {
            let forcing = InputForces::new(self.system, source);
            self.contact_run(&forcing, source.check(), state)
        }
    }
}
