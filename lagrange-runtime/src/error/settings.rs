//! Settings, spans, initial values and data that cannot be used.

/// A setting, a time span, an initial state or a piece of data that cannot
/// be used (wrapped in [`Error::Settings`](super::Error::Settings)). The cause
/// is data, so that a caller can match on it, and the message is written from
/// that data, so that the two cannot drift apart.
///
/// `owner` names what holds the setting (`"DOPRI5"`, `"Simulation"`,
/// `"Linearizer"`, `"LQR"`, `"input table"`, ...).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SettingsError {
    /// A number outside the values a setting may take: a tolerance, a step,
    /// a period, a coefficient.
    #[error("{owner}: {setting} must be {requirement}, got {value}")]
    Value {
        /// What holds the setting.
        owner: &'static str,
        /// The setting, as its builder method or field is named.
        setting: &'static str,
        /// The value given.
        value: f64,
        /// What it must be, e.g. "non-negative and finite".
        requirement: String,
    },

    /// Slices that must hold one entry per item and do not (a batch's q,
    /// v and τ, one of each per state).
    #[error("{owner}: {what}")]
    Lengths {
        /// What was given the slices.
        owner: &'static str,
        /// Each slice's length.
        what: String,
    },

    /// A count that must be at least 1 (`max_steps`, `max_events`,
    /// `repeats`, an iteration limit).
    #[error("{owner}: {setting} must be at least 1")]
    ZeroCount {
        /// What holds the setting.
        owner: &'static str,
        /// The setting.
        setting: &'static str,
    },

    /// A choice among a few (Gauss's number of stages).
    #[error("{owner}: {setting} = {value} is not one of {allowed}")]
    Choice {
        /// What holds the setting.
        owner: &'static str,
        /// The setting.
        setting: &'static str,
        /// The value given.
        value: usize,
        /// The values allowed, e.g. "1 or 2".
        allowed: &'static str,
    },

    /// A run's time span is not finite, or is empty or reversed.
    #[error("time span {start}..{end} {}", span_fault(*start, *end))]
    TimeSpan {
        /// Its start.
        start: f64,
        /// Its end.
        end: f64,
    },

    /// A run's initial state holds NaN or ∞.
    #[error("initial state is not finite: q0 = {q:?}, v0 = {v:?}")]
    InitialState {
        /// The initial coordinates.
        q: Vec<f64>,
        /// The initial velocities.
        v: Vec<f64>,
    },

    /// A matrix of the wrong shape, or holding NaN or ∞.
    #[error(
        "{owner}: {name} must be a finite {}x{} matrix{}, got {}x{}{}",
        expected.0, expected.1, meaning_of(meaning), got.0, got.1,
        if *finite { "" } else { " with non-finite entries" }
    )]
    Shape {
        /// What needs it.
        owner: &'static str,
        /// The matrix.
        name: &'static str,
        /// Its rows and columns as they must be.
        expected: (usize, usize),
        /// As given.
        got: (usize, usize),
        /// Whether every entry is finite.
        finite: bool,
        /// What the rows and columns are, e.g. "inputs x the model's states"
        /// (empty when plain).
        meaning: &'static str,
    },

    /// The settings would take more than a budget allows before any work
    /// is done: the points a recording would keep, the restarts an input
    /// source would cause.
    #[error("{owner}: {what} {asked:.3e} times in [{start}, {end}], more than {limit:e}: {advice}")]
    Budget {
        /// What would exceed it.
        owner: &'static str,
        /// What is counted, e.g. "asks to record a point".
        what: &'static str,
        /// How many.
        asked: f64,
        /// The limit.
        limit: f64,
        /// The span.
        start: f64,
        /// The span's end.
        end: f64,
        /// What it would cost, and how to stay within it.
        advice: String,
    },

    /// The system or the settings lack what this computation needs
    /// (Hamilton's form for Gauss, holonomic constraints for RATTLE, a
    /// constant mass matrix, inputs for LQR, an atlas layout that agrees
    /// with itself, ...).
    #[error("{owner} needs {needs}: {remedy}")]
    Unsupported {
        /// What needs it.
        owner: &'static str,
        /// What it needs.
        needs: String,
        /// What to do.
        remedy: String,
    },

    /// Data given to a builder is inconsistent (an input table's times, a
    /// scene's runs and styles, a table's columns, a state's name).
    #[error("{owner}: {problem}")]
    Data {
        /// What was given it.
        owner: &'static str,
        /// What is wrong with it.
        problem: String,
    },
}

fn span_fault(start: f64, end: f64) -> &'static str {
    if !(start.is_finite() && end.is_finite()) {
        "is not finite"
    } else {
        "is empty or reversed; the end must be after the start"
    }
}

fn meaning_of(meaning: &str) -> String {
    if meaning.is_empty() {
        String::new()
    } else {
        format!(" ({meaning})")
    }
}
