//! Unilateral contacts: what a system says about each of its contacts, for
//! the event-driven contact runs ([`Simulation::run_contacts`]).
//!
//! [`Simulation::run_contacts`]: crate::Simulation::run_contacts

use super::Lagrangian;
use crate::numeric::Real;
use nalgebra::SVector;

/// The laws of one contact: how it bounces and how it rubs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactLaw {
    /// The contact's name, for reports and errors.
    pub name: &'static str,
    /// Newton's coefficient of restitution e ∈ [0, 1]: the normal speed after
    /// an impact is −e times the one before (0: plastic, 1: elastic).
    pub restitution: f64,
    /// Coulomb's friction coefficient μ ≥ 0 (isotropic cone) of a
    /// unilateral contact, 0 for a frictionless contact or a stop on a
    /// coordinate; for [`ContactKind::DryFriction`], the bound itself.
    pub friction: f64,
    /// What bounds the friction: the normal force, or a fixed bound.
    pub kind: ContactKind,
}

/// What kind of contact a [`ContactLaw`] governs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactKind {
    /// A gap that opens and closes, a normal force that can only push, and
    /// friction inside the cone |λ_t| ≤ μ λₙ.
    Unilateral,
    /// Dry (Coulomb) friction with a fixed bound |λ_t| ≤ `friction`: a
    /// joint's friction torque or force, whatever the load on it. Always in
    /// force: it has no gap (its rows' gap and normal are not read), no
    /// normal force and takes no impulse at an impact (a bounded force
    /// transmits none in an instant); it sticks while the torque that
    /// holds it is within the bound, and slides against its slip
    /// otherwise. Its one tangent row is the coordinate's.
    DryFriction,
}

impl ContactLaw {
    /// A unilateral contact named `name` with restitution e and friction
    /// coefficient μ.
    pub fn unilateral(name: &'static str, restitution: f64, friction: f64) -> Self {
        Self {
            name,
            restitution,
            friction,
            kind: ContactKind::Unilateral,
        }
    }

    /// Dry friction named `name`, bounded by `bound` (N·m on an angle, N on
    /// a length): see [`ContactKind::DryFriction`].
    pub fn dry_friction(name: &'static str, bound: f64) -> Self {
        Self {
            name,
            restitution: 0.0,
            friction: bound,
            kind: ContactKind::DryFriction,
        }
    }

    /// Whether this is [`ContactKind::DryFriction`].
    pub fn is_dry_friction(&self) -> bool {
        self.kind == ContactKind::DryFriction
    }

    /// The largest friction force the contact can take under the normal
    /// force λₙ: μ λₙ, or the fixed bound.
    pub fn friction_bound<T: Real>(&self, normal: T) -> T {
        match self.kind {
            ContactKind::Unilateral => T::lit(self.friction) * normal,
            ContactKind::DryFriction => T::lit(self.friction),
        }
    }
}

/// One contact's kinematics at (q, q̇, t), each a row of the Jacobian of a
/// velocity with the matching bias, so that the velocity is `row · q̇` and its
/// rate `row · q̈ + bias`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactRows<T: Real, const N: usize> {
    /// The gap φ(q, t): positive apart, zero touching, negative penetrating.
    pub gap: T,
    /// ∂φ/∂q: the normal speed is `normal · q̇` (for a scleronomic gap).
    pub normal: SVector<T, N>,
    /// J̇ q̇ of the normal row (with ∂²φ/∂t² and the mixed terms of a moving
    /// surface): the normal acceleration is `normal · q̈ + normal_bias`.
    pub normal_bias: T,
    /// The rows of the contact point's slip velocity along two orthonormal
    /// tangents of the surface (for a sphere, with the ω × (−r n) term): zero
    /// rows where the motion has no slip in that direction (a planar
    /// description, a stop on a coordinate).
    pub tangents: [SVector<T, N>; 2],
    /// J̇ q̇ of each tangent row.
    pub tangent_bias: [T; 2],
}

/// A system's unilateral contacts: the laws and the rows of each.
///
/// `#[derive(Lagrangian)]` implements it for a description with `contact(...)`
/// or `stop(...)` items; the default says "no contacts", so a hand-written
/// system opts in with `impl Contacts<f64, N> for MySystem {}` and runs as
/// without contacts, or overrides both methods. With free orientations q
/// has Q entries (the quaternions) and the rows are in the N velocities
/// (ω in body axes): `Contacts<T, N, Q>`.
pub trait Contacts<T: Real, const N: usize, const Q: usize = N>: Lagrangian<T, N, Q> {
    /// The contacts' laws, one per contact, in the order of their rows.
    fn contact_laws(&self) -> Vec<ContactLaw> {
        Vec::new()
    }

    /// The rows of contact `index` at (q, v, t), each a row acting on v;
    /// `None` for an index past the last contact.
    fn contact_rows(
        &self,
        index: usize,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> Option<ContactRows<T, N>> {
        let _ = (index, q, v, t);
        None
    }

    /// The function whose fall through zero is contact `index`'s touch,
    /// where it is not the gap; `None` (the default) where it is. Two
    /// spheres' gap can dip below zero and rise again within one step of an
    /// integrator (a glancing blow between its samples); their function
    /// stays below zero once the straight paths have passed within the sum
    /// of the radii, so the touch shows as a sign change whatever the step.
    /// The derive writes it for `contact(.., against = ..)`.
    fn contact_approach(
        &self,
        index: usize,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> Option<T> {
        let _ = (index, q, v, t);
        None
    }
}
