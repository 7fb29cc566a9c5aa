//! What a run through the atlas hands back ([`AtlasRun`]).

use super::{angles, user_chart, user_view};
use crate::error::{Error, Progress};
use crate::event::Occurrence;
use crate::numeric::Real;
use crate::numeric::orientation;
use crate::ode::{Sample, Trajectory};
use crate::system::{EulerRotation, Lagrangian};
use crate::table::Table;
use nalgebra::{Matrix3, SVector, Vector3};

/// Where a rotation's angles may still be read in the user's chart: its
/// conditioning above this (θ one micro-radian from the pole of z-x-z).
pub const USER_CHART_VALID: f64 = 1e-6;

/// One change of chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChartSwitch<T> {
    /// When.
    pub t: T,
    /// Which rotation ([`Atlas::EULER`](crate::Atlas::EULER)'s order).
    pub rotation: usize,
    /// Into its second chart (`true`) or back into the user's.
    pub to_second: bool,
}

/// A run through the atlas: the trajectory, each point in the charts it was
/// computed in, and the switches between them.
///
/// The trajectory's q holds every rotation's angles in the chart of the
/// moment ([`charts`](Self::charts)); read the motion chart-free with
/// [`rotation`](Self::rotation) and [`quaternion`](Self::quaternion), or in
/// the user's coordinates with [`user_state`](Self::user_state) wherever
/// their chart is valid. A switch's point holds the state after it.
///
/// A run with inputs ([`ControlledSimulation::run_atlas`](crate::ControlledSimulation::run_atlas))
/// has P of them and records them at every point ([`inputs`](Self::inputs));
/// a run with events records the user's events' occurrences
/// ([`occurrences`](Self::occurrences)) in the user's coordinates, the
/// switches apart.
#[derive(Clone, Debug)]
pub struct AtlasRun<T: Real, const N: usize, const P: usize = 0> {
    pub(super) trajectory: Trajectory<T, N>,
    pub(super) switches: Vec<ChartSwitch<T>>,
    pub(super) rotations: &'static [EulerRotation],
    /// Per point, bit k set while rotation k is in its second chart.
    pub(super) charts: Vec<u64>,
    /// The charts the run started in, before any switch.
    pub(super) start: u64,
    /// The user's angles each rotation is read nearest after each switch,
    /// and after the start.
    pub(super) near: Vec<[T; 3]>,
    pub(super) start_near: Vec<[T; 3]>,
    pub(super) inputs: Vec<SVector<T, P>>,
    pub(super) input_names: [&'static str; P],
    pub(super) occurrences: Vec<Occurrence<T, N>>,
    pub(super) terminated_by: Option<usize>,
}

impl<T: Real, const N: usize, const P: usize> AtlasRun<T, N, P> {
    /// The inputs at the trajectory's points, one per point, as
    /// [`ControlRun::inputs`](crate::ControlRun::inputs) records them
    /// (empty without inputs).
    pub fn inputs(&self) -> &[SVector<T, P>] {
        &self.inputs
    }

    /// The inputs' names ([`Driven::INPUTS`](crate::Driven::INPUTS)).
    pub fn input_names(&self) -> &[&'static str; P] {
        &self.input_names
    }

    /// The user's events' occurrences, in time order, numbered by the order
    /// the events were added; their states in the user's coordinates (the
    /// angles nearest those each rotation had when it left the user's
    /// chart, as [`user_state`](Self::user_state) reads them).
    pub fn occurrences(&self) -> &[Occurrence<T, N>] {
        &self.occurrences
    }

    /// The times of the user's event `event`, in increasing order.
    pub fn times(&self, event: usize) -> Vec<T> {
        (self.occurrences.iter())
            .filter(|o| o.event == event)
            .map(|o| o.t)
            .collect()
    }

    /// The user's terminal event that ended the run, if one did.
    pub fn terminated_by(&self) -> Option<usize> {
        self.terminated_by
    }

    /// The trajectory, each point in its own charts.
    pub fn trajectory(&self) -> &Trajectory<T, N> {
        &self.trajectory
    }

    /// The trajectory, each point in its own charts.
    pub fn into_trajectory(self) -> Trajectory<T, N> {
        self.trajectory
    }

    /// Every switch, in time order.
    pub fn switches(&self) -> &[ChartSwitch<T>] {
        &self.switches
    }

    /// The rotations the atlas covers.
    pub fn rotations(&self) -> &'static [EulerRotation] {
        self.rotations
    }

    /// For each point, which rotations are in their second chart (bit k
    /// for rotation k).
    pub fn charts(&self) -> &[u64] {
        &self.charts
    }

    /// Rotation k's chart at point i.
    fn chart(&self, i: usize, k: usize) -> crate::numeric::euler::EulerChart {
        let user = user_chart(&self.rotations[k]);
        if self.charts[i] >> k & 1 == 1 {
            user.second()
        } else {
            user
        }
    }

    /// The charts at time t (bit k for rotation k): those after every switch
    /// at or before t (a switch's instant reads the state after it).
    pub fn charts_at(&self, t: T) -> u64 {
        (self.switches.iter())
            .take_while(|s| s.t <= t)
            .fold(self.start, |mask, s| mask ^ (1 << s.rotation))
    }

    /// Rotation k's matrix and body-axis angular velocity at time t, from the
    /// dense output read in the chart of that time; `None` outside the run
    /// (or between the stored points of a thinned recording).
    pub fn rotation_at(&self, t: T, k: usize) -> Option<(Matrix3<T>, Vector3<T>)> {
        let (q, v) = self.trajectory.state_at(t)?;
        let user = user_chart(&self.rotations[k]);
        let chart = if self.charts_at(t) >> k & 1 == 1 {
            user.second()
        } else {
            user
        };
        let rotation = &self.rotations[k];
        let x = angles(rotation, &q);
        Some((
            chart.matrix(x),
            chart.rates(x) * Vector3::from(angles(rotation, &v)),
        ))
    }

    /// Rotation k's matrix (body axes into the parent's) at point i: no chart.
    pub fn rotation(&self, i: usize, k: usize) -> Matrix3<T> {
        let q = &self.trajectory.positions()[i];
        self.chart(i, k).matrix(angles(&self.rotations[k], q))
    }

    /// Rotation k's unit quaternion (w, x, y, z), w ≥ 0, at point i.
    pub fn quaternion(&self, i: usize, k: usize) -> [T; 4] {
        orientation::from_rotation_matrix(&self.rotation(i, k))
    }

    /// Rotation k's angular velocity in body axes at point i.
    pub fn angular_velocity(&self, i: usize, k: usize) -> Vector3<T> {
        let (q, v) = (
            &self.trajectory.positions()[i],
            &self.trajectory.velocities()[i],
        );
        let rotation = &self.rotations[k];
        self.chart(i, k).rates(angles(rotation, q)) * Vector3::from(angles(rotation, v))
    }

    /// Point i in the user's coordinates, or `None` where some rotation is
    /// within [`USER_CHART_VALID`] of the user's singular set (there the
    /// angles' rates are unbounded). A rotation in its second chart is read
    /// in the user's chart nearest the angles it had when it left it, so
    /// the user's angles run on continuously across switches (up to 2π if
    /// it stays away long enough to wind round).
    pub fn user_state(&self, i: usize) -> Option<(SVector<T, N>, SVector<T, N>)> {
        for k in 0..self.rotations.len() {
            let user = user_chart(&self.rotations[k]);
            if user.conditioning(&self.rotation(i, k)) < T::lit(USER_CHART_VALID) {
                return None;
            }
        }
        let t = self.trajectory.times()[i];
        let n = self.switches.partition_point(|s| s.t <= t);
        let near = |k: usize| {
            (self.switches[..n].iter().zip(&self.near).rev())
                .find(|(s, _)| s.rotation == k)
                .map_or(self.start_near[k], |(_, n)| *n)
        };
        Some(user_view(
            self.rotations,
            self.charts[i],
            near,
            &self.trajectory.positions()[i],
            &self.trajectory.velocities()[i],
        ))
    }

    /// The run in the user's coordinates, points only (no dense output, as
    /// a thinned recording): every point where [`user_state`](Self::user_state)
    /// has one, with its energy and statistics. What a figure or a
    /// [`Scene`](crate::Scene) of the user's description reads.
    pub fn user_trajectory(&self) -> Option<Trajectory<T, N>> {
        let traj = &self.trajectory;
        let points = (0..traj.len())
            .filter_map(|i| {
                let (q, v) = self.user_state(i)?;
                let sample = Sample {
                    integral: traj.integrals()[i],
                    residuals: traj.residuals()[i],
                    unit_error: T::zero(),
                };
                Some((traj.times()[i], q, v, sample))
            })
            .collect();
        Trajectory::from_points(points, *traj.stats())
    }

    /// The run as a CSV table ([`Table`]): q and q̇ as held (each rotation's
    /// angles in the chart of the moment), then per rotation its chart
    /// (`<body>.chart`: 1 the user's, 2 the second) and its unit quaternion
    /// (`<body>.w`, `.x`, `.y`, `.z`, chart-free), then the energies and
    /// residuals as for any run; with inputs, then the inputs (named as
    /// in [`Driven::INPUTS`](crate::Driven::INPUTS)).
    ///
    /// # Errors
    /// None in practice: the columns match the points by construction.
    pub fn table<S: Lagrangian<T, N>>(&self, sys: &S) -> Result<Table<'_, T, N>, Error> {
        let mut names = Vec::new();
        for r in self.rotations {
            names.push(format!("{}.chart", r.body));
            names.extend(["w", "x", "y", "z"].map(|c| format!("{}.{c}", r.body)));
        }
        let inputs = if self.inputs.len() == self.trajectory.len() {
            names.extend(self.input_names.iter().map(|n| n.to_string()));
            P
        } else {
            0
        };
        let values = (0..self.trajectory.len())
            .map(|i| {
                (0..self.rotations.len())
                    .flat_map(|k| {
                        let chart = T::lit(if self.chart(i, k).offset { 2.0 } else { 1.0 });
                        std::iter::once(chart).chain(self.quaternion(i, k))
                    })
                    .chain((0..inputs).map(|j| self.inputs[i][j]))
                    .collect()
            })
            .collect();
        Table::of(&self.trajectory, sys).columns(names, values)
    }
}

impl<T: Real, const N: usize, const P: usize> Progress for AtlasRun<T, N, P> {
    fn progress(&self) -> (usize, Option<f64>) {
        self.trajectory.progress()
    }
}
