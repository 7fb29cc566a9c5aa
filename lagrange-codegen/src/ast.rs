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

/// `point(name, mass = m, at = [x, y, z])`, or `point(name, on = body, at = [..])`
/// for a point fixed in a body (coordinates in the body frame, mass optional: a
/// contact or attachment point). A missing key is reported by `check`, which keeps
/// the point so its name still resolves.
#[derive(Clone, Debug)]
pub struct Point {
    pub name: Ident,
    pub mass: Option<Expr>,
    pub at: Option<Expr>,
    pub on: Option<Ident>,
}

/// `body(name, mass = m, inertia = [A, B, C], at = [x, y, z], rotation = R)`: a rigid
/// body with its reference point at `at` (the centre of mass, unless `com` places
/// it in body coordinates), principal (or full, six entries
/// `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]`) inertia about the centre in the body frame,
/// and orientation R(q,t) mapping body to world coordinates.
#[derive(Clone, Debug)]
pub struct Body {
    pub name: Ident,
    pub mass: Option<Expr>,
    pub inertia: Option<Expr>,
    pub at: Option<Expr>,
    /// `com = [bx, by, bz]`: the centre of mass in body coordinates relative to
    /// the reference point `at`; absent, `at` is the centre of mass.
    pub com: Option<Expr>,
    /// `about = [ax, ay, az]`: the point (body coordinates relative to `at`)
    /// the inertia tensor is given about; absent, the centre of mass. The
    /// macro moves it to the centre of mass by the parallel-axis theorem.
    pub about: Option<Expr>,
    pub rotation: Option<Expr>,
    /// The inertia is used as written, its physical check skipped: a body
    /// read by `urdf("..", inertia = as_written)`.
    pub inertia_unchecked: bool,
}

/// A named constraint: `holonomic(name = f(q, t))` or `nonholonomic(name = a(q,t)·q̇ + b)`.
#[derive(Clone, Debug)]
pub struct Constraint {
    pub name: Ident,
    pub value: Expr,
}

/// How constrained equations are emitted, spelled in
/// `attr::keyword::FORMULATIONS`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// M q̈ + h = Q + Gᵀν with G q̈ = γ: gives reactions.
    Multipliers,
    /// Projected onto independent speeds (Maggi / Gibbs–Appell): no multipliers.
    Reduced,
}

/// Optional outputs a scene asks for with `emit(...)`, spelled (with what
/// each gives, for the errors) in `attr::keyword::OUTPUTS`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extra {
    /// Cartesian reactions on points and bodies from the multipliers.
    Reactions,
    /// The Coriolis matrix C(q, q̇) with h = C q̇ (+ rheonomic terms).
    Coriolis,
    /// Jacobians of the right-hand side, for the implicit integrators.
    Jacobians,
    /// Hamilton's form: the momentum ∂T/∂q̇ and ∂T/∂q, for the symplectic integrators.
    Hamiltonian,
    /// q̈ by the articulated-body algorithm (O(n), no mass matrix), for a
    /// kinematic tree; the unconstrained dynamics use it instead of M and Cholesky.
    Articulated,
    /// τ = M q̈ + h − Q (recursive Newton–Euler on a tree) and the gravity
    /// torques.
    InverseDynamics,
    /// The bodies' frame Jacobians and J̇ q̇, the centre of mass and its
    /// Jacobian.
    Kinematics,
    /// A second chart for each rotation written in Euler angles, through the
    /// free twin (`crate::atlas`).
    Atlas,
}

/// `force(point, [fx, fy, fz])`: a Cartesian force applied at a point.
#[derive(Clone, Debug)]
pub struct Force {
    pub point: Ident,
    pub value: Expr,
}

/// `torque(body, [tx, ty, tz])`: a torque on a body, in world axes or (with
/// `axes = body`) in the body's own.
#[derive(Clone, Debug)]
pub struct Torque {
    pub body: Ident,
    pub value: Expr,
    /// Whether the components are in the body's axes (else the world's).
    pub body_axes: bool,
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

/// The solid of a `shape(...)` item, with its sizes as written (lowered later
/// as parameter-only expressions).
#[derive(Clone, Debug)]
pub enum Solid {
    /// `box(size = [lx, ly, lz])`: full edge lengths along the body axes.
    Box { size: Expr },
    /// `sphere(radius = r)`.
    Sphere { radius: Expr },
    /// `cylinder(radius = r, length = l, axis = x|y|z)`, centred on its place.
    Cylinder {
        radius: Expr,
        length: Expr,
        axis: usize,
    },
    /// `capsule(radius = r, length = l, axis = x|y|z)`: a cylinder of length l
    /// with hemispherical ends.
    Capsule {
        radius: Expr,
        length: Expr,
        axis: usize,
    },
}

/// `shape(target, solid(...), at = [..])` or `shape(line(a, b, ...))`: what the
/// scene draws; visual only, no equation reads it.
#[derive(Clone, Debug)]
pub enum Shape {
    /// A solid fixed in a body (at body coordinates `at` from its reference
    /// point, in its axes) or centred on a point (world axes).
    Solid {
        target: Ident,
        solid: Box<Solid>,
        /// The keyword as written, where errors about the solid point.
        keyword: Ident,
        at: Option<Box<Expr>>,
    },
    /// A polyline through points and bodies' reference points.
    Line(Vec<Ident>),
}

/// Everything `#[lagrange(...)]` says about one struct.
#[derive(Clone, Debug)]
pub struct System {
    pub ident: Ident,
    pub generics: Generics,
    pub scalar: Scalar,
    pub parameters: Vec<Parameter>,
    pub coordinates: Vec<Ident>,
    /// `orientation(a, ...)`: free orientations, each a unit quaternion in q
    /// and a body-axis angular velocity in v, usable as a rotation factor.
    pub orientations: Vec<Ident>,
    /// `inputs(u1, u2, ...)`: named scalar signals supplied at run time, allowed
    /// in forces, generalized forces, the potential and the dissipation.
    pub inputs: Vec<Ident>,
    pub definitions: Vec<Definition>,
    pub points: Vec<Point>,
    pub bodies: Vec<Body>,
    pub holonomic: Vec<Constraint>,
    pub nonholonomic: Vec<Constraint>,
    /// `speeds(u = expr, ...)`: independent speeds of the reduced form.
    pub speeds: Vec<Definition>,
    /// `formulation(...)`; empty means the default (multipliers when there are constraints).
    pub formulations: Vec<(Ident, Formulation)>,
    pub extras: Vec<(Ident, Extra)>,
    pub gravity: Option<Expr>,
    pub potential: Option<Expr>,
    pub dissipation: Option<Expr>,
    pub forces: Vec<Force>,
    pub torques: Vec<Torque>,
    pub generalized_forces: Vec<GeneralizedForce>,
    /// `shape(...)`: visual shapes for the scene, in order.
    pub shapes: Vec<Shape>,
    /// Where to point errors that concern the whole description (e.g. "no coordinates").
    pub span: Span,
    /// `urdf = "path"`: the robot file the description was read from.
    pub urdf: Option<UrdfSource>,
}

/// What a description read from URDF publishes beside the equations.
#[derive(Clone, Debug)]
pub struct UrdfSource {
    /// The file's absolute path (the generated code includes its bytes, so the
    /// crate rebuilds when it changes).
    pub path: String,
    /// The robot's name.
    pub robot: String,
    /// The coordinates the file's joints give, in coordinate order.
    pub coordinates: Vec<String>,
    /// Each coordinate's position limits, in coordinate order.
    pub limits: Vec<(f64, f64)>,
    /// `snap`: the angles made exact multiples of π/2 (where, written, snapped).
    pub snapped: Vec<(String, f64, f64)>,
    /// `inertia = repair`: the links' inertias changed (link, written, used).
    pub repaired: Vec<(String, [f64; 6], [f64; 6])>,
}
