//! Finding the tree in a description: joints from the bodies' rotation factors,
//! parents by the longest proper prefix of joints, offsets from the anchors, and
//! the masses gathered onto the links. Where the description is not a tree,
//! the answer says why: which body or point, and what about it, so that the
//! user can see what keeps a model off the recursive route.

use lagrange_symbolic::{Context, Expr as Sym, SymbolKind};

use super::{Inertia, Link, Masses, Tree};
use crate::lowered::Skeleton;

/// Whether `e` depends on parameters only (fixed in space and time).
fn fixed(ctx: &Context, e: Sym) -> bool {
    ctx.free_symbols(e)
        .iter()
        .all(|&s| matches!(ctx.symbol_kind(s), SymbolKind::Parameter(_)))
}

/// The name of coordinate `i`, for the reasons.
fn coordinate_name(ctx: &Context, i: usize) -> String {
    let q = ctx.coordinates()[i];
    ctx.as_symbol(q)
        .map_or_else(String::new, |s| ctx.symbol_name(s).to_string())
}

/// The kinematic tree the description spans, or why it is not one.
pub fn detect(ctx: &mut Context, skeleton: &Skeleton, masses: &Masses) -> Result<Tree, String> {
    let n = ctx.coordinates().len();
    if skeleton.bodies.is_empty() || n == 0 {
        return Err("it has no rigid bodies (point masses alone)".into());
    }
    let joints = body_joints(ctx, skeleton, masses.body_names)?;
    let (mut links, last_link) = link_bodies(ctx, skeleton, &joints, masses.body_names)?;
    attach_masses(ctx, skeleton, masses, &mut links, &last_link)?;
    let gravity = match masses.gravity {
        None => None,
        Some(g) if g.len() == 3 && g.iter().all(|&x| fixed(ctx, x)) => Some([g[0], g[1], g[2]]),
        Some(_) => return Err("gravity is not a constant vector".into()),
    };
    Ok(Tree { links, gravity })
}

/// Each body's joints as (axis, coordinate index), from its rotation factors.
fn body_joints(
    ctx: &Context,
    skeleton: &Skeleton,
    names: &[String],
) -> Result<Vec<Vec<(usize, usize)>>, String> {
    let coordinates = ctx.coordinates();
    let mut joints = Vec::new();
    for (b, body) in skeleton.bodies.iter().enumerate() {
        let Some(factors) = body.factors.as_ref() else {
            return Err(format!(
                "body `{}`: its rotation is not a product of rot_x/rot_y/rot_z factors",
                names[b]
            ));
        };
        let mut js = Vec::new();
        for &(axis, angle) in factors {
            let Some(q) = coordinates.iter().position(|&q| q == angle) else {
                return Err(format!(
                    "body `{}`: its factor rot_{} turns by an angle that is not one coordinate",
                    names[b],
                    ["x", "y", "z"][axis]
                ));
            };
            js.push((axis, q));
        }
        joints.push(js);
    }
    Ok(joints)
}

/// The links, parents first, and each body's last link; an error unless every
/// body hangs on its parent at a fixed point by new joints and every
/// coordinate is one joint.
fn link_bodies(
    ctx: &mut Context,
    skeleton: &Skeleton,
    joints: &[Vec<(usize, usize)>],
    names: &[String],
) -> Result<(Vec<Link>, Vec<Option<usize>>), String> {
    let bodies = &skeleton.bodies;
    let n = ctx.coordinates().len();
    // Parents: the body whose joints are the longest proper prefix.
    let mut order: Vec<usize> = (0..bodies.len()).collect();
    order.sort_by_key(|&b| joints[b].len());
    let mut links: Vec<Link> = Vec::new();
    let mut last_link: Vec<Option<usize>> = vec![None; bodies.len()];
    let mut used = vec![false; n];
    let zero = ctx.zero();
    for &b in &order {
        let mine = &joints[b];
        let parent = (0..bodies.len())
            .filter(|&p| p != b && joints[p].len() < mine.len() && mine.starts_with(&joints[p]))
            .max_by_key(|&p| joints[p].len());
        let prefix = parent.map_or(0, |p| joints[p].len());
        if prefix == mine.len() {
            return Err(format!(
                "body `{}`: its rotation adds no joint to another body's",
                names[b]
            ));
        }
        if parent
            .is_some_and(|p| (0..bodies.len()).any(|o| o != p && o != b && joints[o] == joints[p]))
        {
            return Err(format!(
                "body `{}`: two bodies have its parent's rotation, so which one carries it is unclear",
                names[b]
            ));
        }
        let offset = joint_offset(ctx, skeleton, b, parent).ok_or_else(|| match parent {
            None => format!(
                "body `{}`: its reference point moves, but it has no parent body",
                names[b]
            ),
            Some(p) => format!(
                "body `{}`: its reference point is not a point fixed in its parent `{}`",
                names[b], names[p]
            ),
        })?;
        let mut up = parent.map(|p| last_link[p].expect("parents come first"));
        for (k, &(axis, coordinate)) in mine[prefix..].iter().enumerate() {
            if std::mem::replace(&mut used[coordinate], true) {
                let q = coordinate_name(ctx, coordinate);
                return Err(format!(
                    "body `{}`: coordinate `{q}` turns a second joint",
                    names[b]
                ));
            }
            links.push(Link {
                parent: up,
                axis,
                coordinate,
                offset: if k == 0 { offset } else { [zero; 3] },
                inertia: None,
            });
            up = Some(links.len() - 1);
        }
        last_link[b] = up;
    }
    if let Some(q) = used.iter().position(|u| !u) {
        let q = coordinate_name(ctx, q);
        return Err(format!(
            "coordinate `{q}` turns no joint (a translation, or a coordinate outside the rotations)"
        ));
    }
    Ok((links, last_link))
}

/// Where body `b`'s first new joint sits: its reference point, fixed in space
/// for a root, or an anchor fixed in the parent.
fn joint_offset(
    ctx: &Context,
    skeleton: &Skeleton,
    b: usize,
    parent: Option<usize>,
) -> Option<[Sym; 3]> {
    let reference = &skeleton.bodies[b].reference;
    let at = match parent {
        None => reference,
        Some(p) => {
            let (_, _, local) = skeleton
                .anchors
                .iter()
                .find(|(at, body, _)| *body == p && at == reference)?;
            local
        }
    };
    if at.len() != 3 || !at.iter().all(|&x| fixed(ctx, x)) {
        return None;
    }
    Some([at[0], at[1], at[2]])
}

/// Masses: point masses fixed in bodies (body centres included) and the bodies'
/// rotational inertia; a point mass fixed in space moves with nothing.
fn attach_masses(
    ctx: &mut Context,
    skeleton: &Skeleton,
    masses: &Masses,
    links: &mut [Link],
    last_link: &[Option<usize>],
) -> Result<(), String> {
    let zero = ctx.zero();
    let jointless = |b: usize| {
        format!(
            "body `{}` carries mass but turns on no joint",
            masses.body_names[b]
        )
    };
    for (i, at) in skeleton.masses.iter().enumerate() {
        match at {
            Some((b, local)) if local.len() == 3 && local.iter().all(|&x| fixed(ctx, x)) => {
                let link = last_link[*b].ok_or_else(|| jointless(*b))?;
                let add =
                    point_inertia(ctx, masses.point_masses[i], [local[0], local[1], local[2]]);
                links[link].inertia = Some(add_inertia(ctx, links[link].inertia, add));
            }
            None if masses.point_positions[i].iter().all(|&x| fixed(ctx, x)) => {}
            _ => {
                return Err(format!(
                    "point `{}`: it has mass and moves, but is not fixed in a body",
                    masses.point_names[i]
                ));
            }
        }
    }
    for (b, tensor) in masses.inertias.iter().enumerate() {
        let link = last_link[b].ok_or_else(|| jointless(b))?;
        let spin = Inertia {
            mass: zero,
            first: [zero; 3],
            rot: *tensor,
        };
        links[link].inertia = Some(add_inertia(ctx, links[link].inertia, spin));
    }
    Ok(())
}

/// A point mass μ at r: (μ, μ r, μ(|r|² 1 − r rᵀ)).
pub(super) fn point_inertia(ctx: &mut Context, mass: Sym, r: [Sym; 3]) -> Inertia {
    let first = r.map(|x| ctx.mul(mass, x));
    let squares: Vec<Sym> = r.iter().map(|&x| ctx.mul(x, x)).collect();
    let norm = ctx.sum(&squares);
    let rot = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let outer = ctx.mul(r[i], r[j]);
            let e = if i == j {
                ctx.sub(norm, outer)
            } else {
                ctx.neg(outer)
            };
            ctx.mul(mass, e)
        })
    });
    Inertia { mass, first, rot }
}

pub(super) fn add_inertia(ctx: &mut Context, a: Option<Inertia>, b: Inertia) -> Inertia {
    let Some(a) = a else { return b };
    Inertia {
        mass: ctx.add(a.mass, b.mass),
        first: [0, 1, 2].map(|i| ctx.add(a.first[i], b.first[i])),
        rot: [0, 1, 2].map(|i| [0, 1, 2].map(|j| ctx.add(a.rot[i][j], b.rot[i][j]))),
    }
}
