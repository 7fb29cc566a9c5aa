//! The parsed description of a system: what the user wrote, with spans kept and
//! expressions still as `syn::Expr`. Produced by `attr`, consumed by `check` and `lower`.

use proc_macro2::Span;
use syn::{Expr, Generics, Ident};

/// The scalar the generated code computes in.
#[derive(Clone, Debug, PartialEq)]
pub enum Scalar {
    /// `f64` (the default).
    F64,
    /// `f32`.
    F32,
    /// A type parameter of the struct, e.g. `T` in `struct Pendulum<T> { m: T }`.
    Generic(Ident),
}

/// One float field of the struct: a physical parameter.
#[derive(Clone, Debug)]
pub struct Parameter {
    /// The field's name, as expressions use it.
    pub name: Ident,
}

/// `point(name, mass = m, at = [x, y, z])`, or `point(name, on = body, at = [..])`
/// for a point fixed in a body (coordinates in the body frame, mass optional: a
/// contact or attachment point). A missing key is reported by `check`, which keeps
/// the point so its name still resolves.
#[derive(Clone, Debug)]
pub struct Point {
    /// The point's name.
    pub name: Ident,
    /// `mass = m`; `None` for a massless point.
    pub mass: Option<Expr>,
    /// `at = [x, y, z]`: world position ξ(q, t), or body coordinates with `on`.
    pub at: Option<Expr>,
    /// `on = body`: the body the point is fixed in.
    pub on: Option<Ident>,
}

/// `body(name, mass = m, inertia = [A, B, C], at = [x, y, z], rotation = R)`: a rigid
/// body with its reference point at `at` (the centre of mass, unless `com` places
/// it in body coordinates), principal (or full, six entries
/// `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]`) inertia about the centre in the body frame,
/// and orientation R(q,t) mapping body to world coordinates.
#[derive(Clone, Debug)]
pub struct Body {
    /// The body's name.
    pub name: Ident,
    /// `mass = m`.
    pub mass: Option<Expr>,
    /// `inertia = [..]`: three principal moments or six tensor entries.
    pub inertia: Option<Expr>,
    /// `at = [x, y, z]`: the reference point's world position ξ(q, t).
    pub at: Option<Expr>,
    /// `com = [bx, by, bz]`: the centre of mass in body coordinates relative to
    /// the reference point `at`; absent, `at` is the centre of mass.
    pub com: Option<Expr>,
    /// `about = [ax, ay, az]`: the point (body coordinates relative to `at`)
    /// the inertia tensor is given about; absent, the centre of mass. The
    /// macro moves it to the centre of mass by the parallel-axis theorem.
    pub about: Option<Expr>,
    /// `rotation = R`: R(q, t), body → world.
    pub rotation: Option<Expr>,
    /// The inertia is used as written, its physical check skipped: a body
    /// read by `urdf("..", inertia = as_written)`.
    pub inertia_unchecked: bool,
}

/// A named constraint: `holonomic(name = f(q, t))` or `nonholonomic(name = a(q,t)·q̇ + b)`.
#[derive(Clone, Debug)]
pub struct Constraint {
    /// The constraint's name (its multiplier's and its row's).
    pub name: Ident,
    /// f(q, t), or a(q, t)·q̇ + b(q, t).
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
    /// The q̈ program (with `articulated` or `jacobians`) and the derivatives
    /// program (with `jacobians`) over four states at once, for an `f64`
    /// system without constraints.
    Batched,
    /// The dynamics regressor Y(q, q̇, q̈) with M q̈ + h − Q_gravity = Y π, π
    /// the bodies' inertial parameters, on a kinematic tree.
    Regressor,
}

/// `force(point, [fx, fy, fz])`: a Cartesian force applied at a point.
#[derive(Clone, Debug)]
pub struct Force {
    /// The point the force acts at.
    pub point: Ident,
    /// The force `[fx, fy, fz]`, world axes.
    pub value: Expr,
}

/// `torque(body, [tx, ty, tz])`: a torque on a body, in world axes or (with
/// `axes = body`) in the body's own.
#[derive(Clone, Debug)]
pub struct Torque {
    /// The body the torque turns.
    pub body: Ident,
    /// The torque `[tx, ty, tz]`.
    pub value: Expr,
    /// Whether the components are in the body's axes (else the world's).
    pub body_axes: bool,
}

/// `generalized_force(q = expr)`.
#[derive(Clone, Debug)]
pub struct GeneralizedForce {
    /// The coordinate the force is conjugate to.
    pub coordinate: Ident,
    /// The generalized force Q_q.
    pub value: Expr,
}

/// `joint(q, damping = b, friction = fc, armature = Ia, motor = u, gear = n,
/// rotor = Ir)`: what a joint's drive adds on its coordinate: viscous
/// damping, −b q̇ in Q, and the rotor's reflected inertia, Ia on M's
/// diagonal entry (q, q), each an expression of the parameters (≥ 0);
/// Coulomb friction bounded by fc (a number), a dry-friction contact named
/// `<q>_friction`; and a motor behind a gearbox of ratio n: its torque u
/// (an input) gives n u in Q, its rotor's inertia Ir adds n² Ir to the
/// armature.
#[derive(Clone, Debug)]
pub struct Joint {
    /// The coordinate.
    pub coordinate: Ident,
    /// The viscous damping coefficient b.
    pub damping: Option<Expr>,
    /// The armature Ia.
    pub armature: Option<Expr>,
    /// Coulomb friction's bound fc > 0 (`None` for none, or 0 written).
    pub friction: Option<f64>,
    /// The input that is the motor's torque, on the motor's side of the gear.
    pub motor: Option<Ident>,
    /// The gear ratio n: the motor turns n times per turn of the joint
    /// (1 when left out).
    pub gear: Option<Expr>,
    /// The rotor's own inertia Ir, on the motor's side of the gear.
    pub rotor: Option<Expr>,
}

impl Joint {
    /// The name of the dry-friction contact a joint's `friction` makes.
    pub fn friction_name(&self) -> String {
        format!("{}_friction", self.coordinate)
    }
}

impl System {
    /// The contacts' names in the order of their laws: the `contact` and
    /// `stop` items, then each joint's dry friction.
    pub fn contact_names(&self) -> Vec<String> {
        let items = self.contacts.iter().map(|c| c.name.to_string());
        let frictions = (self.joints.iter())
            .filter(|j| j.friction.is_some())
            .map(Joint::friction_name);
        items.chain(frictions).collect()
    }
}

/// `define(name = expr)`: an intermediate quantity usable in later expressions.
#[derive(Clone, Debug)]
pub struct Definition {
    /// The quantity's name.
    pub name: Ident,
    /// Its expression.
    pub value: Expr,
}

/// The solid of a `shape(...)` item, with its sizes as written (lowered later
/// as parameter-only expressions).
#[derive(Clone, Debug)]
pub enum Solid {
    /// `box(size = [lx, ly, lz])`: full edge lengths along the body axes.
    Box {
        /// Edge lengths `[lx, ly, lz]`.
        size: Expr,
    },
    /// `sphere(radius = r)`.
    Sphere {
        /// The radius.
        radius: Expr,
    },
    /// `cylinder(radius = r, length = l, axis = x|y|z)`, centred on its place.
    Cylinder {
        /// The radius.
        radius: Expr,
        /// The full length along `axis`.
        length: Expr,
        /// The body axis: 0 = x, 1 = y, 2 = z.
        axis: usize,
    },
    /// `capsule(radius = r, length = l, axis = x|y|z)`: a cylinder of length l
    /// with hemispherical ends.
    Capsule {
        /// The radius of the cylinder and its ends.
        radius: Expr,
        /// The cylinder's length between the ends' centres.
        length: Expr,
        /// The body axis: 0 = x, 1 = y, 2 = z.
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
        /// The body or point the solid is fixed to.
        target: Ident,
        /// The solid and its sizes.
        solid: Box<Solid>,
        /// The keyword as written, where errors about the solid point.
        keyword: Ident,
        /// `at = [..]`: the centre relative to the target; `None` for the target itself.
        at: Option<Box<Expr>>,
    },
    /// A polyline through points and bodies' reference points.
    Line(Vec<Ident>),
}

/// Everything `#[lagrange(...)]` says about one struct.
#[derive(Clone, Debug)]
pub struct System {
    /// The struct's name.
    pub ident: Ident,
    /// The struct's generics (a scalar type parameter, if any).
    pub generics: Generics,
    /// The scalar the generated code computes in.
    pub scalar: Scalar,
    /// The struct's float fields.
    pub parameters: Vec<Parameter>,
    /// `coordinates(q1, q2, ...)`: the generalized coordinates.
    pub coordinates: Vec<Ident>,
    /// `orientation(a, ...)`: free orientations, each a unit quaternion in q
    /// and a body-axis angular velocity in v, usable as a rotation factor.
    pub orientations: Vec<Ident>,
    /// `inputs(u1, u2, ...)`: named scalar signals supplied at run time, allowed
    /// in forces, generalized forces, the potential and the dissipation.
    pub inputs: Vec<Ident>,
    /// `define(...)`: intermediate quantities, in order.
    pub definitions: Vec<Definition>,
    /// `point(...)` items, in order.
    pub points: Vec<Point>,
    /// `body(...)` items, in order.
    pub bodies: Vec<Body>,
    /// `holonomic(...)` constraints f(q, t) = 0.
    pub holonomic: Vec<Constraint>,
    /// `nonholonomic(...)` constraints, linear in the velocities.
    pub nonholonomic: Vec<Constraint>,
    /// `speeds(u = expr, ...)`: independent speeds of the reduced form.
    pub speeds: Vec<Definition>,
    /// `formulation(...)`; empty means the default (multipliers when there are constraints).
    pub formulations: Vec<(Ident, Formulation)>,
    /// `emit(...)`: the optional outputs, each with the keyword where it was written.
    pub extras: Vec<(Ident, Extra)>,
    /// `gravity = [gx, gy, gz]`: a uniform field acting on every mass.
    pub gravity: Option<Expr>,
    /// `potential = V`: the user's potential energy V(q, t).
    pub potential: Option<Expr>,
    /// `dissipation = D`: Rayleigh's dissipation function, D(q, q̇, t).
    pub dissipation: Option<Expr>,
    /// `force(...)` items.
    pub forces: Vec<Force>,
    /// `torque(...)` items.
    pub torques: Vec<Torque>,
    /// `generalized_force(...)` items.
    pub generalized_forces: Vec<GeneralizedForce>,
    /// `shape(...)`: visual shapes for the scene, in order.
    pub shapes: Vec<Shape>,
    /// `contact(...)` and `stop(...)`: unilateral contacts, in order.
    pub contacts: Vec<Contact>,
    /// `joint(...)`: each coordinate's viscous damping and rotor inertia.
    pub joints: Vec<Joint>,
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
    /// Each coordinate's effort limit (∞ where none), in coordinate order.
    pub efforts: Vec<f64>,
    /// Each coordinate's velocity limit (∞ where none), in coordinate order.
    pub velocities: Vec<f64>,
    /// `snap`: the angles made exact multiples of π/2 (where, written, snapped).
    pub snapped: Vec<(String, f64, f64)>,
    /// `inertia = repair`: the links' inertias changed (link, written, used).
    pub repaired: Vec<(String, [f64; 6], [f64; 6])>,
}

/// A unilateral contact: `contact(name, on = p, normal = [..], ..)` (a point,
/// or a sphere on a body, against a fixed plane) or `stop(name, q >= lower,
/// ..)` (a one-sided stop on a coordinate).
#[derive(Clone, Debug)]
pub struct Contact {
    /// The contact's name.
    pub name: Ident,
    /// What touches what.
    pub geometry: ContactGeometry,
    /// Newton's coefficient of restitution, in [0, 1].
    pub restitution: f64,
    /// Coulomb's friction coefficient, ≥ 0 (0 for a stop).
    pub friction: f64,
}

/// What touches what in a [`Contact`].
#[derive(Clone, Debug)]
pub enum ContactGeometry {
    /// A point (or a body's centre, with a sphere of `radius` around it)
    /// against the plane n·x = offset, n a unit normal written as numbers.
    Plane {
        /// The point or body.
        on: Ident,
        /// The sphere's radius; `None` for a point.
        radius: Option<Expr>,
        /// The plane's unit normal, pointing to the side the point stays on.
        normal: [f64; 3],
        /// The plane's offset along the normal (0 if not written).
        offset: Option<Expr>,
    },
    /// Two spheres, around the points or bodies `on` and `against`, apart
    /// while their centres are further than the sum of the radii; the
    /// normal is the line of centres, so it turns with them.
    Spheres {
        /// The first point or body.
        on: Ident,
        /// Its sphere's radius (0 for a point).
        radius: Option<Expr>,
        /// The other point or body.
        against: Ident,
        /// Its sphere's radius (0 for a point).
        against_radius: Option<Expr>,
    },
    /// `q >= bound` (`lower`) or `q <= bound`.
    Stop {
        /// The coordinate.
        coordinate: Ident,
        /// Whether the bound is a lower one.
        lower: bool,
        /// The bound.
        bound: Expr,
    },
}
