//! Failures of parameter identification ([`crate::identify`]).

/// Why the inertial parameters could not be identified from the data given.
/// The cause is data, so that a caller can match on it; the message names
/// the sample, joint or parameters at fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IdentifyError {
    /// The system has no regressor: `Lagrangian::regressor` or
    /// `inertial_parameters` returned `None`.
    #[error(
        "the system has no regressor: add `regressor` to `emit(...)` in its \
         #[derive(Lagrangian)] (a kinematic tree), or implement `Lagrangian::{method}`"
    )]
    NoRegressor {
        /// The trait method that returned `None`.
        method: &'static str,
    },

    /// Fewer equations (samples × joints) than parameters to estimate.
    #[error(
        "too few samples: {samples} sample(s) of {joints} joint(s) give {equations} equation(s) \
         for {parameters} base parameter(s); record at least {needed} samples"
    )]
    TooFewSamples {
        /// Samples given.
        samples: usize,
        /// Equations per sample (the joints).
        joints: usize,
        /// Equations in all.
        equations: usize,
        /// Parameters to estimate.
        parameters: usize,
        /// The fewest samples that give as many equations.
        needed: usize,
    },

    /// A NaN or an infinity in the data.
    #[error("sample {sample}: {field}[{index}] is {value}, not a finite number")]
    NotFinite {
        /// The sample's index.
        sample: usize,
        /// `q`, `v`, `a` or `tau`.
        field: &'static str,
        /// The entry's index in it.
        index: usize,
        /// The value found.
        value: f64,
    },

    /// The data do not excite every base parameter: these columns of the
    /// stacked regressor are (to the rank tolerance) combinations of the
    /// ones before them.
    #[error(
        "the data excite {rank} of {parameters} base parameter(s); these cannot be identified \
         from them: {}; record a motion that moves every joint (faster, farther, in more \
         directions)",
        unidentifiable.join(", ")
    )]
    RankDeficient {
        /// The rank of the stacked regressor.
        rank: usize,
        /// The base parameters to estimate.
        parameters: usize,
        /// The base parameters the data cannot tell apart from the others.
        unidentifiable: Vec<String>,
    },

    /// A joint's noise level that cannot weight its equations.
    #[error(
        "joint {joint}: the noise's standard deviation must be positive and finite, got {value}"
    )]
    Noise {
        /// The joint's index.
        joint: usize,
        /// The value given.
        value: f64,
    },

    /// A parameter vector of the wrong length.
    #[error("{what} has {got} entries, the system's regressor {expected}")]
    Lengths {
        /// What was given.
        what: &'static str,
        /// Its length.
        got: usize,
        /// The length it must have.
        expected: usize,
    },
}
