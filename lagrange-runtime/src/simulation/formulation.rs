//! The formulations a run integrates: the unconstrained dynamics, the
//! multiplier form and the reduced form. Each builds its dynamics for the
//! forcing a run's options bring (none, or a controller's inputs) and checks
//! a run's start: every run of every builder option goes through
//! [`Formulation::start`], so the checks live here and nowhere else.

use super::Settings;
use crate::error::{Error, unit_quaternions};
use crate::mechanics::Forcing;
use crate::mechanics::constraint::ConstrainedDynamics;
use crate::mechanics::dynamics::Dynamics;
use crate::mechanics::reduced::ReducedDynamics;
use crate::numeric::Real;
use crate::ode::{SecondOrder, check_problem};
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
}

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
    unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q0)
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
