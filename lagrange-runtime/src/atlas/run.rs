//! What a run through the atlas hands back ([`AtlasRun`]).

use super::{ChartedTrajectory, angles, user_chart, user_view};
use crate::error::{Error, Progress};
use crate::event::Occurrence;
use crate::numeric::Real;
use crate::numeric::orientation;
use crate::ode::{Sample, Trajectory};
use crate::system::{EulerRotation, Lagrangian};
use crate::table::{Cell, Table};
use nalgebra::{Matrix3, SVector, Vector3};
use std::borrow::Cow;

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
/// The run computes every rotation's angles in the chart of the moment
/// ([`charted`](Self::charted), [`charts`](Self::charts)), which are the
/// user's angles only where that chart is the user's; so it hands out no
/// bare [`Trajectory`] of those numbers. Read the motion chart-free with
/// [`rotation`](Self::rotation) and [`quaternion`](Self::quaternion), in
/// the user's coordinates with [`user_state`](Self::user_state) wherever
/// their chart is valid (all of it as [`user_trajectory`](Self::user_trajectory)),
/// draw it with [`scene`](Self::scene), write it with [`table`](Self::table).
/// A switch's point holds the state after it.
///
/// A run with inputs ([`Simulation::run_atlas`](crate::Simulation::run_atlas) with an input source)
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

    /// The run as computed, each point in its own charts ([`ChartedTrajectory`]):
    /// what reads points without their charts (a scene, a table, a CSV,
    /// `crossings`) takes the run in the user's coordinates instead
    /// ([`user_trajectory`](Self::user_trajectory), [`scene`](Self::scene),
    /// [`table`](Self::table)).
    pub fn charted(&self) -> ChartedTrajectory<'_, T, N> {
        ChartedTrajectory {
            trajectory: &self.trajectory,
            charts: &self.charts,
            switches: &self.switches,
            start: self.start,
        }
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
        self.charted().charts_at(t)
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
        if (0..self.rotations.len()).any(|k| !self.user_valid(i, k)) {
            return None;
        }
        Some(self.user_view(i))
    }

    /// Whether rotation k's user chart is valid at point i (conditioning at
    /// least [`USER_CHART_VALID`]).
    fn user_valid(&self, i: usize, k: usize) -> bool {
        let user = user_chart(&self.rotations[k]);
        user.conditioning(&self.rotation(i, k)) >= T::lit(USER_CHART_VALID)
    }

    /// Point i in the user's chart, each rotation in its second chart read
    /// nearest the angles it had when it left the user's; the rates of a
    /// rotation where the user's chart is not valid are not finite.
    fn user_view(&self, i: usize) -> (SVector<T, N>, SVector<T, N>) {
        let t = self.trajectory.times()[i];
        let n = self.switches.partition_point(|s| s.t <= t);
        let near = |k: usize| {
            (self.switches[..n].iter().zip(&self.near).rev())
                .find(|(s, _)| s.rotation == k)
                .map_or(self.start_near[k], |(_, n)| *n)
        };
        user_view(
            self.rotations,
            self.charts[i],
            near,
            &self.trajectory.positions()[i],
            &self.trajectory.velocities()[i],
        )
    }

    /// Every point in the user's coordinates, with the cells that do not
    /// exist there: the rates of a rotation at a point where the user's
    /// chart is not valid (within [`USER_CHART_VALID`] of its singular set),
    /// held as zero in the trajectory and listed in the second part. The
    /// angles exist at every point (a rotation matrix has angles in any
    /// chart; only their rates blow up at its singular set).
    pub(crate) fn user_points(&self) -> (Trajectory<T, N>, Vec<(usize, usize)>) {
        let traj = &self.trajectory;
        let mut missing = Vec::new();
        let points = (0..traj.len())
            .map(|i| {
                let (q, mut v) = self.user_view(i);
                for (k, rotation) in self.rotations.iter().enumerate() {
                    if !self.user_valid(i, k) {
                        for &j in &rotation.coordinates {
                            v[j] = T::zero();
                            missing.push((i, j));
                        }
                    }
                }
                let sample = Sample {
                    integral: traj.integrals()[i],
                    residuals: traj.residuals()[i],
                    unit_error: T::zero(),
                };
                (traj.times()[i], q, v, sample)
            })
            .collect();
        let user = Trajectory::from_points(points, *traj.stats());
        (user.expect("a run has its first point"), missing)
    }

    /// The run in the user's coordinates, points only (no dense output, as
    /// a thinned recording): every point where [`user_state`](Self::user_state)
    /// has one, with its energy and statistics (the points within
    /// [`USER_CHART_VALID`] of the user's singular set are left out: their
    /// rates do not exist). What a figure of the user's description reads;
    /// its scene, every point drawn, is [`scene`](Self::scene).
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

    /// The run as a CSV table ([`Table`]) in the user's coordinates: t, q
    /// and q̇ by the system's names, each rotation's angles read in the
    /// user's chart at every point (nearest the angles it had when it left
    /// it, as [`user_state`](Self::user_state) reads them); then per
    /// rotation its chart (`<body>.chart`: 1 the user's, 2 the second, the
    /// one the run computed in) and its unit quaternion (`<body>.w`, `.x`,
    /// `.y`, `.z`, chart-free); with inputs, the inputs (named as in
    /// [`Driven::INPUTS`](crate::Driven::INPUTS)); then the energies and
    /// residuals as for any run.
    ///
    /// Where a rotation is within [`USER_CHART_VALID`] of the user's
    /// singular set its angles' rates do not exist (ω does, in the
    /// quaternion's derivative): those cells, and the kinetic energy's, are
    /// written empty.
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
        let (user, missing) = self.user_points();
        let mut blank = Vec::with_capacity(missing.len() * 2);
        for (i, j) in missing {
            if !matches!(blank.last(), Some(&(r, _)) if r == i) {
                blank.push((i, Cell::Kinetic));
            }
            blank.push((i, Cell::Rate(j)));
        }
        let table = Table::of_cow(Cow::Owned(user), sys).blank(blank);
        table.columns(names, values)
    }
}

impl<T: Real, const N: usize, const P: usize> Progress for AtlasRun<T, N, P> {
    fn progress(&self) -> (usize, Option<f64>) {
        self.trajectory.progress()
    }
}
