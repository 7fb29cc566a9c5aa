//! The scene's part of the lowering: every body's pose and every point's
//! position, read from the frames the lowering already built (so no node is
//! added for a description without shapes, and the equations' code is
//! unchanged), and the `shape(...)` items with their sizes lowered as
//! parameter-only expressions.

use lagrange_symbolic::Expr as Sym;
use syn::{Expr, Ident};

use crate::ast::{Shape, Solid, System};
use crate::lower::{Lowerer, Mode, NoInputs};
use crate::lowered::{
    Anchor, BodyPose, PointModel, PointPose, Poses, ShapeModel, SolidModel, SpinModel,
};

/// The poses of the bodies and points and the lowered shapes. A body or point
/// that did not lower (an error already reported) is left out.
pub fn collect(
    lw: &mut Lowerer,
    system: &System,
    masses: &[PointModel],
    spins: &[SpinModel],
) -> Poses {
    let mut poses = Poses::default();
    for b in &system.bodies {
        if let Some(pose) = body_pose(lw, &b.name, masses, spins) {
            poses.bodies.push(pose);
        }
    }
    for p in &system.points {
        let Some(i) = lw.frame_of(&p.name) else {
            continue;
        };
        let body = p.on.as_ref().and_then(|b| body_index(&poses, b));
        poses.points.push(PointPose {
            name: p.name.to_string(),
            position: lw.frames[i].position.clone(),
            body,
        });
    }
    for shape in &system.shapes {
        lower_shape(lw, shape, &mut poses);
    }
    poses
}

fn body_pose(
    lw: &Lowerer,
    name: &Ident,
    masses: &[PointModel],
    spins: &[SpinModel],
) -> Option<BodyPose> {
    let frame = &lw.frames[lw.frame_of(name)?];
    let key = name.to_string();
    let centre = masses.iter().find(|m| m.name == key)?;
    let spin = spins.iter().find(|s| s.name == key)?;
    Some(BodyPose {
        name: key,
        origin: frame.position.clone(),
        centre: centre.position.clone(),
        rotation: frame.axes?,
        mass: centre.mass,
        inertia: spin.inertia,
    })
}

fn body_index(poses: &Poses, name: &Ident) -> Option<usize> {
    poses.bodies.iter().position(|b| *name == b.name)
}

fn anchor(poses: &Poses, name: &Ident) -> Option<Anchor> {
    body_index(poses, name).map(Anchor::Body).or_else(|| {
        poses
            .points
            .iter()
            .position(|p| *name == p.name)
            .map(Anchor::Point)
    })
}

/// One `shape(...)` item: a solid, or a line as one segment per pair of
/// neighbours. (`shape::check` has reported unknown names.)
fn lower_shape(lw: &mut Lowerer, shape: &Shape, poses: &mut Poses) {
    match shape {
        Shape::Line(names) => {
            let anchors: Option<Vec<Anchor>> = names.iter().map(|n| anchor(poses, n)).collect();
            for pair in anchors.unwrap_or_default().windows(2) {
                poses.shapes.push(ShapeModel {
                    on: pair[0],
                    at: Vec::new(),
                    solid: SolidModel::Line(pair[1]),
                });
            }
        }
        Shape::Solid {
            target, solid, at, ..
        } => {
            let on = anchor(poses, target);
            let solid = lower_solid(lw, solid);
            let at = match at {
                Some(e) => size_vector(lw, e),
                None => Some(Vec::new()),
            };
            if let (Some(on), Some(solid), Some(at)) = (on, solid, at) {
                poses.shapes.push(ShapeModel { on, at, solid });
            }
        }
    }
}

fn lower_solid(lw: &mut Lowerer, solid: &Solid) -> Option<SolidModel> {
    Some(match solid {
        Solid::Box { size } => {
            let v = size_vector(lw, size)?;
            SolidModel::Box([v[0], v[1], v[2]])
        }
        Solid::Sphere { radius } => SolidModel::Sphere(size(lw, radius)?),
        Solid::Cylinder {
            radius,
            length,
            axis,
        } => SolidModel::Cylinder {
            radius: size(lw, radius)?,
            length: size(lw, length)?,
            axis: *axis,
        },
        Solid::Capsule {
            radius,
            length,
            axis,
        } => SolidModel::Capsule {
            radius: size(lw, radius)?,
            length: size(lw, length)?,
            axis: *axis,
        },
    })
}

fn size(lw: &mut Lowerer, e: &Expr) -> Option<Sym> {
    lw.without_inputs(NoInputs::SHAPE, |lw| lw.expr(e, Mode::Constant))
}

/// A three-component vector of parameter-only expressions.
fn size_vector(lw: &mut Lowerer, e: &Expr) -> Option<Vec<Sym>> {
    let v = lw.without_inputs(NoInputs::SHAPE, |lw| lw.vector(e, Mode::Constant))?;
    (v.len() == 3).then_some(v)
}
