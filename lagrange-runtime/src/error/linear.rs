//! Failures of linearisation, eigen-analysis and LQR design.

/// Failures specific to linearisation, eigen-analysis and LQR design (wrapped in
/// [`Error::Linear`](super::Error::Linear)).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LinearError {
    /// The operating point violates the constraints: Φ(q0, t0) ≠ 0 or
    /// G q̇0 + g ≠ 0 (or, for a reduced system, q̇0 is not W u + w) beyond the
    /// tolerance. Complete it with [`Linearizer::complete_state`](crate::linear::Linearizer::complete_state) first.
    #[error(
        "inconsistent operating point at t = {t}, q = {q:?} ({coordinates:?}): |Phi| = \
         {position_residual:e}, |G v + g| = {velocity_residual:e}, tolerance {tolerance:e}; \
         worst: {worst}; complete the state from the independent coordinates and speeds \
         first (Linearizer::complete_state)"
    )]
    InconsistentOperatingPoint {
        /// Time of the operating point.
        t: f64,
        /// Its coordinates.
        q: Vec<f64>,
        /// Their names.
        coordinates: Vec<&'static str>,
        /// max |Φ_i| over the holonomic rows.
        position_residual: f64,
        /// max |(G q̇ + g)_i| (reduced systems: max |q̇ − W u − w|).
        velocity_residual: f64,
        /// The tolerance both must meet.
        tolerance: f64,
        /// The worst constraint (or, for a reduced system, the worst velocity).
        worst: String,
    },

    /// The named independent coordinates or speeds are not a valid choice:
    /// unknown or repeated names, or the wrong number of them.
    #[error("invalid choice of independent {what}: {reason}")]
    InvalidPartition {
        /// `coordinates` or `speeds`.
        what: &'static str,
        /// What is wrong.
        reason: String,
    },

    /// The dependent coordinates (speeds) left by the choice of independent ones
    /// cannot be solved for: Φ_{q_d} (G_d) is singular at the operating point.
    #[error(
        "the dependent {what} {dependent:?} cannot be solved for at the operating point \
         (condition ratio sigma_min / sigma_max = {ratio:e}); choose other independent {what}"
    )]
    SingularPartition {
        /// `coordinates` or `speeds`.
        what: &'static str,
        /// The dependent ones.
        dependent: Vec<String>,
        /// Smallest over largest singular value of Φ_{q_d} (G_d).
        ratio: f64,
    },

    /// A state name given to [`Linear::select`](crate::linear::Linear::select) does not exist.
    #[error("no state named `{name}`; the states are {states:?}")]
    UnknownState {
        /// The name asked for.
        name: String,
        /// The available names.
        states: Vec<String>,
    },

    /// [`Linear::select`](crate::linear::Linear::select) would drop a state that a kept one depends on.
    #[error(
        "cannot drop `{dropped}`: kept state `{kept}` depends on it (A[{kept}, {dropped}] = \
         {coupling:e}, tolerance {tolerance:e})"
    )]
    CoupledStates {
        /// The kept state.
        kept: String,
        /// The dropped state it depends on.
        dropped: String,
        /// The coupling entry of A.
        coupling: f64,
        /// The absolute tolerance it exceeds.
        tolerance: f64,
    },

    /// A stability boundary could not be resolved to the requested tolerance.
    #[error(
        "stability boundary between p = {lo} and p = {hi} not resolved to relative \
         tolerance {tolerance:e}"
    )]
    BoundaryNotResolved {
        /// Lower end of the final bracket.
        lo: f64,
        /// Upper end of the final bracket.
        hi: f64,
        /// The relative tolerance asked for.
        tolerance: f64,
    },

    /// (A, B) is not stabilisable: an eigenvalue of A with Re λ ≥ 0 is
    /// uncontrollable (PBH test: [A − λI, B] loses rank), or the Riccati solution
    /// does not stabilise A − BK.
    #[error(
        "(A, B) is not stabilisable: the mode with eigenvalue {re} + {im}i cannot be \
         moved by the inputs (rank ratio {ratio:e})"
    )]
    NotStabilisable {
        /// Real part of the offending eigenvalue.
        re: f64,
        /// Imaginary part.
        im: f64,
        /// σ_min / σ_max of [A − λI, B] (or, for a closed loop that is not
        /// Hurwitz, the largest closed-loop Re λ).
        ratio: f64,
    },

    /// No equilibrium was found: the Gauss–Newton iteration of
    /// [`Trim`](crate::linear::Trim) stopped (out of iterations, or no step
    /// lowered the residual) with q̈ (and, for a constrained system, the
    /// constraints' residuals) still above the tolerance. The best iterate
    /// is kept: there the residual is smallest.
    #[error(
        "no equilibrium found: after {iterations} iteration(s) the largest residual is \
         {residual:e} ({worst}), above the tolerance {tolerance:e}; {why}. The best point \
         reached is in the error (`best`)"
    )]
    NoEquilibrium {
        /// max |q̈| (and the constraints' |residuals|) at the best iterate.
        residual: f64,
        /// Which is largest there: an acceleration by its velocity's name
        /// (`theta`); for a constrained system `q̈ along the constraints`,
        /// a constraint (`constraint \`loop_x\``), its velocity row
        /// (`velocity of constraint \`roll\``) or its γ (`acceleration of
        /// constraint \`roll\``).
        worst: String,
        /// The tolerance asked for.
        tolerance: f64,
        /// Iterations done.
        iterations: usize,
        /// Why the iteration stopped.
        why: String,
        /// The best iterate: where |q̈| is smallest.
        best: Box<StatePoint>,
    },

    /// The Riccati iteration failed or its residual is too large.
    #[error("Riccati equation not solved: {reason} (relative residual {residual:e})")]
    Riccati {
        /// What went wrong.
        reason: String,
        /// The relative residual reached (NaN if none).
        residual: f64,
    },
}

/// A state and its inputs as plain numbers: the best point an iteration
/// reached ([`LinearError::NoEquilibrium`]).
#[derive(Clone, Debug, PartialEq)]
pub struct StatePoint {
    /// The configuration (Q numbers: unit quaternions for orientations).
    pub q: Vec<f64>,
    /// The velocities.
    pub v: Vec<f64>,
    /// The inputs.
    pub u: Vec<f64>,
}
