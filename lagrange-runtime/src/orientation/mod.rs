//! Orientations as a user handles them: a unit quaternion from an axis and
//! an angle, from Euler angles or from a rotation matrix, and back; q ⊕ δ
//! and q ⊖ q₀ for one quaternion and for a whole configuration; and the
//! tangent-space error of a run against a reference.
//!
//! A quaternion is a [`Vector4`] **(w, x, y, z), scalar first**, turning body
//! axes into the world's (p_world = R(q) p_body): what a system's q holds in
//! the four slots of each `orientation(..)` and what
//! [`Linearizer::tangent_driven`](crate::linear::Linearizer::tangent_driven)
//! and [`OperatingPoint::on_group`](crate::linear::OperatingPoint::on_group)
//! take. (nalgebra's `Quaternion::coords` stores (x, y, z, w): do not copy
//! it into q.)
//!
//! **⊕ and ⊖** are the ones every linearisation, controller and projection
//! of the library uses: q ⊕ δ = q ⊗ exp(δ) turns q by the rotation vector δ
//! **in body axes** (Pinocchio's `integrate`), and q ⊖ q₀ is its inverse,
//! the rotation vector of q₀⁻¹ ⊗ q, taken the short way (q and −q are one
//! orientation, so |q ⊖ q₀| ≤ π). For a whole configuration
//! ([`configuration_plus`], [`configuration_minus`], [`state_minus`]) an
//! ordinary coordinate moves by its own δ and every orientation as above, in
//! the system's layout: δ has N entries, the states of a tangent
//! linearisation (`x`, `att.θx`, …) in their order.
//!
//! Every function checks what it is given as a run checks its initial state:
//! a quaternion within [`UNIT_TOLERANCE`] (1e-6) of unit norm is normalised,
//! one further is [`Error::NonUnitQuaternion`]; a non-finite number is an
//! [`Error::Settings`].
//!
//! ```
//! use lagrange_runtime::orientation::{self, EulerSequence};
//! use nalgebra::Vector3;
//! # fn main() -> Result<(), lagrange_runtime::Error> {
//! let quarter = std::f64::consts::FRAC_PI_2;
//! let q0 = orientation::from_axis_angle(&Vector3::z(), quarter)?; // yaw 90°
//! let q = orientation::plus(&q0, &Vector3::new(0.1, 0.0, 0.0))?; // then roll 0.1 in body axes
//! let delta = orientation::minus(&q, &q0)?; // back: (0.1, 0, 0)
//! assert!((delta - Vector3::new(0.1, 0.0, 0.0)).amax() < 1e-15);
//! // The same attitude as `euler_zyx(yaw, pitch, roll)` of a description:
//! let zyx = orientation::from_euler(EulerSequence::ZYX, [quarter, 0.0, 0.1])?;
//! assert!(orientation::minus(&zyx, &q)?.amax() < 1e-15);
//! # Ok(()) }
//! ```
//!
//! [`UNIT_TOLERANCE`]: crate::numeric::orientation::UNIT_TOLERANCE

mod state;
#[cfg(test)]
pub(crate) mod tests;

pub use state::{TangentError, configuration_minus, configuration_plus, state_minus};

use crate::error::{Error, SettingsError};
use crate::numeric::Real;
use crate::numeric::euler::EulerChart;
use crate::numeric::orientation::{self as group, UNIT_TOLERANCE};
use nalgebra::{Matrix3, Vector3, Vector4};

/// An Euler-angle sequence of body axes (a, b, c): R = R_a(α) R_b(β)
/// R_c(γ), each turn about the axis of the frame the previous ones made, as
/// the description language's `euler_zxz(ψ, θ, φ)` (= `rot_z(ψ) * rot_x(θ) *
/// rot_z(φ)`) and `euler_zyx(yaw, pitch, roll)` define them.
///
/// ```
/// use lagrange_runtime::orientation::EulerSequence;
/// let xyz = EulerSequence::new([0, 1, 2])?; // rot_x(α) rot_y(β) rot_z(γ)
/// assert_eq!(xyz.axes(), [0, 1, 2]);
/// assert!(EulerSequence::new([0, 0, 1]).is_err()); // no turn about one axis twice running
/// # Ok::<(), lagrange_runtime::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EulerSequence(EulerChart);

impl EulerSequence {
    /// z-x-z: `euler_zxz(ψ, θ, φ)`, precession, nutation, spin.
    pub const ZXZ: Self = Self(EulerChart {
        axes: [2, 0, 2],
        offset: false,
    });
    /// z-y-x: `euler_zyx(yaw, pitch, roll)`, Tait–Bryan.
    pub const ZYX: Self = Self(EulerChart {
        axes: [2, 1, 0],
        offset: false,
    });

    /// The sequence of `axes` (0 = x, 1 = y, 2 = z), as a system's
    /// [`EulerRotation::axes`](crate::EulerRotation::axes) gives them.
    ///
    /// # Errors
    /// [`Error::Settings`] unless every axis is 0, 1 or 2 and the middle one
    /// differs from both ends (twelve sequences).
    pub fn new(axes: [usize; 3]) -> Result<Self, Error> {
        EulerChart::new(axes).map(Self).ok_or_else(|| {
            invalid(
                "EulerSequence::new",
                format!("{axes:?} is not an Euler sequence: axes 0, 1, 2, the middle one unlike both ends"),
            )
        })
    }

    /// The axes (0 = x, 1 = y, 2 = z).
    pub fn axes(&self) -> [usize; 3] {
        self.0.axes
    }

    /// R = R_a(α) R_b(β) R_c(γ), body → world.
    pub fn matrix<T: Real>(&self, angles: [T; 3]) -> Matrix3<T> {
        self.0.matrix(angles)
    }

    /// The angular velocity in body axes of the angles moving at `rates`:
    /// ω = E(α, β, γ) (α̇, β̇, γ̇), what v holds for a free orientation in
    /// the attitude these angles give.
    pub fn angular_velocity<T: Real>(&self, angles: [T; 3], rates: [T; 3]) -> Vector3<T> {
        self.0.rates(angles) * Vector3::from(rates)
    }
}

/// The identity orientation (1, 0, 0, 0).
pub fn identity<T: Real>() -> Vector4<T> {
    Vector4::new(T::one(), T::zero(), T::zero(), T::zero())
}

/// The quaternion of a turn by `angle` (radians, right-handed) about
/// `axis` (any length but zero): (cos(angle/2), sin(angle/2) axis/|axis|).
///
/// # Errors
/// [`Error::Settings`] for a zero or non-finite axis or a non-finite angle.
pub fn from_axis_angle<T: Real>(axis: &Vector3<T>, angle: T) -> Result<Vector4<T>, Error> {
    let length = axis.norm();
    if !(finite(axis.iter().copied()) && angle.is_finite()) || length == T::zero() {
        return Err(invalid(
            "orientation::from_axis_angle",
            format!(
                "axis {:?} and angle {}: the axis must be finite and not zero, the angle finite",
                axis.iter().map(|x| x.to_f64()).collect::<Vec<_>>(),
                angle.to_f64()
            ),
        ));
    }
    Ok(Vector4::from(group::exp((axis * (angle / length)).into())))
}

/// The quaternion of the Euler angles `angles` of `sequence`: q_a(α) ⊗
/// q_b(β) ⊗ q_c(γ), whose rotation matrix is
/// [`sequence.matrix(angles)`](EulerSequence::matrix).
///
/// # Errors
/// [`Error::Settings`] for a non-finite angle.
pub fn from_euler<T: Real>(sequence: EulerSequence, angles: [T; 3]) -> Result<Vector4<T>, Error> {
    if !finite(angles) {
        return Err(invalid(
            "orientation::from_euler",
            format!("angles {:?} are not finite", angles.map(|a| a.to_f64())),
        ));
    }
    let turn = |k: usize| {
        let mut theta = [T::zero(); 3];
        theta[sequence.0.axes[k]] = angles[k];
        group::exp(theta)
    };
    Ok(Vector4::from(group::multiply(
        group::multiply(turn(0), turn(1)),
        turn(2),
    )))
}

/// The Euler angles of `sequence` that give q: of the two solutions (and
/// their 2π shifts) the one nearest `near`, or without it the principal
/// one (β in [0, π] for a proper sequence such as z-x-z, [−π/2, π/2] for
/// Tait–Bryan). On the sequence's singular set (β = 0 or π, β = ±π/2) α is
/// taken from `near` (or 0) and γ carries the rest.
///
/// # Errors
/// [`Error::NonUnitQuaternion`] for q off the unit sphere.
pub fn to_euler<T: Real>(
    sequence: EulerSequence,
    q: &Vector4<T>,
    near: Option<[T; 3]>,
) -> Result<[T; 3], Error> {
    Ok(sequence.0.angles(&rotation_matrix(q)?, near))
}

/// R(q), body → world: p_world = R p_body.
///
/// # Errors
/// [`Error::NonUnitQuaternion`] for q off the unit sphere.
pub fn rotation_matrix<T: Real>(q: &Vector4<T>) -> Result<Matrix3<T>, Error> {
    let r = group::rotation_matrix(unit(q, "q")?);
    Ok(Matrix3::from_fn(|i, j| r[i][j]))
}

/// The unit quaternion (w ≥ 0) of a rotation matrix.
///
/// # Errors
/// [`Error::Settings`] unless `r` is a rotation: finite, RᵀR within 1e-6
/// of I entry by entry, det R > 0.
pub fn from_rotation_matrix<T: Real>(r: &Matrix3<T>) -> Result<Vector4<T>, Error> {
    let off = (r.transpose() * r - Matrix3::identity()).amax().to_f64();
    let det = r.determinant().to_f64();
    if !(finite(r.iter().copied()) && off <= UNIT_TOLERANCE && det > 0.0) {
        return Err(invalid(
            "orientation::from_rotation_matrix",
            format!("not a rotation: |RᵀR − I| = {off:e}, det R = {det}"),
        ));
    }
    Ok(Vector4::from(group::from_rotation_matrix(r)))
}

/// q ⊕ δ = q ⊗ exp(δ): q turned by the rotation vector δ in body axes (the
/// tangent space of every linearisation and controller of the library).
///
/// # Errors
/// [`Error::NonUnitQuaternion`] for q off the unit sphere;
/// [`Error::Settings`] for a non-finite δ.
pub fn plus<T: Real>(q: &Vector4<T>, delta: &Vector3<T>) -> Result<Vector4<T>, Error> {
    let q = unit(q, "q")?;
    if !finite(delta.iter().copied()) {
        return Err(invalid(
            "orientation::plus",
            "the rotation vector δ is not finite".into(),
        ));
    }
    Ok(Vector4::from(group::multiply(
        q,
        group::exp((*delta).into()),
    )))
}

/// q ⊖ q₀: the rotation vector δ in q₀'s body axes with q₀ ⊕ δ = q, the
/// short way round (|δ| ≤ π; q and −q give the same δ).
///
/// # Errors
/// [`Error::NonUnitQuaternion`] for q or q₀ off the unit sphere.
pub fn minus<T: Real>(q: &Vector4<T>, q0: &Vector4<T>) -> Result<Vector3<T>, Error> {
    let [w, x, y, z] = unit(q0, "q0")?;
    Ok(Vector3::from(group::log(group::multiply(
        [w, -x, -y, -z],
        unit(q, "q")?,
    ))))
}

/// q scaled to unit norm if it is within [`UNIT_TOLERANCE`] of it; named
/// `what` in the error otherwise.
fn unit<T: Real>(q: &Vector4<T>, what: &str) -> Result<[T; 4], Error> {
    let q: [T; 4] = (*q).into();
    let norm = group::norm(q);
    // A NaN norm fails the test too.
    let unit = (norm.to_f64() - 1.0).abs() <= UNIT_TOLERANCE;
    if !unit {
        return Err(Error::NonUnitQuaternion {
            orientation: what.to_string(),
            norm: norm.to_f64(),
            tolerance: UNIT_TOLERANCE,
        });
    }
    Ok(q.map(|x| x / norm))
}

fn finite<T: Real>(values: impl IntoIterator<Item = T>) -> bool {
    values.into_iter().all(|x| x.is_finite())
}

/// Data a function of this module cannot use.
fn invalid(owner: &'static str, problem: String) -> Error {
    SettingsError::Data { owner, problem }.into()
}
