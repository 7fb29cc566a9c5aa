//! The trajectory of a run through the atlas as it was computed: every
//! point in the charts of its moment ([`ChartedTrajectory`]).
//!
//! Why a view and not a [`Trajectory`]: the numbers are the user's angles
//! only where every rotation is in the user's chart. Everything that reads
//! a `Trajectory` (a scene, a still, a CSV, a table, a plot, `crossings`,
//! `state_at`) would read the second chart's angles as the user's and draw,
//! write or locate a wrong rotation. The view hands out each number with
//! its chart, and nothing that reads points without charts; the run in the
//! user's coordinates is [`AtlasRun::user_trajectory`](super::AtlasRun::user_trajectory),
//! its scene [`AtlasRun::scene`](super::AtlasRun::scene), its table
//! [`AtlasRun::table`](super::AtlasRun::table).

use super::ChartSwitch;
use crate::numeric::Real;
use crate::ode::{Stats, Trajectory};
use nalgebra::SVector;

/// A run through the atlas as computed: q and q̇ hold each rotation's angles
/// in the chart of the moment, [`charts`](Self::charts) says which (bit k
/// set while rotation k is in its second chart).
#[derive(Clone, Copy, Debug)]
pub struct ChartedTrajectory<'a, T: Real, const N: usize> {
    pub(super) trajectory: &'a Trajectory<T, N>,
    pub(super) charts: &'a [u64],
    pub(super) switches: &'a [ChartSwitch<T>],
    pub(super) start: u64,
}

impl<'a, T: Real, const N: usize> ChartedTrajectory<'a, T, N> {
    /// The number of stored points.
    pub fn len(&self) -> usize {
        self.trajectory.len()
    }

    /// Whether there is no point (never, for a run).
    pub fn is_empty(&self) -> bool {
        self.trajectory.is_empty()
    }

    /// The times of the stored points.
    pub fn times(&self) -> &'a [T] {
        self.trajectory.times()
    }

    /// q at the stored points, each in the charts [`charts`](Self::charts)
    /// gives for it.
    pub fn positions(&self) -> &'a [SVector<T, N>] {
        self.trajectory.positions()
    }

    /// q̇ at the stored points, each in its point's charts.
    pub fn velocities(&self) -> &'a [SVector<T, N>] {
        self.trajectory.velocities()
    }

    /// Per point, which rotations are in their second chart (bit k for
    /// rotation k).
    pub fn charts(&self) -> &'a [u64] {
        self.charts
    }

    /// The charts at time t (bit k for rotation k): those after every switch
    /// at or before t (a switch's instant reads the state after it).
    pub fn charts_at(&self, t: T) -> u64 {
        (self.switches.iter())
            .take_while(|s| s.t <= t)
            .fold(self.start, |mask, s| mask ^ (1 << s.rotation))
    }

    /// The state at time t from the dense output, with the charts it is in
    /// (those after every switch at or before t); `None` outside the run or
    /// between the points of a thinned recording.
    pub fn state_at(&self, t: T) -> Option<(SVector<T, N>, SVector<T, N>, u64)> {
        let (q, v) = self.trajectory.state_at(t)?;
        Some((q, v, self.charts_at(t)))
    }

    /// The times at which `g(t, q, v, charts)` crosses zero, as
    /// [`Trajectory::crossings`] finds them; g is given each state with the
    /// charts it is in (those of [`charts_at`](Self::charts_at) its time),
    /// so it reads the angles in their own chart (or reads the rotation
    /// chart-free, through [`AtlasRun::rotation_at`](super::AtlasRun::rotation_at)).
    ///
    /// # Errors
    /// As [`Trajectory::crossings`] (a thinned recording).
    pub fn crossings(
        &self,
        g: impl Fn(T, &SVector<T, N>, &SVector<T, N>, u64) -> T,
    ) -> Result<Vec<T>, crate::error::Error> {
        (self.trajectory).crossings(|t, q, v| g(t, q, v, self.charts_at(t)))
    }

    /// The conserved integral at the stored points (chart-free: the same
    /// energy in either chart).
    pub fn integrals(&self) -> &'a [T] {
        self.trajectory.integrals()
    }

    /// The integral's largest drift relative to its start
    /// ([`Trajectory::integral_drift`]).
    pub fn integral_drift(&self) -> T {
        self.trajectory.integral_drift()
    }

    /// The constraint residuals at the stored points (chart-free).
    pub fn residuals(&self) -> &'a [[T; 2]] {
        self.trajectory.residuals()
    }

    /// The largest residuals ([`Trajectory::max_residuals`]).
    pub fn max_residuals(&self) -> [T; 2] {
        self.trajectory.max_residuals()
    }

    /// Work statistics of the run.
    pub fn stats(&self) -> &'a Stats {
        self.trajectory.stats()
    }
}
