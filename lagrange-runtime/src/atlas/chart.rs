//! The charts of a run through the atlas as they change: which rotations
//! are in their second chart, every switch so far with when it happened,
//! and the maps between the charts of the moment and the user's
//! coordinates that controllers and events read.

use super::{LEAVE_BELOW, RETURN_ABOVE, angles, user_chart};
use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::euler::EulerChart;
use crate::system::EulerRotation;
use nalgebra::{SVector, Vector3};
use std::cell::{Cell, RefCell};

/// One switch as the run made it: when, which rotation, and the user's
/// angles the rotation is read nearest while in its second chart (those
/// it had when it left the user's chart).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Logged<T> {
    pub t: T,
    pub rotation: usize,
    pub near: [T; 3],
    /// The charts after it.
    pub mask: u64,
}

/// The charts of a run: bit k of the mask is set while rotation k is in its
/// second chart. Shared by the dynamics, the switching events and the
/// views of the user's coordinates, so one switch moves them all.
pub(crate) struct Charts<T: Real> {
    rotations: &'static [EulerRotation],
    /// The charts now.
    second: Cell<u64>,
    /// The charts the run started in, and the user's angles each rotation
    /// that started in its second chart is read nearest.
    start: Cell<u64>,
    start_near: RefCell<Vec<[T; 3]>>,
    /// Every switch after the start, in time order.
    log: RefCell<Vec<Logged<T>>>,
}

impl<T: Real> Charts<T> {
    /// Every rotation in the user's chart.
    pub fn new(rotations: &'static [EulerRotation]) -> Self {
        Self {
            rotations,
            second: Cell::new(0),
            start: Cell::new(0),
            start_near: RefCell::new(vec![[T::zero(); 3]; rotations.len()]),
            log: RefCell::new(Vec::new()),
        }
    }

    /// The charts now (bit k for rotation k).
    pub fn mask(&self) -> u64 {
        self.second.get()
    }

    /// The charts the run started in.
    pub fn start(&self) -> u64 {
        self.start.get()
    }

    /// The switches after the start, in time order.
    pub fn log(&self) -> Vec<Logged<T>> {
        self.log.borrow().clone()
    }

    /// The user's angles each rotation that started in its second chart
    /// is read nearest.
    pub fn start_near(&self) -> Vec<[T; 3]> {
        self.start_near.borrow().clone()
    }

    /// Rotation k's chart in the charts `mask`.
    pub fn chart_in(&self, mask: u64, k: usize) -> EulerChart {
        chart_in(self.rotations, mask, k)
    }

    /// The user's chart's conditioning of rotation k at q, read in the
    /// charts of the moment.
    pub fn user_conditioning<const N: usize>(&self, k: usize, q: &SVector<T, N>) -> T {
        let rotation = &self.rotations[k];
        let (chart, x) = (
            self.chart_in(self.mask(), k),
            rotation.coordinates.map(|i| q[i]),
        );
        if chart.offset {
            user_chart(rotation).conditioning(&chart.matrix(x))
        } else {
            chart.own_conditioning(x)
        }
    }

    /// Moves every rotation whose user's chart is poor at q (below
    /// [`LEAVE_BELOW`]) to its second chart before the run starts, mapping
    /// (q, v).
    pub fn enter_regular<const N: usize>(
        &self,
        t: T,
        q: &mut SVector<T, N>,
        v: &mut SVector<T, N>,
    ) -> Result<(), Error> {
        for (k, rotation) in self.rotations.iter().enumerate() {
            if self.chart_in(self.mask(), k).offset
                || self.user_conditioning(k, q) >= T::lit(LEAVE_BELOW)
            {
                continue;
            }
            self.start_near.borrow_mut()[k] = angles(rotation, q);
            self.map(t, k, q, v, None)?;
            self.start.set(self.mask());
        }
        Ok(())
    }

    /// Moves rotation k to its other chart at t, recording the switch: the
    /// same rotation matrix and the same ω, read in the other chart. Coming
    /// back to the user's chart the angles nearest those it had when it
    /// left are taken, so that ψ and φ go on from where they were, up to 2π.
    pub fn switch<const N: usize>(
        &self,
        t: T,
        k: usize,
        q: &mut SVector<T, N>,
        v: &mut SVector<T, N>,
    ) -> Result<(), Error> {
        let leaving = !self.chart_in(self.mask(), k).offset;
        let near = if leaving {
            angles(&self.rotations[k], q)
        } else {
            self.near_at(t, k)
        };
        self.map(t, k, q, v, (!leaving).then_some(near))?;
        self.log.borrow_mut().push(Logged {
            t,
            rotation: k,
            near,
            mask: self.mask(),
        });
        Ok(())
    }

    /// Switches, at t, every rotation whose chart of the moment is on the
    /// wrong side of its threshold (the user's below [`LEAVE_BELOW`], the
    /// second with the user's above [`RETURN_ABOVE`]): after an event's
    /// action, which may put the state anywhere, so that the run goes on in
    /// a regular chart and each switching event starts on its own side.
    pub fn settle<const N: usize>(
        &self,
        t: T,
        q: &mut SVector<T, N>,
        v: &mut SVector<T, N>,
    ) -> Result<(), Error> {
        for k in 0..self.rotations.len() {
            let s = self.user_conditioning(k, q);
            let wrong = if self.chart_in(self.mask(), k).offset {
                s > T::lit(RETURN_ABOVE)
            } else {
                s < T::lit(LEAVE_BELOW)
            };
            if wrong {
                self.switch(t, k, q, v)?;
            }
        }
        Ok(())
    }

    /// The map of [`switch`](Self::switch), unrecorded.
    fn map<const N: usize>(
        &self,
        t: T,
        k: usize,
        q: &mut SVector<T, N>,
        v: &mut SVector<T, N>,
        near: Option<[T; 3]>,
    ) -> Result<(), Error> {
        let rotation = &self.rotations[k];
        let from = self.chart_in(self.mask(), k);
        let to = from.second();
        let x = angles(rotation, q);
        let dx = angles(rotation, v);
        let r = from.matrix(x);
        let omega = from.rates(x) * Vector3::from(dx);
        let y = to.angles(&r, near);
        let dy = to
            .rates(y)
            .try_inverse()
            .map(|e| e * omega)
            .filter(|d| d.iter().all(|z| z.is_finite()))
            .ok_or_else(|| Error::non_finite(t, q, v))?;
        for (j, &i) in rotation.coordinates.iter().enumerate() {
            q[i] = y[j];
            v[i] = dy[j];
        }
        self.second.set(self.mask() ^ (1 << k));
        Ok(())
    }

    /// The charts at time t: those after every switch at or before t (a
    /// switch's instant reads the state after it). During the run, every
    /// time the integrator visits is at or after the last switch.
    pub fn mask_at(&self, t: T) -> u64 {
        let log = self.log.borrow();
        match log.partition_point(|s| s.t <= t) {
            0 => self.start(),
            n => log[n - 1].mask,
        }
    }

    /// The charts just before time t: those after every switch strictly
    /// before t (what an occurrence's state before its action is held in).
    pub fn mask_before(&self, t: T) -> u64 {
        let log = self.log.borrow();
        match log.partition_point(|s| s.t < t) {
            0 => self.start(),
            n => log[n - 1].mask,
        }
    }

    /// The user's angles rotation k is read nearest at time t while in its
    /// second chart.
    pub fn near_at(&self, t: T, k: usize) -> [T; 3] {
        let log = self.log.borrow();
        let n = log.partition_point(|s| s.t <= t);
        (log[..n].iter().rev())
            .find(|s| s.rotation == k)
            .map_or(self.start_near.borrow()[k], |s| s.near)
    }

    /// (q, v) held in the charts of time t, in the user's coordinates: each
    /// rotation in its second chart read in the user's chart nearest the
    /// angles it had when it left (see [`user_view`]).
    pub fn user_view<const N: usize>(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> (SVector<T, N>, SVector<T, N>) {
        let mask = self.mask_at(t);
        user_view(self.rotations, mask, |k| self.near_at(t, k), q, v)
    }

    /// (q, v) given in the user's coordinates, in the charts of time t:
    /// each rotation in its second chart read there nearest the angles
    /// `held` holds (the state before an event's action).
    pub fn user_to_charts<const N: usize>(
        &self,
        t: T,
        held: &SVector<T, N>,
        q: &mut SVector<T, N>,
        v: &mut SVector<T, N>,
    ) {
        let mask = self.mask_at(t);
        for (k, rotation) in self.rotations.iter().enumerate() {
            let chart = self.chart_in(mask, k);
            if !chart.offset {
                continue;
            }
            let user = user_chart(rotation);
            let x = angles(rotation, q);
            let dx = angles(rotation, v);
            let r = user.matrix(x);
            let omega = user.rates(x) * Vector3::from(dx);
            let y = chart.angles(&r, Some(angles(rotation, held)));
            let dy = (chart.rates(y).try_inverse())
                .map_or(Vector3::repeat(T::lit(f64::NAN)), |e| e * omega);
            for (j, &i) in rotation.coordinates.iter().enumerate() {
                q[i] = y[j];
                v[i] = dy[j];
            }
        }
    }
}

/// Rotation k's chart in the charts `mask`.
pub(crate) fn chart_in(rotations: &[EulerRotation], mask: u64, k: usize) -> EulerChart {
    let user = user_chart(&rotations[k]);
    if mask >> k & 1 == 1 {
        user.second()
    } else {
        user
    }
}

/// (q, v) held in the charts `mask`, in the user's coordinates: each
/// rotation in its second chart read in the user's chart, its angles
/// nearest `near(k)` (of the two solutions and their 2π shifts), its rates
/// E⁻¹ ω. On the user's singular set the angles are still defined (the
/// first angle taken from `near`) but the rates are not: they come back NaN.
pub(crate) fn user_view<T: Real, const N: usize>(
    rotations: &[EulerRotation],
    mask: u64,
    near: impl Fn(usize) -> [T; 3],
    q: &SVector<T, N>,
    v: &SVector<T, N>,
) -> (SVector<T, N>, SVector<T, N>) {
    let mut qu = *q;
    let mut vu = *v;
    for (k, rotation) in rotations.iter().enumerate() {
        let chart = chart_in(rotations, mask, k);
        if !chart.offset {
            continue;
        }
        let user = user_chart(rotation);
        let y = angles(rotation, q);
        let dy = angles(rotation, v);
        let r = chart.matrix(y);
        let omega = chart.rates(y) * Vector3::from(dy);
        let x = user.angles(&r, Some(near(k)));
        let dx = (user.rates(x).try_inverse())
            .filter(|_| user.conditioning(&r) > T::zero())
            .map_or(Vector3::repeat(T::lit(f64::NAN)), |e| e * omega);
        for (j, &i) in rotation.coordinates.iter().enumerate() {
            qu[i] = x[j];
            vu[i] = dx[j];
        }
    }
    (qu, vu)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    static YAW_PITCH_ROLL: [EulerRotation; 1] = [EulerRotation {
        body: "load",
        coordinates: [1, 2, 3],
        axes: [2, 1, 0],
    }];

    /// The rotation and ω of the state (q, v) in the charts `mask`.
    fn pose(
        mask: u64,
        q: &SVector<f64, 4>,
        v: &SVector<f64, 4>,
    ) -> (nalgebra::Matrix3<f64>, Vector3<f64>) {
        let chart = chart_in(&YAW_PITCH_ROLL, mask, 0);
        let x = angles(&YAW_PITCH_ROLL[0], q);
        let dx = angles(&YAW_PITCH_ROLL[0], v);
        (chart.matrix(x), chart.rates(x) * Vector3::from(dx))
    }

    /// Out to the second chart and back: the same rotation and ω at every
    /// stage, the user's angles read back where they were, the charts of
    /// each time from the log, the kept coordinate untouched.
    #[test]
    fn a_switch_keeps_the_motion_and_the_log_reads_the_charts_of_each_time() {
        let charts = Charts::<f64>::new(&YAW_PITCH_ROLL);
        let q0 = SVector::from([7.0, 0.4, 1.0, -0.3]);
        let v0 = SVector::from([2.0, 0.5, 1.5, -0.7]);
        let (r0, w0) = pose(0, &q0, &v0);
        let mut q = q0;
        let mut v = v0;
        charts.switch(1.0, 0, &mut q, &mut v).unwrap();
        assert_eq!((charts.mask(), q[0], v[0]), (1, 7.0, 2.0));
        let (r1, w1) = pose(1, &q, &v);
        assert!((r1 - r0).amax() < 1e-14 && (w1 - w0).amax() < 1e-14);
        // Read in the user's coordinates: the angles it left with.
        let (qu, vu) = charts.user_view(1.5, &q, &v);
        assert!(
            (qu - q0).amax() < 1e-13 && (vu - v0).amax() < 1e-13,
            "{qu} {vu}"
        );
        charts.switch(2.0, 0, &mut q, &mut v).unwrap();
        assert!((q - q0).amax() < 1e-13 && (v - v0).amax() < 1e-13);
        let masks = [0.5, 1.0, 1.5, 2.0, 2.5].map(|t| charts.mask_at(t));
        assert_eq!(masks, [0, 1, 1, 0, 0]);
        assert_eq!(charts.mask_before(1.0), 0);
        assert_eq!(charts.mask_before(2.0), 1);
        assert_eq!(charts.log().len(), 2);
    }
}
