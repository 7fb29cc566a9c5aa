//! The lowered description: what `scene` hands to `mechanics`, every quantity an
//! expression in one [`Context`] with the names resolved. Kept apart from both
//! stages so that neither has to import the other's internals.

use lagrange_symbolic::{Context, Expr as Sym};

use crate::ast::Extra;
use crate::mat3::Mat3;

/// A point mass (or a body's centre of mass) after lowering.
pub struct PointModel {
    pub name: String,
    pub mass: Sym,
    pub position: Vec<Sym>,
}

/// The rotational part of a rigid body: inertia about the centre in body axes and
/// the body-frame angular velocity ω(q, q̇, t).
pub struct SpinModel {
    pub name: String,
    pub inertia: Mat3,
    pub omega: [Sym; 3],
}

/// The lowered description: everything as expressions, names resolved.
pub struct Lowered {
    pub ctx: Context,
    pub coordinates: Vec<String>,
    /// The free orientations, whose θ coordinates follow `coordinates`.
    pub orientations: Vec<OrientationModel>,
    /// Names of the inputs, in the order of their symbols (`Context::inputs`).
    pub inputs: Vec<String>,
    pub parameters: Vec<String>,
    pub points: Vec<PointModel>,
    pub spins: Vec<SpinModel>,
    /// Where the masses sit relative to the bodies (for the recursive route).
    pub skeleton: Skeleton,
    pub gravity: Option<Vec<Sym>>,
    pub potential: Option<Sym>,
    pub dissipation: Option<Sym>,
    /// (position of the point of application, Cartesian force)
    pub forces: Vec<(Vec<Sym>, Vec<Sym>)>,
    /// (coordinate index, generalized force)
    pub generalized_forces: Vec<(usize, Sym)>,
    pub holonomic: Vec<ConstraintModel>,
    pub nonholonomic: Vec<ConstraintModel>,
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

/// A mass or an inertia computed from the parameters, checked at run time by
/// `Lagrangian::check_parameters` (one given by literals is checked at compile
/// time, in `physical`). Each names its point or body.
pub enum PhysicalCheck {
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
        theta: [Sym; 3],
        quaternion: [Sym; 4],
    },
}

/// A body's rotation factors (`None` for an explicit matrix), rotation
/// matrix and reference point.
pub struct BodyFrame {
    pub factors: Option<Vec<Factor>>,
    pub matrix: Mat3,
    pub reference: Vec<Sym>,
}

/// One constraint after lowering and composition with ξ(q,t).
pub struct ConstraintModel {
    pub name: String,
    /// f(q,t) for a holonomic constraint, a(q,t)·q̇ + b(q,t) for a nonholonomic one.
    pub value: Sym,
    /// For each point or body named in the constraint: ∂f/∂ξ (holonomic) or ∂f/∂ξ̇
    /// (nonholonomic) per Cartesian component, composed with ξ(q,t). The reaction of
    /// this constraint on that point is its multiplier times this vector.
    pub cartesian: Vec<(String, Vec<Sym>)>,
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
    pub shapes: Vec<ShapeModel>,
}

/// A free orientation as the derivation sees it (see
/// [`OrientationSymbols`](crate::lower::OrientationSymbols)): θ, three
/// coordinates set to zero once everything is derived, and the quaternion
/// read from q.
#[derive(Clone)]
pub struct OrientationModel {
    pub name: String,
    pub theta: [Sym; 3],
    pub quaternion: [Sym; 4],
}

/// A body's reference point, centre of mass and rotation (body → world), and
/// its mass and inertia about the centre in body axes (for the default shape).
pub struct BodyPose {
    pub name: String,
    pub origin: Vec<Sym>,
    pub centre: Vec<Sym>,
    pub rotation: Mat3,
    pub mass: Sym,
    pub inertia: Mat3,
}

/// A point's world position (two components in a planar description) and the
/// body it is fixed in, if any.
pub struct PointPose {
    pub name: String,
    pub position: Vec<Sym>,
    pub body: Option<usize>,
}

/// What a shape is attached to: an index into [`Poses::bodies`] or [`Poses::points`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    Body(usize),
    Point(usize),
}

/// A `shape(...)` item with its sizes as parameter-only expressions.
pub struct ShapeModel {
    pub on: Anchor,
    /// The centre, in body coordinates from the reference point (world axes
    /// from a point); empty for none.
    pub at: Vec<Sym>,
    pub solid: SolidModel,
}

/// The lowered solid; a line runs from the shape's anchor to another.
pub enum SolidModel {
    Box([Sym; 3]),
    Sphere(Sym),
    Cylinder {
        radius: Sym,
        length: Sym,
        axis: usize,
    },
    Capsule {
        radius: Sym,
        length: Sym,
        axis: usize,
    },
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
