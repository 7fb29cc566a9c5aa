//! Central differences, for the linearisations that differentiate the
//! dynamics numerically: on the group, in an atlas's charts, and without
//! emitted Jacobians. One step rule and one column for all of them.

use crate::numeric::Real;
use nalgebra::SVector;

/// The central-difference step for an entry of scale `x`: the cube root of
/// the scalar's epsilon (the step that balances truncation and round-off,
/// about 1e-10 relative error in f64), times max(1, |x|).
fn step<T: Real>(x: f64) -> f64 {
    T::default_epsilon().to_f64().cbrt() * x.abs().max(1.0)
}

/// The central-difference step for an entry of scale `x` and the vector with
/// that step in entry `j`.
pub(super) fn unit<T: Real, const R: usize>(j: usize, x: f64) -> (f64, SVector<T, R>) {
    let h = step::<T>(x);
    let mut e = SVector::<T, R>::zeros();
    e[j] = T::lit(h);
    (h, e)
}

/// (f(+h) − f(−h)) / 2h, zero where it is below the round-off of the
/// difference, 16 ε (|f(+h)| + |f(−h)|) / 2h (ε the scalar's epsilon): a direction the
/// function does not depend on (a cyclic coordinate, a spin about an axis of symmetry)
/// gives an exact zero, as the symbolic derivatives would, so that
/// [`Linear::stability`](super::Linear::stability) sees its zero eigenvalue as structural.
pub(super) fn column<T: Real, const R: usize>(
    plus: SVector<T, R>,
    minus: SVector<T, R>,
    h: f64,
) -> Vec<f64> {
    let f = |x: SVector<T, R>| x.iter().map(|e| e.to_f64()).collect::<Vec<f64>>();
    difference::<T>(&f(plus), &f(minus), h)
}

/// [`column`] of plain numbers.
pub(super) fn difference<T: Real>(plus: &[f64], minus: &[f64], h: f64) -> Vec<f64> {
    let eps = T::default_epsilon().to_f64();
    (plus.iter().zip(minus))
        .map(|(&p, &m)| {
            let d = (p - m) / (2.0 * h);
            let floor = 16.0 * eps * (p.abs() + m.abs()) / (2.0 * h);
            if d.abs() <= floor { 0.0 } else { d }
        })
        .collect()
}
