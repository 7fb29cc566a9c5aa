//! Evaluations at a configuration checked as a run checks its start
//! ([`Configuration`]).
//!
//! The trait methods ([`Lagrangian::mass_matrix`], [`Kinematics::frame_jacobian`],
//! [`Posed::poses`], …) are the generated straight-line code, called at every
//! stage of a run on states the run keeps on the unit sphere; they check
//! nothing, and at a quaternion of norm s they answer for the rotation scaled
//! by s² (`frame_jacobian` at 2u differed from the one at u by 4.2). A
//! `Configuration` is q accepted by the rule every run applies to its initial
//! state: every entry finite, and each quaternion within
//! [`UNIT_TOLERANCE`](crate::numeric::orientation::UNIT_TOLERANCE) of unit
//! norm, normalised (beyond it refused with [`Error::NonUnitQuaternion`]);
//! its methods then evaluate there.

use crate::error::{Error, to_vec, unit_quaternions};
use crate::numeric::Real;
use crate::pose::{BodyInertia, BodyPose, Kinematics, Posed};
use crate::system::Lagrangian;
use nalgebra::{SMatrix, SVector, Vector3};

/// A configuration q of `S` at time t, checked and normalised as a run checks
/// its initial state: every entry finite, each quaternion within
/// [`UNIT_TOLERANCE`](crate::numeric::orientation::UNIT_TOLERANCE) (1e-6) of
/// unit norm and scaled to it (q / |q|), one further refused. The trait
/// methods it calls check nothing: at a quaternion of norm s they answer for
/// the rotation scaled by s².
pub struct Configuration<'a, S, T: Real, const N: usize, const Q: usize = N> {
    sys: &'a S,
    q: SVector<T, Q>,
    t: T,
}

impl<S, T: Real, const N: usize, const Q: usize> Clone for Configuration<'_, S, T, N, Q> {
    fn clone(&self) -> Self {
        *self
    }
}

/// q and t (the system need not be `Debug`).
impl<S, T: Real, const N: usize, const Q: usize> std::fmt::Debug for Configuration<'_, S, T, N, Q> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Configuration")
            .field("q", &self.q)
            .field("t", &self.t)
            .finish()
    }
}

impl<S, T: Real, const N: usize, const Q: usize> Copy for Configuration<'_, S, T, N, Q> {}

/// [`Error::NonFiniteState`] unless every entry of q (and v) is finite.
fn finite<T: Real, const N: usize, const Q: usize>(
    t: T,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
) -> Result<(), Error> {
    if t.is_finite() && q.iter().chain(v.iter()).all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFiniteState {
            t: t.to_f64(),
            q: to_vec(q),
            v: to_vec(v),
        })
    }
}

impl<'a, S: Lagrangian<T, N, Q>, T: Real, const N: usize, const Q: usize>
    Configuration<'a, S, T, N, Q>
{
    /// q of `sys` at time t, checked.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for a NaN or ∞ in q or t;
    /// [`Error::NonUnitQuaternion`] for a quaternion further than
    /// `UNIT_TOLERANCE` from unit norm (within it, it is normalised, as a
    /// run normalises its start).
    pub fn new(sys: &'a S, q: SVector<T, Q>, t: T) -> Result<Self, Error> {
        finite(t, &q, &SVector::<T, 0>::zeros())?;
        let q = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q)?;
        Ok(Self { sys, q, t })
    }

    /// The configuration as evaluated (its quaternions normalised).
    pub fn q(&self) -> &SVector<T, Q> {
        &self.q
    }

    /// The mass matrix M(q, t).
    pub fn mass_matrix(&self) -> SMatrix<T, N, N> {
        self.sys.mass_matrix(&self.q, self.t)
    }

    /// The potential energy V(q, t).
    pub fn potential_energy(&self) -> T {
        self.sys.potential_energy(&self.q, self.t)
    }

    /// The kinetic energy at velocity v.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for a NaN or ∞ in v.
    pub fn kinetic_energy(&self, v: &SVector<T, N>) -> Result<T, Error> {
        finite(self.t, &self.q, v)?;
        Ok(self.sys.kinetic_energy(&self.q, v, self.t))
    }

    /// The conserved integral at velocity v ([`Lagrangian::integral`]).
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for a NaN or ∞ in v.
    pub fn integral(&self, v: &SVector<T, N>) -> Result<T, Error> {
        finite(self.t, &self.q, v)?;
        Ok(self.sys.integral(&self.q, v, self.t))
    }

    /// The generalized momentum ∂L/∂q̇ at velocity v.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for a NaN or ∞ in v.
    pub fn momentum(&self, v: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        finite(self.t, &self.q, v)?;
        Ok(self.sys.momentum(&self.q, v, self.t))
    }

    /// τ = M a + h − Q ([`Lagrangian::inverse_dynamics`]) at velocity v and
    /// acceleration a.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for a NaN or ∞ in v or a.
    pub fn inverse_dynamics(
        &self,
        v: &SVector<T, N>,
        a: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        finite(self.t, &self.q, v)?;
        finite(self.t, &self.q, a)?;
        Ok(self.sys.inverse_dynamics(&self.q, v, a, self.t))
    }

    /// ∂V_gravity/∂q ([`Lagrangian::gravity_torques`]), if emitted.
    pub fn gravity_torques(&self) -> Option<SVector<T, N>> {
        self.sys.gravity_torques(&self.q, self.t)
    }
}

impl<S: Lagrangian<T, N, Q> + Posed<T, N, Q>, T: Real, const N: usize, const Q: usize>
    Configuration<'_, S, T, N, Q>
{
    /// The bodies' poses and the points' positions ([`Posed::poses`]), in
    /// the order of [`Posed::BODIES`] and [`Posed::POINTS`].
    pub fn poses(&self) -> (Vec<BodyPose<T>>, Vec<Vector3<T>>) {
        let mut bodies = vec![BodyPose::default(); S::BODIES.len()];
        let mut points = vec![Vector3::zeros(); S::POINTS.len()];
        self.sys.poses(&self.q, self.t, &mut bodies, &mut points);
        (bodies, points)
    }

    /// The pose of body `body` ([`Posed::frame_pose`]), indexing
    /// [`Posed::BODIES`]; `None` past the bodies.
    pub fn frame_pose(&self, body: usize) -> Option<BodyPose<T>> {
        self.sys.frame_pose(body, &self.q, self.t)
    }

    /// Each body's mass and inertia ([`Posed::inertias`]).
    pub fn inertias(&self) -> Vec<BodyInertia<T>> {
        let mut out = vec![BodyInertia::default(); S::BODIES.len()];
        self.sys.inertias(&mut out);
        out
    }
}

impl<S: Lagrangian<T, N, Q> + Kinematics<T, N, Q>, T: Real, const N: usize, const Q: usize>
    Configuration<'_, S, T, N, Q>
{
    /// [`Kinematics::frame_jacobian`] of body `body`; `None` past the bodies.
    pub fn frame_jacobian(&self, body: usize) -> Option<SMatrix<T, 6, N>> {
        self.sys.frame_jacobian(body, &self.q, self.t)
    }

    /// [`Kinematics::frame_jacobian_local`] of body `body`.
    pub fn frame_jacobian_local(&self, body: usize) -> Option<SMatrix<T, 6, N>> {
        self.sys.frame_jacobian_local(body, &self.q, self.t)
    }

    /// [`Kinematics::frame_bias`] of body `body` at velocity v; `Ok(None)`
    /// past the bodies.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for a NaN or ∞ in v.
    pub fn frame_bias(
        &self,
        body: usize,
        v: &SVector<T, N>,
    ) -> Result<Option<SVector<T, 6>>, Error> {
        finite(self.t, &self.q, v)?;
        Ok(self.sys.frame_bias(body, &self.q, v, self.t))
    }

    /// [`Kinematics::center_of_mass`].
    pub fn center_of_mass(&self) -> Vector3<T> {
        self.sys.center_of_mass(&self.q, self.t)
    }

    /// [`Kinematics::center_of_mass_jacobian`].
    pub fn center_of_mass_jacobian(&self) -> SMatrix<T, 3, N> {
        self.sys.center_of_mass_jacobian(&self.q, self.t)
    }
}
