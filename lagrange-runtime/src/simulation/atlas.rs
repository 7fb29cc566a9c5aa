//! [`Simulation::run_atlas`]: a system written in Euler angles, run through
//! every orientation by switching charts.

use super::Simulation;
use crate::atlas::{self, AtlasRun};
use crate::error::Failure;
use crate::numeric::Real;
use crate::ode::{Integrator, Sample, Trajectory};
use crate::system::Atlas;
use nalgebra::SVector;
use std::ops::Range;

impl<S, I: Integrator> Simulation<'_, S, I> {
    /// Runs a system that has an atlas (`emit(atlas)`) from (q0, v0), given in
    /// the user's coordinates, through every orientation: each Euler-angle
    /// rotation moves to its second chart when its own degrades and comes back
    /// when it can (see [`crate::atlas`]). [`run`](Self::run) on the same
    /// system stays in the user's chart and stops at its singular set with
    /// [`Error::SingularMassMatrix`](crate::Error::SingularMassMatrix): that is the opt-out.
    ///
    /// On the singular set itself (θ = 0 of z-x-z) the initial rates still
    /// fix ω = E q̇ (e.g. ψ̇ + φ̇ is the spin about the axis), which the
    /// second chart takes over exactly.
    ///
    /// # Errors
    /// As [`run`](Self::run); [`Error::InvalidSettings`](crate::Error::InvalidSettings) also for an [`Atlas`]
    /// whose free twin does not have the documented layout.
    pub fn run_atlas<T: Real, const N: usize, const F: usize>(
        &self,
        q0: impl Into<SVector<T, N>>,
        v0: impl Into<SVector<T, N>>,
        span: Range<T>,
    ) -> Result<AtlasRun<T, N>, Failure<AtlasRun<T, N>>>
    where
        S: Atlas<T, N, F>,
    {
        let (q0, v0) = (q0.into(), v0.into());
        let terms = self.system.parameter_terms();
        let dynamics = self.dynamics().with_parameter_terms(&terms);
        if let Err(error) = self.check_singular_tolerance::<T, N, N>() {
            let sample = Sample::of(&dynamics, span.start, &q0, &v0);
            let trajectory = Trajectory::start(span.start, q0, v0, sample);
            return Err(Failure::new(
                error,
                AtlasRun::unstarted(trajectory, S::EULER),
            ));
        }
        atlas::integrate(&self.integrator, dynamics, (span.start, span.end), q0, v0)
    }
}
