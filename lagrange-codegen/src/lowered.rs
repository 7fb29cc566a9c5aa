//! The lowered description: what `scene` hands to `mechanics`, every quantity an
//! expression in one [`Context`] with the names resolved. Kept apart from both
//! stages so that neither has to import the other's internals.

use lagrange_symbolic::{Context, Expr as Sym};

use crate::ast::Extra;
use crate::mat3::Mat3;

/// A point mass (or a body's centre of mass) after lowering.
pub struct PointModel {
    /// The point's (or body's) name.
    pub name: String,
    /// Its mass.
    pub mass: Sym,
    /// Its world position ξ(q, t).
    pub position: Vec<Sym>,
}

/// The rotational part of a rigid body: inertia about the centre in body axes and
/// the body-frame angular velocity ω(q, q̇, t).
pub struct SpinModel {
    /// The body's name.
    pub name: String,
    /// Its inertia about the centre of mass, body axes.
    pub inertia: Mat3,
    /// Its angular velocity ω(q, q̇, t), body axes.
    pub omega: [Sym; 3],
}

/// The lowered description: everything as expressions, names resolved.
pub struct Lowered {
    /// The context every expression of the description lives in.
    pub ctx: Context,
    /// The coordinates' names, in the order of q.
    pub coordinates: Vec<String>,
    /// The free orientations, whose θ coordinates follow `coordinates`.
    pub orientations: Vec<OrientationModel>,
    /// Names of the inputs, in the order of their symbols (`Context::inputs`).
    pub inputs: Vec<String>,
    /// The parameters' names (the struct's float fields).
    pub parameters: Vec<String>,
    /// Every point mass and body centre, in declaration order.
    pub points: Vec<PointModel>,
    /// Every body's rotational part, in declaration order.
    pub spins: Vec<SpinModel>,
    /// Where the masses sit relative to the bodies (for the recursive route).
    pub skeleton: Skeleton,
    /// The uniform gravity field, if any.
    pub gravity: Option<Vec<Sym>>,
    /// The user's potential V(q, t), if any.
    pub potential: Option<Sym>,
    /// Rayleigh's dissipation function D(q, q̇, t), if any.
    pub dissipation: Option<Sym>,
    /// (position of the point of application, Cartesian force)
    pub forces: Vec<(Vec<Sym>, Vec<Sym>)>,
    /// (coordinate index, generalized force); a `joint`'s damping −b q̇
    /// among them, after the user's.
    pub generalized_forces: Vec<(usize, Sym)>,
    /// The joints' damping, armature and friction: the armatures added to
    /// M's diagonal (`armature`), and each a parameter of the regressor
    /// beside the bodies' (`emit(regressor)`).
    pub joint_coefficients: Vec<JointCoefficient>,
    /// The holonomic constraints, in declaration order.
    pub holonomic: Vec<ConstraintModel>,
    /// The nonholonomic constraints, in declaration order.
    pub nonholonomic: Vec<ConstraintModel>,
    /// The unilateral contacts.
    pub contacts: Vec<ContactModel>,
    /// The reduced form's speeds, if that form is asked for.
    pub speeds: Option<ReducedSpeeds>,
    /// Whether to build the multiplier form.
    pub multipliers: bool,
    /// Optional outputs asked for with `emit(...)`.
    pub extras: Vec<Extra>,
    /// The masses and inertias computed from parameters, for the run-time check.
    pub checks: Vec<PhysicalCheck>,
    /// The poses and shapes the scene draws.
    pub poses: Poses,
}

impl Lowered {
    /// (coordinate index, Ia + n² Ir) of each joint with an armature: added
    /// to M's diagonal entry, and ½ Ia q̇² to T, by both routes.
    pub fn armature(&self) -> Vec<(usize, Sym)> {
        (self.joint_coefficients.iter())
            .filter(|c| c.kind == JointTerm::Armature)
            .map(|c| (c.coordinate.0, c.value))
            .collect()
    }
}

/// A joint's coefficient that the equations are linear in: a column of the
/// regressor Y, `<q>.damping`, `<q>.armature` or `<q>.friction`.
pub struct JointCoefficient {
    /// The coordinate's index and name.
    pub coordinate: (usize, String),
    /// What it multiplies.
    pub kind: JointTerm,
    /// Its value in the struct's parameters.
    pub value: Sym,
}

/// What a joint's coefficient multiplies on its coordinate's row of Y.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointTerm {
    /// b, times q̇ (the torque −b q̇ takes to overcome).
    Damping,
    /// Ia + n² Ir, times q̈.
    Armature,
    /// fc, times sign(q̇) (the torque a slipping joint's friction takes).
    Friction,
}

impl JointTerm {
    /// The parameter's suffix after the coordinate's name.
    pub fn suffix(self) -> &'static str {
        match self {
            JointTerm::Damping => "damping",
            JointTerm::Armature => "armature",
            JointTerm::Friction => "friction",
        }
    }
}

/// A mass or an inertia computed from the parameters, checked at run time by
/// `Lagrangian::check_parameters` (one given by literals is checked at compile
/// time, in `physical`). Each names its point or body.
pub enum PhysicalCheck {
    /// The mass of the named point or body.
    Mass(String, Sym),
    /// Principal moments [A, B, C] of a body turning about all three axes.
    Principal(String, [Sym; 3]),
    /// [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] about the centre of mass, of a body
    /// turning about all three axes.
    Tensor(String, [Sym; 6]),
    /// The moments (named A, B, C or Ixx, Iyy, Izz) of a body that turns
    /// about fewer axes, whose other moments the equations never read: only
    /// their signs are checked.
    Moments(String, [&'static str; 3], [Sym; 3]),
    /// A joint's damping, armature or rotor inertia (named by its
    /// coordinate and the option), which must be ≥ 0.
    Joint(String, &'static str, Sym),
    /// A joint's gear ratio (named by its coordinate), which must be > 0.
    Gear(String, Sym),
}

/// Where bodies and points sit, recorded while lowering.
#[derive(Default)]
pub struct Skeleton {
    /// Per body, parallel to `Lowered::spins`.
    pub bodies: Vec<BodyFrame>,
    /// Per point mass, parallel to `Lowered::points`: the body it is fixed in and
    /// its offset from that body's reference point in body axes.
    pub masses: Vec<Option<(usize, Vec<Sym>)>>,
    /// Every point fixed in a body (its world position, the body, the offset):
    /// where children may be attached.
    pub anchors: Vec<(Vec<Sym>, usize, Vec<Sym>)>,
}

/// One factor of a rotation product, as the recursive route reads it.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Factor {
    /// rot_axis(angle): `rot_x`, `rot_y`, `rot_z` (axis 0, 1, 2).
    Turn(usize, Sym),
    /// A free orientation, R₀(quaternion)·exp(θ): a spherical joint whose
    /// velocity is the angular velocity in its own axes.
    Free {
        /// θ: the chart's three coordinates (zero where evaluated).
        theta: [Sym; 3],
        /// (w, x, y, z), read from q.
        quaternion: [Sym; 4],
    },
}

/// A body's rotation factors (`None` for an explicit matrix), rotation
/// matrix and reference point.
pub struct BodyFrame {
    /// The elementary factors of R in order; `None` when R was written as a matrix.
    pub factors: Option<Vec<Factor>>,
    /// The rotation matrix R, body → world.
    pub matrix: Mat3,
    /// The body's reference point, world axes.
    pub reference: Vec<Sym>,
}

/// One constraint after lowering and composition with ξ(q,t).
pub struct ConstraintModel {
    /// The constraint's name.
    pub name: String,
    /// f(q,t) for a holonomic constraint, a(q,t)·q̇ + b(q,t) for a nonholonomic one.
    pub value: Sym,
    /// For each point or body named in the constraint: ∂f/∂ξ (holonomic) or ∂f/∂ξ̇
    /// (nonholonomic) per Cartesian component, composed with ξ(q,t). The reaction of
    /// this constraint on that point is its multiplier times this vector.
    pub cartesian: Vec<(String, Vec<Sym>)>,
}

/// One unilateral contact after lowering: its gap as a holonomic
/// expression, its slips (two for a contact on a plane, none for a stop) as
/// expressions linear in the velocities, and its laws.
pub struct ContactModel {
    /// The contact's name.
    pub name: String,
    /// Newton's coefficient of restitution.
    pub restitution: f64,
    /// Coulomb's coefficient of friction.
    pub friction: f64,
    /// φ(q, t).
    pub gap: ConstraintModel,
    /// The contact point's slip along each tangent.
    pub slips: Vec<ConstraintModel>,
    /// For two spheres, the touch event's function (`Contacts::
    /// contact_approach`): the gap, or below zero while their straight
    /// paths pass within the sum of the radii; `None` elsewhere (the gap).
    pub approach: Option<lagrange_symbolic::Expr>,
    /// A joint's dry friction (no gap; `friction` is its bound).
    pub dry: bool,
}

/// What the scene draws, lowered: every body's pose and inertia, every
/// point's position and the `shape(...)` items. No equation reads it; it only
/// names nodes the lowering built anyway (the shapes' sizes excepted).
#[derive(Default)]
pub struct Poses {
    /// In declaration order.
    pub bodies: Vec<BodyPose>,
    /// Every point, with or without mass, in declaration order.
    pub points: Vec<PointPose>,
    /// The `shape(...)` items, in declaration order.
    pub shapes: Vec<ShapeModel>,
}

/// A free orientation as the derivation sees it (see
/// [`OrientationSymbols`](crate::lower::OrientationSymbols)): θ, three
/// coordinates set to zero once everything is derived, and the quaternion
/// read from q.
#[derive(Clone)]
pub struct OrientationModel {
    /// The orientation's name.
    pub name: String,
    /// θ: the chart's three coordinates (zero where evaluated).
    pub theta: [Sym; 3],
    /// (w, x, y, z), read from q.
    pub quaternion: [Sym; 4],
}

/// A body's reference point, centre of mass and rotation (body → world), and
/// its mass and inertia about the centre in body axes (for the default shape).
pub struct BodyPose {
    /// The body's name.
    pub name: String,
    /// The reference point, world axes.
    pub origin: Vec<Sym>,
    /// The centre of mass, world axes.
    pub centre: Vec<Sym>,
    /// R, body → world.
    pub rotation: Mat3,
    /// The body's mass.
    pub mass: Sym,
    /// Its inertia about the centre, body axes.
    pub inertia: Mat3,
}

/// A point's world position (two components in a planar description) and the
/// body it is fixed in, if any.
pub struct PointPose {
    /// The point's name.
    pub name: String,
    /// Its world position.
    pub position: Vec<Sym>,
    /// The body it is fixed in (index into `Poses::bodies`).
    pub body: Option<usize>,
}

/// What a shape is attached to: an index into [`Poses::bodies`] or [`Poses::points`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// A body, by its index in `Poses::bodies`.
    Body(usize),
    /// A point, by its index in `Poses::points`.
    Point(usize),
}

/// A `shape(...)` item with its sizes as parameter-only expressions.
pub struct ShapeModel {
    /// What the shape is fixed to.
    pub on: Anchor,
    /// The centre, in body coordinates from the reference point (world axes
    /// from a point); empty for none.
    pub at: Vec<Sym>,
    /// The solid and its sizes.
    pub solid: SolidModel,
}

/// The lowered solid; a line runs from the shape's anchor to another.
pub enum SolidModel {
    /// A box's full edge lengths along the body axes.
    Box([Sym; 3]),
    /// A sphere's radius.
    Sphere(Sym),
    /// A cylinder centred on its place.
    Cylinder {
        /// The radius.
        radius: Sym,
        /// The full length along `axis`.
        length: Sym,
        /// The body axis: 0 = x, 1 = y, 2 = z.
        axis: usize,
    },
    /// A cylinder with hemispherical ends.
    Capsule {
        /// The radius of the cylinder and its ends.
        radius: Sym,
        /// The cylinder's length between the ends' centres.
        length: Sym,
        /// The body axis: 0 = x, 1 = y, 2 = z.
        axis: usize,
    },
    /// A line from the shape's anchor to this one.
    Line(Anchor),
}

/// The independent speeds of the reduced form.
#[derive(Clone, Debug)]
pub enum ReducedSpeeds {
    /// The user's speeds, (name, u(q, q̇, t)), each linear in the velocities.
    Named(Vec<(String, Sym)>),
    /// Velocities chosen from the constraints.
    Chosen,
}

impl ReducedSpeeds {
    /// The user's speeds, if named.
    pub fn named(&self) -> Option<&[(String, Sym)]> {
        match self {
            ReducedSpeeds::Named(speeds) => Some(speeds),
            ReducedSpeeds::Chosen => None,
        }
    }
}
