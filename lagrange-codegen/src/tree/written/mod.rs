//! Finding the tree where positions and rotations are written out: a body
//! whose rotation is an explicit matrix, or whose reference point is an
//! expression ξ(q) rather than a point of its parent, still hangs on a parent
//! by one joint when, relative to that parent, its rotation R_pᵀ R_b and
//! position R_pᵀ (ξ_b − ξ_p) depend on one further coordinate only: turning
//! about a fixed axis (revolute) or moving along a fixed line (prismatic). No
//! coordinate at all is a fixed joint.
//!
//! The parent is the body already placed whose coordinates are the most
//! among those the body depends on (in a tree a body depends on its
//! ancestors' joints and its own). The joint is read off at q = 0, where the
//! written-out trigonometry folds to constants: the placement R₀, the axis n
//! from R₀ᵀ ∂R_rel/∂q, the body's offset from the axis from ∂r/∂q. Nothing in
//! that reading proves the form, since the engine does not apply sin² + cos²
//! = 1: each joint is then checked numerically, R_rel(q) = R₀ rot(n, q) and
//! r(q) = a + R₀ rot(n, q) s at random configurations and parameters (in
//! f64, to 1e-9 relative). A body that fails (an axis that moves, a
//! coordinate that does not cancel) leaves the system to the generic route
//! with the reason, naming the body.

mod probe;

use std::collections::BTreeSet;

use lagrange_symbolic::{Context, Expr as Sym, SymbolKind};

use super::frame::{Frame, PlacedMass, coordinate_name};
use super::link::add3;
use super::{BodyFault, Link, Masses, NotATree};
use crate::lowered::Skeleton;
use crate::mat3::{Mat3, cross, mat_mul, mat_vec, transpose, vee};
use probe::{check, settled};

/// The links, each body's frame and each point mass's body, read from the
/// written-out positions and rotations.
pub(super) struct Written {
    pub links: Vec<Link>,
    pub frames: Vec<Frame>,
    pub masses: Vec<PlacedMass>,
}

/// A body's rotation and reference point as written, and the coordinates
/// they depend on.
struct Pose {
    rotation: Mat3,
    origin: [Sym; 3],
    depends: BTreeSet<usize>,
}

/// How a body moves relative to its parent's axes.
enum Joint {
    /// Fixed: constant rotation and offset.
    Fixed { rotation: Mat3, origin: [Sym; 3] },
    /// R_rel = R₀ P rot_axis(q) Pᵀ, r = a + R_rel s (`turn` = R₀ P).
    Revolute {
        coordinate: usize,
        turn: Mat3,
        unturn: Mat3,
        axis: usize,
        a: [Sym; 3],
        s: [Sym; 3],
    },
    /// R_rel = R₀, r = r₀ + d q.
    Prismatic {
        coordinate: usize,
        rotation: Mat3,
        origin: [Sym; 3],
        direction: [Sym; 3],
    },
}

/// The tree the written-out bodies span, or why they span none.
pub(super) fn read(
    ctx: &mut Context,
    skeleton: &Skeleton,
    masses: &Masses,
) -> Result<Written, NotATree> {
    let names = masses.body_names;
    let poses = skeleton
        .bodies
        .iter()
        .zip(names)
        .map(|(b, name)| pose(ctx, b.matrix, &b.reference, name))
        .collect::<Result<Vec<_>, _>>()?;
    let mut order: Vec<usize> = (0..poses.len()).collect();
    order.sort_by_key(|&b| poses[b].depends.len());
    let mut links: Vec<Link> = Vec::new();
    let mut frames: Vec<Option<Frame>> = vec![None; poses.len()];
    let mut used = vec![false; ctx.coordinates().len()];
    for (k, &b) in order.iter().enumerate() {
        let (parent, joint) = parent_and_joint(ctx, &poses, &order[..k], b)
            .map_err(|fault| NotATree::body(&names[b], fault))?;
        if let Some(q) = joint.coordinate() {
            used[q] = true;
        }
        let up = parent.map(|j| frames[j].expect("parents are placed first"));
        frames[b] = Some(hang(ctx, joint, up, &mut links));
    }
    if let Some(q) = used.iter().position(|&u| !u) {
        let coordinate = coordinate_name(ctx, q);
        return Err(NotATree::IdleCoordinate {
            coordinate,
            written: true,
        });
    }
    let frames: Vec<Frame> = frames.into_iter().map(|f| f.expect("placed")).collect();
    let masses = point_bodies(ctx, skeleton, masses.point_positions, &poses);
    Ok(Written {
        links,
        frames,
        masses,
    })
}

/// The parent and joint of body `b` among the bodies `placed`: the
/// candidates whose coordinates are among `b`'s, the most first (a tree's
/// parent has all but the joint's own); the first whose joint reads and
/// checks. Two bodies on the same coordinates that move apart (a mimic
/// joint's two fingers) are not each other's parent, so the search goes on
/// to the body they both hang on. The reason is the first candidate's.
fn parent_and_joint(
    ctx: &mut Context,
    poses: &[Pose],
    placed: &[usize],
    b: usize,
) -> Result<(Option<usize>, Joint), BodyFault> {
    let mut candidates: Vec<Option<usize>> = placed
        .iter()
        .copied()
        .filter(|&j| poses[j].depends.is_subset(&poses[b].depends))
        .map(Some)
        .collect();
    candidates.sort_by_key(|j| std::cmp::Reverse(j.map_or(0, |j| poses[j].depends.len())));
    candidates.push(None);
    let mut first = None;
    for parent in candidates {
        match joint(ctx, parent.map(|j| &poses[j]), &poses[b]) {
            Ok(joint) => return Ok((parent, joint)),
            Err(why) => {
                first.get_or_insert(why);
            }
        }
    }
    Err(first.expect("the ground is always a candidate"))
}

impl Joint {
    fn coordinate(&self) -> Option<usize> {
        match self {
            Joint::Fixed { .. } => None,
            Joint::Revolute { coordinate, .. } | Joint::Prismatic { coordinate, .. } => {
                Some(*coordinate)
            }
        }
    }
}

/// A body's pose as written, refusing time, inputs and quaternions.
fn pose(ctx: &Context, rotation: Mat3, reference: &[Sym], name: &str) -> Result<Pose, NotATree> {
    let [x, y, z] = reference else {
        return Err(NotATree::body(name, BodyFault::ReferenceNot3D));
    };
    let origin = [*x, *y, *z];
    let mut depends = BTreeSet::new();
    for &e in rotation.iter().flatten().chain(&origin) {
        for s in ctx.free_symbols(e) {
            match ctx.symbol_kind(s) {
                SymbolKind::Coordinate(i) => {
                    depends.insert(i);
                }
                SymbolKind::Parameter(_) => {}
                kind => {
                    let what = match kind {
                        SymbolKind::Time => "time",
                        SymbolKind::Input(_) => "an input",
                        // A free orientation's quaternion: read from
                        // rotation factors, never from a written-out matrix.
                        _ => "a free orientation",
                    };
                    return Err(NotATree::body(name, BodyFault::PoseDependsOn(what)));
                }
            }
        }
    }
    Ok(Pose {
        rotation,
        origin,
        depends,
    })
}

/// The joint that carries `body` in `parent`'s axes (the ground's: none).
fn joint(ctx: &mut Context, parent: Option<&Pose>, body: &Pose) -> Result<Joint, BodyFault> {
    let (rotation, origin) = relative(ctx, parent, body);
    let inherited = parent.map(|p| p.depends.clone()).unwrap_or_default();
    let new: Vec<usize> = body.depends.difference(&inherited).copied().collect();
    let joint = match new[..] {
        [] => Joint::Fixed {
            rotation: matrix_at_zero(ctx, &rotation),
            origin: origin.map(|e| at_zero(ctx, e)),
        },
        [q] => one_coordinate(ctx, q, &rotation, origin)?,
        _ => {
            let coordinates = new.iter().map(|&q| coordinate_name(ctx, q)).collect();
            return Err(BodyFault::SeveralCoordinates { coordinates });
        }
    };
    check(ctx, &joint, (&rotation, &origin)).map(|()| joint)
}

/// R_pᵀ R_b and R_pᵀ (ξ_b − ξ_p).
fn relative(ctx: &mut Context, parent: Option<&Pose>, body: &Pose) -> (Mat3, [Sym; 3]) {
    let Some(p) = parent else {
        return (body.rotation, body.origin);
    };
    let back = transpose(&p.rotation);
    let rotation = mat_mul(ctx, &back, &body.rotation);
    let d = [0, 1, 2].map(|i| ctx.sub(body.origin[i], p.origin[i]));
    (rotation, mat_vec(ctx, &back, d))
}

/// `e` at q = 0 (every coordinate), where the trigonometry folds, then
/// [`settled`].
fn at_zero(ctx: &mut Context, e: Sym) -> Sym {
    let zero = ctx.zero();
    let map: Vec<(Sym, Sym)> = ctx.coordinates().into_iter().map(|q| (q, zero)).collect();
    let e = ctx.substitute(e, &map);
    let e = ctx.simplify(e);
    settled(ctx, e)
}

fn matrix_at_zero(ctx: &mut Context, m: &Mat3) -> Mat3 {
    m.map(|row| row.map(|e| at_zero(ctx, e)))
}

/// A revolute or prismatic joint about coordinate `q`, read at q = 0.
fn one_coordinate(
    ctx: &mut Context,
    q: usize,
    rotation: &Mat3,
    origin: [Sym; 3],
) -> Result<Joint, BodyFault> {
    let x = ctx.coordinates()[q];
    let r0 = matrix_at_zero(ctx, rotation);
    let dr = rotation.map(|row| row.map(|e| ctx.diff(e, x)));
    let dr0 = matrix_at_zero(ctx, &dr);
    let w = mat_mul(ctx, &transpose(&r0), &dr0);
    let n = vee(ctx, &w).map(|e| settled(ctx, e));
    let o = origin.map(|e| at_zero(ctx, e));
    let d = origin.map(|e| {
        let d = ctx.diff(e, x);
        at_zero(ctx, d)
    });
    if n.iter().all(|&c| ctx.is_zero(c)) {
        return Ok(Joint::Prismatic {
            coordinate: q,
            rotation: r0,
            origin: o,
            direction: d,
        });
    }
    let (placement, axis) = axis_placement(ctx, n)?;
    let turn = mat_mul(ctx, &r0, &placement);
    // r'(0) = R₀ (n × s), so s ⊥ n is (R₀ᵀ r'(0)) × n; a = r(0) − R₀ s.
    let local = mat_vec(ctx, &transpose(&r0), d);
    let s = cross(ctx, local, n).map(|e| {
        let e = ctx.simplify(e);
        settled(ctx, e)
    });
    let turned = mat_vec(ctx, &r0, s);
    let a = [0, 1, 2].map(|i| {
        let e = ctx.sub(o[i], turned[i]);
        let e = ctx.simplify(e);
        settled(ctx, e)
    });
    Ok(Joint::Revolute {
        coordinate: q,
        turn,
        unturn: transpose(&placement),
        axis,
        a,
        s,
    })
}

/// A placement P with P e_axis = n for a constant unit axis n: the identity
/// or a half turn for ±e_i (exact), otherwise the shortest turn taking e_z
/// to n (floats, evaluated here once).
fn axis_placement(ctx: &mut Context, n: [Sym; 3]) -> Result<(Mat3, usize), BodyFault> {
    let values: Vec<Option<f64>> = n
        .iter()
        .map(|&e| {
            if ctx.is_constant(e) {
                ctx.as_f64(e)
            } else {
                None
            }
        })
        .collect();
    let Some(v) = values.into_iter().collect::<Option<Vec<f64>>>() else {
        return Err(BodyFault::AxisDependsOnParameters);
    };
    let zero = ctx.zero();
    let one = ctx.one();
    let minus = ctx.int(-1);
    for i in 0..3 {
        let j = (i + 1) % 3;
        let k = (i + 2) % 3;
        if v[j] != 0.0 || v[k] != 0.0 || v[i].abs() != 1.0 {
            continue;
        }
        let mut p = [[zero; 3]; 3];
        // A half turn about e_j flips e_i and e_k.
        let flip = if v[i] > 0.0 { one } else { minus };
        (p[i][i], p[j][j], p[k][k]) = (flip, one, flip);
        return Ok((p, i));
    }
    Ok((shortest_turn(&v).map(|row| row.map(|x| ctx.float(x))), 2))
}

/// The rotation taking e_z to the unit vector `n` about e_z × n (a half
/// turn about e_x when n = −e_z).
fn shortest_turn(n: &[f64]) -> [[f64; 3]; 3] {
    let norm = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let [x, y, z] = [n[0] / norm, n[1] / norm, n[2] / norm];
    if 1.0 + z < 1e-12 {
        return [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]];
    }
    // R = I + [k]× + [k]×² / (1 + c), k = e_z × n = (−y, x, 0), c = z.
    let f = 1.0 / (1.0 + z);
    [
        [1.0 - x * x * f, -x * y * f, x],
        [-x * y * f, 1.0 - y * y * f, y],
        [-x, -y, z],
    ]
}

/// Hangs the body on its joint: a new link for a revolute or prismatic one
/// (in the link its parent is fixed in, `up`; `None`: the ground), the
/// body's frame in its link.
fn hang(ctx: &mut Context, joint: Joint, up: Option<Frame>, links: &mut Vec<Link>) -> Frame {
    let zero = ctx.zero();
    let (link, at, turned) = match up {
        Some(f) => (f.link, f.origin, Some(f.rotation)),
        None => (None, [zero; 3], None),
    };
    // Parent body axes → parent link axes.
    let to_link = |ctx: &mut Context, v: [Sym; 3]| {
        let v = turned.map_or(v, |r| mat_vec(ctx, &r, v));
        add3(ctx, at, v)
    };
    let rotate = |ctx: &mut Context, m: Mat3| turned.map_or(m, |r| mat_mul(ctx, &r, &m));
    match joint {
        Joint::Fixed { rotation, origin } => Frame {
            link,
            origin: to_link(ctx, origin),
            rotation: rotate(ctx, rotation),
        },
        Joint::Revolute {
            coordinate,
            turn,
            unturn,
            axis,
            a,
            s,
        } => {
            let offset = to_link(ctx, a);
            let placement = rotate(ctx, turn);
            links.push(Link {
                parent: link,
                placement: (!is_identity(ctx, &placement)).then_some(placement),
                slide: None,
                axis,
                coordinate,
                offset,
                inertia: None,
                chart: None,
            });
            Frame {
                link: Some(links.len() - 1),
                origin: mat_vec(ctx, &unturn, s),
                rotation: unturn,
            }
        }
        Joint::Prismatic {
            coordinate,
            rotation,
            origin,
            direction,
        } => {
            let offset = to_link(ctx, origin);
            let slide = turned.map_or(direction, |r| mat_vec(ctx, &r, direction));
            links.push(Link {
                parent: link,
                placement: None,
                slide: Some(slide),
                axis: 0,
                coordinate,
                offset,
                inertia: None,
                chart: None,
            });
            Frame {
                link: Some(links.len() - 1),
                origin: [zero; 3],
                rotation: rotate(ctx, rotation),
            }
        }
    }
}

fn is_identity(ctx: &Context, m: &Mat3) -> bool {
    (0..9).all(|k| {
        let want = if k / 3 == k % 3 { 1.0 } else { 0.0 };
        ctx.is_constant(m[k / 3][k % 3]) && ctx.as_f64(m[k / 3][k % 3]) == Some(want)
    })
}

/// Each point mass's body: as the description placed it, or, for a point
/// written out as ξ(q), the body with the fewest coordinates in whose axes
/// it stays put (checked as the joints are); `None` for one fixed in space
/// or in no body (which `attach_masses` tells apart).
fn point_bodies(
    ctx: &mut Context,
    skeleton: &Skeleton,
    positions: &[Vec<Sym>],
    poses: &[Pose],
) -> Vec<PlacedMass> {
    skeleton
        .masses
        .iter()
        .zip(positions)
        .map(|(at, position)| at.clone().or_else(|| fixed_in(ctx, position, poses)))
        .collect()
}

/// The body in whose axes `position` stays put, and where.
fn fixed_in(ctx: &mut Context, position: &[Sym], poses: &[Pose]) -> Option<(usize, Vec<Sym>)> {
    let [x, y, z] = position else { return None };
    let depends: BTreeSet<usize> = [*x, *y, *z]
        .iter()
        .flat_map(|&e| ctx.free_symbols(e))
        .filter_map(|s| match ctx.symbol_kind(s) {
            SymbolKind::Coordinate(i) => Some(i),
            _ => None,
        })
        .collect();
    if depends.is_empty() {
        return None;
    }
    let mut candidates: Vec<usize> = (0..poses.len())
        .filter(|&b| depends.is_subset(&poses[b].depends))
        .collect();
    candidates.sort_by_key(|&b| poses[b].depends.len());
    candidates.into_iter().find_map(|b| {
        let pose = &poses[b];
        let d = [0, 1, 2].map(|i| ctx.sub(position[i], pose.origin[i]));
        let local = mat_vec(ctx, &transpose(&pose.rotation), d);
        let constant = local.map(|e| at_zero(ctx, e));
        let joint = Joint::Fixed {
            rotation: pose.rotation,
            origin: constant,
        };
        let written = (&pose.rotation, &local);
        check(ctx, &joint, written)
            .ok()
            .map(|()| (b, constant.to_vec()))
    })
}
