//! What a system written in Euler angles gives the atlas ([`Atlas`]): which
//! of its coordinates are Euler angles of which sequence, and the same
//! system with each of those rotations free (a quaternion and ω), through
//! which the atlas evaluates the dynamics in any chart.

use super::{Driven, Lagrangian};
use crate::numeric::Real;
use nalgebra::SVector;

/// One rotation of a system written as three Euler angles of its coordinates
/// (`euler_zxz(ψ, θ, φ)`, `euler_zyx(..)`, or three successive `rot_*` about
/// one point).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EulerRotation {
    /// The body it turns (the first, if several share it), for reports.
    pub body: &'static str,
    /// Where its three angles sit in q (and their rates in v), in the
    /// sequence's order.
    pub coordinates: [usize; 3],
    /// The sequence's axes, 0 = x, 1 = y, 2 = z.
    pub axes: [usize; 3],
}

/// A system whose Euler-angle rotations can leave their chart: emitted by
/// `emit(atlas)` and run by [`Simulation::run_atlas`](crate::Simulation::run_atlas).
///
/// F is the length of the free twin's q: N plus one per rotation. The twin
/// is the same description (its inputs and constraints included, in the
/// multiplier form when there are constraints, through
/// [`Lagrangian::visit_form`]) with every rotation of [`EULER`](Self::EULER)
/// replaced by a free orientation: its q holds the other coordinates in
/// order, then one unit quaternion (w, x, y, z) per rotation in `EULER`'s
/// order; its v those coordinates' rates, then each rotation's ω in body
/// axes. Its M and h depend on no chart, so any chart's equations follow
/// from it exactly.
pub trait Atlas<T: Real, const N: usize, const F: usize>: Lagrangian<T, N> {
    /// The rotations written in Euler angles, each with its own chart.
    const EULER: &'static [EulerRotation];

    /// Hands the free twin to `visitor`.
    fn visit_free<V: FreeVisitor<T, N, F>>(&self, visitor: V) -> V::Output;
}

/// What [`Atlas::visit_free`] calls with the free twin.
pub trait FreeVisitor<T: Real, const N: usize, const F: usize> {
    /// What the visit returns.
    type Output;
    /// Visits the twin.
    fn visit<L: Lagrangian<T, N, F>>(self, free: &L) -> Self::Output;
}

/// An [`Atlas`] system with P inputs ([`Driven`]): the twin's generalized
/// forces of the same inputs, in its own coordinates (the kept coordinates,
/// then each rotation's three components of ω in body axes). Emitted with
/// every `emit(atlas)` (P = 0 without `inputs`); what
/// [`Simulation::run_atlas`](crate::Simulation::run_atlas) with inputs
/// reads while a rotation is in its second chart.
pub trait DrivenAtlas<T: Real, const N: usize, const P: usize, const F: usize>:
    Atlas<T, N, F> + Driven<T, N, P>
{
    /// The twin's ΔQ(q, v, u, t) at its state (q of F entries with the
    /// quaternions, v with ω).
    fn free_input_forces(
        &self,
        q: &SVector<T, F>,
        v: &SVector<T, N>,
        u: &SVector<T, P>,
        t: T,
    ) -> SVector<T, N>;
}
