//! The checks that turn a bad setting, a quaternion off unit norm or a
//! non-finite input into the error that names it.

use super::{Error, SettingsError, to_vec};
use crate::numeric::Real;
use crate::numeric::orientation::{self, Orientation, UNIT_TOLERANCE};
use nalgebra::SVector;

/// Refuses a tolerance that is negative, NaN or infinite, naming the setting:
/// every tolerance of the library is checked this way, so a sign slip is an
/// error rather than a verdict (a negative stability tolerance would call an
/// undamped oscillator asymptotically stable; a negative consistency
/// tolerance would call an exactly consistent state inconsistent).
pub(crate) fn check_tolerance(
    owner: &'static str,
    setting: &'static str,
    tol: f64,
) -> Result<(), Error> {
    if tol.is_finite() && tol >= 0.0 {
        Ok(())
    } else {
        Err(SettingsError::Value {
            owner,
            setting,
            value: tol,
            requirement: "non-negative and finite".into(),
        }
        .into())
    }
}

/// The initial configuration with its quaternions normalised, or
/// [`Error::NonUnitQuaternion`] naming the first one that is further than
/// [`UNIT_TOLERANCE`] from unit norm (or not finite). `names` are the
/// coordinates' names; an orientation is named by its `w`'s name without the
/// `.w`.
pub(crate) fn unit_quaternions<T: Real, const Q: usize>(
    layout: &[Orientation],
    names: &[&'static str; Q],
    mut q: SVector<T, Q>,
) -> Result<SVector<T, Q>, Error> {
    if let Some((o, norm)) = orientation::first_off_unit(layout, q.as_slice()) {
        let name = names[o.q];
        return Err(Error::NonUnitQuaternion {
            orientation: name.strip_suffix(".w").unwrap_or(name).to_string(),
            norm,
            tolerance: UNIT_TOLERANCE,
        });
    }
    orientation::normalise(layout, q.as_mut_slice());
    Ok(q)
}

/// The first non-finite entry of the inputs `u` as
/// [`Error::NonFiniteInput`], named from `names`, with the state it was
/// computed for.
pub(crate) fn check_finite_inputs<T: Real, const N: usize, const P: usize, const Q: usize>(
    names: &[&'static str; P],
    t: T,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
    u: &SVector<T, P>,
) -> Result<(), Error> {
    match u.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(i) => Err(Error::NonFiniteInput {
            t: t.to_f64(),
            input: names[i],
            value: u[i].to_f64(),
            q: to_vec(q),
            v: to_vec(v),
        }),
    }
}
