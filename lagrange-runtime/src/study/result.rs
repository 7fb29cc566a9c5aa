//! What a study gives: the reference it measured against, and a row per
//! run with its measurement (or the error that ended the run).

use super::Setting;
use crate::error::Error;
use crate::ode::Stats;
use std::time::Duration;

/// Where a study's reference came from.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum ReferenceKind {
    /// A closed form.
    Exact,
    /// A trajectory given by the caller.
    Given,
    /// DOP853 through the study's closure.
    Computed {
        /// Its tolerance.
        tolerance: f64,
        /// Its right-hand-side evaluations.
        evaluations: usize,
        /// Its wall time.
        wall_time: Duration,
        /// max |q_ref(t_end) − q_check(t_end)| against the run at 10 × tolerance,
        /// if checked: an estimate of the reference's own error. Errors below it
        /// are not resolved.
        uncertainty: Option<f64>,
    },
}

impl ReferenceKind {
    /// The estimated error of the reference itself, if known (zero for a closed
    /// form).
    pub fn uncertainty(&self) -> Option<f64> {
        match *self {
            ReferenceKind::Exact => Some(0.0),
            ReferenceKind::Given => None,
            ReferenceKind::Computed { uncertainty, .. } => uncertainty,
        }
    }
}

/// What one successful run measured.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Measurement {
    /// max_i |q_i(t_end) − q_ref,i(t_end)|.
    pub error: f64,
    /// `error` over max_i |q_ref,i(t_end)| (over 1 when the reference is at the
    /// origin): the error in units of the motion's size.
    pub relative_error: f64,
    /// max_i |q̇_i(t_end) − q̇_ref,i(t_end)|, when the reference has velocities
    /// (a computed or given reference; a closed form gives positions only).
    pub velocity_error: Option<f64>,
    /// The largest constraint residual along the run, max(|Φ|, |G q̇ + g|)
    /// (zero for an unconstrained system).
    pub residual: f64,
    /// Whether the error is above the reference's own uncertainty (an error
    /// below it is not resolved: the reference cannot tell it from zero).
    pub resolved: bool,
    /// The run's final positions and velocities, as f64.
    pub final_state: (Vec<f64>, Vec<f64>),
    /// max over the run of |I(t) − I(t0)| / |I(t0)| for the conserved integral I
    /// (energy or Jacobi integral); `None` for a study of a non-conservative system.
    pub drift: Option<f64>,
    /// The integrator's counters (its own `wall_time` covers the integration
    /// alone, without the closure's setup).
    pub stats: Stats,
    /// Median wall time of the closure over the timed repeats.
    pub wall_time: Duration,
}

/// One run of a study: which method, which setting, and what came out.
#[derive(Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Row {
    /// The sweep's name.
    pub method: String,
    /// The step size or tolerance.
    pub setting: Setting,
    /// The measurement, or the typed error the run stopped with (serialized
    /// as its message).
    #[cfg_attr(feature = "serde", serde(serialize_with = "outcome"))]
    pub outcome: Result<Measurement, Error>,
}

/// A row's outcome for serde: `{"Ok": measurement}` or `{"Err": "message"}`.
#[cfg(feature = "serde")]
fn outcome<S: serde::Serializer>(o: &Result<Measurement, Error>, s: S) -> Result<S::Ok, S::Error> {
    use serde::Serialize;
    match o {
        Ok(m) => Ok::<&Measurement, String>(m).serialize(s),
        Err(e) => Err::<&Measurement, String>(e.to_string()).serialize(s),
    }
}

impl Row {
    /// The measurement of a successful run.
    pub fn measurement(&self) -> Option<&Measurement> {
        self.outcome.as_ref().ok()
    }
}

/// The measured study: the reference's description and one row per run, in the
/// order of the sweeps and their settings.
#[derive(Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Study {
    pub(super) reference: ReferenceKind,
    pub(super) uncertainty: Option<f64>,
    pub(super) rows: Vec<Row>,
}

impl Study {
    /// Where the reference came from.
    pub fn reference(&self) -> &ReferenceKind {
        &self.reference
    }

    /// The reference's own error: the one given with
    /// [`WorkPrecision::uncertainty`](super::WorkPrecision::uncertainty), else the reference kind's estimate.
    pub fn uncertainty(&self) -> Option<f64> {
        self.uncertainty
    }

    /// All rows.
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    /// The fastest successful run (by wall time) whose final error is at most
    /// `max_error`, if any.
    pub fn cheapest(&self, max_error: f64) -> Option<&Row> {
        self.rows
            .iter()
            .filter(|r| r.measurement().is_some_and(|m| m.error <= max_error))
            .min_by_key(|r| r.measurement().map(|m| m.wall_time))
    }

    /// The fastest successful run of each method whose final error is at most
    /// `max_error`, fastest first.
    pub fn cheapest_per_method(&self, max_error: f64) -> Vec<&Row> {
        let mut best: Vec<&Row> = Vec::new();
        for row in &self.rows {
            let Some(m) = row.measurement().filter(|m| m.error <= max_error) else {
                continue;
            };
            match best.iter_mut().find(|b| b.method == row.method) {
                Some(b) if b.measurement().is_some_and(|bm| bm.wall_time > m.wall_time) => *b = row,
                Some(_) => {}
                None => best.push(row),
            }
        }
        best.sort_by_key(|r| r.measurement().map(|m| m.wall_time));
        best
    }

    /// Appends the rows of `other` (a study of the same problem, e.g. in another
    /// scalar type); the reference description of `self` is kept.
    pub fn merge(mut self, other: Study) -> Study {
        self.rows.extend(other.rows);
        self
    }
}
