//! A system driven by inputs: the [`Driven`] trait, what a controller, an
//! input signal or a planner supplies to the equations of [`Lagrangian`].

use super::Lagrangian;
use crate::numeric::Real;
use nalgebra::{SMatrix, SVector};

/// A system driven by P named inputs u ∈ Rᴾ (forces, torques, set-points)
/// supplied at run time:
///
/// ```text
/// M(q,t) q̈ + h(q,q̇,t) = Q(q,q̇,u,t)
/// ```
///
/// `#[derive(Lagrangian)]` implements it for a description with `inputs(...)`.
/// The [`Lagrangian`] methods of such a system are its equations with every
/// input at zero (the unforced system, energies included); the inputs enter
/// through [`input_forces`](Self::input_forces), which the runtime adds to Q − h
/// wherever a controller or an input signal drives the system. Inputs never
/// enter M, h or the constraints, so the multiplier and reduced forms are driven
/// the same way.
///
/// With free orientations (Q = N + 1 per orientation) q holds the
/// quaternions and the forces are in v's tangent space: an orientation's
/// three entries are torques in body axes (the coefficients of ω).
///
/// `#[derive(Lagrangian)]` implements it for every system: with the declared
/// inputs, or with P = 0 for a system without inputs, so that code written for
/// driven systems (linearisation, controlled simulation) takes undriven ones
/// too and the number of inputs is always the system's own (an operating point
/// or controller never needs it spelled out). A hand-written system without
/// inputs writes `impl Driven<f64, N, 0> for MySystem {}`: every item has a
/// default for P = 0 (and only for P = 0: a driven hand-written system must
/// implement them, or the build stops at its impl).
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not driven by {P} input(s) with {Q} numbers in q: a controller, input signal or operating point supplies a different number of inputs than `inputs(...)` declares, or the system holds orientations and this call takes it in N coordinates",
    label = "{P} input(s) and {Q} numbers in q supplied here",
    note = "a controller returns `[T; P]` or `SVector<T, P>` with P the number of names in `inputs(...)`; a system without inputs takes P = 0",
    note = "a system with `orientation(...)` has four numbers per quaternion in q: give `linearize` (or `Linearizer::tangent_driven`) its point as `OperatingPoint::on_group(q, v)`, q with each unit quaternion (w, x, y, z) and v with each angular velocity in body axes; with constraints use `Linearizer::constrained_tangent` or `Linearizer::reduced_tangent`"
)]
pub trait Driven<T: Real, const N: usize, const P: usize, const Q: usize = N>:
    Lagrangian<T, N, Q>
{
    /// Names of the inputs, in order.
    const INPUTS: [&'static str; P] = {
        assert!(
            P == 0,
            "a driven system names its inputs in `Driven::INPUTS`"
        );
        [""; P]
    };

    /// Whether Q is affine in u (∂Q/∂u does not depend on u: forces and
    /// torques proportional to the inputs), so that q̈ is too and its second
    /// derivative in u vanishes, which the direct method's curvature uses
    /// to difference fewer columns. `#[derive(Lagrangian)]` sets it from the
    /// derived ∂Q/∂u; the default, false, is always safe.
    const INPUTS_AFFINE: bool = false;

    /// ΔQ = Q(q, q̇, u, t) − Q(q, q̇, 0, t): the generalized forces the inputs add.
    fn input_forces(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        u: &SVector<T, P>,
        t: T,
    ) -> SVector<T, N> {
        const { assert!(P == 0, "a driven system implements `Driven::input_forces`") };
        let _ = (q, v, u, t);
        SVector::zeros()
    }

    /// The input Jacobians at (q, q̇, u, t):
    ///
    /// ```text
    /// ( ∂Q/∂u (N × P),   ∂ΔQ/∂q (N × N),   ∂ΔQ/∂q̇ (N × N) )
    /// ```
    ///
    /// ∂Q/∂u = ∂(Q − h)/∂u since h does not depend on u; the other two are what
    /// the inputs add to the right-hand-side Jacobians when u ≠ 0.
    #[allow(clippy::type_complexity)]
    fn input_jacobians(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        u: &SVector<T, P>,
        t: T,
    ) -> (SMatrix<T, N, P>, SMatrix<T, N, N>, SMatrix<T, N, N>) {
        const {
            assert!(
                P == 0,
                "a driven system implements `Driven::input_jacobians`"
            )
        };
        let _ = (q, v, u, t);
        (SMatrix::zeros(), SMatrix::zeros(), SMatrix::zeros())
    }
}
