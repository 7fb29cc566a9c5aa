//! Identification of a system's inertial parameters from measured motion.
//!
//! The equations of motion are linear in the inertial parameters π (per
//! body its mass, first moments and inertia, see
//! [`Lagrangian::REGRESSOR_PARAMETERS`]): τ = Y(q, q̇, q̈) π, Y the regressor
//! `emit(regressor)` writes. Not every parameter shows in the motion: some
//! never move anything (a base fixed in space), some only ever act together
//! (a link's mass and its parent's first moment). [`BaseParameters`] finds
//! the smallest set that does, each a linear combination of the standard
//! ones, from the regressor stacked at random states; [`identify`]
//! estimates them by weighted least squares from recorded samples, with
//! their covariance (Atkeson, An and Hollerbach 1986; Gautier and Khalil
//! 1990).
//!
//! Around them: [`exciting_trajectory`] chooses a periodic motion
//! ([`Fourier`]) within [`JointLimits`] that conditions the stacked
//! regressor well (Swevers et al. 1997); [`identify_consistent`] estimates
//! a full π that a real body has (each pseudo-inertia positive definite,
//! [`is_physically_consistent`]); [`identify_subset`] estimates a few
//! parameters with the rest known (a payload on an identified robot);
//! [`body_parameters`] and [`add_to_body`] write a tool's or a payload's ten
//! parameters into a known π, and [`body_from_parameters`] reads a mass,
//! centre and inertia back.

mod base;
mod columns;
mod consistent;
mod estimate;
mod excite;
mod fourier;
mod nelder_mead;
mod pseudo_inertia;
mod rigid;
mod subset;

pub use base::BaseParameters;
pub use consistent::{Consistency, ConsistentEstimate, identify_consistent};
pub use estimate::{Estimate, Sample, identify};
pub use excite::{Excitation, Excited, condition_number, exciting_trajectory};
pub use fourier::{Fourier, JointLimits};
pub use pseudo_inertia::{inconsistent_bodies, is_physically_consistent, pseudo_inertia};
pub use rigid::{add_to_body, body_from_parameters, body_parameters};
pub use subset::{SubsetEstimate, identify_subset};

use nalgebra::{DMatrix, SVector};

use crate::error::IdentifyError;
use crate::system::Lagrangian;

/// Y at (q, q̇, q̈), or the error naming the missing method.
fn regressor_at<S, const N: usize, const Q: usize>(
    sys: &S,
    q: &SVector<f64, Q>,
    v: &SVector<f64, N>,
    a: &SVector<f64, N>,
) -> Result<DMatrix<f64>, IdentifyError>
where
    S: Lagrangian<f64, N, Q>,
{
    sys.regressor(q, v, a, 0.0)
        .ok_or(IdentifyError::NoRegressor {
            method: "regressor",
        })
}

/// Regressors at `states` stacked, one block of N rows per state.
fn stacked<S, const N: usize, const Q: usize>(
    sys: &S,
    states: &[State<N, Q>],
) -> Result<DMatrix<f64>, IdentifyError>
where
    S: Lagrangian<f64, N, Q>,
{
    let columns = S::REGRESSOR_PARAMETERS.len();
    let mut w = DMatrix::zeros(states.len() * N, columns);
    // Each block written in place: no matrix per state.
    for (k, (q, v, a)) in states.iter().enumerate() {
        sys.regressor_into(q, v, a, 0.0, w.view_mut((k * N, 0), (N, columns)))?;
    }
    Ok(w)
}

/// One state (q, q̇, q̈).
type State<const N: usize, const Q: usize> = (SVector<f64, Q>, SVector<f64, N>, SVector<f64, N>);

/// `count` states drawn from a fixed sequence: every coordinate in [−π, π]
/// (each free orientation's quaternion then put back on the unit sphere),
/// every speed and acceleration in [−2, 2]. Deterministic, so the base
/// parameters a system has are the same on every run.
fn random_states<S, const N: usize, const Q: usize>(count: usize) -> Vec<State<N, Q>>
where
    S: Lagrangian<f64, N, Q>,
{
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        // SplitMix64: a well-mixed sequence from a counter, enough for
        // states in general position.
        seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = seed;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..count)
        .map(|_| {
            let mut q = SVector::<f64, Q>::from_fn(|_, _| std::f64::consts::PI * next());
            crate::numeric::orientation::normalise(S::ORIENTATIONS, q.as_mut_slice());
            let v = SVector::<f64, N>::from_fn(|_, _| 2.0 * next());
            let a = SVector::<f64, N>::from_fn(|_, _| 2.0 * next());
            (q, v, a)
        })
        .collect()
}
