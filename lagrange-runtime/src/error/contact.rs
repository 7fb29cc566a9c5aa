//! What a contact run cannot do: a rigid-contact problem without an answer,
//! or with many, and a start the contacts forbid.

use std::fmt;

/// A contact run stopped where rigid contact has no answer, or many, or
/// where the description's contacts are not usable (wrapped in
/// [`Error::Contact`](super::Error::Contact)). The run so far is kept in the
/// [`Failure`](super::Failure).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("contact `{contact}` at t = {t}, q = {q:?}: {fault}")]
pub struct ContactError {
    /// The contact's name.
    pub contact: String,
    /// When.
    pub t: f64,
    /// The configuration there.
    pub q: Vec<f64>,
    /// What is wrong.
    pub fault: ContactFault,
}

/// Why a contact run stopped.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ContactFault {
    /// The state penetrates the surface: the gap is below −tolerance (at the
    /// start, or after an event).
    Penetrates {
        /// The gap.
        gap: f64,
        /// The tolerance it missed.
        tolerance: f64,
    },
    /// Painlevé's paradox: while the contact slides, pressing it harder
    /// opens it faster (the normal row's effective compliance under the
    /// friction force, `n M⁻¹ (n − μ û·t)ᵀ`, is not positive), so the rigid
    /// problem has no solution or several.
    Painleve {
        /// The effective compliance.
        compliance: f64,
    },
    /// No set of contacts in force gives compressive normal forces, friction
    /// inside the cone and no penetrating acceleration.
    NoConsistentMode,
    /// The impulse problem of an impact has no solution (dependent contact
    /// normals, e.g. a body wedged between surfaces).
    NoImpulse,
    /// Newton's restitution law applied to simultaneous impacts would raise
    /// the kinetic energy, which no e ≤ 1 may do.
    ImpactGainsEnergy {
        /// Kinetic energy before.
        before: f64,
        /// Kinetic energy after.
        after: f64,
    },
    /// The time-stepping scheme's impulse problem of one step did not settle
    /// within its Gauss–Seidel sweeps ([`MoreauJean::sweeps`]): the last
    /// sweep still moved a contact's velocities by `change`. Raise the
    /// sweeps, loosen the tolerance, or shorten the step.
    ///
    /// [`MoreauJean::sweeps`]: crate::MoreauJean::sweeps
    ImpulsesUnsettled {
        /// The sweeps taken.
        sweeps: usize,
        /// How far the last sweep moved a contact's velocities.
        change: f64,
    },
    /// The system lists more contact laws than it gives rows for.
    MissingRows {
        /// The number of laws.
        laws: usize,
    },
    /// A run other than [`Simulation::run_contacts`] was asked of a system
    /// with contacts or stops ([`Lagrangian::CONTACTS`]): it would integrate
    /// the motion as if they were not there (a ball through its floor), so it
    /// is refused at its start.
    ///
    /// [`Simulation::run_contacts`]: crate::Simulation::run_contacts
    /// [`Lagrangian::CONTACTS`]: crate::Lagrangian::CONTACTS
    NeedsContactRun,
    /// The system's contact laws ([`Contacts::contact_laws`]) and its
    /// [`Lagrangian::CONTACTS`] disagree: the runs other than
    /// `run_contacts` read the latter to refuse a system with contacts, so a
    /// hand-written system that leaves a contact out of it would run through
    /// that contact elsewhere without a word.
    ///
    /// [`Contacts::contact_laws`]: crate::Contacts::contact_laws
    /// [`Lagrangian::CONTACTS`]: crate::Lagrangian::CONTACTS
    /// The error's `contact` is the first law whose name is not in its
    /// place in `CONTACTS` (or, where the laws run out first, the first
    /// name listed beyond them).
    NotListed {
        /// The names in `CONTACTS`.
        listed: &'static [&'static str],
    },
}

impl fmt::Display for ContactFault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ContactFault::Penetrates { gap, tolerance } => write!(
                f,
                "the state penetrates the surface (gap {gap:e}, tolerance {tolerance:e}); \
                 start on or above it"
            ),
            ContactFault::Painleve { compliance } => write!(
                f,
                "Painlevé's paradox: the sliding contact's effective normal compliance is \
                 {compliance:e} (not positive), so rigid contact with Coulomb friction has no \
                 answer or several here; lower the friction coefficient"
            ),
            ContactFault::NoConsistentMode => f.write_str(
                "no set of contacts in force gives compressive normal forces with friction \
                 inside the cone (rigid contact has no answer here)",
            ),
            ContactFault::NoImpulse => f.write_str(
                "the impact's impulse problem has no solution (dependent contact normals)",
            ),
            ContactFault::ImpactGainsEnergy { before, after } => write!(
                f,
                "Newton's law on these simultaneous impacts would raise the kinetic energy \
                 from {before} to {after}"
            ),
            ContactFault::ImpulsesUnsettled { sweeps, change } => write!(
                f,
                "the step's impulse problem did not settle in {sweeps} Gauss–Seidel sweeps (the \
                 last moved a contact's velocities by {change:e}); raise `MoreauJean::sweeps`, \
                 loosen its tolerance or shorten the step"
            ),
            ContactFault::MissingRows { laws } => write!(
                f,
                "the system lists {laws} contact laws but gives no rows for this one"
            ),
            ContactFault::NotListed { listed } => write!(
                f,
                "the system's contact laws and `Lagrangian::CONTACTS` = {listed:?} do not name \
                 the same contacts in the same order; list every law's name, in order, in \
                 `CONTACTS` (the derive does), so that runs other than `run_contacts` refuse \
                 the system"
            ),
            ContactFault::NeedsContactRun => f.write_str(
                "this run would ignore the system's contacts and stops (it would move through \
                 them); run it with `Simulation::run_contacts`",
            ),
        }
    }
}
