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

    /// A parameter vector or a coefficient that is not a finite number.
    #[error("{what}[{index}] is {value}, not a finite number")]
    NotFiniteValue {
        /// What was given (`the prior π`, `the known π`, a coefficient).
        what: &'static str,
        /// The entry's index in it.
        index: usize,
        /// The value found.
        value: f64,
    },

    /// A mass, centre or inertia no rigid body has
    /// (`identify::body_parameters`).
    #[error(
        "body_parameters: {what} is {value}, which no rigid body has ({rule}); give the body's \
         mass, its centre and its inertia about that centre, in the frame's axes"
    )]
    NotABody {
        /// What was refused.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },

    // Exciting trajectories (`identify::Fourier`, `identify::exciting_trajectory`).
    /// A joint's position limits that leave no room to move.
    #[error(
        "joint {joint}: the position limits [{lower}, {upper}] leave no room: give finite \
         limits with lower < upper"
    )]
    LimitRange {
        /// The joint's index.
        joint: usize,
        /// The lower limit given.
        lower: f64,
        /// The upper limit given.
        upper: f64,
    },

    /// A joint's speed or acceleration limit that is not positive and
    /// finite.
    #[error(
        "joint {joint}: the {quantity} limit must be positive and finite (a bound on its \
         magnitude), got {value}"
    )]
    LimitRate {
        /// The joint's index.
        joint: usize,
        /// `speed` or `acceleration`.
        quantity: &'static str,
        /// The value given.
        value: f64,
    },

    /// A trajectory that leaves its limits.
    #[error(
        "joint {joint}: the trajectory's {quantity} is {value} at t = {time}, beyond the limit \
         {limit}; scale its coefficients down or move its offset inside the range"
    )]
    OutsideLimits {
        /// The joint's index.
        joint: usize,
        /// `position`, `speed` or `acceleration`.
        quantity: &'static str,
        /// The time of the sample found outside.
        time: f64,
        /// The value there.
        value: f64,
        /// The limit it passes.
        limit: f64,
    },

    /// A setting that cannot be used.
    #[error("the setting `{setting}` is {value}: {reason}")]
    Setting {
        /// The setting's name.
        setting: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },

    /// No trajectory tried excites every base parameter.
    #[error(
        "no trajectory tried excites every base parameter (the best stacked regressor's \
         condition number is {condition}): widen the limits, add harmonics or samples, or \
         lengthen the period"
    )]
    NotExcited {
        /// The best condition number reached.
        condition: f64,
    },

    // Physically consistent estimates (`identify::identify_consistent`).
    /// A body's parameters that no mass distribution has (its 4 × 4
    /// pseudo-inertia is not positive definite), or a point mass or a
    /// joint's damping, armature or friction that is not positive.
    #[error(
        "{what}: the parameters of `{body}` are not physically consistent (a mass or a joint's \
         coefficient that is not positive, or an inertia that breaks the triangle inequalities \
         or does not fit the first moment); start from a π that a real body has, such as the \
         model's own, with a positive guess for each joint's coefficient"
    )]
    Inconsistent {
        /// Which vector (`the prior π`).
        what: &'static str,
        /// The body, point mass or joint coefficient (`elbow.damping`).
        body: String,
    },

    /// Levenberg–Marquardt stopped before converging; `best` is the best
    /// iterate, physically consistent.
    #[error(
        "the consistent estimate did not converge in {iterations} iterations (weighted residual \
         {residual}); the best iterate is in the error: allow more iterations or record a \
         motion that excites every base parameter"
    )]
    NotConverged {
        /// Iterations made.
        iterations: usize,
        /// The best iterate's weighted residual (root mean square).
        residual: f64,
        /// The best iterate's full π.
        best: nalgebra::DVector<f64>,
    },

    // Estimates of a subset of π (`identify::identify_subset`).
    /// A name that is neither a parameter nor a body of the system.
    #[error(
        "`{name}` is neither one of the system's inertial parameters nor one of its bodies \
         (see Lagrangian::REGRESSOR_PARAMETERS: `body.m`, `body.mx`, ..., `point.m`, \
         `q.damping`, `q.armature`, `q.friction`)"
    )]
    UnknownParameter {
        /// The name given.
        name: String,
    },

    /// Parameters chosen for estimation that the data cannot tell apart.
    #[error(
        "the data cannot separate these parameters from the other chosen ones: {}; estimate \
         fewer (each of them acts only together with others) or record a motion that moves \
         every joint",
        parameters.join(", ")
    )]
    Inseparable {
        /// The parameters whose columns are combinations of the others'.
        parameters: Vec<String>,
    },
}
