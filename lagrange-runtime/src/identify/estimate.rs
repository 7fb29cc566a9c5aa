//! The base parameters estimated from recorded samples by weighted least
//! squares, with their covariance.

use nalgebra::{DMatrix, DVector, SVector};

use super::base::BaseParameters;
use super::columns::independent;
use crate::error::IdentifyError;
use crate::system::Lagrangian;

/// One recorded sample: the configuration, speeds, accelerations and the
/// generalized forces τ that drove them (every force but the masses' own:
/// the motors' torques, less any friction or spring the model has outside
/// π).
#[derive(Clone, Debug, PartialEq)]
pub struct Sample<const N: usize, const Q: usize = N> {
    /// q.
    pub q: SVector<f64, Q>,
    /// q̇.
    pub v: SVector<f64, N>,
    /// q̈.
    pub a: SVector<f64, N>,
    /// τ.
    pub tau: SVector<f64, N>,
}

/// The base parameters estimated: values, covariance and the fit's residual.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// π_b, in [`BaseParameters::names`]' order.
    pub values: DVector<f64>,
    /// Their covariance (WᵀW)⁻¹, W the stacked base regressor with each
    /// joint's rows divided by its noise's standard deviation: the
    /// estimate's covariance when τ's errors are independent with those
    /// deviations.
    pub covariance: DMatrix<f64>,
    /// The weighted residual's root mean square, ‖W π_b − τ/σ‖/√rows: near 1
    /// when the noise levels given are right and the model fits.
    pub residual: f64,
}

impl Estimate {
    /// Each estimate's standard deviation, √diag(covariance).
    pub fn standard_deviations(&self) -> DVector<f64> {
        self.covariance.diagonal().map(f64::sqrt)
    }
}

/// π_b from `samples` by least squares, each joint's equations weighted by
/// the inverse of its torque noise's standard deviation `noise[j]`.
///
/// # Errors
/// [`IdentifyError::Noise`] for a noise level that is not positive and
/// finite; [`IdentifyError::NotFinite`] for a NaN or an infinity in a
/// sample; [`IdentifyError::TooFewSamples`] for fewer equations than base
/// parameters; [`IdentifyError::RankDeficient`], naming them, when the
/// samples do not excite every base parameter;
/// [`IdentifyError::NoRegressor`] unless the system was derived with
/// `emit(regressor)`; [`IdentifyError::Lengths`] for base parameters found
/// for another system.
pub fn identify<S, const N: usize, const Q: usize>(
    sys: &S,
    base: &BaseParameters,
    samples: &[Sample<N, Q>],
    noise: &SVector<f64, N>,
) -> Result<Estimate, IdentifyError>
where
    S: Lagrangian<f64, N, Q>,
{
    check_data(samples, noise)?;
    let parameters = base.len();
    if samples.len() * N < parameters {
        return Err(IdentifyError::TooFewSamples {
            samples: samples.len(),
            joints: N,
            equations: samples.len() * N,
            parameters,
            needed: parameters.div_ceil(N.max(1)),
        });
    }
    let (w, y) = weighted(sys, base, samples, noise)?;
    if parameters == 0 {
        // Nothing to estimate (no mass moves): the data are all residual.
        return Ok(Estimate {
            values: DVector::zeros(0),
            covariance: DMatrix::zeros(0, 0),
            residual: y.norm() / (y.len().max(1) as f64).sqrt(),
        });
    }
    let flags = independent(&w);
    if flags.iter().any(|&kept| !kept) {
        let names = base.names();
        let unidentifiable = (0..parameters)
            .filter(|&k| !flags[k])
            .map(|k| names[k].to_string())
            .collect();
        let rank = flags.iter().filter(|&&kept| kept).count();
        return Err(IdentifyError::RankDeficient {
            rank,
            parameters,
            unidentifiable,
        });
    }
    Ok(solve(&w, &y))
}

/// The noise levels positive and finite, every sample's entries finite.
pub(super) fn check_data<const N: usize, const Q: usize>(
    samples: &[Sample<N, Q>],
    noise: &SVector<f64, N>,
) -> Result<(), IdentifyError> {
    if let Some((joint, &value)) =
        (noise.iter().enumerate()).find(|(_, s)| !(s.is_finite() && **s > 0.0))
    {
        return Err(IdentifyError::Noise { joint, value });
    }
    for (k, s) in samples.iter().enumerate() {
        let fields = [
            ("q", s.q.as_slice()),
            ("v", s.v.as_slice()),
            ("a", s.a.as_slice()),
            ("tau", s.tau.as_slice()),
        ];
        finite(k, &fields)?;
    }
    Ok(())
}

/// W and τ/σ stacked, one block of N rows per sample.
pub(super) fn weighted<S, const N: usize, const Q: usize>(
    sys: &S,
    base: &BaseParameters,
    samples: &[Sample<N, Q>],
    noise: &SVector<f64, N>,
) -> Result<(DMatrix<f64>, DVector<f64>), IdentifyError>
where
    S: Lagrangian<f64, N, Q>,
{
    stack(samples, noise, base.len(), |s| {
        base.regressor(sys, &s.q, &s.v, &s.a)
    })
}

/// The full regressor Y (every column of π) and τ, weighted and stacked as
/// [`weighted`] stacks Y_b.
pub(super) fn weighted_full<S, const N: usize, const Q: usize>(
    sys: &S,
    samples: &[Sample<N, Q>],
    noise: &SVector<f64, N>,
) -> Result<(DMatrix<f64>, DVector<f64>), IdentifyError>
where
    S: Lagrangian<f64, N, Q>,
{
    let columns = S::REGRESSOR_PARAMETERS.len();
    stack(samples, noise, columns, |s| {
        let y = super::regressor_at(sys, &s.q, &s.v, &s.a)?;
        if y.ncols() != columns {
            return Err(IdentifyError::Lengths {
                what: "Lagrangian::regressor's matrix",
                got: y.ncols(),
                expected: columns,
            });
        }
        Ok(y)
    })
}

/// Each sample's N × `columns` block from `regressor`, its row j divided by
/// σ_j, and τ_j/σ_j beside it.
fn stack<const N: usize, const Q: usize>(
    samples: &[Sample<N, Q>],
    noise: &SVector<f64, N>,
    columns: usize,
    regressor: impl Fn(&Sample<N, Q>) -> Result<DMatrix<f64>, IdentifyError>,
) -> Result<(DMatrix<f64>, DVector<f64>), IdentifyError> {
    let rows = samples.len() * N;
    let mut w = DMatrix::zeros(rows, columns);
    let mut y = DVector::zeros(rows);
    for (k, s) in samples.iter().enumerate() {
        let block = regressor(s)?;
        for j in 0..N {
            let r = k * N + j;
            w.row_mut(r).copy_from(&(block.row(j) / noise[j]));
            y[r] = s.tau[j] / noise[j];
        }
    }
    Ok((w, y))
}

/// The least-squares solution by QR (W = Q R: π_b = R⁻¹ Qᵀ y, covariance
/// R⁻¹ R⁻ᵀ), W of full column rank.
pub(super) fn solve(w: &DMatrix<f64>, y: &DVector<f64>) -> Estimate {
    let qr = w.clone().qr();
    let r = qr.r();
    let n = r.nrows();
    // Full column rank was checked: R's diagonal has no zero.
    let r_inv = r
        .solve_upper_triangular(&DMatrix::identity(n, n))
        .unwrap_or_else(|| DMatrix::zeros(n, n));
    let values = &r_inv * (qr.q().transpose() * y);
    let covariance = &r_inv * r_inv.transpose();
    let residual = (w * &values - y).norm() / (y.len().max(1) as f64).sqrt();
    Estimate {
        values,
        covariance,
        residual,
    }
}

/// The first entry that is not a finite number, as the error naming it.
pub(super) fn finite(
    sample: usize,
    fields: &[(&'static str, &[f64])],
) -> Result<(), IdentifyError> {
    for &(field, values) in fields {
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(IdentifyError::NotFinite {
                sample,
                field,
                index,
                value,
            });
        }
    }
    Ok(())
}
