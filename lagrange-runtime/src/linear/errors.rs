//! The errors a linearisation builds, in one place.

use crate::error::{Error, to_vec};
use crate::numeric::Real;
use crate::system::Constrained;
use nalgebra::SVector;

pub(super) fn missing(method: &'static str) -> Error {
    Error::MissingDerivatives {
        method,
        needed_for: "linearisation",
    }
}

pub(super) fn singular<T: Real, const N: usize>(t: T, q: &SVector<T, N>, ratio: f64) -> Error {
    Error::SingularMassMatrix {
        t: t.to_f64(),
        q: to_vec(q),
        ratio,
        direction: String::new(),
        atlas: false,
    }
}

pub(super) fn redundant<S, T, const N: usize, const K: usize, const Q: usize>(
    t: T,
    q: &SVector<T, Q>,
    ratio: f64,
    rows: Vec<usize>,
) -> Error
where
    S: Constrained<T, N, K, Q>,
    T: Real,
{
    Error::RedundantConstraints {
        t: t.to_f64(),
        q: to_vec(q),
        coordinates: S::COORDINATES.to_vec(),
        ratio,
        dependent: rows.iter().map(|&i| S::CONSTRAINTS[i]).collect(),
    }
}
