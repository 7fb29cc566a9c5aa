//! What a system reports for drawing: the world pose of each body and the
//! position of each point as functions of (q, t), each body's mass and
//! inertia, and the visual shapes of its description. `#[derive(Lagrangian)]`
//! implements [`Posed`] for every description; the [`scene`](crate::scene)
//! service samples it along a trajectory.
//!
//! Shapes are visual only: nothing in the equations of motion reads them.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::numeric::Real;

/// A body's pose: its reference point (`at` in the description), its centre
/// of mass and its rotation R (body → world: column j is the body's j-th axis
/// in world components).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyPose<T> {
    /// The body's reference point (`at` in the description), world axes.
    pub origin: Vector3<T>,
    /// The body's centre of mass, world axes.
    pub centre: Vector3<T>,
    /// R, body → world: column j is the body's j-th axis in world components.
    pub rotation: Matrix3<T>,
}

impl<T: Real> Default for BodyPose<T> {
    fn default() -> Self {
        BodyPose {
            origin: Vector3::zeros(),
            centre: Vector3::zeros(),
            rotation: Matrix3::identity(),
        }
    }
}

/// A body's mass and its inertia tensor about the centre of mass, in body axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyInertia<T> {
    /// The body's mass.
    pub mass: T,
    /// The inertia tensor about the centre of mass, body axes.
    pub inertia: Matrix3<T>,
}

impl<T: Real> Default for BodyInertia<T> {
    fn default() -> Self {
        BodyInertia {
            mass: T::zero(),
            inertia: Matrix3::zeros(),
        }
    }
}

/// What a shape is fixed to: an index into [`Posed::BODIES`] or [`Posed::POINTS`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// Body k of [`Posed::BODIES`]: the shape turns with it.
    Body(usize),
    /// Point k of [`Posed::POINTS`]: the shape moves with it, world axes.
    Point(usize),
}

/// The solid of a shape, sizes in the description's length unit; a cylinder's
/// or capsule's `axis` is 0, 1 or 2 for the body's x, y or z axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Solid<T> {
    /// Full edge lengths along the body axes.
    Box {
        /// Edge lengths along x, y and z.
        size: Vector3<T>,
    },
    /// A ball.
    Sphere {
        /// Its radius.
        radius: T,
    },
    /// A right circular cylinder centred on its anchor point.
    Cylinder {
        /// Its radius.
        radius: T,
        /// Its full length along `axis`.
        length: T,
        /// The body axis it lies along (0 = x, 1 = y, 2 = z).
        axis: usize,
    },
    /// A cylinder of `length` with hemispherical ends.
    Capsule {
        /// The radius of the cylinder and of its end caps.
        radius: T,
        /// The cylinder's length between the caps' centres.
        length: T,
        /// The body axis it lies along (0 = x, 1 = y, 2 = z).
        axis: usize,
    },
    /// A straight line from the shape's anchor to `to`.
    Line {
        /// The other end: a body's reference point or a point.
        to: Anchor,
    },
}

/// A `shape(...)` item: a solid centred `at` (body coordinates from the body's
/// reference point, or world axes from a point) on its anchor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shape<T> {
    /// What the shape is fixed to.
    pub on: Anchor,
    /// The solid's centre relative to the anchor (body axes on a body, world
    /// axes on a point).
    pub at: Vector3<T>,
    /// The solid itself.
    pub solid: Solid<T>,
}

/// The poses of a system's bodies and points, in the order of [`Posed::BODIES`]
/// and [`Posed::POINTS`]. Planar descriptions report points with z = 0.
pub trait Posed<T: Real, const N: usize, const Q: usize = N> {
    /// The bodies' names, in declaration order.
    const BODIES: &'static [&'static str];
    /// Every point's name (with or without mass), in declaration order.
    const POINTS: &'static [&'static str];
    /// Per point, the index of the body it is fixed in, if any.
    const POINT_BODIES: &'static [Option<usize>];

    /// Writes the pose of every body and the position of every point at
    /// (q, t). The slices hold `BODIES.len()` and `POINTS.len()` entries.
    fn poses(&self, q: &SVector<T, Q>, t: T, bodies: &mut [BodyPose<T>], points: &mut [Vector3<T>]);

    /// The pose of one body at (q, t): `poses(..)`'s entry `body`, without
    /// the caller allocating a slice for every body and point; `None` for an
    /// index past [`BODIES`](Self::BODIES). With `emit(kinematics)` the
    /// derive overrides it with one program per body, which computes that
    /// body's pose alone; the default evaluates every pose (allocating the
    /// slices) and keeps the one asked for.
    ///
    /// Like [`poses`](Self::poses) it checks nothing:
    /// [`Configuration::frame_pose`](crate::Configuration::frame_pose)
    /// evaluates it at a q checked as a run checks its start.
    fn frame_pose(&self, body: usize, q: &SVector<T, Q>, t: T) -> Option<BodyPose<T>> {
        if body >= Self::BODIES.len() {
            return None;
        }
        let mut bodies = vec![BodyPose::default(); Self::BODIES.len()];
        let mut points = vec![Vector3::zeros(); Self::POINTS.len()];
        self.poses(q, t, &mut bodies, &mut points);
        Some(bodies[body])
    }

    /// Writes each body's mass and inertia (`BODIES.len()` entries).
    fn inertias(&self, out: &mut [BodyInertia<T>]);

    /// Calls `out` with each shape of the description, in order.
    fn shapes(&self, out: &mut dyn FnMut(Shape<T>));
}

/// The bodies' frame Jacobians and the centre of mass with its Jacobian, as
/// robot code calls them; `#[derive(Lagrangian)]` implements it with
/// `emit(kinematics)`. A frame is a body's: its origin (the reference point)
/// and its axes; `body` indexes [`Posed::BODIES`]. Everything is at a fixed
/// time: a rheonomic description's explicit ∂/∂t terms are left out. With
/// orientations (Q ≠ N) q holds the quaternions and the Jacobians' columns
/// are v's: an orientation's three the body-axis ω (the tangent space).
///
/// These methods check nothing (they are the generated code): q must hold
/// unit quaternions and finite numbers, or the answer is that of another
/// rotation, or NaN. [`Configuration`](crate::Configuration) evaluates them
/// at q checked as a run checks its start, with typed errors.
pub trait Kinematics<T: Real, const N: usize, const Q: usize = N>: Posed<T, N, Q> {
    /// The geometric Jacobian of the frame at its origin in world-aligned
    /// axes: rows 0–2 map q̇ to the origin's velocity, rows 3–5 to the
    /// angular velocity (Pinocchio's `LOCAL_WORLD_ALIGNED`). `None` for an
    /// index past the bodies.
    fn frame_jacobian(&self, body: usize, q: &SVector<T, Q>, t: T) -> Option<SMatrix<T, 6, N>>;

    /// J̇ q̇ of the frame: the origin's classical acceleration and the angular
    /// acceleration at q̈ = 0, so that the frame's acceleration is J q̈ + J̇ q̇.
    fn frame_bias(
        &self,
        body: usize,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> Option<SVector<T, 6>>;

    /// The centre of mass of the moving masses: a mass fixed in space (a
    /// robot's base) moves with nothing and is left out, as Pinocchio's
    /// `centerOfMass` leaves out the universe's.
    fn center_of_mass(&self, q: &SVector<T, Q>, t: T) -> Vector3<T>;

    /// ∂(centre of mass)/∂q.
    fn center_of_mass_jacobian(&self, q: &SVector<T, Q>, t: T) -> SMatrix<T, 3, N>;

    /// The frame Jacobian in the frame's own axes (Pinocchio's `LOCAL`):
    /// [`frame_jacobian`](Self::frame_jacobian) with both blocks turned by Rᵀ,
    /// R the body's rotation from [`Posed::frame_pose`].
    fn frame_jacobian_local(
        &self,
        body: usize,
        q: &SVector<T, Q>,
        t: T,
    ) -> Option<SMatrix<T, 6, N>> {
        let world = self.frame_jacobian(body, q, t)?;
        let rt = self.frame_pose(body, q, t)?.rotation.transpose();
        let mut local = world;
        local
            .fixed_rows_mut::<3>(0)
            .copy_from(&(rt * world.fixed_rows::<3>(0)));
        local
            .fixed_rows_mut::<3>(3)
            .copy_from(&(rt * world.fixed_rows::<3>(3)));
        Some(local)
    }

    /// The index of the body named `name` in [`Posed::BODIES`].
    fn body_index(name: &str) -> Option<usize> {
        Self::BODIES.iter().position(|&b| b == name)
    }
}
