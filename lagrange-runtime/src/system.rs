//! The contract between `#[derive(Lagrangian)]` and the runtime.
//!
//! The derive macro implements [`Lagrangian`] for the annotated struct; everything
//! in the runtime (forward dynamics, integrators, diagnostics) is written against
//! this trait only, so a hand-written implementation is a first-class citizen too
//! (the benchmarks compare exactly that).

use crate::real::Real;
use nalgebra::{SMatrix, SVector};

/// A holonomic system in minimal coordinates q ∈ Rᴺ, with equations of motion
///
/// ```text
/// M(q,t) q̈ + h(q,q̇,t) = Q(q,q̇,t)
/// ```
///
/// `T` is the scalar the parameters are stored in (f64, f32, or any [`Real`]);
/// `N` is the number of degrees of freedom, a type-level constant so that every
/// state is a stack-allocated [`SVector`].
pub trait Lagrangian<T: Real, const N: usize> {
    /// Names of the generalized coordinates, in order.
    const COORDINATES: [&'static str; N];
    /// Whether a position map depends explicitly on time. When it does, the
    /// conserved quantity (if any) is the Jacobi integral T2 − T0 + V, not T + V.
    const RHEONOMIC: bool;

    /// Mass matrix M(q,t): symmetric, positive definite where the chart is regular.
    fn mass_matrix(&self, q: &SVector<T, N>, t: T) -> SMatrix<T, N, N>;

    /// Bias h(q,q̇,t): Coriolis/centrifugal terms plus the rheonomic terms from T1, T0.
    fn bias(&self, q: &SVector<T, N>, v: &SVector<T, N>, t: T) -> SVector<T, N>;

    /// Generalized forces Q(q,q̇,t): −∂V/∂q, Σ Jᵀ F, −∂D/∂q̇ and explicit generalized forces.
    fn generalized_forces(&self, q: &SVector<T, N>, v: &SVector<T, N>, t: T) -> SVector<T, N>;

    /// M and the right-hand side Q − h, computed in one pass so that subexpressions
    /// shared between them (sines and cosines of the coordinates, Jacobian entries)
    /// are evaluated once. This is what the integrators call.
    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
        t: T,
    ) -> (SMatrix<T, N, N>, SVector<T, N>);

    /// Kinetic energy T = T2 + T1 + T0.
    fn kinetic_energy(&self, q: &SVector<T, N>, v: &SVector<T, N>, t: T) -> T;

    /// Potential energy V(q,t), gravity included.
    fn potential_energy(&self, q: &SVector<T, N>, t: T) -> T;

    /// The quantity conserved when the forces are conservative: T + V for a
    /// scleronomic system, the Jacobi integral T2 − T0 + V for a rheonomic one.
    /// It is the runtime's accuracy diagnostic.
    fn integral(&self, q: &SVector<T, N>, v: &SVector<T, N>, t: T) -> T;
}
