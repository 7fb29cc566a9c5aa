//! Finding the tree in a description: joints and placements from the bodies'
//! rotation factors, parents by the longest prefix of factors among the bodies
//! the child hangs on, offsets from the anchors, and the masses gathered onto
//! the links (those of a body fixed in its parent onto the parent's link).
//! Where the description is not a tree, the answer says why: which body or
//! point, and what about it, so that the user can see what keeps a model off
//! the recursive route.

use lagrange_symbolic::{Context, Expr as Sym};

use super::frame::{Frame, PlacedMass, coordinate_name, fixed};
use super::link::{add3, elementary};
use super::{BodyFault, Inertia, Link, Masses, NotATree, Spheres, Tree};
use crate::lowered::{Factor, Skeleton};
use crate::mat3::{Mat3, mat_mul, mat_vec, parallel_axis, quaternion_matrix, transpose};

/// An elementary rotation factor by a constant angle: (axis, angle).
type Constant = (usize, Sym);

/// One joint of a body's rotation: the constant factors since the previous
/// joint (its placement), its axis and its coordinate, and whether it is an
/// axis of a spherical joint.
#[derive(Clone, PartialEq)]
struct Joint {
    placement: Vec<Constant>,
    axis: usize,
    coordinate: usize,
    sphere: Sphere,
}

/// A joint's part in a spherical joint (a free orientation's three axes).
#[derive(Clone, Copy, PartialEq)]
enum Sphere {
    /// A revolute joint.
    No,
    /// The first axis, placed by the quaternion's R₀ after the placement;
    /// the chart's θ.
    First([Sym; 4], [Sym; 3]),
    /// The second or third axis, in the first's frame.
    Next,
}

/// A body's rotation read as joints, the constant factors after the last one,
/// and the factors in all (but turns by zero, which are none).
struct Chain {
    joints: Vec<Joint>,
    trailing: Vec<Constant>,
    factors: Vec<Factor>,
}

/// Links with their masses attached, and the spherical joints.
type Linked = (Vec<Link>, Spheres);

/// The kinematic tree the description spans, or why it is not one.
pub fn detect(ctx: &mut Context, skeleton: &Skeleton, masses: &Masses) -> Result<Tree, NotATree> {
    if skeleton.bodies.is_empty() || ctx.coordinates().is_empty() {
        return Err(NotATree::NoRigidBodies);
    }
    let (mut links, spheres) = from_factors(ctx, skeleton, masses).or_else(|reason| {
        let factored = skeleton.bodies.iter().all(|b| b.factors.is_some());
        from_written(ctx, skeleton, masses).map_err(|why| if factored { reason } else { why })
    })?;
    let gravity = match masses.gravity {
        None => None,
        Some(g) if g.len() == 3 && g.iter().all(|&x| fixed(ctx, x)) => Some([g[0], g[1], g[2]]),
        Some(_) => return Err(NotATree::GravityNotConstant),
    };
    for link in &mut links {
        as_floats(ctx, link);
    }
    Ok(Tree {
        links,
        gravity,
        spheres,
        armature: Vec::new(),
    })
}

/// The tree read from the bodies' rotation factors and the points their
/// reference points are fixed at.
fn from_factors(
    ctx: &mut Context,
    skeleton: &Skeleton,
    masses: &Masses,
) -> Result<Linked, NotATree> {
    let chains = body_chains(ctx, skeleton, masses.body_names)?;
    let (mut links, frames, spheres) = link_bodies(ctx, skeleton, &chains, masses.body_names)?;
    attach_masses(ctx, &skeleton.masses, masses, &mut links, &frames)?;
    Ok((links, spheres))
}

/// The tree read from written-out positions and rotations
/// ([`super::written`]).
fn from_written(
    ctx: &mut Context,
    skeleton: &Skeleton,
    masses: &Masses,
) -> Result<Linked, NotATree> {
    let mut written = super::written::read(ctx, skeleton, masses)?;
    attach_masses(
        ctx,
        &written.masses,
        masses,
        &mut written.links,
        &written.frames,
    )?;
    Ok((written.links, Vec::new()))
}

/// A number as a float constant (an expression otherwise unchanged).
fn float(ctx: &mut Context, x: Sym) -> Sym {
    match ctx.as_f64(x) {
        Some(v) if ctx.is_constant(x) => ctx.float(v),
        _ => x,
    }
}

/// The link's numbers as floats: the engine does not distribute a float
/// coefficient over a sum, so m a, I α and d × f stay one product each.
fn as_floats(ctx: &mut Context, link: &mut Link) {
    link.offset = link.offset.map(|x| float(ctx, x));
    if let Some(i) = &mut link.inertia {
        i.mass = float(ctx, i.mass);
        i.first = i.first.map(|x| float(ctx, x));
        i.rot = i.rot.map(|r| r.map(|x| float(ctx, x)));
    }
}

/// Each body's rotation factors read as joints (about coordinates) and
/// placements (by constant angles).
fn body_chains(
    ctx: &Context,
    skeleton: &Skeleton,
    names: &[String],
) -> Result<Vec<Chain>, NotATree> {
    let coordinates = ctx.coordinates();
    let mut chains = Vec::new();
    for (b, body) in skeleton.bodies.iter().enumerate() {
        let Some(factors) = body.factors.as_ref() else {
            return Err(NotATree::body(&names[b], BodyFault::NotFactored));
        };
        let mut joints = Vec::new();
        let mut pending = Vec::new();
        for &factor in factors {
            let (axis, angle) = match factor {
                Factor::Turn(axis, angle) => (axis, angle),
                Factor::Free { theta, quaternion } => {
                    for (axis, &x) in theta.iter().enumerate() {
                        let coordinate = coordinates
                            .iter()
                            .position(|&q| q == x)
                            .expect("a free orientation's θ are coordinates");
                        let sphere = if axis == 0 {
                            Sphere::First(quaternion, theta)
                        } else {
                            Sphere::Next
                        };
                        joints.push(Joint {
                            placement: std::mem::take(&mut pending),
                            axis,
                            coordinate,
                            sphere,
                        });
                    }
                    continue;
                }
            };
            if let Some(coordinate) = coordinates.iter().position(|&q| q == angle) {
                let placement = std::mem::take(&mut pending);
                joints.push(Joint {
                    placement,
                    axis,
                    coordinate,
                    sphere: Sphere::No,
                });
            } else if fixed(ctx, angle) {
                pending.push((axis, angle));
            } else {
                let fault = BodyFault::AngleNotACoordinate { axis };
                return Err(NotATree::body(&names[b], fault));
            }
        }
        // A turn by zero is no factor: a body written `rotation = rot_z(0)`
        // (a sliding link, whose joint turns nothing) is the parent of one
        // whose factors begin with its parent's and go on with a placement.
        let factors = factors
            .iter()
            .filter(|f| !matches!(f, Factor::Turn(_, angle) if ctx.is_zero(*angle)))
            .copied()
            .collect();
        chains.push(Chain {
            joints,
            trailing: pending,
            factors,
        });
    }
    Ok(chains)
}

/// The product of constant factors as a matrix (`None`: the identity).
fn constant_rotation(ctx: &mut Context, factors: &[Constant]) -> Option<Mat3> {
    let mut out: Option<Mat3> = None;
    for &(axis, angle) in factors {
        let m = elementary(ctx, axis, angle);
        out = Some(match out {
            None => m,
            Some(r) => mat_mul(ctx, &r, &m),
        });
    }
    out
}

fn identity(ctx: &mut Context) -> Mat3 {
    let zero = ctx.zero();
    let one = ctx.one();
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| if i == j { one } else { zero }))
}

/// The body `b` hangs on: among the bodies placed before it whose factors
/// begin its own and which carry a point at its reference point, the one with
/// the most factors; and that point in the parent's axes.
fn parent_of(
    skeleton: &Skeleton,
    chains: &[Chain],
    placed: &[usize],
    b: usize,
) -> Option<(usize, Vec<Sym>)> {
    let reference = &skeleton.bodies[b].reference;
    placed
        .iter()
        .filter(|&&p| chains[b].factors.starts_with(&chains[p].factors))
        .filter_map(|&p| {
            let anchor = skeleton
                .anchors
                .iter()
                .find(|(at, body, _)| *body == p && at == reference)?;
            Some((p, anchor.2.clone()))
        })
        .max_by_key(|(p, _)| chains[*p].factors.len())
}

/// Where a body hangs: the link it hangs on (`None`: the ground), the point in
/// that link's axes, the sliding joints there (direction and coordinate) if
/// the point moves along fixed lines, and how many of its joints its parent
/// has.
struct Hook {
    up: Option<usize>,
    at: [Sym; 3],
    slides: Vec<([Sym; 3], usize)>,
    inherited: usize,
}

/// A sliding joint: its direction and its coordinate.
type Slide = ([Sym; 3], usize);

/// `x = c + Σ a_k q_k` with c and every a_k constant, for one coordinate or
/// more: a point sliding along fixed lines (a free body's `at = [x, y, z]`
/// slides along the three axes), one sliding joint per coordinate.
fn sliding(ctx: &mut Context, x: &[Sym]) -> Option<([Sym; 3], Vec<Slide>)> {
    if x.len() != 3 {
        return None;
    }
    let qs = ctx.coordinates();
    let mut found = Vec::new();
    for (k, &q) in qs.iter().enumerate() {
        let a: Vec<Sym> = x.iter().map(|&e| ctx.diff(e, q)).collect();
        if a.iter().all(|&d| ctx.is_zero(d)) {
            continue;
        }
        if !a.iter().all(|&d| fixed(ctx, d)) {
            return None;
        }
        found.push(([a[0], a[1], a[2]], k));
    }
    if found.is_empty() {
        return None;
    }
    let zero = ctx.zero();
    let at: Vec<(Sym, Sym)> = found.iter().map(|&(_, k)| (qs[k], zero)).collect();
    let c: Vec<Sym> = x.iter().map(|&e| ctx.substitute(e, &at)).collect();
    c.iter()
        .all(|&e| fixed(ctx, e))
        .then(|| ([c[0], c[1], c[2]], found))
}

/// Where body `b` hangs, from its parent's frame (or the ground's).
fn hook(
    ctx: &mut Context,
    skeleton: &Skeleton,
    chains: &[Chain],
    frames: &[Option<Frame>],
    (placed, b): (&[usize], usize),
    names: &[String],
) -> Result<Hook, NotATree> {
    let Some((p, anchor)) = parent_of(skeleton, chains, placed, b) else {
        let reference = skeleton.bodies[b].reference.clone();
        if let Some((at, slides)) = sliding(ctx, &reference) {
            return Ok(Hook {
                up: None,
                at,
                slides,
                inherited: 0,
            });
        }
        let at = root_point(ctx, skeleton, chains, b, names)?;
        return Ok(Hook {
            up: None,
            at,
            slides: Vec::new(),
            inherited: 0,
        });
    };
    let parent = frames[p].expect("parents are placed first");
    let (local, slides) = if anchor.len() == 3 && anchor.iter().all(|&x| fixed(ctx, x)) {
        ([anchor[0], anchor[1], anchor[2]], Vec::new())
    } else if let Some((c, found)) = sliding(ctx, &anchor) {
        let turned = found
            .into_iter()
            .map(|(a, k)| (mat_vec(ctx, &parent.rotation, a), k))
            .collect();
        (c, turned)
    } else {
        let parent = names[p].clone();
        return Err(NotATree::body(
            &names[b],
            BodyFault::SlidesOffALine { parent },
        ));
    };
    let turned = mat_vec(ctx, &parent.rotation, local);
    let at = add3(ctx, parent.origin, turned);
    let inherited = chains[p].joints.len();
    Ok(Hook {
        up: parent.link,
        at,
        slides,
        inherited,
    })
}

/// Claims coordinate `q` for a joint of body `b`: a coordinate may drive
/// joints of different bodies (a mimic joint: the tree algorithms sum the
/// joints' shares), not two joints of one body.
fn claim(
    ctx: &Context,
    used: &mut [Option<usize>],
    q: usize,
    b: usize,
    body: &str,
) -> Result<(), NotATree> {
    if used[q] == Some(b) {
        let coordinate = coordinate_name(ctx, q);
        return Err(NotATree::body(
            body,
            BodyFault::CoordinateTwice { coordinate },
        ));
    }
    used[q] = Some(b);
    Ok(())
}

/// The links, parents first, and each body's frame; an error unless every
/// body hangs on a parent at a point fixed in it or sliding along a fixed
/// line (or is fixed in space), by joints that extend the parent's, and every
/// coordinate is one joint.
fn link_bodies(
    ctx: &mut Context,
    skeleton: &Skeleton,
    chains: &[Chain],
    names: &[String],
) -> Result<(Vec<Link>, Vec<Frame>, Spheres), NotATree> {
    let mut order: Vec<usize> = (0..chains.len()).collect();
    order.sort_by_key(|&b| chains[b].factors.len());
    let mut links: Vec<Link> = Vec::new();
    let mut frames: Vec<Option<Frame>> = vec![None; chains.len()];
    let mut used: Vec<Option<usize>> = vec![None; ctx.coordinates().len()];
    let mut spheres = Vec::new();
    let zero = ctx.zero();
    for (k, &b) in order.iter().enumerate() {
        let hook = hook(ctx, skeleton, chains, &frames, (&order[..k], b), names)?;
        let mut up = hook.up;
        let mut offset = Some(hook.at);
        for &(dir, q) in &hook.slides {
            claim(ctx, &mut used, q, b, &names[b])?;
            links.push(Link {
                parent: up,
                placement: None,
                slide: Some(dir),
                axis: 0,
                coordinate: q,
                offset: offset.replace([zero; 3]).expect("set above"),
                inertia: None,
                chart: None,
            });
            up = Some(links.len() - 1);
        }
        for joint in &chains[b].joints[hook.inherited..] {
            claim(ctx, &mut used, joint.coordinate, b, &names[b])?;
            let at = offset.take().unwrap_or([zero; 3]);
            links.push(joint_link(ctx, joint, up, at, &mut spheres, links.len()));
            up = Some(links.len() - 1);
        }
        let origin = offset.unwrap_or([zero; 3]);
        let trailing = constant_rotation(ctx, &chains[b].trailing);
        let rotation = trailing.unwrap_or_else(|| identity(ctx));
        frames[b] = Some(Frame {
            link: up,
            origin,
            rotation,
        });
    }
    if let Some(q) = used.iter().position(Option::is_none) {
        let coordinate = coordinate_name(ctx, q);
        return Err(NotATree::IdleCoordinate {
            coordinate,
            written: false,
        });
    }
    let frames = frames
        .into_iter()
        .map(|f| f.expect("every body placed"))
        .collect();
    Ok((links, frames, spheres))
}

/// The link of `joint` (at index `index`, hanging on `up` at `offset`): a
/// spherical joint's first axis is placed by R₀ too, recorded in `spheres`
/// with its θ, and its later axes point back at it.
fn joint_link(
    ctx: &mut Context,
    joint: &Joint,
    up: Option<usize>,
    offset: [Sym; 3],
    spheres: &mut Spheres,
    index: usize,
) -> Link {
    let mut placement = constant_rotation(ctx, &joint.placement);
    let chart = match joint.sphere {
        Sphere::No => None,
        Sphere::First(quaternion, theta) => {
            let r0 = quaternion_matrix(ctx, quaternion);
            placement = Some(placement.map_or(r0, |p| mat_mul(ctx, &p, &r0)));
            spheres.push((index, theta));
            Some(index)
        }
        Sphere::Next => spheres.last().map(|&(first, _)| first),
    };
    Link {
        parent: up,
        placement,
        slide: None,
        axis: joint.axis,
        coordinate: joint.coordinate,
        offset,
        inertia: None,
        chart,
    }
}

/// A body that hangs on no other: its reference point, which must be fixed in
/// space; the reason otherwise names the body whose rotation its own extends.
fn root_point(
    ctx: &Context,
    skeleton: &Skeleton,
    chains: &[Chain],
    b: usize,
    names: &[String],
) -> Result<[Sym; 3], NotATree> {
    let at = &skeleton.bodies[b].reference;
    if at.len() == 3 && at.iter().all(|&x| fixed(ctx, x)) {
        return Ok([at[0], at[1], at[2]]);
    }
    let extended = (0..chains.len()).find(|&p| {
        p != b && !chains[p].joints.is_empty() && chains[b].factors.starts_with(&chains[p].factors)
    });
    let fault = match extended {
        Some(p) => BodyFault::NotFixedInParent {
            parent: names[p].clone(),
        },
        None => BodyFault::MovesWithoutParent,
    };
    Err(NotATree::body(&names[b], fault))
}

/// Masses: point masses fixed in bodies (body centres included) and the bodies'
/// rotational inertia, in the axes of the link each body is fixed in; a mass
/// fixed in space moves with nothing.
fn attach_masses(
    ctx: &mut Context,
    placed: &[PlacedMass],
    masses: &Masses,
    links: &mut [Link],
    frames: &[Frame],
) -> Result<(), NotATree> {
    let zero = ctx.zero();
    for (i, at) in placed.iter().enumerate() {
        match at {
            Some((b, local)) if local.len() == 3 && local.iter().all(|&x| fixed(ctx, x)) => {
                let frame = frames[*b];
                let Some(link) = frame.link else { continue };
                let turned = mat_vec(ctx, &frame.rotation, [local[0], local[1], local[2]]);
                let r = add3(ctx, frame.origin, turned);
                let add = point_inertia(ctx, masses.point_masses[i], r);
                links[link].inertia = Some(add_inertia(ctx, links[link].inertia, add));
            }
            None if masses.point_positions[i].iter().all(|&x| fixed(ctx, x)) => {}
            _ => {
                let point = masses.point_names[i].clone();
                return Err(NotATree::LoosePoint { point });
            }
        }
    }
    for (b, tensor) in masses.inertias.iter().enumerate() {
        let Some(link) = frames[b].link else { continue };
        let r = frames[b].rotation;
        let turned = mat_mul(ctx, &r, tensor);
        let spin = Inertia {
            mass: zero,
            first: [zero; 3],
            rot: mat_mul(ctx, &turned, &transpose(&r)),
        };
        links[link].inertia = Some(add_inertia(ctx, links[link].inertia, spin));
    }
    Ok(())
}

/// A point mass μ at r: (μ, μ r, μ(|r|² 1 − r rᵀ)).
pub(super) fn point_inertia(ctx: &mut Context, mass: Sym, r: [Sym; 3]) -> Inertia {
    let first = r.map(|x| ctx.mul(mass, x));
    let rot = parallel_axis(ctx, mass, r);
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
