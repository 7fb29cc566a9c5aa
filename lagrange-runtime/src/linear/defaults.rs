//! The linearisations with the default [`Linearizer`] settings.

use super::Linear;
use super::settings::{Linearizer, OperatingPoint};
use crate::error::Error;
use crate::numeric::Real;
use crate::system::{Constrained, Driven, Lagrangian, Reduced};
use nalgebra::SVector;

/// [`Linearizer::unconstrained`] with the default settings.
///
/// # Errors
/// As [`Linearizer::unconstrained`].
pub fn linearize<S, T, const N: usize, const P: usize, const U: usize>(
    sys: &S,
    op: &OperatingPoint<T, N, U>,
) -> Result<Linear, Error>
where
    S: Driven<T, N, P>,
    T: Real,
{
    Linearizer::new().unconstrained(sys, op)
}

/// [`Linearizer::constrained`] with the default settings (automatic independent
/// coordinates and speeds).
///
/// # Errors
/// As [`Linearizer::constrained`].
pub fn linearize_constrained<S, T, const N: usize, const K: usize, const P: usize, const U: usize>(
    sys: &S,
    op: &OperatingPoint<T, N, U>,
) -> Result<Linear, Error>
where
    S: Constrained<T, N, K> + Driven<T, N, P>,
    T: Real,
{
    Linearizer::new().constrained(sys, op)
}

/// [`Linearizer::reduced`] with the default settings.
///
/// # Errors
/// As [`Linearizer::reduced`].
pub fn linearize_reduced<S, T, const N: usize, const K: usize, const P: usize, const U: usize>(
    sys: &S,
    op: &OperatingPoint<T, N, U>,
) -> Result<Linear, Error>
where
    S: Reduced<T, N, K> + Driven<T, N, P>,
    T: Real,
{
    Linearizer::new().reduced(sys, op)
}

/// [`Linearizer::complete_state`] with the given independent coordinates and
/// speeds (empty slices for the automatic choice) and default tolerances.
///
/// # Errors
/// As [`Linearizer::complete_state`].
pub fn complete_state<S, T, const N: usize>(
    sys: &S,
    q: SVector<T, N>,
    v: SVector<T, N>,
    t: T,
    coordinates: &[&str],
    speeds: &[&str],
) -> Result<(SVector<T, N>, SVector<T, N>), Error>
where
    S: Lagrangian<T, N>,
    T: Real,
{
    let mut lin = Linearizer::new();
    if !coordinates.is_empty() {
        lin = lin.coordinates(coordinates);
    }
    if !speeds.is_empty() {
        lin = lin.speeds(speeds);
    }
    lin.complete_state(sys, q, v, t)
}
