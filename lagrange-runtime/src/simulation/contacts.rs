//! The contact runs of the builder.

use super::{NoEvents, Simulation, Unforced};
use crate::contact::{ContactRun, run_contacts};
use crate::error::Failure;
use crate::numeric::Real;
use crate::ode::Integrator;
use crate::system::Contacts;
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
    pub fn run_contacts<T: Real, const N: usize>(
        &self,
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<ContactRun<T, N>, Failure<ContactRun<T, N>>>
    where
        S: Contacts<T, N>,
    {
        let singular = T::lit(self.settings.tolerances.singular);
        let state = (q0.into(), v0.into(), span);
        run_contacts(
            self.system,
            &self.integrator,
            (self.settings.contacts, self.settings.compliant),
            singular,
            state,
        )
    }
}
