//! The parsed description of a system: what the user wrote, with spans kept and
//! expressions still as `syn::Expr`. Produced by `attr`, consumed by `check` and `lower`.

use proc_macro2::Span;
use syn::{Expr, Generics, Ident};

/// The scalar the generated code computes in.
#[derive(Clone, Debug, PartialEq)]
pub enum Scalar {
    F64,
    F32,
    /// A type parameter of the struct, e.g. `T` in `struct Pendulum<T> { m: T }`.
    Generic(Ident),
}

/// One float field of the struct: a physical parameter.
#[derive(Clone, Debug)]
pub struct Parameter {
    pub name: Ident,
}

/// `point(name, mass = m, at = [x, y, z])`. Both keys are required; a missing one
/// is reported by `check`, which keeps the point so its name still resolves.
#[derive(Clone, Debug)]
pub struct Point {
    pub name: Ident,
    pub mass: Option<Expr>,
    pub at: Option<Expr>,
}

/// `force(point, [fx, fy, fz])`: a Cartesian force applied at a point.
#[derive(Clone, Debug)]
pub struct Force {
    pub point: Ident,
    pub value: Expr,
}

/// `generalized_force(q = expr)`.
#[derive(Clone, Debug)]
pub struct GeneralizedForce {
    pub coordinate: Ident,
    pub value: Expr,
}

/// `define(name = expr)`: an intermediate quantity usable in later expressions.
#[derive(Clone, Debug)]
pub struct Definition {
    pub name: Ident,
    pub value: Expr,
}

/// Everything `#[lagrange(...)]` says about one struct.
#[derive(Clone, Debug)]
pub struct System {
    pub ident: Ident,
    pub generics: Generics,
    pub scalar: Scalar,
    pub parameters: Vec<Parameter>,
    pub coordinates: Vec<Ident>,
    pub definitions: Vec<Definition>,
    pub points: Vec<Point>,
    pub gravity: Option<Expr>,
    pub potential: Option<Expr>,
    pub dissipation: Option<Expr>,
    pub forces: Vec<Force>,
    pub generalized_forces: Vec<GeneralizedForce>,
    /// Where to point errors that concern the whole description (e.g. "no coordinates").
    pub span: Span,
}
