//! What the program `emit(jacobians)` emits gives ([`AccelerationDerivatives`]):
//! plain data of the contract, read by `mechanics` and by generic code
//! through [`Lagrangian::emitted_derivatives`](crate::Lagrangian::emitted_derivatives).

use nalgebra::{SMatrix, SVector};

/// q̈ = M⁻¹(Q − h + τ) at a state and its derivatives, N × N each.
#[derive(Clone, Debug, PartialEq)]
pub struct AccelerationDerivatives<T, const N: usize> {
    /// q̈ itself, at the τ the derivatives were taken at.
    pub acceleration: SVector<T, N>,
    /// ∂q̈/∂δ: along q ⊕ δ (∂q̈/∂q without orientations), at fixed q̇.
    pub dq: SMatrix<T, N, N>,
    /// ∂q̈/∂q̇.
    pub dv: SMatrix<T, N, N>,
    /// ∂q̈/∂τ = M⁻¹, for generalized forces τ added to Q (joint torques of
    /// a robot; for an orientation, a torque in its body axes).
    pub dtau: SMatrix<T, N, N>,
}
