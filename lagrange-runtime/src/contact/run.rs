//! What a contact run takes (its settings) and gives (the motion, the
//! changes of the contacts' modes, the forces on request).

use super::compliant::Compliant;
use super::form::{ContactForm, Mode};
use crate::error::{Error, Progress, SettingsError};
use crate::mechanics::{Forcing, NoForcing};
use crate::numeric::Real;
use crate::ode::Trajectory;
use crate::system::{Contacts, Driven};
use nalgebra::SVector;

/// The thresholds of a contact run
/// ([`Simulation::contact_settings`](crate::Simulation::contact_settings)).
///
/// They are in the units of the contacts' rows: speeds in the units of
/// `normal · q̇` (m/s for a point on a plane), gaps in those of the gap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactSettings {
    /// An impact that would leave a contact slower than this, while the free
    /// motion presses it back, closes it plastically (Zeno's accumulation of
    /// bounces, cut short); a contact at the surface moving this slowly
    /// counts as touching. Default 1e-6.
    pub rest_speed: f64,
    /// Below this slip speed a contact that starts to slide takes the
    /// direction friction gives it rather than the slip's, and a sliding
    /// contact whose slip has stopped counts as stopped. Default 1e-9.
    pub stick_speed: f64,
    /// How far below the surface a state may be (after round-off) before it
    /// counts as penetrating. Default 1e-9. The time stepper
    /// ([`MoreauJean`](crate::MoreauJean)) counts a contact closed once its
    /// gap is below this, and checks it only at the start (its steps sink by
    /// up to a step's travel at impact).
    pub gap_tolerance: f64,
    /// How many changes of mode a run may have. Default 10 000.
    pub max_changes: usize,
}

impl Default for ContactSettings {
    fn default() -> Self {
        Self {
            rest_speed: 1e-6,
            stick_speed: 1e-9,
            gap_tolerance: 1e-9,
            max_changes: 10_000,
        }
    }
}

impl ContactSettings {
    /// Each threshold positive and finite, the budget at least 1.
    pub(crate) fn check(&self) -> Result<(), Error> {
        let owner = "contact settings";
        for (setting, value) in [
            ("rest_speed", self.rest_speed),
            ("stick_speed", self.stick_speed),
            ("gap_tolerance", self.gap_tolerance),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(SettingsError::Value {
                    owner,
                    setting,
                    value,
                    requirement: "positive and finite".into(),
                }
                .into());
            }
        }
        if self.max_changes == 0 {
            return Err(SettingsError::ZeroCount {
                owner,
                setting: "max_changes",
            }
            .into());
        }
        Ok(())
    }
}

/// What a contact is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactState {
    /// Apart, or touching without force.
    Apart,
    /// Pressed, and slipping against Coulomb's friction.
    Sliding,
    /// Pressed, and not slipping.
    Sticking,
}

impl<T> From<Mode<T>> for ContactState {
    fn from(mode: Mode<T>) -> Self {
        match mode {
            Mode::Open => ContactState::Apart,
            Mode::Sliding { .. } => ContactState::Sliding,
            Mode::Sticking => ContactState::Sticking,
        }
    }
}

/// What happened to a contact at a change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ChangeKind<T> {
    /// An impact by Newton's law: the normal speeds before (negative,
    /// approaching) and after (−e times before; zero for a plastic one).
    Impact {
        /// The normal speed before.
        before: T,
        /// The normal speed after.
        after: T,
    },
    /// The contact closed, pressed, with no normal speed left to lose (for
    /// compliant contacts: the touch, or pressing again, at any speed).
    Closes,
    /// Zeno: an impact that would have left at `speed`, below the rest
    /// speed, closed the contact plastically; the bounces it cut short would
    /// have accumulated at `accumulation`.
    Rests {
        /// The speed the impact would have left with.
        speed: T,
        /// Where the bounces would have accumulated.
        accumulation: T,
    },
    /// The normal force fell to zero: the contact opened (for compliant
    /// contacts, while still sunk: the spring and damper let go).
    LiftsOff,
    /// The slip stopped and friction holds the contact.
    Sticks,
    /// The friction force reached the cone's edge: the contact slides.
    Slips,
}

/// A change of one contact's mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactChange<T> {
    /// When.
    pub t: T,
    /// Which contact (its index among the system's contact laws).
    pub contact: usize,
    /// What happened.
    pub kind: ChangeKind<T>,
}

/// The forces of one contact, in its normal and tangent axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactForce<T> {
    /// λ_n ≥ 0, the normal force (zero apart).
    pub normal: T,
    /// The friction force along the two tangents: holding a sticking
    /// contact, or −μ λ_n û on a sliding one.
    pub tangential: [T; 2],
}

/// A run with contacts: the motion, joined across the events, and every
/// change of a contact's mode.
#[derive(Clone, Debug)]
pub struct ContactRun<T: Real, const N: usize, const Q: usize = N> {
    /// The motion. At a change the point recorded is the state after it (an
    /// impact's velocities after the impulse).
    pub trajectory: Trajectory<T, N, Q>,
    /// The changes, in time order.
    pub changes: Vec<ContactChange<T>>,
    /// Each stretch's start and its contacts' modes.
    pub(crate) phases: Vec<(T, Vec<Mode<T>>)>,
    pub(crate) singular: T,
    pub(crate) stick_speed: T,
    /// The compliant model the run had, if any: its forces are the model's.
    pub(crate) compliant: Option<Compliant>,
}

impl<T: Real, const N: usize, const Q: usize> ContactRun<T, N, Q> {
    /// The contacts' modes at t (after the changes at t).
    pub fn states(&self, t: T) -> Vec<ContactState> {
        self.modes(t).iter().map(|&m| m.into()).collect()
    }

    fn modes(&self, t: T) -> &[Mode<T>] {
        let at = self.phases.iter().rposition(|(start, _)| *start <= t);
        at.map_or(&[], |k| &self.phases[k].1)
    }

    /// The changes of contact `contact`, in time order.
    pub fn of(&self, contact: usize) -> impl Iterator<Item = &ContactChange<T>> {
        self.changes.iter().filter(move |c| c.contact == contact)
    }

    /// The contact forces at the state (q, v) at t, in the modes of t (for
    /// a run with compliant contacts, the model's spring, damper and
    /// regularised friction at that state). For a run driven by inputs,
    /// [`forces_with`](Self::forces_with).
    ///
    /// # Errors
    /// Whatever the contacts' equations report there (a singular M, rows
    /// missing, dependent rows).
    pub fn forces<S: Contacts<T, N, Q>>(
        &self,
        system: &S,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<Vec<ContactForce<T>>, Error> {
        self.forces_under(system, &NoForcing, (t, q, v))
    }

    /// The contact forces at (q, v) at t of a run driven by inputs, given
    /// the inputs u there (the source's value at that state).
    ///
    /// # Errors
    /// As [`forces`](Self::forces).
    pub fn forces_with<S: Contacts<T, N, Q> + Driven<T, N, P, Q>, const P: usize>(
        &self,
        system: &S,
        t: T,
        (q, v): (&SVector<T, Q>, &SVector<T, N>),
        u: &SVector<T, P>,
    ) -> Result<Vec<ContactForce<T>>, Error> {
        let given = Given(system.input_forces(q, v, u, t));
        self.forces_under(system, &given, (t, q, v))
    }

    fn forces_under<S: Contacts<T, N, Q>, F: Forcing<T, N, Q>>(
        &self,
        system: &S,
        forcing: &F,
        (t, q, v): (T, &SVector<T, Q>, &SVector<T, N>),
    ) -> Result<Vec<ContactForce<T>>, Error> {
        let laws = system.contact_laws();
        let form = ContactForm {
            system,
            forcing,
            laws: &laws,
            modes: self.modes(t).to_vec(),
            singular: self.singular,
            stick_speed: self.stick_speed,
        };
        if let Some(model) = self.compliant {
            return model.forces(&form, t, q, v);
        }
        let solution = form.solve(t, q, v)?;
        Ok(solution
            .normal
            .iter()
            .zip(&solution.tangential)
            .map(|(&normal, &tangential)| ContactForce { normal, tangential })
            .collect())
    }
}

/// Generalized forces given at one state, whatever the state.
struct Given<T: Real, const N: usize>(SVector<T, N>);

impl<T: Real, const N: usize, const Q: usize> Forcing<T, N, Q> for Given<T, N> {
    fn force(&self, _: T, _: &SVector<T, Q>, _: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        Ok(self.0)
    }
}

impl<T: Real, const N: usize, const Q: usize> Progress for ContactRun<T, N, Q> {
    fn progress(&self) -> (usize, Option<f64>) {
        self.trajectory.progress()
    }
}
