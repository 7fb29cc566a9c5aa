//! The result of an integration: states at the accepted steps, the conserved
//! quantity along them, and dense output in between.

use crate::error::Error;
use crate::error::SettingsError;
use crate::numeric::Real;
use crate::numeric::func::abs;
use crate::numeric::root::brent;
use crate::ode::{Continuation, DenseSegment, Record, Sample, Stats};
use nalgebra::SVector;

/// A computed motion: the state (q, v) and the integral (energy or Jacobi
/// integral) at the initial time and after every accepted step, plus one dense
/// output segment per step.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Trajectory<T: Real, const N: usize, const Q: usize = N> {
    times: Vec<T>,
    q: Vec<SVector<T, Q>>,
    v: Vec<SVector<T, N>>,
    integral: Vec<T>,
    residual: Vec<[T; 2]>,
    unit: Vec<T>,
    segments: Vec<DenseSegment<T, N, Q>>,
    stats: Stats,
    /// What is kept of the run, and the state of that policy.
    record: Record,
    /// Where the policy stands: the grid of `Record::Interval`, the steps
    /// counted for `Record::Every`.
    #[cfg_attr(feature = "serde", serde(skip, default = "fresh_continuation"))]
    resume: Continuation<T>,
    /// The last point was stored by `close` (the end of a piece), not by the
    /// policy: a thinned recording drops it when the run goes on.
    #[cfg_attr(feature = "serde", serde(skip))]
    closed_extra: bool,
    /// The latest step when it was not stored: stored by `close`, so that a
    /// thinned trajectory still ends at the final state.
    #[cfg_attr(feature = "serde", serde(skip, default = "Option::default"))]
    pending: Option<Point<T, N, Q>>,
}

/// One recorded point: t, q, q̇ and the sample there.
pub(crate) type Point<T, const N: usize, const Q: usize> =
    (T, SVector<T, Q>, SVector<T, N>, Sample<T>);

#[cfg(feature = "serde")]
fn fresh_continuation<T: Real>() -> Continuation<T> {
    Continuation::start(T::zero())
}

impl<T: Real, const N: usize, const Q: usize> Trajectory<T, N, Q> {
    /// A trajectory holding only the initial point.
    pub fn start(t0: T, q0: SVector<T, Q>, v0: SVector<T, N>, sample: Sample<T>) -> Self {
        Self {
            times: vec![t0],
            q: vec![q0],
            v: vec![v0],
            integral: vec![sample.integral],
            residual: vec![sample.residuals],
            unit: vec![sample.unit_error],
            segments: Vec::new(),
            stats: Stats::default(),
            record: Record::Steps,
            resume: Continuation::start(t0),
            closed_extra: false,
            pending: None,
        }
    }

    /// A trajectory of points only, without dense output (as a thinned
    /// recording keeps), from (t, q, v, sample) in time order: what a run
    /// hands back after mapping its points into other coordinates.
    pub(crate) fn from_points(points: Vec<Point<T, N, Q>>, stats: Stats) -> Option<Self> {
        let mut points = points.into_iter();
        let (t0, q0, v0, sample) = points.next()?;
        let mut out = Self::start(t0, q0, v0, sample);
        out.record = Record::Every(1);
        points.for_each(|p| out.store(p));
        out.stats = stats;
        Some(out)
    }

    /// A trajectory holding only the initial point that keeps what `record`
    /// says of the steps pushed into it, going on from `from` (a fresh
    /// [`Continuation::start`], or the [`continuation`](Self::continuation) of
    /// the run so far when this is one of its pieces).
    pub fn start_recording(
        record: Record,
        from: Continuation<T>,
        t0: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        sample: Sample<T>,
    ) -> Self {
        let mut traj = Self::start(t0, q0, v0, sample);
        traj.record = record;
        traj.resume = from;
        traj
    }

    /// Where the recording stands, for the next piece of the same run to go on
    /// from (see [`Continuation`]).
    pub fn continuation(&self) -> Continuation<T> {
        self.resume
    }

    /// What this trajectory keeps of its steps.
    pub fn recording(&self) -> Record {
        self.record
    }

    /// The heap memory the recording holds, in bytes (capacities included).
    pub fn memory(&self) -> usize {
        use std::mem::size_of;
        self.times.capacity() * size_of::<T>()
            + (self.q.capacity() + self.v.capacity()) * size_of::<SVector<T, N>>()
            + self.integral.capacity() * size_of::<T>()
            + self.residual.capacity() * size_of::<[T; 2]>()
            + self.unit.capacity() * size_of::<T>()
            + self.segments.capacity() * size_of::<DenseSegment<T, N, Q>>()
    }

    /// Reserves room for `steps` more steps, as many points as the recording
    /// will keep of them.
    pub fn reserve(&mut self, steps: usize) {
        let steps = match self.record {
            Record::Steps => steps,
            Record::Every(k) => steps / k.max(1) + 1,
            // The number of output times is not known from the step count.
            Record::Interval(_) | Record::Final => return,
        };
        self.times.reserve(steps);
        self.q.reserve(steps);
        self.v.reserve(steps);
        self.integral.reserve(steps);
        self.residual.reserve(steps);
        self.unit.reserve(steps);
        if self.record == Record::Steps {
            self.segments.reserve(steps);
        }
    }

    /// Appends an accepted step ending at `segment.end()`.
    ///
    /// Integrators outside this crate build their trajectories with
    /// [`start`](Self::start), `push` and [`set_stats`](Self::set_stats).
    /// With a thinning [`Record`] the point is kept or not as it says, and
    /// [`push_sampled`](Self::push_sampled) is needed for `Record::Interval`
    /// (its points need samples between the steps); here they get the step
    /// end's sample.
    pub fn push(
        &mut self,
        segment: DenseSegment<T, N, Q>,
        q: SVector<T, Q>,
        v: SVector<T, N>,
        sample: Sample<T>,
    ) {
        self.push_sampled(segment, q, v, |_, _, _| sample);
    }

    /// [`push`](Self::push) with the sample computed on demand by
    /// `sample(t, q, q̇)`: at the step's end, and at the output times inside the
    /// step for `Record::Interval`.
    pub fn push_sampled(
        &mut self,
        segment: DenseSegment<T, N, Q>,
        q: SVector<T, Q>,
        v: SVector<T, N>,
        sample: impl Fn(T, &SVector<T, Q>, &SVector<T, N>) -> Sample<T>,
    ) {
        let end = segment.end();
        match self.record {
            Record::Steps => {
                self.store((end, q, v, sample(end, &q, &v)));
                self.segments.push(segment);
            }
            Record::Every(k) => {
                self.resume.steps_seen += 1;
                let point = (end, q, v, sample(end, &q, &v));
                if self.resume.steps_seen.is_multiple_of(k) {
                    self.pending = None;
                    self.store(point);
                } else {
                    self.pending = Some(point);
                }
            }
            Record::Interval(dt) => {
                // The integrators refuse a bad interval up front (Record::check);
                // a hand-made trajectory with one records no grid rather than
                // looping forever.
                while dt > 0.0 && self.resume.grid_time(self.resume.next, dt) < end {
                    let t = self.resume.grid_time(self.resume.next, dt);
                    let (qi, vi) = segment.eval(t);
                    self.store((t, qi, vi, sample(t, &qi, &vi)));
                    self.resume.next += 1;
                }
                self.pending = Some((end, q, v, sample(end, &q, &v)));
            }
            Record::Final => self.pending = Some((end, q, v, sample(end, &q, &v))),
        }
    }

    fn store(&mut self, (t, q, v, sample): Point<T, N, Q>) {
        self.times.push(t);
        self.q.push(q);
        self.v.push(v);
        self.integral.push(sample.integral);
        self.residual.push(sample.residuals);
        self.unit.push(sample.unit_error);
    }

    /// Stores the final state if the policy left it pending; integrators call
    /// this when the run ends (done by [`set_stats`](Self::set_stats)).
    pub fn close(&mut self) {
        if let Some(point) = self.pending.take()
            && self.times.last() != Some(&point.0)
        {
            self.store(point);
            self.closed_extra = true;
        }
    }

    /// Removes the last stored point (never the initial one).
    fn pop_point(&mut self) {
        if self.len() > 1 {
            self.times.pop();
            self.q.pop();
            self.v.pop();
            self.integral.pop();
            self.residual.pop();
            self.unit.pop();
        }
    }

    /// Records the work done by the integration, and closes the recording
    /// (see [`close`](Self::close)).
    pub fn set_stats(&mut self, stats: Stats) {
        self.close();
        self.stats = stats;
    }

    /// Cuts the last step at `t` (between its start and its end, the time of an
    /// event) and records (q, v) as the state there. When `t` is the start of the
    /// last step, the step is dropped and the state recorded at its start is
    /// replaced instead. A thinned recording drops the points it took past `t`
    /// (they came from the part of the step beyond the event) and ends at the
    /// cut.
    pub(crate) fn truncate_last(
        &mut self,
        t: T,
        q: SVector<T, Q>,
        v: SVector<T, N>,
        sample: Sample<T>,
    ) {
        if self.record != Record::Steps {
            return self.truncate_thinned((t, q, v, sample));
        }
        let last = self.len() - 1;
        if last > 0 && self.times[last - 1] >= t {
            self.pop_point();
            self.segments.pop();
        } else if let Some(segment) = self.segments.last_mut() {
            segment.truncate(t);
        }
        let last = self.len() - 1;
        self.times[last] = t;
        self.q[last] = q;
        self.v[last] = v;
        self.integral[last] = sample.integral;
        self.residual[last] = sample.residuals;
        self.unit[last] = sample.unit_error;
    }

    /// [`truncate_last`](Self::truncate_last) for a recording without
    /// segments: the points after the cut go, the grid steps back to the first
    /// time after it, and the cut state closes the recording.
    fn truncate_thinned(&mut self, cut: Point<T, N, Q>) {
        let t = cut.0;
        if self.closed_extra {
            self.pop_point();
            self.closed_extra = false;
        }
        while self.len() > 1 && self.times[self.len() - 1] > t {
            self.pop_point();
        }
        if let Record::Interval(dt) = self.record {
            let r = &mut self.resume;
            while r.next > 1 && r.grid_time(r.next - 1, dt) > t {
                r.next -= 1;
            }
        }
        self.pending = Some(cut);
        self.close();
    }

    /// Appends `other`, the next piece of the same run, which starts where
    /// `self` ends (same time), and returns the index of the first point that
    /// came from it. The work statistics add up.
    ///
    /// The first point of `other` replaces the last one of `self` (after an
    /// event action the two differ, and the trajectory records the state
    /// after it), except when a thinned recording stored that last point only
    /// to end the piece: then neither is kept, since the instant where the
    /// pieces join is not one of its points.
    pub(crate) fn append(&mut self, other: Trajectory<T, N, Q>) -> usize {
        debug_assert_eq!(self.times.last(), other.times.first());
        self.times.pop();
        self.q.pop();
        self.v.pop();
        self.integral.pop();
        self.residual.pop();
        self.unit.pop();
        let skip = usize::from(self.closed_extra);
        let from = self.len();
        self.times.extend_from_slice(&other.times[skip..]);
        self.q.extend_from_slice(&other.q[skip..]);
        self.v.extend_from_slice(&other.v[skip..]);
        self.integral.extend_from_slice(&other.integral[skip..]);
        self.residual.extend_from_slice(&other.residual[skip..]);
        self.unit.extend_from_slice(&other.unit[skip..]);
        self.segments.extend_from_slice(&other.segments);
        self.stats.add(&other.stats);
        self.resume = other.resume;
        self.closed_extra = other.closed_extra;
        self.pending = other.pending;
        from
    }

    /// Number of recorded points: accepted steps + 1 (the initial point).
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Never true for a trajectory returned by an integrator (it holds at least the
    /// initial point).
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Times of the recorded points, increasing, from the start to the end time.
    pub fn times(&self) -> &[T] {
        &self.times
    }

    /// Generalized coordinates at [`times`](Self::times).
    pub fn positions(&self) -> &[SVector<T, Q>] {
        &self.q
    }

    /// Generalized velocities at [`times`](Self::times).
    pub fn velocities(&self) -> &[SVector<T, N>] {
        &self.v
    }

    /// The conserved quantity (energy or Jacobi integral) at [`times`](Self::times).
    pub fn integrals(&self) -> &[T] {
        &self.integral
    }

    /// Constraint residuals [|Φ|∞, |G q̇ + g|∞] at [`times`](Self::times); zeros for
    /// an unconstrained system.
    pub fn residuals(&self) -> &[[T; 2]] {
        &self.residual
    }

    /// The largest | |q_k| − 1 | of the orientation quaternions at each
    /// recorded point ([`Sample::unit_error`]); zeros without orientations.
    pub fn unit_errors(&self) -> &[T] {
        &self.unit
    }

    /// The largest unit-norm error of the quaternions along the run:
    /// round-off, since every integrator normalises them after each step.
    pub fn max_unit_error(&self) -> T {
        self.unit.iter().fold(T::zero(), |m, &e| m.max(e))
    }

    /// The largest position and velocity constraint residuals along the run.
    pub fn max_residuals(&self) -> [T; 2] {
        self.residual
            .iter()
            .fold([T::zero(); 2], |m, r| [m[0].max(r[0]), m[1].max(r[1])])
    }

    /// Dense output, one segment per accepted step.
    pub fn segments(&self) -> &[DenseSegment<T, N, Q>] {
        &self.segments
    }

    /// Work statistics of the run.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// The state (q, v) at the end time.
    pub fn final_state(&self) -> (SVector<T, Q>, SVector<T, N>) {
        let last = self.len() - 1;
        (self.q[last], self.v[last])
    }

    /// The state (q, v) at time `t`, interpolated by the dense output; `None`
    /// outside the integrated span, and between the stored points of a thinned
    /// recording (it keeps no dense output). Exact (the stored state) at
    /// recorded times.
    ///
    /// The interpolant's order is the integrator's dense-output order: 4 for
    /// [`Dopri5`](crate::Dopri5), 3 (cubic Hermite) for [`Rk4`](crate::Rk4).
    pub fn state_at(&self, t: T) -> Option<(SVector<T, Q>, SVector<T, N>)> {
        let (&first, &last) = (self.times.first()?, self.times.last()?);
        if !(first <= t && t <= last) {
            return None;
        }
        // Index of the first recorded time > t; the segment before it holds t.
        let i = self.times.partition_point(|&ti| ti <= t);
        if self.times[i - 1] == t {
            return Some((self.q[i - 1], self.v[i - 1]));
        }
        // A thinned recording keeps no segments: only its stored points.
        self.segments.get(i - 1).map(|s| s.eval(t))
    }

    /// max_k |I(t_k) − I(t_0)| / max(|I(t_0)|, tiny): the relative drift of the
    /// conserved quantity, the run's accuracy diagnostic. (`tiny` is the smallest
    /// normal f64, so a zero initial integral makes this an absolute drift scaled
    /// up enormously: choose the potential's datum so that I(0) ≠ 0.)
    pub fn integral_drift(&self) -> T {
        let i0 = self.integral[0];
        let scale = abs(i0).max(T::lit(f64::MIN_POSITIVE));
        self.integral
            .iter()
            .fold(T::zero(), |m, &i| m.max(abs(i - i0)))
            / scale
    }

    /// The times at which `g(t, q, v)` crosses zero, increasing.
    ///
    /// A crossing is detected by a sign change of g between consecutive recorded
    /// points (a point where g is exactly zero is reported itself) and then located
    /// by Brent's method on the dense output, to about 4 ε relative in t. Two
    /// crossings inside one step cancel and are missed: g must not oscillate
    /// faster than the step size.
    ///
    /// # Errors
    /// [`Error::Settings`] on a thinned recording ([`Record::Every`],
    /// [`Record::Interval`], [`Record::Final`]): it keeps no dense output, and
    /// sign changes between its stored points would miss crossings (a pair
    /// between two stored points cancels) and misplace the others. Record
    /// [`Record::Steps`], or watch the crossing as an event during the run.
    pub fn crossings(
        &self,
        g: impl Fn(T, &SVector<T, Q>, &SVector<T, N>) -> T,
    ) -> Result<Vec<T>, Error> {
        if self.segments.len() + 1 != self.len() {
            return Err(SettingsError::Unsupported {
                owner: "crossings",
                needs: "the dense output".into(),
                remedy: format!(
                    "the run was recorded with {:?}, which keeps none, so crossings \
                     between its {} stored points cannot be found; record Record::Steps, \
                     or watch the crossing as an event during the run",
                    self.record,
                    self.len()
                ),
            }
            .into());
        }
        let mut out = Vec::new();
        let mut g_prev = g(self.times[0], &self.q[0], &self.v[0]);
        if g_prev == T::zero() {
            out.push(self.times[0]);
        }
        for (k, segment) in self.segments.iter().enumerate() {
            let t = self.times[k + 1];
            let q = &self.q[k + 1];
            let v = &self.v[k + 1];
            let g_next = g(t, q, v);
            if g_next == T::zero() {
                out.push(t);
            } else if g_prev != T::zero() && (g_prev > T::zero()) != (g_next > T::zero()) {
                let on_segment = |s: T| {
                    let (q, v) = segment.eval(s);
                    g(s, &q, &v)
                };
                out.push(brent(on_segment, self.times[k], t, g_prev, g_next));
            }
            g_prev = g_next;
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use crate::ode::test_problems::Oscillator;
    use crate::{Dopri5, Rk4, ode::Integrator};
    use nalgebra::Vector1;

    fn oscillator_run(method: impl Integrator, t_end: f64) -> super::Trajectory<f64, 1> {
        let osc = Oscillator { omega: 1.0 };
        method
            .integrate(&osc, 0.0, t_end, Vector1::new(1.0), Vector1::new(0.0))
            .unwrap()
    }

    #[test]
    fn state_at_and_crossings() {
        let tr = oscillator_run(Dopri5::tol(1e-12), 10.0);
        assert!(tr.state_at(-0.1).is_none() && tr.state_at(10.1).is_none());
        let t = tr.times()[3];
        assert_eq!(tr.state_at(t).unwrap().0, tr.positions()[3]);
        let (q, v) = tr.state_at(2.5).unwrap();
        assert!((q[0] - 2.5f64.cos()).abs() < 1e-10 && (v[0] + 2.5f64.sin()).abs() < 1e-10);
        // cos t = 0 at π/2 + kπ.
        let c = tr.crossings(|_, q, _| q[0]).unwrap();
        assert_eq!(c.len(), 3);
        for (k, t) in c.iter().enumerate() {
            let exact = std::f64::consts::FRAC_PI_2 + k as f64 * std::f64::consts::PI;
            assert!((t - exact).abs() < 1e-10, "{t} vs {exact}");
        }
        // A function that is zero exactly at a node is reported once.
        let t3 = tr.times()[3];
        assert_eq!(tr.crossings(|t, _, _| t - t3).unwrap(), vec![t3]);
        assert!(tr.integral_drift() < 1e-10);
    }

    #[test]
    fn rk4_dense_output_is_third_order() {
        // Max interpolation error at mid-steps should fall by ~2⁴ per halving of h
        // locally; over the span it's dominated by the O(h⁴) local term.
        let err = |h: f64| {
            let tr = oscillator_run(Rk4::step(h), 2.0);
            (0..tr.len() - 1)
                .map(|k| {
                    let t = 0.5 * (tr.times()[k] + tr.times()[k + 1]);
                    (tr.state_at(t).unwrap().0[0] - t.cos()).abs()
                })
                .fold(0.0, f64::max)
        };
        let ratio = err(0.1) / err(0.05);
        assert!(ratio > 12.0, "ratio {ratio}");
    }

    #[test]
    fn csv_header_and_rows() {
        let tr = oscillator_run(Rk4::step(0.5), 1.0);
        let mut buf = Vec::new();
        tr.write_csv(&mut buf, &["x"]).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("t,x,dot_x,integral,residual_position,residual_velocity")
        );
        assert_eq!(lines.next(), Some("0,1,0,0.5,0,0"));
        assert_eq!(lines.count(), 2);
        let mut buf = Vec::new();
        tr.write_csv(&mut buf, &[]).unwrap();
        assert!(
            String::from_utf8(buf)
                .unwrap()
                .starts_with("t,q0,dot_q0,integral,residual_position,residual_velocity\n")
        );
        assert!(tr.write_csv(Vec::new(), &["a", "b"]).is_err());
    }
}
