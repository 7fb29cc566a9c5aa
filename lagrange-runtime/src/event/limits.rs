//! Position limits watched during a run: until limits are contacts, a
//! coordinate that leaves its limits stops the run with
//! [`Error::JointLimit`], at the first point of the step's dense output past
//! the limit, rather than passing through silently.
//!
//! Each accepted step is sampled at [`SAMPLES`] points of its dense output
//! (and its end); the first sample past a limit and the one before it bracket
//! the crossing, which Brent's method locates to round-off in t. A limit
//! crossed and recrossed between two samples (a step more than
//! [`SAMPLES`] times longer than the excursion) is missed.

use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::root::brent_bracket;
use crate::ode::{DenseSegment, Mechanical, SecondOrder};
use crate::system::JointLimit;
use nalgebra::{SMatrix, SVector};

/// Sample points per step, besides its end.
pub const SAMPLES: usize = 8;

/// Whether a run watches the system's position limits
/// ([`Lagrangian::position_limits`](crate::Lagrangian::position_limits)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LimitPolicy {
    /// Stop with [`Error::JointLimit`] when a coordinate leaves its limits
    /// (the default).
    #[default]
    Stop,
    /// Run through the limits.
    Ignore,
}

/// The limits watched under `policy`: all of them, or none.
pub(crate) fn watched(limits: &'static [JointLimit], policy: LimitPolicy) -> &'static [JointLimit] {
    match policy {
        LimitPolicy::Stop => limits,
        LimitPolicy::Ignore => &[],
    }
}

/// The system `rhs` with its limits watched: everything is delegated, and
/// [`after_step`](SecondOrder::after_step) fails at a crossing. A run with
/// events watches the limits in its event observer instead, which sees them
/// only up to the first stopping event of the step.
pub(crate) struct Limited<'r, F> {
    rhs: &'r F,
    limits: &'static [JointLimit],
}

impl<'r, F> Limited<'r, F> {
    /// `rhs` watched for `limits` under `policy` (none watched with `Ignore`).
    pub fn new(rhs: &'r F, limits: &'static [JointLimit], policy: LimitPolicy) -> Self {
        Self {
            rhs,
            limits: watched(limits, policy),
        }
    }
}

/// The earliest crossing of any of `limits` on `segment` (ending at `q`)
/// up to `until`, as the error that stops the run.
pub(crate) fn first_crossing<T: Real, const N: usize, const Q: usize>(
    limits: &[JointLimit],
    segment: &DenseSegment<T, N, Q>,
    q: &SVector<T, Q>,
    until: T,
) -> Option<Error> {
    let (l, t, value) = limits
        .iter()
        .filter(|l| l.coordinate < Q)
        .filter_map(|l| crossing(l, segment, q, until).map(|(t, x)| (l, t, x)))
        .min_by(|a, b| a.1.partial_cmp(&b.1).unwrap_or(std::cmp::Ordering::Equal))?;
    Some(Error::JointLimit {
        joint: l.joint,
        coordinate: l.coordinate,
        value,
        lower: l.lower,
        upper: l.upper,
        t: t.to_f64(),
    })
}

/// The signed distance of x past the nearer violated bound of `limit`
/// (positive past it), and that bound; `None` inside.
fn past(limit: &JointLimit, x: f64) -> Option<(f64, f64)> {
    if x < limit.lower {
        Some((limit.lower - x, limit.lower))
    } else if x > limit.upper {
        Some((x - limit.upper, limit.upper))
    } else {
        None
    }
}

/// The first crossing of `limit` on `segment` (ending at `q`) up to `until`:
/// its time and the coordinate's value there, on or just past the limit.
fn crossing<T: Real, const N: usize, const Q: usize>(
    limit: &JointLimit,
    segment: &DenseSegment<T, N, Q>,
    q: &SVector<T, Q>,
    until: T,
) -> Option<(T, f64)> {
    let i = limit.coordinate;
    let ta = segment.start();
    let tb = segment.end();
    let at = |k: usize| ta + (until - ta) * T::lit(k as f64 / SAMPLES as f64);
    let value = |t: T| match t == tb {
        true => q[i].to_f64(),
        false => segment.eval(t).0[i].to_f64(),
    };
    let first = (0..=SAMPLES).find(|&k| past(limit, value(at(k))).is_some())?;
    let t1 = at(first);
    let x1 = value(at(first));
    if first == 0 {
        return Some((t1, x1));
    }
    let (_, bound) = past(limit, x1)?;
    let side = |t: T| T::lit((value(t) - bound) * (x1 - bound).signum());
    let t0 = at(first - 1);
    let (b, fb, c, fc) = brent_bracket(side, t0, t1, side(t0), side(t1));
    // The end of the final bracket past the limit; b itself when it is on
    // the limit exactly (Brent then stops with c anywhere in the bracket).
    let t = if fb >= T::zero() || fc <= T::zero() {
        b
    } else {
        c
    };
    Some((t, value(t)))
}

impl<F: SecondOrder<T, N, Q>, T: Real, const N: usize, const Q: usize> SecondOrder<T, N, Q>
    for Limited<'_, F>
{
    const ORIENTATIONS: &'static [crate::numeric::orientation::Orientation] = F::ORIENTATIONS;

    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        self.rhs.acceleration(t, q, v)
    }

    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        self.rhs.integral(t, q, v)
    }

    fn residuals(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> [T; 2] {
        self.rhs.residuals(t, q, v)
    }

    fn project(&self, t: T, q: &mut SVector<T, Q>, v: &mut SVector<T, N>) -> Result<bool, Error> {
        self.rhs.project(t, q, v)
    }

    fn mechanical(&self) -> Option<&dyn Mechanical<T, N, Q>> {
        self.rhs.mechanical()
    }

    fn jacobian(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Option<Result<(SMatrix<T, N, Q>, SMatrix<T, N, N>), Error>> {
        self.rhs.jacobian(t, q, v)
    }

    fn after_step(
        &self,
        segment: &DenseSegment<T, N, Q>,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<bool, Error> {
        let stop = self.rhs.after_step(segment, q, v)?;
        match first_crossing(self.limits, segment, q, segment.end()) {
            None => Ok(stop),
            Some(error) => Err(error),
        }
    }
}
