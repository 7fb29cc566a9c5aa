//! A run through the atlas: the switching events, and what the run hands
//! back ([`AtlasRun`]).

use super::{Charted, LEAVE_BELOW, RETURN_ABOVE, angles, layout_agrees, user_chart};
use crate::error::{Error, Failure, Progress};
use crate::event::{Event, EventRun, Events};
use crate::mechanics::Dynamics;
use crate::numeric::Real;
use crate::numeric::orientation;
use crate::ode::{Integrator, Sample, Trajectory};
use crate::system::{Atlas, EulerRotation, Lagrangian};
use crate::table::Table;
use nalgebra::{Matrix3, SVector, Vector3};
use std::cell::RefCell;

/// Where a rotation's angles may still be read in the user's chart: its
/// conditioning above this (θ one micro-radian from the pole of z-x-z).
pub const USER_CHART_VALID: f64 = 1e-6;

/// One change of chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChartSwitch<T> {
    /// When.
    pub t: T,
    /// Which rotation ([`Atlas::EULER`]'s order).
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
#[derive(Clone, Debug)]
pub struct AtlasRun<T: Real, const N: usize> {
    trajectory: Trajectory<T, N>,
    switches: Vec<ChartSwitch<T>>,
    rotations: &'static [EulerRotation],
    /// Per point, bit k set while rotation k is in its second chart.
    charts: Vec<u64>,
    /// The charts the run started in, before any switch.
    start: u64,
}

impl<T: Real, const N: usize> AtlasRun<T, N> {
    /// A run that stopped before its first step, in the user's charts.
    pub(crate) fn unstarted(
        trajectory: Trajectory<T, N>,
        rotations: &'static [EulerRotation],
    ) -> Self {
        finish(EventRun::unstarted(trajectory), 0, rotations)
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
    /// angles' rates are unbounded). Each angle is taken nearest the point
    /// before it, so the user's angles run on continuously across switches.
    pub fn user_state(&self, i: usize) -> Option<(SVector<T, N>, SVector<T, N>)> {
        let (mut q, mut v) = (
            self.trajectory.positions()[i],
            self.trajectory.velocities()[i],
        );
        for (k, rotation) in self.rotations.iter().enumerate() {
            let user = user_chart(rotation);
            let r = self.rotation(i, k);
            if user.conditioning(&r) < T::lit(USER_CHART_VALID) {
                return None;
            }
            if !self.chart(i, k).offset {
                continue; // held in the user's chart already
            }
            let near = (i > 0).then(|| self.user_angles_before(i, k)).flatten();
            let x = user.angles(&r, near);
            let dx = user.rates(x).try_inverse()? * self.angular_velocity(i, k);
            for (j, &c) in rotation.coordinates.iter().enumerate() {
                q[c] = x[j];
                v[c] = dx[j];
            }
        }
        Some((q, v))
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
    /// residuals as for any run.
    ///
    /// # Errors
    /// None in practice: the columns match the points by construction.
    pub fn table<S: Lagrangian<T, N>>(&self, sys: &S) -> Result<Table<'_, T, N>, Error> {
        let mut names = Vec::new();
        for r in self.rotations {
            names.push(format!("{}.chart", r.body));
            names.extend(["w", "x", "y", "z"].map(|c| format!("{}.{c}", r.body)));
        }
        let values = (0..self.trajectory.len())
            .map(|i| {
                (0..self.rotations.len())
                    .flat_map(|k| {
                        let chart = T::lit(if self.chart(i, k).offset { 2.0 } else { 1.0 });
                        std::iter::once(chart).chain(self.quaternion(i, k))
                    })
                    .collect()
            })
            .collect();
        Table::of(&self.trajectory, sys).columns(names, values)
    }

    /// The user's angles of rotation k at the last point before i that was
    /// in the user's chart, if any.
    fn user_angles_before(&self, i: usize, k: usize) -> Option<[T; 3]> {
        (0..i)
            .rev()
            .find(|&j| !self.chart(j, k).offset)
            .map(|j| angles(&self.rotations[k], &self.trajectory.positions()[j]))
    }
}

impl<T: Real, const N: usize> Progress for AtlasRun<T, N> {
    fn progress(&self) -> (usize, Option<f64>) {
        self.trajectory.progress()
    }
}

/// Integrates `dynamics` from (q0, v0) in the user's charts over [t0, t1],
/// switching charts as the rotations go.
///
/// # Errors
/// [`Error::InvalidSettings`] if the system's [`Atlas`] layout disagrees
/// with itself; whatever the integrator and the dynamics report.
pub(crate) fn integrate<S, T, I, const N: usize, const F: usize>(
    integrator: &I,
    dynamics: Dynamics<'_, S, T>,
    (t0, t1): (T, T),
    q0: SVector<T, N>,
    v0: SVector<T, N>,
) -> Result<AtlasRun<T, N>, Failure<AtlasRun<T, N>>>
where
    S: Atlas<T, N, F>,
    T: Real,
    I: Integrator,
{
    let charted = Charted::<S, T, N, F>::new(dynamics);
    let unstarted = |error: Error, q: SVector<T, N>, v: SVector<T, N>| {
        let trajectory = Trajectory::start(t0, q, v, Sample::of(&charted, t0, &q, &v));
        Failure::new(error, AtlasRun::unstarted(trajectory, S::EULER))
    };
    if !layout_agrees(charted.dynamics.system()) {
        return Err(unstarted(
            Error::InvalidSettings(
                "the system's Atlas twin does not have the documented layout".into(),
            ),
            q0,
            v0,
        ));
    }
    // Where the user's angles stood when each rotation left their chart.
    let left = RefCell::new(vec![[T::zero(); 3]; S::EULER.len()]);
    let (mut q, mut v) = (q0, v0);
    if let Err(e) = charted.enter_regular(t0, &mut q, &mut v, &mut left.borrow_mut()) {
        return Err(unstarted(e, q0, v0));
    }
    let start = charted.charts();
    let events = (0..S::EULER.len())
        .fold(Events::new().max_events(usize::MAX >> 8), |events, k| {
            events.with(switching(&charted, &left, k))
        });
    match events.integrate(integrator, &charted, t0, t1, q, v) {
        Ok(run) => Ok(finish(run, start, S::EULER)),
        Err(failure) => Err(failure.map(|run| finish(run, start, S::EULER))),
    }
}

/// The event that moves rotation k out of its chart of the moment when that
/// chart degrades: g is the margin left before the threshold, falling
/// through zero.
fn switching<'e, S, T, const N: usize, const F: usize>(
    charted: &'e Charted<'_, S, T, N, F>,
    left: &'e RefCell<Vec<[T; 3]>>,
    k: usize,
) -> Event<'e, T, N>
where
    S: Atlas<T, N, F>,
    T: Real,
{
    let in_second = move || charted.charts() >> k & 1 == 1;
    Event::new(move |_, q: &SVector<T, N>, _: &SVector<T, N>| {
        let s = charted.user_conditioning(k, q);
        if in_second() {
            T::lit(RETURN_ABOVE) - s
        } else {
            s - T::lit(LEAVE_BELOW)
        }
    })
    .falling()
    .action(move |t, q, v| {
        let near = if in_second() {
            Some(left.borrow()[k])
        } else {
            left.borrow_mut()[k] = angles(&S::EULER[k], q);
            None
        };
        // The map cannot fail away from the target chart's singular set,
        // which the thresholds keep far off; if it did, the non-finite
        // state ends the run with a typed error.
        if charted.switch(t, k, q, v, near).is_err() {
            q.fill(T::lit(f64::NAN));
        }
    })
    .named(format!("chart switch of {}", S::EULER[k].body))
}

/// The run's switches from its occurrences (event k is rotation k's
/// switch), and each point's charts.
fn finish<T: Real, const N: usize>(
    run: EventRun<T, N>,
    start: u64,
    rotations: &'static [EulerRotation],
) -> AtlasRun<T, N> {
    let mut mask = start;
    let switches: Vec<ChartSwitch<T>> = (run.occurrences.iter())
        .map(|o| {
            mask ^= 1 << o.event;
            ChartSwitch {
                t: o.t,
                rotation: o.event,
                to_second: mask >> o.event & 1 == 1,
            }
        })
        .collect();
    // A switch's point holds the state after it.
    let mut mask = start;
    let mut next = switches.iter().peekable();
    let charts = (run.trajectory.times().iter())
        .map(|&t| {
            while let Some(s) = next.next_if(|s| s.t <= t) {
                mask ^= 1 << s.rotation;
            }
            mask
        })
        .collect();
    AtlasRun {
        trajectory: run.trajectory,
        switches,
        rotations,
        charts,
        start,
    }
}
