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
    /// Coulomb's friction coefficient μ ≥ 0 (isotropic cone); 0 for a
    /// frictionless contact or a stop on a coordinate.
    pub friction: f64,
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
/// without contacts, or overrides both methods.
pub trait Contacts<T: Real, const N: usize>: Lagrangian<T, N> {
    /// The contacts' laws, one per contact, in the order of their rows.
    fn contact_laws(&self) -> Vec<ContactLaw> {
        Vec::new()
    }

    /// The rows of contact `index` at (q, q̇, t); `None` for an index past the
    /// last contact.
    fn contact_rows(
        &self,
        index: usize,
        q: &SVector<T, N>,
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
        q: &SVector<T, N>,
        v: &SVector<T, N>,
        t: T,
    ) -> Option<T> {
        let _ = (index, q, v, t);
        None
    }
}
