//! The bodies and points of a description lowered: each body's frame, its
//! centre as a point mass and its spin, each point's position and mass, and
//! where both sit for the recursive route (`Skeleton`).

use super::*;
use crate::mat3::{mat_vec, parallel_axis};

/// Point masses, spins and body frames lowered so far.
#[derive(Default)]
pub(super) struct Items {
    pub(super) points: Vec<PointModel>,
    pub(super) spins: Vec<SpinModel>,
    /// (body, rotation matrix, reference point) for the points fixed in bodies.
    pub(super) rotations: Vec<(Ident, Mat3, Vec<Sym>)>,
    /// Where the masses sit relative to the bodies, for the recursive derivation.
    pub(super) skeleton: Skeleton,
    /// Masses and inertias computed from parameters, checked at run time.
    pub(super) checks: Vec<PhysicalCheck>,
}

/// A rigid body: its frame (for `B.x`, `B.omega_x` and points on it), its centre
/// of mass as a point mass, and its spin. The reference point is `at`; the centre
/// of mass is at + R·com when `com` is given.
pub(super) fn lower_body(lw: &mut Lowerer, b: &crate::ast::Body, items: &mut Items) {
    let (Some(mass), Some(inertia), Some(at), Some(rotation)) =
        (&b.mass, &b.inertia, &b.at, &b.rotation)
    else {
        return;
    };
    let whose = |key: &str| format!("the {key} of body `{}`", b.name);
    let mass = lw.lowering_as(whose("mass"), |lw| {
        lw.without_inputs(NoInputs::MASS, |lw| lw.expr(mass, Mode::Constant))
    });
    let inertia = lw.lowering_as(whose("inertia"), |lw| {
        lw.without_inputs(NoInputs::INERTIA, |lw| inertia_matrix(lw, inertia))
    });
    let reference = lw.lowering_as(whose("position `at`"), |lw| {
        lw.without_inputs(NoInputs::POSITION, |lw| lw.vector(at, Mode::Configuration))
    });
    let com = b.com.as_ref().map(|c| {
        lw.lowering_as(whose("centre of mass `com`"), |lw| {
            lw.without_inputs(NoInputs::POSITION, |lw| lw.vector(c, Mode::Constant))
        })
    });
    let about = b.about.as_ref().map(|a| {
        lw.lowering_as(whose("inertia's reference point `about`"), |lw| {
            lw.without_inputs(NoInputs::POSITION, |lw| lw.vector(a, Mode::Constant))
        })
    });
    let rotation = lw.lowering_as(whose("rotation"), |lw| {
        lw.without_inputs(NoInputs::ROTATION, |lw| lw.rotation(rotation))
    });
    let (Some(mass), Some(inertia), Some(reference), Some(rotation)) =
        (mass, inertia, reference, rotation)
    else {
        return;
    };
    let inertia = match about {
        None => inertia,
        Some(Some(point)) if point.len() == 3 => {
            let zero = lw.ctx.zero();
            let com = match &com {
                Some(Some(c)) if c.len() == 3 => c.clone(),
                _ => vec![zero; 3],
            };
            to_centre_of_mass(lw, inertia, mass, &point, &com)
        }
        Some(_) => return,
    };
    // `check` has reported a reference point or `com` that is not [x, y, z].
    if reference.len() != 3 {
        return;
    }
    let mass_syntax = b.mass.as_ref().unwrap_or(at);
    check_body(lw, b, items, (mass, mass_syntax), &inertia, &rotation);
    let zero = lw.ctx.zero();
    let (centre, offset) = match com {
        None => (reference.clone(), vec![zero; 3]),
        Some(Some(offset)) if offset.len() == 3 => {
            let centre = offset_in_body(lw, &rotation.matrix, &reference, &offset);
            (centre, offset)
        }
        Some(_) => return,
    };
    let body = LoweredBody {
        mass,
        inertia,
        reference,
        centre,
        offset,
        rotation,
    };
    record_body(lw, b, items, body);
}

/// The physical checks of a body's mass (written at `syntax`) and inertia
/// (`physical`): refused at its literal, or kept for the emitted
/// `check_parameters`.
fn check_body(
    lw: &mut Lowerer,
    b: &crate::ast::Body,
    items: &mut Items,
    (mass, syntax): (Sym, &Expr),
    inertia: &Mat3,
    rotation: &Rotation,
) {
    let what = format!("body `{}`", b.name);
    let name = b.name.to_string();
    items
        .checks
        .extend(physical::mass(lw, &name, &what, syntax, mass));
    let spatial = rotation.omega_body.iter().all(|&w| !lw.ctx.is_zero(w));
    let shape = physical::Shape {
        moved: b.about.is_some(),
        spatial,
    };
    items
        .checks
        .extend(physical::inertia(lw, b, inertia, shape));
}

/// A body lowered and checked, for [`record_body`].
struct LoweredBody {
    mass: Sym,
    /// About the centre of mass, in body axes.
    inertia: Mat3,
    /// The reference point `at`, in the world.
    reference: Vec<Sym>,
    /// The centre of mass, in the world.
    centre: Vec<Sym>,
    /// The centre of mass in body axes from the reference point (`com`, or
    /// zero).
    offset: Vec<Sym>,
    rotation: Rotation,
}

/// Brings a lowered body into scope and records its centre as a point mass, its
/// spin, and its frame for the points fixed in it and the recursive route.
fn record_body(lw: &mut Lowerer, b: &crate::ast::Body, items: &mut Items, body: LoweredBody) {
    let LoweredBody {
        mass,
        inertia,
        reference,
        centre,
        offset,
        rotation,
    } = body;
    lw.declare_frame(
        &b.name,
        Frame {
            name: b.name.to_string(),
            position: reference.clone(),
            omega: Some([rotation.omega_world, rotation.omega_body]),
            axes: Some(rotation.matrix),
        },
    );
    let index = items.spins.len();
    let zero = lw.ctx.zero();
    items.skeleton.bodies.push(BodyFrame {
        factors: rotation.factors,
        matrix: rotation.matrix,
        reference: reference.clone(),
    });
    items.skeleton.masses.push(Some((index, offset)));
    items
        .skeleton
        .anchors
        .push((reference.clone(), index, vec![zero; 3]));
    items
        .rotations
        .push((b.name.clone(), rotation.matrix, reference));
    items.points.push(PointModel {
        name: b.name.to_string(),
        mass,
        position: centre,
    });
    items.spins.push(SpinModel {
        name: b.name.to_string(),
        inertia,
        omega: rotation.omega_body,
    });
}

/// The parallel-axis theorem: an inertia tensor about the body point `about`
/// moved to the centre of mass `com` (both in body coordinates),
/// I_com = I_about − m (|d|² E − d dᵀ) with d = com − about.
fn to_centre_of_mass(
    lw: &mut Lowerer,
    about_point: [[Sym; 3]; 3],
    mass: Sym,
    about: &[Sym],
    com: &[Sym],
) -> [[Sym; 3]; 3] {
    let d = [0, 1, 2].map(|i| lw.ctx.sub(com[i], about[i]));
    let shift = parallel_axis(&mut lw.ctx, mass, d);
    let mut out = about_point;
    for i in 0..3 {
        for j in 0..3 {
            let entry = lw.ctx.sub(out[i][j], shift[i][j]);
            out[i][j] = lw.ctx.collect(entry);
        }
    }
    out
}

/// origin + R·local: a point given in body coordinates.
fn offset_in_body(lw: &mut Lowerer, r: &Mat3, origin: &[Sym], local: &[Sym]) -> Vec<Sym> {
    let rb = mat_vec(&mut lw.ctx, r, [local[0], local[1], local[2]]);
    (0..3).map(|i| lw.ctx.add(origin[i], rb[i])).collect()
}

/// A point: in world coordinates, or fixed in a body (`on = B`, coordinates
/// relative to the body's reference point in its axes); a point mass if it has
/// a mass.
pub(super) fn lower_point(lw: &mut Lowerer, p: &crate::ast::Point, items: &mut Items) {
    let Some(at) = &p.at else { return };
    let local = lw.lowering_as(format!("the position of point `{}`", p.name), |lw| {
        lw.without_inputs(NoInputs::POSITION, |lw| lw.vector(at, Mode::Configuration))
    });
    let mass = p.mass.as_ref().map(|m| {
        lw.lowering_as(format!("the mass of point `{}`", p.name), |lw| {
            lw.without_inputs(NoInputs::MASS, |lw| lw.expr(m, Mode::Constant))
        })
    });
    let (position, fixed_in) = match (&p.on, local) {
        (_, None) => return,
        (None, Some(x)) => (x, None),
        (Some(body), Some(local)) => {
            let Some(index) = items.rotations.iter().position(|(n, _, _)| n == body) else {
                return;
            };
            // `check` has reported body coordinates that are not [x, y, z].
            if local.len() != 3 {
                return;
            }
            let r = items.rotations[index].1;
            let c = items.rotations[index].2.clone();
            let position = offset_in_body(lw, &r, &c, &local);
            items
                .skeleton
                .anchors
                .push((position.clone(), index, local.clone()));
            (position, Some((index, local)))
        }
    };
    lw.declare_frame(
        &p.name,
        Frame {
            name: p.name.to_string(),
            position: position.clone(),
            omega: None,
            axes: None,
        },
    );
    if let (Some(Some(mass)), Some(syntax)) = (mass, &p.mass) {
        let what = format!("point `{}`", p.name);
        let name = p.name.to_string();
        items
            .checks
            .extend(physical::mass(lw, &name, &what, syntax, mass));
        items.skeleton.masses.push(fixed_in);
        items.points.push(PointModel {
            name: p.name.to_string(),
            mass,
            position,
        });
    }
}

/// `[A, B, C]` → diag(A, B, C); `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]` → the symmetric tensor.
fn inertia_matrix(lw: &mut Lowerer, e: &Expr) -> Option<[[Sym; 3]; 3]> {
    let entries = lw.vector(e, Mode::Constant)?;
    // `check` has reported any other length.
    if !(entries.len() == 3 || entries.len() == 6) {
        return None;
    }
    let zero = lw.ctx.zero();
    let mut m = [[zero; 3]; 3];
    for i in 0..3 {
        m[i][i] = entries[i];
    }
    if entries.len() == 6 {
        for (k, (i, j)) in [(0, 1), (0, 2), (1, 2)].into_iter().enumerate() {
            m[i][j] = entries[3 + k];
            m[j][i] = entries[3 + k];
        }
    }
    Some(m)
}
