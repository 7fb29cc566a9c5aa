//! The formulations a run integrates: the unconstrained dynamics, the
//! multiplier form and the reduced form. Each builds its dynamics for the
//! forcing a run's options bring (none, or a controller's inputs) and checks
//! a run's start: every run of every builder option goes through
//! [`Formulation::start`], so the checks live here and nowhere else.

use super::Settings;
use crate::error::{ContactError, ContactFault, Error, Failure, SettingsError, unit_quaternions};
use crate::mechanics::constraint::ConstrainedDynamics;
use crate::mechanics::dynamics::Dynamics;
use crate::mechanics::reduced::ReducedDynamics;
use crate::mechanics::{Forcing, NoForcing, Rattle};
use crate::numeric::Real;
use crate::ode::{SecondOrder, Trajectory, check_problem, failed_at_start};
use crate::system::JointLimit;
use crate::system::{Constrained, Lagrangian, Reduced};
use nalgebra::SVector;
use std::ops::Range;

/// A formulation of a system's motion, ready to integrate.
///
/// Public only so that the run methods can name it in their bounds; it is
/// not re-exported and cannot be implemented outside the crate.
pub trait Formulation<T: Real, const N: usize, const Q: usize> {
    /// The dynamics with the forcing `G` added to Q − h.
    type Dynamics<G: Forcing<T, N, Q>>: SecondOrder<T, N, Q>;

    /// The dynamics with `forcing`.
    fn dynamics<G: Forcing<T, N, Q>>(&self, forcing: G) -> Self::Dynamics<G>;

    /// The checks of a run over `span` from (q0, v0): the settings, the
    /// system's parameters, the span and the initial state (quaternions
    /// scaled to unit norm), then the form's own (consistency with the
    /// constraints). Gives the state to start from.
    fn start(
        &self,
        span: &Range<T>,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<(SVector<T, Q>, SVector<T, N>), Error>;

    /// A run with RATTLE from the checked start, for a form that can hand it
    /// the holonomic constraints (the multiplier form); `None` for the
    /// others, where the method refuses the run as an integrator of
    /// accelerations. `limits` are the position limits the run watches,
    /// which RATTLE does not.
    fn rattle(
        &self,
        _rattle: &Rattle,
        _limits: &'static [JointLimit],
        _span: &Range<T>,
        _start: (SVector<T, Q>, SVector<T, N>),
    ) -> Option<RattleRun<T, N, Q>> {
        None
    }
}

/// What a run with RATTLE gives: the trajectory, or a failure with its part.
pub(super) type RattleRun<T, const N: usize, const Q: usize> =
    Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>>;

/// What every run checks first (the formulations here, and the atlas's
/// runs); gives q0 with its quaternions scaled to unit norm.
pub(super) fn checked_start<S, T, const N: usize, const Q: usize>(
    system: &S,
    settings: &Settings,
    span: &Range<T>,
    q0: SVector<T, Q>,
    v0: &SVector<T, N>,
) -> Result<SVector<T, Q>, Error>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    system.check_parameters()?;
    settings.check()?;
    check_problem(span.start, span.end, &q0, v0)?;
    refuse_contacts::<S, T, N, Q>(span.start, &q0)?;
    unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q0)
}

/// A system with contacts or stops is run by `run_contacts` alone: any
/// other run would let it pass through them without a word, which is worse
/// than no run.
fn refuse_contacts<S, T, const N: usize, const Q: usize>(
    t0: T,
    q0: &SVector<T, Q>,
) -> Result<(), Error>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    match S::CONTACTS.first() {
        None => Ok(()),
        Some(first) => Err(ContactError {
            contact: (*first).to_owned(),
            t: t0.to_f64(),
            q: q0.iter().map(|x| x.to_f64()).collect(),
            fault: ContactFault::NeedsContactRun,
        }
        .into()),
    }
}

/// The unconstrained dynamics, q̈ = M⁻¹ (Q − h).
pub(super) struct Unconstrained<'r, S, T> {
    pub settings: &'r Settings,
    pub dynamics: Dynamics<'r, S, T>,
}

impl<'r, S, T, const N: usize, const Q: usize> Formulation<T, N, Q> for Unconstrained<'r, S, T>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    type Dynamics<G: Forcing<T, N, Q>> = Dynamics<'r, S, T, G>;

    fn dynamics<G: Forcing<T, N, Q>>(&self, forcing: G) -> Self::Dynamics<G> {
        self.dynamics.with_forcing(forcing)
    }

    fn start(
        &self,
        span: &Range<T>,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<(SVector<T, Q>, SVector<T, N>), Error> {
        let q0 = checked_start(self.dynamics.system(), self.settings, span, q0, &v0)?;
        Ok((q0, v0))
    }
}

/// The multiplier form: the saddle-point system, with drift control.
pub(super) struct Multipliers<'r, S, T, const K: usize> {
    pub settings: &'r Settings,
    pub dynamics: ConstrainedDynamics<'r, S, T, K>,
}

impl<'r, S, T, const N: usize, const K: usize, const Q: usize> Formulation<T, N, Q>
    for Multipliers<'r, S, T, K>
where
    S: Constrained<T, N, K, Q>,
    T: Real,
{
    type Dynamics<G: Forcing<T, N, Q>> = ConstrainedDynamics<'r, S, T, K, G>;

    fn dynamics<G: Forcing<T, N, Q>>(&self, forcing: G) -> Self::Dynamics<G> {
        self.dynamics.with_forcing(forcing)
    }

    /// The initial state checked against the constraints at both levels, or
    /// projected onto them ([`Settings::project_initial`]).
    fn start(
        &self,
        span: &Range<T>,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<(SVector<T, Q>, SVector<T, N>), Error> {
        let q0 = checked_start(self.dynamics.system(), self.settings, span, q0, &v0)?;
        if self.settings.project_initial {
            return self.dynamics.consistent_state(span.start, q0, v0);
        }
        let tolerance = T::lit(self.settings.tolerances.consistency);
        (self.dynamics).check_consistency(span.start, &q0, &v0, tolerance)?;
        Ok((q0, v0))
    }

    /// RATTLE on the system's constraints, from the start checked (or
    /// projected) as any run of this form's; refused with position limits
    /// watched.
    fn rattle(
        &self,
        rattle: &Rattle,
        limits: &'static [JointLimit],
        span: &Range<T>,
        (q0, v0): (SVector<T, Q>, SVector<T, N>),
    ) -> Option<RattleRun<T, N, Q>> {
        let refuse = |e: Error| failed_at_start(&self.dynamics(NoForcing), span.start, q0, v0, e);
        if !limits.is_empty() {
            let e = SettingsError::Unsupported {
                owner: "RATTLE",
                needs: "a run without watched position limits (it does not stop at one)".into(),
                remedy: "`.joint_limits(LimitPolicy::Ignore)`, or another integrator".into(),
            };
            return Some(Err(refuse(e.into())));
        }
        Some(match self.start(span, q0, v0) {
            Ok((q, v)) => rattle.integrate(self.dynamics.system(), span.start, span.end, q, v),
            Err(e) => Err(refuse(e)),
        })
    }
}

/// The reduced form: independent speeds, no multipliers.
pub(super) struct Speeds<'r, S, T, const K: usize> {
    pub settings: &'r Settings,
    pub dynamics: ReducedDynamics<'r, S, T, K>,
}

impl<'r, S, T, const N: usize, const K: usize, const Q: usize> Formulation<T, N, Q>
    for Speeds<'r, S, T, K>
where
    S: Reduced<T, N, K, Q>,
    T: Real,
{
    type Dynamics<G: Forcing<T, N, Q>> = ReducedDynamics<'r, S, T, K, G>;

    fn dynamics<G: Forcing<T, N, Q>>(&self, forcing: G) -> Self::Dynamics<G> {
        self.dynamics.with_forcing(forcing)
    }

    /// v0 replaced by the admissible velocity with the same speeds.
    fn start(
        &self,
        span: &Range<T>,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<(SVector<T, Q>, SVector<T, N>), Error> {
        let q0 = checked_start(self.dynamics.system(), self.settings, span, q0, &v0)?;
        let v0 = self.dynamics.consistent_velocities(span.start, &q0, &v0)?;
        Ok((q0, v0))
    }
}
