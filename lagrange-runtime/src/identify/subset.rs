//! Estimates of some of π with the rest known: a payload on a robot whose
//! own parameters were identified (or given by its maker) before,
//! τ − Y_known π_known = Y_chosen π_chosen.

use nalgebra::{DMatrix, DVector, SVector};

use super::columns::independent;
use super::estimate::{Sample, check_data, solve, weighted_full};
use super::pseudo_inertia::{Block, layout};
use crate::error::IdentifyError;
use crate::system::Lagrangian;

/// The chosen parameters estimated, with their covariance.
#[derive(Clone, Debug, PartialEq)]
pub struct SubsetEstimate {
    /// The chosen parameters' names, in π's order.
    pub names: Vec<String>,
    /// Their indices in π.
    pub indices: Vec<usize>,
    /// Their estimates.
    pub values: DVector<f64>,
    /// The estimates' covariance, as [`super::Estimate`]'s: (WᵀW)⁻¹ of the
    /// chosen columns, weighted.
    pub covariance: DMatrix<f64>,
    /// The weighted residual's root mean square: near 1 when the noise
    /// levels are right and the known parameters are.
    pub residual: f64,
}

impl SubsetEstimate {
    /// Each estimate's standard deviation, √diag(covariance).
    pub fn standard_deviations(&self) -> DVector<f64> {
        self.covariance.diagonal().map(f64::sqrt)
    }

    /// The estimate of the parameter named `name`, if it was chosen.
    pub fn value(&self, name: &str) -> Option<f64> {
        let k = self.names.iter().position(|n| n == name)?;
        Some(self.values[k])
    }

    /// The estimates less the known π's values of the same parameters:
    /// what was added to them (a payload's own parameters, about the
    /// body's reference point, when `known` is the robot's π without it).
    ///
    /// # Errors
    /// [`IdentifyError::Lengths`] when `known` is shorter than the indices
    /// reach.
    pub fn change_from(&self, known: &DVector<f64>) -> Result<DVector<f64>, IdentifyError> {
        let expected = self.indices.iter().map(|&k| k + 1).max().unwrap_or(0);
        if known.len() < expected {
            return Err(IdentifyError::Lengths {
                what: "the known π",
                got: known.len(),
                expected,
            });
        }
        Ok(DVector::from_fn(self.indices.len(), |i, _| {
            self.values[i] - known[self.indices[i]]
        }))
    }
}

/// The parameters `chosen` estimated from `samples` by weighted least
/// squares, every other parameter of π held at its value in `known`:
/// τ/σ − W_known π_known = W_chosen π_chosen. An entry of `chosen` is a
/// parameter's name (`wrist_3_link.m`) or a body's (`wrist_3_link`: its
/// ten parameters). `known` is a full π (`known`'s entries for the chosen
/// parameters are not read). The model passed supplies only the regressor.
///
/// # Errors
/// [`IdentifyError::UnknownParameter`] for a name that is neither a
/// parameter nor a body; [`IdentifyError::Lengths`] for a `known` not as
/// long as π; [`IdentifyError::NotFiniteValue`] for a NaN in it;
/// [`IdentifyError::TooFewSamples`] for fewer equations than chosen
/// parameters; [`IdentifyError::Inseparable`], naming them, when the data
/// cannot tell some chosen parameters from the others (a parameter that
/// acts only with another, or a motion that does not excite it); the data
/// errors of [`super::identify`].
pub fn identify_subset<S, const N: usize, const Q: usize>(
    sys: &S,
    samples: &[Sample<N, Q>],
    noise: &SVector<f64, N>,
    chosen: &[&str],
    known: &DVector<f64>,
) -> Result<SubsetEstimate, IdentifyError>
where
    S: Lagrangian<f64, N, Q>,
{
    check_data(samples, noise)?;
    let names = S::REGRESSOR_PARAMETERS;
    let indices = resolve(names, chosen)?;
    if known.len() != names.len() {
        return Err(IdentifyError::Lengths {
            what: "the known π",
            got: known.len(),
            expected: names.len(),
        });
    }
    let unread = |k: &usize| indices.binary_search(k).is_err();
    if let Some(index) = (0..known.len())
        .filter(unread)
        .find(|&k| !known[k].is_finite())
    {
        return Err(IdentifyError::NotFiniteValue {
            what: "the known π",
            index,
            value: known[index],
        });
    }
    if samples.len() * N < indices.len() {
        return Err(IdentifyError::TooFewSamples {
            samples: samples.len(),
            joints: N,
            equations: samples.len() * N,
            parameters: indices.len(),
            needed: indices.len().div_ceil(N.max(1)),
        });
    }
    let (w, y) = weighted_full(sys, samples, noise)?;
    let mut held = known.clone();
    for &k in &indices {
        held[k] = 0.0;
    }
    let y = y - &w * held;
    let w_chosen = w.select_columns(&indices);
    let flags = independent(&w_chosen);
    let inseparable: Vec<String> = (flags.iter().zip(&indices))
        .filter(|(kept, _)| !**kept)
        .map(|(_, &k)| names[k].to_string())
        .collect();
    if !inseparable.is_empty() {
        return Err(IdentifyError::Inseparable {
            parameters: inseparable,
        });
    }
    let fit = solve(&w_chosen, &y);
    Ok(SubsetEstimate {
        names: indices.iter().map(|&k| names[k].to_string()).collect(),
        indices,
        values: fit.values,
        covariance: fit.covariance,
        residual: fit.residual,
    })
}

/// The indices, in π's order and each once, of the parameters and bodies
/// named.
fn resolve(names: &[&str], chosen: &[&str]) -> Result<Vec<usize>, IdentifyError> {
    let blocks = layout(names)?;
    let mut indices = Vec::new();
    for &name in chosen {
        if let Some(k) = names.iter().position(|n| *n == name) {
            indices.push(k);
            continue;
        }
        match blocks.iter().find(|b| b.name() == name) {
            Some(Block::Body { first, .. }) => indices.extend(*first..*first + 10),
            Some(Block::Point { index, .. } | Block::Joint { index, .. }) => indices.push(*index),
            None => {
                return Err(IdentifyError::UnknownParameter {
                    name: name.to_string(),
                });
            }
        }
    }
    indices.sort_unstable();
    indices.dedup();
    Ok(indices)
}
