//! Why a description is not a kinematic tree the recursive route can take:
//! the body, point or coordinate at fault and what about it. Its text is the
//! reason `Lagrangian::ROUTE` gives (and a compile error's, with
//! `route = recursive`).

use std::fmt;

/// The reason the tree algorithms cannot take a description.
#[derive(Clone, Debug, PartialEq)]
pub enum NotATree {
    /// `route = generic` was written.
    GenericAsked,
    /// Point masses alone (or no coordinates): nothing for the recursions.
    NoRigidBodies,
    /// Gravity that depends on the state, time or inputs.
    GravityNotConstant,
    /// A body that does not hang on a joint of its parent.
    Body {
        /// The body's name.
        body: String,
        /// What about it.
        fault: BodyFault,
    },
    /// A coordinate that no joint reads.
    IdleCoordinate {
        /// The coordinate's name.
        coordinate: String,
        /// Whether the bodies were read from written-out poses (rather than
        /// rotation factors).
        written: bool,
    },
    /// A point with mass that moves but is fixed in no body.
    LoosePoint {
        /// The point's name.
        point: String,
    },
}

/// What keeps a body off the tree.
#[derive(Clone, Debug, PartialEq)]
pub enum BodyFault {
    /// Its rotation is not a product of rot_x/rot_y/rot_z factors.
    NotFactored,
    /// A factor turns by neither one coordinate nor a constant.
    AngleNotACoordinate {
        /// The factor's axis, 0..3.
        axis: usize,
    },
    /// Its reference point moves in its parent, not along a fixed line.
    SlidesOffALine {
        /// The parent body.
        parent: String,
    },
    /// One coordinate drives two of its joints.
    CoordinateTwice {
        /// The coordinate.
        coordinate: String,
    },
    /// Its reference point is not fixed in the parent its rotation extends.
    NotFixedInParent {
        /// The parent body.
        parent: String,
    },
    /// Its reference point moves, yet no body's rotation it extends.
    MovesWithoutParent,
    /// Its written-out reference point does not have three coordinates.
    ReferenceNot3D,
    /// Its written-out pose depends on time, an input or a free orientation.
    PoseDependsOn(&'static str),
    /// It moves by several coordinates relative to its parent, as written out.
    SeveralCoordinates {
        /// Those coordinates.
        coordinates: Vec<String>,
    },
    /// Its joint axis depends on parameters.
    AxisDependsOnParameters,
    /// Relative to its parent it neither turns about a fixed axis nor slides
    /// along a fixed line as its coordinate changes.
    NotAJoint {
        /// The coordinate.
        coordinate: String,
        /// How far the reading is off, at random configurations.
        off: f64,
    },
    /// It depends on no coordinate beyond its parent's, yet moves in it.
    MovesWithoutCoordinate,
}

impl fmt::Display for NotATree {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NotATree::GenericAsked => f.write_str("the generic route was asked for"),
            NotATree::NoRigidBodies => f.write_str("it has no rigid bodies (point masses alone)"),
            NotATree::GravityNotConstant => f.write_str("gravity is not a constant vector"),
            NotATree::Body { body, fault } => write!(f, "body `{body}`: {fault}"),
            NotATree::IdleCoordinate {
                coordinate,
                written: true,
            } => {
                write!(f, "coordinate `{coordinate}` moves no joint of a body")
            }
            NotATree::IdleCoordinate {
                coordinate,
                written: false,
            } => write!(
                f,
                "coordinate `{coordinate}` moves no joint (it enters a position other than \
                 along a fixed line)"
            ),
            NotATree::LoosePoint { point } => write!(
                f,
                "point `{point}`: it has mass and moves, but is not fixed in a body"
            ),
        }
    }
}

impl fmt::Display for BodyFault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BodyFault::NotFactored => {
                f.write_str("its rotation is not a product of rot_x/rot_y/rot_z factors")
            }
            BodyFault::AngleNotACoordinate { axis } => write!(
                f,
                "its factor rot_{} turns by an angle that is neither one coordinate nor constant",
                ["x", "y", "z"][*axis]
            ),
            BodyFault::SlidesOffALine { parent } => write!(
                f,
                "its reference point moves in its parent `{parent}`, and not along a fixed line"
            ),
            BodyFault::CoordinateTwice { coordinate } => {
                write!(f, "coordinate `{coordinate}` moves two of its joints")
            }
            BodyFault::NotFixedInParent { parent } => write!(
                f,
                "its reference point is not a point fixed in its parent `{parent}`"
            ),
            BodyFault::MovesWithoutParent => {
                f.write_str("its reference point moves, but it has no parent body")
            }
            BodyFault::ReferenceNot3D => f.write_str("its reference point is not in 3-D"),
            BodyFault::PoseDependsOn(what) => {
                write!(f, "its written-out pose depends on {what}")
            }
            BodyFault::SeveralCoordinates { coordinates } => write!(
                f,
                "it moves by {} coordinates ({}) relative to its parent; read from written-out \
                 positions, a body hangs on one joint (write a rotation as rot_x/rot_y/rot_z \
                 factors for several)",
                coordinates.len(),
                coordinates.join(", ")
            ),
            BodyFault::AxisDependsOnParameters => f.write_str(
                "its joint axis depends on parameters; the recursive route needs a constant axis",
            ),
            BodyFault::NotAJoint { coordinate, off } => write!(
                f,
                "relative to its parent (the body whose coordinates its own extend), it neither \
                 turns about a fixed axis nor slides along a fixed line as `{coordinate}` \
                 changes (checked at random configurations: off by {off:.1e})"
            ),
            BodyFault::MovesWithoutCoordinate => {
                f.write_str("it depends on no coordinate beyond its parent's, yet moves in it")
            }
        }
    }
}

impl NotATree {
    /// `fault` of the body `body`.
    pub(super) fn body(body: &str, fault: BodyFault) -> Self {
        NotATree::Body {
            body: body.to_string(),
            fault,
        }
    }
}
