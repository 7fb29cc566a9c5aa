//! The recursive route: when the bodies form a kinematic tree of revolute,
//! sliding and spherical joints (a free body: three sliding and a spherical),
//! M by composite rigid bodies (CRBA) and h − Q_gravity by recursive
//! Newton–Euler (RNEA), built as expressions so the engine's CSE emits them as
//! straight-line code (Featherstone, *Rigid Body Dynamics Algorithms*, ch. 5–6).
//!
//! Differentiating ξ(q) of every body costs O(n³) operations in 3-D (Jacobians of
//! products of rotations, then M = Σ Jᵀ m J); the recursions cost O(n²) for M and
//! O(n) for h, in link coordinates where joint axes are unit vectors and offsets
//! are constant, so most products are by 0 or 1 and vanish at construction.
//!
//! A tree is detected from the description, not declared: a body's rotation is
//! its parent's factors followed by elementary rotations, about coordinates
//! (joints) or by constant angles (placements: a robot's fixed `rpy`, a tilted
//! joint axis written `rot_y(w) * rot_z(q) * rot_y(-w)`), and its reference
//! point is a point fixed in the parent (`at = [j.x, j.y, j.z]` with
//! `point(j, on = parent)`) or a fixed point for a root. Each elementary factor
//! about a coordinate is one joint; a body with several (`euler_zxz(ψ, θ, φ)`
//! about a fixed point) hangs on massless links that meet at its reference
//! point; a body with none beyond its parent's is fixed in the parent (a fixed
//! joint: its masses join the parent's link), and one with none at all is fixed
//! in space. A free orientation (`rotation = name` or a factor `.. * name`) is
//! a spherical joint, whose motion subspace in its own axes is the identity on
//! ω; a body whose reference point moves along several fixed directions (a
//! free body's `at = [x, y, z]`) hangs on one sliding joint per coordinate.
//! Anything else — a rotation written as a matrix, a translating
//! coordinate, a point mass that is neither fixed in a body nor in space, a
//! coordinate in two joints, time in a position — leaves the system to the
//! generic route, with the reason.

mod aba;
mod crba;
mod derivatives;
mod detect;
mod frame;
mod link;
mod not_a_tree;
mod regressor;
mod regrouping;
mod rnea;
mod spatial;
mod written;

pub use aba::{ForwardDynamics, forward_dynamics};
pub use crba::mass_matrix;
pub use derivatives::inverse_dynamics_derivatives;
pub use detect::detect;
pub use not_a_tree::{BodyFault, NotATree};
pub use regressor::{link_regressor, regressor};
pub use regrouping::{regrouped, root_axial_inertia};
pub use rnea::{inverse_dynamics, inverse_dynamics_at_accelerations};

use lagrange_symbolic::{Context, Expr as Sym};

use crate::mat3::Mat3;

/// Mass, first moment h = m c and rotational inertia about the link origin, in
/// link axes: the spatial inertia in its ten numbers.
#[derive(Clone, Copy)]
struct Inertia {
    mass: Sym,
    first: [Sym; 3],
    rot: Mat3,
}

/// One revolute joint and the link it moves: the link frame is the parent's
/// turned by the constant `placement` P (none: the identity) and then by
/// rot_axis(q), about the parent point `offset`: E = P rot_axis(q). A joint
/// about a tilted axis n is one whose placement maps the axis onto n.
#[derive(Clone)]
struct Link {
    parent: Option<usize>,
    placement: Option<Mat3>,
    /// A sliding (prismatic) joint's direction in the parent's axes: the link
    /// frame is the parent's, its origin at `offset + slide q`, and
    /// `placement` and `axis` are unused.
    slide: Option<[Sym; 3]>,
    axis: usize,
    coordinate: usize,
    offset: [Sym; 3],
    inertia: Option<Inertia>,
    /// One axis of a spherical joint (a free orientation), taken at the
    /// centre of the chart that moves with it: rot_axis(θ) = 1, θ̇ the angular
    /// velocity's component. The joint is three such links, the first placed
    /// by the quaternion's R₀; this is the index of that first link, whose
    /// entering velocity v the velocity product v × S ω reads (the joint's own
    /// ω × ω vanishes, and with it the terms a chain of three revolute joints
    /// would add).
    chart: Option<usize>,
}

/// A detected kinematic tree; links are ordered parents first.
pub struct Tree {
    links: Vec<Link>,
    gravity: Option<[Sym; 3]>,
    /// Each spherical joint's first link and its chart's θ.
    spheres: Spheres,
    /// (coordinate, Ia): rotor inertias, which M's diagonal, τ's Ia q̈ and
    /// the articulated pivots take (none for a tree as detected).
    armature: Vec<(usize, Sym)>,
}

/// Spherical joints: each one's first link and its chart's θ.
type Spheres = Vec<(usize, [Sym; 3])>;

/// What the tree's bodies carry, as `derive` hands them over.
pub struct Masses<'a> {
    /// The bodies' names (parallel to the skeleton's bodies) and the point
    /// masses' names, for the reason a description is not a tree.
    pub body_names: &'a [String],
    /// The point masses' names.
    pub point_names: &'a [String],
    /// The point masses' masses.
    pub point_masses: &'a [Sym],
    /// The point masses' world positions.
    pub point_positions: &'a [Vec<Sym>],
    /// The bodies' inertias about their centres, body axes.
    pub inertias: &'a [Mat3],
    /// The gravity field, if any.
    pub gravity: Option<&'a [Sym]>,
}

impl Tree {
    /// Number of joints.
    pub fn len(&self) -> usize {
        self.links.len()
    }

    /// A coordinate that drives more than one joint (a mimic joint), if any:
    /// the articulated-body algorithm needs one coordinate per joint.
    pub fn shared_coordinate(&self) -> Option<usize> {
        let mut seen = std::collections::BTreeSet::new();
        self.links
            .iter()
            .map(|l| l.coordinate)
            .find(|&q| !seen.insert(q))
    }

    /// The same tree with each spherical joint turned by R(θ) = 1 + \[θ\]× +
    /// ½\[θ\]×² after R₀ (its velocity still ω in the turned axes): what to
    /// differentiate in θ at θ = 0 for derivatives in the tangent space.
    pub fn perturbed(&self, ctx: &mut Context) -> Tree {
        let mut links = self.links.clone();
        for &(k, theta) in &self.spheres {
            let turn = crate::mat3::second_order_turn(ctx, theta);
            let placed = match &links[k].placement {
                None => turn,
                Some(p) => crate::mat3::mat_mul(ctx, p, &turn),
            };
            links[k].placement = Some(placed);
        }
        Tree {
            links,
            gravity: self.gravity,
            spheres: Vec::new(),
            armature: self.armature.clone(),
        }
    }

    /// The same tree with each coordinate's rotor inertia (`joint(q,
    /// armature = Ia)`): Ia on M's diagonal, Ia q̈ in τ, Ia in the
    /// articulated pivot of the joint it drives.
    pub fn with_armature(mut self, armature: &[(usize, Sym)]) -> Self {
        self.armature = armature.to_vec();
        self
    }

    /// Whether the tree has a spherical joint (a free orientation).
    pub fn turns_freely(&self) -> bool {
        !self.spheres.is_empty()
    }

    /// Whether the tree has no joints (never returned by [`detect`]).
    pub fn is_empty(&self) -> bool {
        self.links.is_empty()
    }
}
