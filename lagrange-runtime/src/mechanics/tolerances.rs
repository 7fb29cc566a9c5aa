//! The tolerances a run and a linearisation of a system share.

use super::constraint::{DEFAULT_CONSISTENCY_TOLERANCE, DEFAULT_REDUNDANT_TOLERANCE};
use super::dynamics::DEFAULT_SINGULAR_TOLERANCE;
use crate::error::{Error, check_tolerance};

/// The thresholds below which a system's matrices count as singular, and the
/// tolerance of its initial state on the constraints.
///
/// A [`Simulation`](crate::Simulation) and a
/// [`Linearizer`](crate::linear::Linearizer) both hold one: given the same
/// `Tolerances`, a linearisation judges a singular mass matrix, redundant
/// constraints and an inconsistent state at the thresholds a run started
/// there would use.
///
/// ```
/// # use lagrange_runtime::mechanics::Tolerances;
/// let tight = Tolerances { singular: 1e-14, ..Tolerances::default() };
/// assert_eq!(tight.consistency, 1e-10);
/// assert!(tight.check().is_ok());
/// assert!(Tolerances { redundant: f64::NAN, ..tight }.check().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// The mass matrix's pivot ratio min L_ii² / max L_ii² below which it is
    /// singular ([`Error::SingularMassMatrix`]); default 1e-12.
    pub singular: f64,
    /// The pivot ratio of G M⁻¹ Gᵀ (or σ_min/σ_max of a constraint block)
    /// below which constraint rows count as redundant
    /// ([`Error::RedundantConstraints`]); default 1e-12.
    pub redundant: f64,
    /// The absolute tolerance on max |Φ| and max |G q̇ + g| of an initial
    /// state or an operating point
    /// ([`Error::InconsistentInitialConditions`]); default 1e-10.
    pub consistency: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            singular: DEFAULT_SINGULAR_TOLERANCE,
            redundant: DEFAULT_REDUNDANT_TOLERANCE,
            consistency: DEFAULT_CONSISTENCY_TOLERANCE,
        }
    }
}

impl Tolerances {
    /// Checks every tolerance is non-negative and finite.
    ///
    /// # Errors
    /// [`Error::Settings`] naming the first that is not.
    pub fn check(&self) -> Result<(), Error> {
        check_tolerance("tolerances", "singular tolerance", self.singular)?;
        check_tolerance("tolerances", "redundant tolerance", self.redundant)?;
        check_tolerance("tolerances", "consistency tolerance", self.consistency)
    }
}
