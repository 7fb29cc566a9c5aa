//! Open-loop inputs from a table of (time, value) breakpoints.

use super::{InputSource, IntoInput};
use crate::error::Error;
use crate::error::SettingsError;
use crate::numeric::Real;
use nalgebra::SVector;

/// How an [`InputTable`] fills the time between its breakpoints.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// Straight lines between consecutive breakpoints.
    Linear,
    /// Zero-order hold: value i on [t_i, t_{i+1}) (right-continuous).
    Hold,
}

/// P inputs given at strictly increasing times t_0 < t_1 < … < t_{n−1}, with
/// [linear interpolation](Self::linear) or [zero-order hold](Self::hold) in
/// between.
///
/// Outside the table's range the end values are held: u(t) = u_0 before t_0
/// and u_{n−1} after t_{n−1} (for both kinds of table), so a table describes a
/// signal on the whole line; add breakpoints to make it anything else (a
/// one-point table is a constant).
///
/// A controlled run restarts the integrator at every breakpoint inside the
/// run's span (see the [module docs](crate::control)): no step straddles a
/// kink or a jump, so the integrator keeps its order. A hold table's piece
/// uses the value at its start throughout, exactly as a sampled controller.
///
/// ```
/// use lagrange_runtime::InputTable;
/// use nalgebra::{SVector, Vector1};
/// let ramp = InputTable::linear([0.0, 1.0, 2.0], [[0.0], [2.0], [2.0]])?;
/// let z = Vector1::zeros();
/// let u = |t: f64| lagrange_runtime::InputSource::<f64, 1, 1>::input(&ramp, t, &z, &z)[0];
/// assert_eq!((u(-1.0), u(0.25), u(1.5), u(5.0)), (0.0, 0.5, 2.0, 2.0));
/// assert!(InputTable::<f64, 1>::hold([0.0, 0.0], [[1.0], [2.0]]).is_err()); // not increasing
/// # Ok::<(), lagrange_runtime::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct InputTable<T: Real, const P: usize> {
    times: Vec<T>,
    values: Vec<SVector<T, P>>,
    interpolation: Interpolation,
}

impl<T: Real, const P: usize> InputTable<T, P> {
    /// A table interpolated linearly between breakpoints.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn linear<V: IntoInput<T, P>>(
        times: impl IntoIterator<Item = T>,
        values: impl IntoIterator<Item = V>,
    ) -> Result<Self, Error> {
        Self::new(times, values, Interpolation::Linear)
    }

    /// A table held constant from each breakpoint to the next (zero-order hold).
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn hold<V: IntoInput<T, P>>(
        times: impl IntoIterator<Item = T>,
        values: impl IntoIterator<Item = V>,
    ) -> Result<Self, Error> {
        Self::new(times, values, Interpolation::Hold)
    }

    /// A table with values `values[i]` (`[T; P]` or `SVector<T, P>`) at
    /// `times[i]`.
    ///
    /// # Errors
    /// [`Error::Settings`] if the table is empty, the two lists differ in
    /// length, a time or a value is not finite, or the times are not strictly
    /// increasing; the message names the offending entry.
    pub fn new<V: IntoInput<T, P>>(
        times: impl IntoIterator<Item = T>,
        values: impl IntoIterator<Item = V>,
        interpolation: Interpolation,
    ) -> Result<Self, Error> {
        let times: Vec<T> = times.into_iter().collect();
        let values: Vec<SVector<T, P>> = values.into_iter().map(IntoInput::into_input).collect();
        let bad = |problem: String| {
            Err(SettingsError::Data {
                owner: "input table",
                problem,
            }
            .into())
        };
        if times.is_empty() {
            return bad("no breakpoints".into());
        }
        if times.len() != values.len() {
            return bad(format!("{} times but {} values", times.len(), values.len()));
        }
        if let Some(i) = times.iter().position(|t| !t.is_finite()) {
            return bad(format!("time #{i} is {}", times[i].to_f64()));
        }
        if let Some(i) = values.iter().position(|u| !u.iter().all(|x| x.is_finite())) {
            return bad(format!(
                "value #{i} at t = {} is not finite",
                times[i].to_f64()
            ));
        }
        if let Some(i) = times.windows(2).position(|w| w[1] <= w[0]) {
            return bad(format!(
                "times must be strictly increasing: #{} = {} follows #{i} = {}",
                i + 1,
                times[i + 1].to_f64(),
                times[i].to_f64()
            ));
        }
        Ok(Self {
            times,
            values,
            interpolation,
        })
    }

    /// The breakpoint times.
    pub fn times(&self) -> &[T] {
        &self.times
    }

    /// The values at the breakpoints.
    pub fn values(&self) -> &[SVector<T, P>] {
        &self.values
    }

    /// Linear or hold.
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// The signal at time t (end values held outside the table's range).
    pub fn value_at(&self, t: T) -> SVector<T, P> {
        // Number of breakpoints at or before t.
        let i = self.times.partition_point(|&ti| ti <= t);
        if i == 0 {
            return self.values[0];
        }
        if i == self.times.len() || self.interpolation == Interpolation::Hold {
            return self.values[i - 1];
        }
        let t0 = self.times[i - 1];
        let t1 = self.times[i];
        let s = (t - t0) / (t1 - t0);
        let u0 = &self.values[i - 1];
        let u1 = &self.values[i];
        let mut u = *u0;
        for k in 0..P {
            u[k] += s * (u1[k] - u0[k]);
        }
        u
    }
}

// A table reads only the time, so it drives a system with or without
// orientations alike (any Q).
impl<T: Real, const N: usize, const P: usize, const Q: usize> InputSource<T, N, P, Q>
    for InputTable<T, P>
{
    #[inline]
    fn input(&self, t: T, _: &SVector<T, Q>, _: &SVector<T, N>) -> SVector<T, P> {
        self.value_at(t)
    }

    /// The first breakpoint after `after`.
    fn next_break(&self, _start: T, after: T) -> Option<T> {
        let i = self.times.partition_point(|&ti| ti <= after);
        self.times.get(i).copied()
    }

    fn held(&self) -> bool {
        self.interpolation == Interpolation::Hold
    }

    fn breaks_within(&self, start: T, end: T) -> Option<f64> {
        let within = self.times.iter().filter(|&&ti| start < ti && ti <= end);
        Some(within.count() as f64)
    }
}
