//! The paths `#[derive(Lagrangian)]`'s code names (`::lagrange::__private::...`),
//! so that it compiles whatever the user's crate imports; not a public API.

pub use lagrange_runtime::{
    AccelerationDerivatives, Atlas, Batched, BatchedDifferentiable, Constrained, ContactLaw,
    ContactRows, Contacts, Differentiable, Driven, DrivenAtlas, Error, EulerRotation, FormVisitor,
    ForwardRoute, FreeVisitor, JointLimit, Lagrangian, LaneDerivatives, Orientation, Real, Reduced,
    Route, factored_derivatives, func,
    numeric::lanes,
    physical,
    pose::{Anchor, BodyInertia, BodyPose, Kinematics, Posed, Shape, Solid},
};
pub use nalgebra::{
    DMatrix, DMatrixView, DMatrixViewMut, DVector, Matrix3, SMatrix, SVector, Vector3,
};
