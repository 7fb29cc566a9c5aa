//! What a run keeps of its steps ([`Record`]), the bound on how much that may
//! be, and where a recording stands between the pieces of one run
//! ([`Continuation`]).

use crate::error::Error;
use crate::error::SettingsError;
use crate::numeric::Real;

/// What a run keeps of its steps, set on the integrator, e.g.
/// `Dopri5::tol(1e-10).record(Record::Every(100))`. `Every(0)`, an `Interval`
/// that is not positive and finite, and an `Interval` that would record more
/// than [`Record::MAX_POINTS`] points are refused when the run starts
/// ([`Error::Settings`], with the count and the memory it would need).
///
/// A run made of pieces (restarts after events, the instants of a sampled
/// controller or the breakpoints of an input table) is recorded as one run:
/// `Interval(dt)` keeps the one grid t0 + k·dt of the whole run (k counted,
/// not accumulated, so the times carry no drift), `Every(k)` counts the steps
/// across pieces, and neither records the instants where pieces join; `Steps`
/// records every step, so those instants are among its points.
///
/// Memory per stored point for f64: 8 (t) + 8 (Q + N) (q, v; Q = N without
/// orientations) + 32 (integral, residuals, unit-norm error) bytes; `Steps`
/// also keeps each step's dense segment, 8 × 8 (Q + N) + 40 bytes more, so that [`state_at`](crate::Trajectory::state_at) and
/// [`crossings`](crate::Trajectory::crossings) work. The other policies keep no
/// segments (`state_at` then answers only at the stored times and `crossings`
/// refuses), so a run of 10⁷ steps with `Every(1000)` stores 10⁴ points and
/// with `Final` two.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Record {
    /// Every accepted step with its dense output (the default).
    #[default]
    Steps,
    /// Every k-th accepted step, and the final state.
    Every(usize),
    /// The state at t0, t0 + dt, t0 + 2 dt, … from the dense output of the steps
    /// that cover those times, and the final state.
    Interval(f64),
    /// The initial and the final state only.
    Final,
}

impl Record {
    /// The most points an [`Interval`](Record::Interval) may ask for: 10⁷
    /// (0.64 GB for six coordinates in f64). More is almost always a mistaken
    /// `dt`; a run that truly needs more is split into spans.
    pub const MAX_POINTS: f64 = 1e7;

    /// Refuses `Every(0)` and an interval that is not positive and finite.
    ///
    /// # Errors
    /// [`Error::Settings`].
    pub fn check(&self) -> Result<(), Error> {
        match *self {
            Record::Every(0) => Err(SettingsError::ZeroCount {
                owner: "record",
                setting: "k of Every(k)",
            }
            .into()),
            Record::Interval(dt) if !(dt.is_finite() && dt > 0.0) => Err(SettingsError::Value {
                owner: "record",
                setting: "dt of Interval(dt)",
                value: dt,
                requirement: "positive and finite".into(),
            }
            .into()),
            _ => Ok(()),
        }
    }

    /// [`check`](Self::check), and refuses an `Interval` whose grid over
    /// [t0, t1] has more than [`MAX_POINTS`](Self::MAX_POINTS) points, before
    /// any work: the message gives the count and the memory for a state of
    /// `len` numbers (Q + N) of `T`.
    ///
    /// # Errors
    /// [`Error::Settings`].
    pub fn check_span<T: Real>(&self, t0: T, t1: T, len: usize) -> Result<(), Error> {
        self.check()?;
        let Record::Interval(dt) = *self else {
            return Ok(());
        };
        let points = ((t1 - t0).to_f64() / dt).floor() + 2.0;
        if points.is_nan() || points <= Self::MAX_POINTS {
            return Ok(());
        }
        Err(SettingsError::Budget {
            owner: "record",
            what: "Interval(dt) asks to record a point",
            asked: points,
            limit: Self::MAX_POINTS,
            start: t0.to_f64(),
            end: t1.to_f64(),
            advice: format!(
                "{:.3e} bytes of memory; take a larger dt, or Record::Every(k) / Record::Final",
                points * Self::point_bytes::<T>(len) as f64
            ),
        }
        .into())
    }

    /// The memory of one stored point without its dense segment: t, the
    /// state's `len` numbers, the integral, two residuals and the unit-norm
    /// error.
    fn point_bytes<T>(len: usize) -> usize {
        (5 + len) * std::mem::size_of::<T>()
    }
}

/// Where a recording stands between the pieces of one run: the origin and the
/// next index of the [`Record::Interval`] grid, and the steps counted for
/// [`Record::Every`]. A piece started from the continuation of the run so far
/// ([`Trajectory::continuation`](crate::Trajectory::continuation)) records as
/// if the run had not been cut.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Continuation<T> {
    pub(crate) origin: T,
    pub(crate) next: u64,
    pub(crate) steps_seen: usize,
}

impl<T: Real> Continuation<T> {
    /// A run that starts at `t0`: the grid is t0 + k·dt from k = 1 (t0 itself
    /// is the initial point), no steps counted yet.
    pub fn start(t0: T) -> Self {
        Self {
            origin: t0,
            next: 1,
            steps_seen: 0,
        }
    }

    /// The k-th grid time origin + k·dt, from k (no accumulated round-off).
    pub(crate) fn grid_time(&self, k: u64, dt: f64) -> T {
        self.origin + T::lit(k as f64 * dt)
    }
}
