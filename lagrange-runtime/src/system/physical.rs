//! The rules a mass and an inertia obey, checked on parameter values:
//! what [`Lagrangian::check_parameters`](crate::Lagrangian::check_parameters)
//! calls in a derived system (the derive refuses literal values at compile
//! time by the same rules), usable by a hand-written one.
//!
//! - A mass is non-negative (zero is allowed: a massless point or body whose
//!   coordinates something else moves).
//! - A principal moment is non-negative (zero is allowed: the idealised
//!   slender rod has no moment about its axis), and the three satisfy the
//!   triangle inequalities A + B ≥ C, B + C ≥ A, C + A ≥ B: the moment about
//!   one axis is ∫(x² + y²) dm, at most the sum of the other two.
//! - A full tensor I is that of a mass distribution iff its second-moment
//!   matrix S = tr(I)/2·E − I (= ∫ r rᵀ dm) is positive semidefinite; that
//!   implies both rules above for its principal moments.
//!
//! - A joint's damping and armature are non-negative.
//!
//! Equalities are allowed up to a relative round-off of 1e-12.

use crate::error::Error;
use crate::numeric::Real;
use nalgebra::Matrix3;

/// Relative round-off allowed on the inequalities.
const ROUND_OFF: f64 = 1e-12;

/// A mass must be finite and non-negative.
///
/// # Errors
/// [`Error::NonPhysicalParameter`] with entry `mass`.
pub fn mass<T: Real>(body: &'static str, m: T) -> Result<(), Error> {
    let m = m.to_f64();
    if m.is_finite() && m >= 0.0 {
        return Ok(());
    }
    Err(Error::NonPhysicalParameter {
        body,
        entry: "mass",
        value: m,
        reason: "a mass must be finite and non-negative".to_string(),
    })
}

/// A joint's damping, armature or rotor inertia (`entry`) on the coordinate `coordinate`
/// must be finite and non-negative: a negative one feeds energy in.
///
/// # Errors
/// [`Error::NonPhysicalParameter`] naming the coordinate (as `body`) and the
/// entry.
pub fn joint<T: Real>(
    coordinate: &'static str,
    entry: &'static str,
    value: T,
) -> Result<(), Error> {
    let x = value.to_f64();
    if x.is_finite() && x >= 0.0 {
        return Ok(());
    }
    Err(Error::NonPhysicalParameter {
        body: coordinate,
        entry,
        value: x,
        reason: format!(
            "a joint's {entry} must be finite and non-negative (a negative one feeds energy in)"
        ),
    })
}

/// A joint's gear ratio (`joint(q, gear = n)`), named by its coordinate.
///
/// # Errors
/// [`Error::NonPhysicalParameter`] (entry `"gear"`) unless it is finite and
/// positive: a ratio of 0 would cut the motor off.
pub fn gear_ratio<T: Real>(coordinate: &'static str, value: T) -> Result<(), Error> {
    let x = value.to_f64();
    if x.is_finite() && x > 0.0 {
        return Ok(());
    }
    Err(Error::NonPhysicalParameter {
        body: coordinate,
        entry: "gear",
        value: x,
        reason: "a joint's gear ratio must be finite and positive (motor turns per joint turn)"
            .to_string(),
    })
}

/// Principal moments `[A, B, C]` about the centre of mass.
///
/// # Errors
/// [`Error::NonPhysicalParameter`] naming the moment that is negative (or not
/// finite), or the one that exceeds the sum of the other two.
pub fn principal<T: Real>(body: &'static str, moments: [T; 3]) -> Result<(), Error> {
    let m = moments.map(|x| x.to_f64());
    let names = ["A", "B", "C"];
    moments_non_negative(body, &names, &m)?;
    let tol = ROUND_OFF * (m[0] + m[1] + m[2]);
    for k in 0..3 {
        let i = (k + 1) % 3;
        let j = (k + 2) % 3;
        if m[i] + m[j] < m[k] - tol {
            let a = names[i];
            let b = names[j];
            let c = names[k];
            return Err(Error::NonPhysicalParameter {
                body,
                entry: names[k],
                value: m[k],
                reason: format!(
                    "the principal moments break the triangle inequality {a} + {b} >= {c} \
                     ({} + {} < {}): no mass distribution has them (the moment about one \
                     axis is at most the sum of the other two)",
                    m[i], m[j], m[k]
                ),
            });
        }
    }
    Ok(())
}

/// The moments of a body that turns about fewer than three of its axes (a
/// planar body, `rot_z` only, written `[0, 0, Iz]`): the equations never read
/// the moments the triangle inequalities would constrain, so only their signs
/// are checked. `names` are `["A", "B", "C"]` or `["Ixx", "Iyy", "Izz"]`.
///
/// # Errors
/// [`Error::NonPhysicalParameter`] naming the moment that is negative (or not
/// finite).
pub fn moments<T: Real>(
    body: &'static str,
    names: [&'static str; 3],
    moments: [T; 3],
) -> Result<(), Error> {
    moments_non_negative(body, &names, &moments.map(|x| x.to_f64()))
}

/// The tensor `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]` about the centre of mass
/// (products with the tensor's sign, I_xy = −∫xy dm).
///
/// # Errors
/// [`Error::NonPhysicalParameter`] naming a negative (or non-finite) diagonal
/// entry, a non-finite product, or the tensor as a whole when its
/// second-moment matrix has a negative eigenvalue (the value reported).
pub fn tensor<T: Real>(body: &'static str, entries: [T; 6]) -> Result<(), Error> {
    let e = entries.map(|x| x.to_f64());
    moments_non_negative(body, &["Ixx", "Iyy", "Izz"], &[e[0], e[1], e[2]])?;
    for (name, &v) in ["Ixy", "Ixz", "Iyz"].iter().zip(&e[3..]) {
        if !v.is_finite() {
            return Err(Error::NonPhysicalParameter {
                body,
                entry: name,
                value: v,
                reason: "a product of inertia must be finite".to_string(),
            });
        }
    }
    let half_trace = 0.5 * (e[0] + e[1] + e[2]);
    let inertia = Matrix3::new(e[0], e[3], e[4], e[3], e[1], e[5], e[4], e[5], e[2]);
    let second = Matrix3::from_diagonal_element(half_trace) - inertia;
    let lowest = second.symmetric_eigenvalues().min();
    if lowest < -ROUND_OFF * half_trace {
        return Err(Error::NonPhysicalParameter {
            body,
            entry: "inertia tensor",
            value: lowest,
            reason: "its second-moment matrix tr(I)/2·E − I has this negative eigenvalue: \
                     no mass distribution has this tensor (its principal moments are \
                     negative or break the triangle inequality A + B >= C); check the \
                     products' sign (I_xy = -∫xy dm) and sizes"
                .to_string(),
        });
    }
    Ok(())
}

/// Moments of inertia (principal or diagonal entries) are finite and non-negative.
fn moments_non_negative(
    body: &'static str,
    names: &[&'static str],
    m: &[f64],
) -> Result<(), Error> {
    for (&name, &v) in names.iter().zip(m) {
        if !(v.is_finite() && v >= 0.0) {
            return Err(Error::NonPhysicalParameter {
                body,
                entry: name,
                value: v,
                reason: "a moment of inertia is ∫ r² dm about an axis, finite and never \
                         negative"
                    .to_string(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(r: Result<(), Error>) -> (&'static str, &'static str, f64) {
        match r {
            Err(Error::NonPhysicalParameter {
                body, entry, value, ..
            }) => (body, entry, value),
            other => panic!("expected NonPhysicalParameter, got {other:?}"),
        }
    }

    #[test]
    fn masses() {
        assert!(mass("bob", 0.0).is_ok());
        assert!(mass("bob", 2.5f32).is_ok());
        assert_eq!(entry(mass("bob", -1.0)), ("bob", "mass", -1.0));
        assert_eq!(entry(mass("bob", f64::NAN)).1, "mass");
    }

    #[test]
    fn principal_moments() {
        // A slender rod and a thin disc sit on the boundary; both are allowed.
        assert!(principal("rod", [1.0 / 12.0, 1.0 / 12.0, 0.0]).is_ok());
        assert!(principal("disc", [0.25, 0.25, 0.5]).is_ok());
        assert_eq!(
            entry(principal("rotor", [1.0, 1.0, -0.5])),
            ("rotor", "C", -0.5)
        );
        assert_eq!(
            entry(principal("rotor", [1.0, 3.0, 1.0])),
            ("rotor", "B", 3.0)
        );
        let e = principal("rotor", [1.0, 1.0, 3.0]).unwrap_err();
        assert!(e.to_string().contains("A + B >= C"), "{e}");
        assert!(e.to_string().contains("`rotor`: C = 3"), "{e}");
    }

    #[test]
    fn planar_moments() {
        assert!(moments("disc", ["A", "B", "C"], [0.0, 0.0, 0.5]).is_ok());
        let e = moments("disc", ["Ixx", "Iyy", "Izz"], [0.0, 0.0, -0.5]);
        assert_eq!(entry(e), ("disc", "Izz", -0.5));
    }

    #[test]
    fn tensors() {
        // A unit cube's tensor about a corner moved to its centre is diagonal;
        // a tilted rod (principal [1, 1, 0] rotated) has products.
        assert!(tensor("cube", [1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0, 0.0, 0.0, 0.0]).is_ok());
        assert!(tensor("rod", [0.5, 0.5, 1.0, 0.5, 0.0, 0.0]).is_ok());
        assert_eq!(
            entry(tensor("b", [1.0, -1.0, 1.0, 0.0, 0.0, 0.0])),
            ("b", "Iyy", -1.0)
        );
        // Positive diagonal, positive definite, but the second moments are not:
        // principal moments 1, 1, 3 in disguise. S = diag(1.5, 1.5, -0.5).
        let (_, name, value) = entry(tensor("b", [1.0, 1.0, 3.0, 0.0, 0.0, 0.0]));
        assert_eq!(name, "inertia tensor");
        assert!((value + 0.5).abs() < 1e-12, "{value}");
        // A product too large for the diagonal: I itself is indefinite.
        let (_, name, _) = entry(tensor("b", [1.0, 1.0, 1.0, 2.0, 0.0, 0.0]));
        assert_eq!(name, "inertia tensor");
    }
}
